#pragma once
// (T)FETI from subdomain matrices to the primal solution, for equality constraints B_E u = c_E
// (gluing and Dirichlet rows built from the meshes, c = 0 there, and the caller's own equality
// rows with any right-hand side) and, optionally, non-penetration inequality rows B_I u <= c_I
// (contact).
//   setup:  factorize K_s (K+), tear (B, c), coarse space (G, G G^T), preconditioner,
//           d = B K+ f - c,  e = R^T f,  lambda~ = G^T (G G^T)^{-1} e
//   solve:  equality rows only: PCPG on the dual problem;
//           with inequality rows: lambda = lambda~ + mu and the dual QP (reference paper,
//           "FETI domain decomposition method (III), (IV)")
//             min 1/2 mu^T P F P mu - mu^T P (d - F lambda~)  s.t.  Q mu = 0,  mu_I >= -lambda~_I
//           by SMALBE (MPRGP inner solver) or by MPRGP on the penalized P F P + rho Q
//   recover: alpha from the rows that hold with equality (equality rows and active inequality
//           rows): alpha = (G_A G_A^T)^{-1} G_A (F lambda - d),  u = K+ (f - B^T lambda) + R alpha
//
// The caller's equality rows (EqualityRow, tfeti_Tearing.hpp): sum_k coef_k u_k = rhs over any
// dofs of any subdomains, dof = dofsPerNode * local node + component of the subdomain with global
// id `subdomain`. c_E enters only d (d = B K+ f - c), so PCPG, SMALBE and the penalty method
// solve them alike, and the recovered u meets B_E u = c_E to the solver's tolerance
// (constraintReport().equalityResidual). Contract:
//  - each row is passed once, by any one rank (rows are gathered and numbered canonically);
//  - the rows together with the automatic ones must be consistent (some u meets them all) and,
//    with the gluing, must hold every subdomain's rigid modes that the loads would excite;
//  - with "Gluing" = none no gluing rows are built: the caller's rows must join the subdomains
//    (a tied interface, u_a - u_b = 0 per shared dof, reproduces the automatic gluing);
//  - FETI formulation: the mesh's Dirichlet dofs are eliminated (held at zero); a caller's row
//    must not touch them (an error on every rank). Use TFETI for non-zero prescribed values on
//    the mesh's own Dirichlet nodes, or leave those nodes out of dirichletNodes and pass rows.
// Malformed rows (unknown subdomain or dof, no non-zero coefficient, non-finite values) are an
// error naming the row, raised on every rank.
#include <BelosTypes.hpp>
#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <vector>

#include "tfeti_CoarseSpace.hpp"
#include "tfeti_CollectiveError.hpp"
#include "tfeti_DualOperators.hpp"
#include "tfeti_LocalSolver.hpp"
#include "tfeti_MemoryUsage.hpp"
#include "tfeti_NodeMemory.hpp"
#include "tfeti_Pcpg.hpp"
#include "tfeti_QpProblem.hpp"
#include "tfeti_RowCarryOver.hpp"
#include "tfeti_SetupMemoryForecast.hpp"
#include "tfeti_SubdomainMesh.hpp"

namespace tfeti {

// What the physics layer hands over for one subdomain.
// mesh.dim is the spatial dimension (coords: dim per node); dofsPerNode is 1 (scalar) or
// mesh.dim (elasticity), or anything with a kernel given. The kernel of K is found from
// mesh.elements (or the graph of K) unless `kernel` is given.
// FetiSolver moves K and f into its subdomains: its data() keeps them empty.
struct SubdomainData {
  SubdomainMesh mesh;
  int dofsPerNode = 1;
  CsrMatrix K;
  // K as a Tpetra::CrsMatrix instead (K then empty): all rows on this rank, row ids 0 .. n-1 the
  // local dofs (tfeti_TpetraInterface.hpp); converted to K by FetiSolver's constructor.
  Teuchos::RCP<const CrsMatrix> tpetraK;
  std::vector<double> f;
  std::vector<double> kernel;  // optional: column-major numDofs x k, checked by ||K R||
};

struct DualResult : PcpgResult {
  std::string method;  // PCPG | SMALBE | penalty
  QpCounters qp;       // SMALBE and penalty: the QP solver's counters
  double rho = 0.0;    // SMALBE and penalty: the penalty parameter used
};

// How well the recovered primal solution meets the constraints (after solve()).
struct ConstraintReport {
  // Non-penetration rows (every inequality row, friction rows included, in inequalityRows):
  GO inequalityRows = 0, activeRows = 0;  // active: lambda_i > 0
  double force = 0.0;                     // sum of the non-penetration multipliers
  double minMultiplier = 0.0;             // min lambda_I: >= 0
  double maxPenetration = 0.0;            // max (B_I u - c_I): <= 0 when feasible
  double maxComplementarity = 0.0;        // max |lambda_i (B_I u - c_I)_i|
  double equalityResidual = 0.0;          // max |B_E u - c_E| (and |B_I u - c_I| when tied)
  // Friction rows (multiplier bounds other than [0, inf), InequalityRow::boundActive):
  GO frictionRows = 0, stickRows = 0;    // stick: lambda strictly inside its bounds
  double maxFrictionBoundExcess = 0.0;   // max (lower - lambda, lambda - upper): <= 0
  double maxFrictionSlipResidual = 0.0;  // max |B u - c| (stick), max(0, -sign(lambda) (B u - c))
};

struct FetiTimings {
  double factorization = 0;   // subdomain K+ (and kernels)
  double tearing = 0;         // B and the maps
  double coarse = 0;          // G, G G^T and its factorization
  double preconditioner = 0;  // interior factorizations (Dirichlet) or K_bb blocks (lumped)
  double dualRhs = 0;         // d, e, lambda0
  double dualOperator = 0;    // "Dual operator" = explicit: the assembly of the local F_s
  // Its memory check before it (the analyses with the dual rows' dofs last it makes).
  double explicitMemoryCheck = 0;
  double solve = 0;     // PCPG
  double recovery = 0;  // primal solution
  // Subdomain factorizations of K+ over all ranks: computed, and kept because a new tangent
  // brought the same K (FetiSolver::updateStiffness; the elastic subdomains of a plastic body).
  long long factorizations = 0, factorizationsReused = 0;
  // Tearings (B with its maps and scaling) and coarse spaces built, and kept by an update whose
  // rows changed only their right-hand sides and bounds (the count is the same on every rank).
  long long tearings = 0, tearingsReused = 0;
  // Symbolic analyses of the local factorizations (subdomains, Dirichlet interiors, coarse
  // problem) over all ranks: made, and shared with a live factor of the same sparsity pattern.
  long long symbolicAnalyses = 0, symbolicAnalysesShared = 0;
  double setup() const {
    return factorization + tearing + coarse + preconditioner + dualRhs + dualOperator +
           explicitMemoryCheck;
  }
};

class FetiSolver {
 public:
  // "Formulation" (TFETI | FETI), "Kernel tolerance" (1e-8), "Gluing" (nonredundant | redundant),
  // "Gluing at Dirichlet nodes" (true), "Inequality row scaling" (joined | separate),
  // "Preconditioner" (none | lumped | dirichlet), "Local solver" (cholmod | klu2 | tacho), "Dual
  // solver" (auto | PCPG | SMALBE | penalty), "Dual operator" (implicit | explicit | auto, with
  // "Explicit assembly", "Explicit storage", "Explicit device" and "Explicit export file";
  // docs/dual_operator.md), "Keep subdomain matrices" (true; false frees K after the
  // preconditioner's set-up, or after the F_s's Schur assembly) and the sublists "PCPG",
  // "MPRGP", "SMALBE" and "Penalty".
  static Teuchos::RCP<const Teuchos::ParameterList> validParameters();
  // "Preconditioning in face" is a parameter of the FETI list only: the solver sets it for MPRGP
  // (alone or inside SMALBE). Throws std::invalid_argument, saying where it belongs, when it is
  // in the "MPRGP" or "SMALBE"/"MPRGP" sublist of `feti` (call before validating a list that
  // holds the FETI list; the constructor calls it).
  static void rejectMisplacedParameters(const Teuchos::ParameterList& feti);
  // Replaces Belos's names ("Convergence Tolerance", "Maximum Iterations") in the "PCPG",
  // "MPRGP", "SMALBE" and "SMALBE"/"MPRGP" sublists by the package's (tfeti_SolverConventions.hpp;
  // both names with different values: std::invalid_argument). The constructor calls it; call it
  // before validating a list that holds the FETI list.
  static void applySolverAliases(Teuchos::ParameterList& feti);
  // The dual solver "Dual solver" (a validated FETI list) selects for a problem with this many
  // inequality rows; throws std::invalid_argument when it cannot handle them (checkable before
  // any set-up, e.g. by a dry run).
  static std::string dualSolverFor(const Teuchos::ParameterList& feti, GO inequalityRows);
  // "Inequality rows" = equalities: the inequality rows are held with equality (B_I u = c_I,
  // lambda_I of either sign), e.g. a tied contact pair.
  static bool inequalitiesTied(const Teuchos::ParameterList& feti);

  // A copy of the FETI list as the solver reads it: misplaced parameters rejected, aliases
  // applied, validated with the defaults set, an unusable "Explicit device" rejected (all
  // std::invalid_argument or Teuchos' validation errors, naming the parameter). The constructor
  // and forecastSetupMemory start with it; a dry run reads its settings from it.
  static Teuchos::ParameterList validatedParameters(const Teuchos::ParameterList& feti);
  // The dry run's forecast (collective, nothing factorized): what the set-up of `local` (the
  // constructor's arguments) will allocate on this rank, as its memory checks count it
  // (tfeti_SetupMemoryForecast.hpp): the rows of B the tearing builds, the factors' bytes from
  // the local solver's own symbolic analyses (the analyses the run makes), the Dirichlet
  // preconditioner's interior factors on the interfaces of that tearing, the explicit F_s. The
  // FETI list is validated here, on a copy; the subdomains are checked as the constructor checks
  // them and built one at a time, unfactorized, for their kernels and fixing dofs (so the
  // constructor's errors, a kernel's residual included, are the forecast's).
  static SetupMemoryForecast forecastSetupMemory(
      const Teuchos::RCP<const Comm>& comm, int numSubdomains,
      const std::vector<SubdomainData>& local, const Teuchos::ParameterList& feti,
      const std::vector<InequalityRow>& inequalities = {},
      const std::vector<EqualityRow>& equalities = {});

  // local: the subdomains assigned to this rank (see subdomainsOfRank), in increasing id order.
  // Every size and index of `local` is checked first (tfeti_InputChecks.hpp); an error found on
  // any rank is thrown on every rank as CollectiveError.
  // inequalities: the non-penetration rows this rank contributes (see buildTearing).
  // equalities: the equality rows with right-hand sides this rank contributes (see above).
  FetiSolver(const Teuchos::RCP<const Comm>& comm, int numSubdomains,
             std::vector<SubdomainData> local, const Teuchos::ParameterList& params,
             const std::vector<InequalityRow>& inequalities = {},
             const std::vector<EqualityRow>& equalities = {});

  DualResult solve();
  // Progress lines of PCPG, MPRGP and SMALBE (their "Verbosity") go here, e.g. a
  // Teuchos::FancyOStream; null (default): std::cout. Its format state is never changed.
  void setOutputStream(Teuchos::RCP<std::ostream> os) { out_ = std::move(os); }

  // Inexact solves, for a Newton method's forcing terms: the following solve() calls stop at
  // `factor` times the configured relative tolerances (PCPG's, SMALBE's relative and equality
  // tolerances, MPRGP's); 1, the default, solves as configured. A factor below 1 (positive)
  // solves tighter than configured: a Newton loop whose own test stalls at the QPs' accuracy.
  void setToleranceFactor(double factor);
  double toleranceFactor() const { return toleranceFactor_; }
  // The next solve() calls start a load step: their warm start (the previous solution) is the
  // last step's, under another load. SMALBE's face phase then lets the slip zone grow before it
  // releases circles (SmalbeSolMgr::setWarmStartFromOtherLoad). False (default): a warm start
  // from the same load (a Newton iteration's previous QP).
  void setLoadStepStart(bool start) { loadStepStart_ = start; }
  // For increments du of a nonlinear method from the state u (per local subdomain, as the loads):
  // from the next update() or updateStiffness() on, the rows the solver owns (gluing and zero
  // Dirichlet rows) read B du = -B u, so that each increment also closes the jumps and the
  // Dirichlet error an inexact earlier solve left in u. Empty (the default): B du = 0.
  void setIncrementOrigin(std::vector<std::vector<double>> u);

  // For nonlinear drivers, which keep K (and its factorizations) and change the rest between
  // solves: new loads f for the local subdomains and new inequality rows (contact rows on the
  // current geometry). Tearing, coarse space and right-hand sides are rebuilt; the Dirichlet
  // preconditioner of a subdomain only if the dofs its rows touch changed.
  // The caller's equality rows stay as they were.
  void update(const std::vector<std::vector<double>>& loads,
              const std::vector<InequalityRow>& inequalities);
  // The same with new equality rows of the caller (e.g. the right-hand side c_E(t) - B_E u of a
  // Newton step towards prescribed values at load factor t).
  void update(const std::vector<std::vector<double>>& loads,
              const std::vector<InequalityRow>& inequalities,
              const std::vector<EqualityRow>& equalities);
  // A new stiffness for every local subdomain (refactorized), its kernel from the rigid modes of
  // `coords` (mesh.dim per node, e.g. the current configuration), with new loads and rows as
  // update(). K must annihilate those modes (||K R|| is checked as in the constructor): the
  // material tangent does, the full tangent of a stressed body does not.
  // An empty K (CsrMatrix{}: 0 x 0, no arrays) keeps the subdomain's K and factor, when the
  // caller knows it unchanged (the elastic subdomains of a small-strain plastic body) and the
  // kernel positions are the same; "Keep subdomain matrices" must then be true. A given K equal
  // to the factorized one is kept too (Subdomain::refactorize), after reading it.
  void updateStiffness(std::vector<CsrMatrix> K, const std::vector<std::vector<double>>& coords,
                       const std::vector<std::vector<double>>& loads,
                       const std::vector<InequalityRow>& inequalities);
  // The same with new equality rows of the caller.
  void updateStiffness(std::vector<CsrMatrix> K, const std::vector<std::vector<double>>& coords,
                       const std::vector<std::vector<double>>& loads,
                       const std::vector<InequalityRow>& inequalities,
                       const std::vector<EqualityRow>& equalities);
  // B^T lambda of the last solve on each local subdomain: the forces the multipliers (gluing,
  // Dirichlet and contact reactions) exert, as in the residual f - B^T lambda - f_int.
  std::vector<std::vector<double>> multiplierForces() const;

  ConstraintReport constraintReport() const;
  // For each local subdomain: every inequality row touching it, as (local dof, the row's
  // coefficient there, lambda); the constraint's force on that dof is -coef * lambda.
  struct InequalityOnDof {
    int dof;
    double coef, lambda;
  };
  std::vector<std::vector<InequalityOnDof>> inequalityMultipliersOnSubdomains() const;
  const Vector& multipliers() const { return *lambda_; }
  // The inequality multipliers on every rank, in the order of tearing().inequalityRows.
  std::vector<double> inequalityMultipliers() const;
  // Likewise 1 where the row holds with equality (a contact row in contact, a friction row
  // sticking) and 0 where its multiplier is at a bound, as the primal fit took them: after the
  // penalty's equality projection MPRGP's, not the projected multipliers' (a hair off a bound).
  std::vector<double> inequalityRowsHolding() const;
  // The multipliers of the caller's equality rows on every rank, in the order of
  // tearing().userEqualityRows (the canonical order): the row's reaction, its force on dof k
  // being -coef_k * lambda.
  std::vector<double> userEqualityMultipliers() const;

  // Mean wall time of one application of F over `repeats` applications (slowest rank).
  double timeDualApply(int repeats) const;
  // The rest of a PCPG iteration, timed like timeDualApply: one projection P (two coarse
  // solves' worth: G^T, the replicated (G G^T)^-1, G), one preconditioner apply (0 without one)
  // and the vector work of an iteration (two dot products and three axpy on the multipliers).
  struct IterationParts {
    double projector = 0.0, preconditioner = 0.0, vectorUpdates = 0.0;
  };
  IterationParts timeIterationParts(int repeats) const;

  // Primal solution of the i-th local subdomain (after solve()).
  const std::vector<double>& solution(std::size_t i) const { return u_[i]; }
  // Collective. The primal solution on the caller's untorn map: entry dofsPerNode * global node +
  // component (SubdomainMesh::globalNode), the mean over the subdomains sharing the dof (equal to
  // the solver's tolerance). The map must hold exactly the dofs of all subdomains, distributed
  // in any way; otherwise CollectiveError on every rank.
  Teuchos::RCP<MultiVector> solution(const Teuchos::RCP<const Map>& untornMap) const;
  const SubdomainList& subdomains() const { return subdomains_; }
  const std::vector<SubdomainData>& data() const { return data_; }

  GO primalDimension() const { return tearing_.dofOffset.back(); }
  GO dualDimension() const { return tearing_.numRows; }
  GO gluingRows() const { return tearing_.numGluingRows; }
  GO dirichletRows() const { return tearing_.numDirichletRows; }
  GO userEqualityRows() const { return tearing_.numUserEqualityRows; }
  GO inequalityRows() const { return tearing_.numInequalityRows; }
  // The rows of the largest scaling group of the preconditioner (docs/qp_solvers.md).
  GO largestScalingGroup() const { return tearing_.largestScalingGroup; }
  GO coarseDimension() const { return coarse_->dimension(); }
  long long dualOperatorApplies() const { return F_->numApplies(); }
  const FetiTimings& timings() const { return timings_; }
  // Resident and peak memory after each phase (the phases of timings(): factorization, tearing,
  // coarse, preconditioner, dual_rhs, solve, recovery), the latest sample of each.
  const MemoryLog& memory() const { return memory_; }
  // Bytes of all subdomain factors on all ranks (K+ and, if any, the preconditioner's).
  std::size_t globalFactorBytes() const;
  std::size_t globalPreconditionerFactorBytes() const;
  // "Dual operator" = explicit: bytes of the dense local F_s, summed over all ranks and the
  // largest rank's (0 and 0 when implicit). Collective.
  struct ExplicitDualBytes {
    unsigned long long total = 0, maxPerRank = 0;
  };
  ExplicitDualBytes explicitDualBytes() const;
  // FETI "Explicit device" ("host" or "gpu") and, with gpu, the device's work since set-up
  // (every explicit operator this solver built): the slowest rank's applies and seconds, the
  // bytes of all ranks per apply. Collective.
  struct ExplicitDeviceWork {
    std::string device = "host";
    long long applies = 0;
    double kernelSeconds = 0.0, applySeconds = 0.0, kernelBytes = 0.0, transferBytes = 0.0;
  };
  ExplicitDeviceWork explicitDeviceWork() const;
  // "Dual operator" = explicit: the assemblies of F_s since set-up (every explicit operator this
  // solver built, all ranks): blocks assembled, the columns solved for, and the columns that
  // assembling each of those blocks anew would have solved (after update() on the same factors
  // only the changed rows are solved for), and the blocks of those assembled from the Schur
  // complement ("Explicit assembly" = schur; their columns count as solved). All 0 when
  // implicit. Collective.
  struct ExplicitAssembly {
    long long blocks = 0, columnsSolved = 0, columnsFull = 0, schurBlocks = 0;
  };
  ExplicitAssembly explicitAssembly() const;
  // "implicit" or "explicit": how F is applied.
  std::string dualOperatorKind() const;
  // How the last set-up chose the dual operator. With "Dual operator" = auto: explicit where it
  // was measured to pay (docs/dual_operator.md): on a device; on the host when the dual problem
  // is a QP (inequality rows with bounds: SMALBE or penalty, many multiplications per
  // factorization) and the F_s, in the chosen storage, take fewer bytes than the subdomain
  // factors (the apply of either reads its bytes once or twice: memory bound), as in 2D and on
  // unstructured 3D meshes, not on structured 3D ones. The bytes are of all ranks. And only
  // where the F_s fit the nodes' memory (checked before the assembly, below): else implicit.
  struct DualOperatorChoice {
    bool automatic = false;
    bool qp = false;
    double explicitBytes = 0.0, factorBytes = 0.0;
    std::string chosen = "implicit";
    // The memory check before the last assembly of new F_s (explicitDoesNotFit):
    // what the node with the least room needs and has; availableBytes < 0 when not checked
    // or unknown (no /proc/meminfo).
    bool fitsMemory = true;
    double nodeNeedBytes = 0.0, nodeAvailableBytes = -1.0;
  };
  const DualOperatorChoice& dualOperatorChoice() const { return dualChoice_; }
  // The memory check before the last factorizations of new subdomains (the constructor's, and
  // updateStiffness's where the kernels moved): the subdomain factors' bytes, told by their
  // symbolic analyses, at the factorizations' peak (the factors made so far and the next one's
  // transient; heldBytes: the factors alone), summed per node, against the node's MemAvailable.
  // known = false where it was not made ("Memory check" = false, a local solver that cannot tell,
  // no /proc/meminfo).
  const NodeMemory& factorMemoryCheck() const { return factorMemory_; }
  // The same before the Dirichlet preconditioner is set up (at every set-up that makes interior
  // factors: the blocks K_bb, K_bi and interior factors to be made with a factorization's
  // transient, less those they replace and the K freed meanwhile, at their peak during the
  // set-up); known = false where none was made or checked.
  const NodeMemory& preconditionerMemoryCheck() const { return preconditionerMemory_; }
  const Tearing& tearing() const { return tearing_; }
  const Teuchos::RCP<DualOperator>& dualOperator() const { return F_; }
  const CoarseSpace& coarseSpace() const { return *coarse_; }
  const Teuchos::RCP<const Comm>& comm() const { return comm_; }

 private:
  Teuchos::RCP<const Comm> comm_;
  Teuchos::ParameterList params_;
  int numSubdomains_ = 0;
  int dofsPerNode_ = 0;
  std::vector<SubdomainData> data_;
  SubdomainList subdomains_;
  Tearing tearing_;
  std::unique_ptr<CoarseSpace> coarse_;
  Teuchos::RCP<PseudoInverseOperator> Kplus_;
  Teuchos::RCP<DualOperator> F_;
  Teuchos::RCP<DualPreconditioner> M_;
  std::vector<EqualityRow> equalities_;  // the caller's rows this rank contributes
  // One switch, in the FETI list, for MPRGP alone and inside SMALBE.
  static constexpr const char* kPreconditioningInFace = "Preconditioning in face";

  // Set-up (tfeti_FetiSolverSetup.cpp; the memory checks, checkFactorMemory, nodesHold,
  // checkPreconditionerMemory, explicitDoesNotFit and what it counts:
  // tfeti_FetiSolverMemoryChecks.cpp).
  void buildSubdomains(const std::vector<std::vector<double>>& coords);
  // Between the subdomains' construction and their factorization: the factors' bytes against
  // the nodes' memory (factorMemory_); throws std::invalid_argument (naming the parameters to
  // change) on every rank where some node falls short. Collective.
  void checkFactorMemory();
  // Collective: each rank's need against its node's memory (nodeMemory; held: what of it stays
  // allocated, for the report); nothing known (known = false, fits) where some rank's local
  // solver cannot tell its bytes.
  NodeMemory nodesHold(double need, bool cannotTell, double held = 0.0) const;
  NodeMemory factorMemory_;
  // Before the preconditioner's set-up: its blocks and interior factors against the nodes' memory
  // (preconditionerMemory_). rebuild: the subdomains whose preconditioner is set up again, with
  // their interface dofs; releaseStiffness: K freed after each. Throws std::invalid_argument on
  // every rank where some node falls short. Collective.
  void checkPreconditionerMemory(const std::vector<std::vector<int>>& dofs,
                                 const std::vector<char>& rebuild, PreconditionerType type,
                                 bool releaseStiffness);
  NodeMemory preconditionerMemory_;
  void refactorizeSubdomains();  // data_'s new K and f into the existing subdomains
  std::vector<std::vector<double>> kernelCoords_;  // the positions of the subdomains' kernels
  // Per local subdomain: K (re)factorized since the last buildConstraints, whose preconditioner
  // must then be set up again.
  std::vector<char> stiffnessChanged_;
  void countFactorizations();  // collective: stiffnessChanged_ into timings_
  // Collective: the local solvers' symbolic analyses since the last count into timings_.
  void countAnalyses();
  LocalAnalysisCounts analysesCounted_ = localAnalysisCounts();
  // updateStiffness's steps: whether the subdomains refactorize in place (collective), and its
  // arguments checked before anything changes (collective, throws naming the subdomain).
  bool sameKernelPositions(const std::vector<std::vector<double>>& coords) const;
  void checkStiffnessUpdate(const std::vector<CsrMatrix>& K,
                            const std::vector<std::vector<double>>& coords,
                            const std::vector<std::vector<double>>& loads, bool inPlace) const;
  // An empty K given to updateStiffness: keep the subdomain's.
  static bool keepsStiffness(const CsrMatrix& K) {
    return K.rows == 0 && K.cols == 0 && K.rowPtr.empty();
  }
  // subdomainsKept: the subdomains (and their kernels) are those of the last call, so rows whose
  // entries did not change keep the tearing and the coarse space (updateTearingValues).
  void buildConstraints(const std::vector<InequalityRow>& inequalities, bool subdomainsKept);
  // buildConstraints' preconditioner step: the subdomains whose K or interface dofs changed set
  // theirs up again (checkPreconditionerMemory first); releaseStiffness: K freed after each.
  void setupPreconditioners(PreconditionerType type, bool releaseStiffness);
  // buildConstraints' first step: true where the tearing was kept (its values updated).
  bool keepOrBuildTearing(const std::vector<InequalityRow>& inequalities, bool subdomainsKept);
  void requireNoRowOnEliminatedDofs() const;
  void buildDualRhs();
  // releaseStiffness: the explicit operator frees every subdomain's K once its F_s is assembled
  // (the Schur assembly needs K; "Keep subdomain matrices" = false).
  void buildDualOperator(bool releaseStiffness = false);
  // Before the explicit F_s are assembled, where any rank assembles some (the blocks not taken
  // over from previous as they are, ExplicitDualOperator::plannedBlocks; a rank that takes all
  // its blocks over takes part with no need): whether the new ones fit, with the Schur
  // assembly's largest transient (explicitAssemblyNeed) and less the K freed
  // meanwhile. Where they do not, auto falls back to implicit (true: go on implicit) and
  // explicit is an error naming the parameter. Collective.
  bool explicitDoesNotFit(DenseStorage storage, const ExplicitDualOperator* previous,
                          bool releaseStiffness);
  // This rank's bytes for that: its new F_s and what their solves leave with the local solvers
  // (LocalSolver::solveKeeps: Tacho's workspace), the largest transient (from the Schur
  // complement: the counts of the analysis with the dual rows' dofs last, made for each set of
  // dofs or kept from an earlier one of the pattern; by solves, a bound; on a device, all the
  // blocks full once as they go up), less the K freed.
  double explicitAssemblyNeed(DenseStorage storage, bool releaseStiffness,
                              const std::vector<ExplicitDualOperator::PlannedBlock>& plan);
  // What assembling local block i as planned takes beyond its values, at its peak
  // (explicitSchurTransient from the subdomain's inverse-block prediction, or
  // explicitSolvesTransient).
  double explicitBlockTransient(std::size_t i, const ExplicitDualOperator::PlannedBlock& p);
  // Sets dualChoice_ from "Dual operator" and, for auto, the tearing and the factors. Collective.
  void chooseDualOperator();
  // The dual solve: PCPG (tfeti_FetiSolverSolve.cpp), the QP of the inequality rows
  // (tfeti_FetiSolverQp.cpp).
  DualResult solvePcpg();
  DualResult solveQp(const std::string& method);
  struct DualQp;  // the QP in mu = lambda - lambda~ and its operators
  Teuchos::RCP<Vector> dualQpLinearTerm() const;
  void setDualQpBounds(BoundConstrainedQp<Scalar, MultiVector, Operator>& qp) const;
  bool warmStartAgreed() const;  // collective: every rank can start from the last solve
  // After update()/updateStiffness() built new rows: the warm start's vectors moved onto them
  // (tfeti_RowCarryOver.hpp), each row continuing its previous row by key.
  // radiiBefore: discRadii() of the rows before.
  void carryWarmStartOver(const RowIdentities& before,
                          const Teuchos::RCP<const Vector>& radiiBefore);
  // Friction's bounds: the radius g of each disc (3D) at both its components and the bound g of
  // each friction box (frictionBox: 2D, or a direction held on both sides in 3D); -1 on every
  // other row.
  Teuchos::RCP<Vector> discRadii() const;
  Teuchos::RCP<Vector> initialIncrement(bool warm, bool penalty) const;
  // The warm start before its projection onto ker G (previous lambda - lambda~).
  Teuchos::RCP<Vector> warmIncrement() const;
  double projectedNormEstimate(const Operator& PFP, const MultiVector& b, bool smalbe, bool warm);
  void setQpOperators(DualQp& dual) const;
  Belos::ReturnType solveSmalbe(DualQp& dual, QpCounters& counters);
  Teuchos::RCP<Vector> smalbeInitialMultiplier(bool warm, const Operator& Q) const;
  // discs (may be null): the dual's disc vector, whose components get no level.
  Teuchos::RCP<Vector> contactGapLevels(const MultiVector* discs = nullptr) const;
  Belos::ReturnType solvePenalty(DualQp& dual, QpCounters& counters);
  // mu <- P mu (Penalty/Equality projection), the rows holding taken before it.
  void projectPenaltySolution(DualQp& dual, QpCounters& counters);
  void completeQpResult(Belos::ReturnType ret, DualResult& result) const;
  // The primal solution (tfeti_PrimalRecovery.cpp). Both return "" or, where the rows holding
  // with equality leave a rigid motion free, why (u then takes the fit on all rows).
  std::string recoverPrimal();
  bool nothingActs() const;  // collective: no load, no multiplier, no prescribed value
  std::string addKernelComponent(MultiVector& u) const;
  void markRowsHoldingWithEquality(const Vector& lambda, Vector& mask) const;
  // The rows holding with equality as the primal fit takes them: holdingRows_, else from lambda_.
  void rowsHoldingWithEquality(Vector& mask) const;
  void keepSubdomainSolutions(const MultiVector& u);
  // Results (tfeti_FetiSolverResults.cpp).
  // source: lambda_ if null.
  std::vector<double> multipliersOfRows(GO first, GO count, const Vector* source = nullptr) const;
  Teuchos::RCP<Vector> d_, lambda0_, lambda_;
  // The penalty's rows holding with equality before its equality projection (null: from lambda_).
  Teuchos::RCP<Vector> holdingRows_;
  // Warm start (update()): the last solve's multipliers, SMALBE's equality multiplier and the
  // estimate of ||P F P||.
  Teuchos::RCP<const Vector> previousLambda_, previousEqualityMultiplier_;
  Teuchos::RCP<const Vector> previousDiscRadii_;  // the discs previousLambda_ was solved in
  // The penalty's Q mu as MPRGP left it (before the equality projection; null after SMALBE or
  // PCPG), and the last one kept for the warm start: its minimizer is P mu + Q mu, not P mu.
  Teuchos::RCP<Vector> penaltyOffset_;
  Teuchos::RCP<const Vector> previousPenaltyOffset_;
  Teuchos::RCP<Vector> equalityMultiplier_;
  double normEstimate_ = 0.0, previousNorm_ = 0.0;
  Teuchos::RCP<Vector> normVector_;  // the last power iterate ("Warm power iterations")
  Teuchos::RCP<MultiVector> f_, u_vec_;
  std::vector<std::vector<double>> u_;
  FetiTimings timings_;
  MemoryLog memory_;
  // The device work of the explicit operators replaced so far (explicitDeviceWork adds the
  // current one's).
  ExplicitDualOperator::DeviceWork deviceWorkDone_;
  ExplicitAssembly explicitAssemblyDone_;  // this rank's, of the explicit operators replaced
  DualOperatorChoice dualChoice_;
  Teuchos::RCP<std::ostream> out_;
  double toleranceFactor_ = 1.0;
  bool loadStepStart_ = false;
  std::vector<std::vector<double>> incrementOrigin_;
  void shiftOwnRowsByOrigin();  // c -= B u on the solver's own rows (setIncrementOrigin)
};

// A tangential friction row's box [-g, g] (both bounds finite and opposite), not a disc.
bool frictionBox(const InequalityRow& r);

Formulation parseFormulation(const std::string& name);
PreconditionerType parsePreconditioner(const std::string& name);

}  // namespace tfeti
