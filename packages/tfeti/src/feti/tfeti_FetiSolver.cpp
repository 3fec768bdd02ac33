#include "tfeti_FetiSolver.hpp"

#include "tfeti_SolverConventions.hpp"
#include "tfeti_TpetraInterface.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <chrono>
#include <exception>
#include <iostream>
#include <limits>

#include "tfeti_Gather.hpp"
#include "tfeti_InputChecks.hpp"
#include "tfeti_MprgpSolMgr_decl.hpp"
#include "tfeti_ProjectedOperators.hpp"
#include "tfeti_SmalbeSolMgr_decl.hpp"
#include "tfeti_StrictParameters.hpp"

namespace tfeti {

namespace {
// Wall time of a phase, measured between barriers so that it is the slowest rank's time, and,
// with a log, the memory after it.
class PhaseTimer {
 public:
  PhaseTimer(const Comm& comm, double& into, MemoryLog* log = nullptr, const char* phase = "")
      : comm_(comm), into_(into), log_(log), phase_(phase) {
    comm_.barrier();
    start_ = std::chrono::steady_clock::now();
  }
  ~PhaseTimer() {
    comm_.barrier();
    into_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    // Unwinding (an error thrown on every rank): no report of a phase that did not finish.
    if (log_ && std::uncaught_exceptions() == 0) log_->record(comm_, phase_);
  }

 private:
  const Comm& comm_;
  double& into_;
  MemoryLog* log_;
  const char* phase_;
  std::chrono::steady_clock::time_point start_;
};

const char* const kPreconditioningInFace = "Preconditioning in face";

Teuchos::RCP<Teuchos::StringToIntegralParameterEntryValidator<int>> choice(
    const std::vector<std::string>& names) {
  return Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
      Teuchos::Array<std::string>(names.begin(), names.end()), names.front()));
}
}  // namespace

Formulation parseFormulation(const std::string& name) {
  return name == "FETI" ? Formulation::FETI : Formulation::TFETI;
}

PreconditionerType parsePreconditioner(const std::string& name) {
  if (name == "lumped") return PreconditionerType::Lumped;
  if (name == "dirichlet") return PreconditionerType::Dirichlet;
  return PreconditionerType::None;
}

void FetiSolver::rejectMisplacedParameters(const Teuchos::ParameterList& feti) {
  const auto misplaced = [&](const Teuchos::ParameterList& list, const std::string& path) {
    if (list.isParameter(kPreconditioningInFace))
      throw std::invalid_argument(
          "FETI: \"" + std::string(kPreconditioningInFace) + "\" is set in the " + path +
          " sublist; it belongs to the FETI list itself (one switch for MPRGP alone and inside "
          "SMALBE): move it there");
  };
  if (feti.isSublist("MPRGP")) misplaced(feti.sublist("MPRGP"), "\"MPRGP\"");
  if (feti.isSublist("SMALBE") && feti.sublist("SMALBE").isSublist("MPRGP"))
    misplaced(feti.sublist("SMALBE").sublist("MPRGP"), "\"SMALBE\" / \"MPRGP\"");
}

void FetiSolver::applySolverAliases(Teuchos::ParameterList& feti) {
  const auto apply = [&](const std::vector<std::string>& path, const std::string& maxIterations) {
    Teuchos::ParameterList* list = &feti;
    std::string name;
    for (const std::string& p : path) {
      if (!list->isSublist(p)) return;
      list = &list->sublist(p);
      name += (name.empty() ? "" : "/") + p;
    }
    applyParameterAliases(*list, "FETI/" + name, belosAliases(maxIterations));
  };
  apply({"PCPG"}, "Maximum iterations");
  apply({"MPRGP"}, "Maximum iterations");
  apply({"SMALBE"}, "Maximum outer iterations");
  apply({"SMALBE", "MPRGP"}, "Maximum iterations");
}

Teuchos::RCP<const Teuchos::ParameterList> FetiSolver::validParameters() {
  static Teuchos::RCP<Teuchos::ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::rcp(new Teuchos::ParameterList("FETI"));
    pl->set("Formulation", "TFETI",
            "TFETI: Dirichlet conditions as multipliers, every subdomain floats; FETI: Dirichlet "
            "dofs eliminated in K",
            choice({"TFETI", "FETI"}));
    pl->set("Kernel tolerance", 1e-8,
            "largest ||K R|| / ||K|| accepted for the kernel R of a subdomain matrix K (rigid "
            "modes of its pieces, or the kernel supplied); above it the subdomain is an error");
    pl->set("Gluing", "nonredundant",
            "nonredundant: m-1 rows at a node shared by m subdomains; redundant: m(m-1)/2; "
            "none: no gluing rows (the caller's equality rows join the subdomains)",
            choice({"nonredundant", "redundant", "none"}));
    pl->set("Gluing at Dirichlet nodes", true,
            "keep gluing rows at interface nodes on the Dirichlet boundary (the paper's count; "
            "in TFETI they duplicate the Dirichlet rows)");
    pl->set("Inequality row scaling", "joined",
            "the preconditioner's scaling (B B^T)^+ of the inequality rows: joined: each joins "
            "the scaling group of the rows it shares dofs with (a tied or contact row on a node "
            "a cut shares joins the node's gluing rows); separate: each row its own group",
            choice({"joined", "separate"}));
    pl->set("Preconditioner", "dirichlet", "dual preconditioner",
            choice({"dirichlet", "lumped", "none"}));
    std::vector<std::string> solvers = localSolverTypes();
    // "cholmod-simplicial" took 23-28 % less CPU time than "cholmod" (CHOLMOD's own choice,
    // supernodal) on the 3D subdomain matrices with this machine's reference BLAS; with OpenBLAS
    // the supernodal choice was faster still (docs/benchmarks.md, "3D setup profile"), so the
    // better default depends on the BLAS installed and stays until measured on every case. G G^T is
    // one larger matrix with large dense fronts: its own parameter, so that forcing the subdomains'
    // kind does not force the coarse one.
    pl->set("Local solver", "cholmod", "sparse direct solver of the subdomain problems",
            choice(solvers));
    pl->set("Coarse solver", "cholmod",
            "sparse direct solver of the coarse problem G G^T (replicated on every rank)",
            choice(solvers));
    pl->set("Dual solver", "auto",
            "auto: PCPG without inequality rows, SMALBE with them; PCPG: projected CG "
            "(equality constraints only); SMALBE: augmented Lagrangian with MPRGP inner solves; "
            "penalty: MPRGP on P F P + rho Q (the reference paper's choice)",
            choice({"auto", "PCPG", "SMALBE", "penalty"}));
    pl->set("Inequality rows", "inequalities",
            "inequalities: B_I u <= c_I with lambda_I >= 0 (frictionless contact); equalities: "
            "B_I u = c_I with lambda_I free (the pair tied: bonded bodies, the gap closed), a "
            "linear problem that \"Dual solver\" = auto solves by PCPG",
            choice({"inequalities", "equalities"}));
    pl->sublist("PCPG").setParameters(*Pcpg::validParameters());
    pl->sublist("MPRGP").setParameters(
        *MprgpSolMgr<Scalar, MultiVector, Operator>::getValidParameters());
    // MPRGP's fixed expansion step 1.9 / ||P F P + rho Q|| = 1.9 / rho hardly moves the iterate
    // when rho >> ||P F P||; the projected CG step is set by the curvature along the
    // (preconditioned) direction instead (docs/qp_solvers.md: penalty method, 8192 subdomains,
    // 1066 -> 281 multiplications).
    auto projectedCg = [](Teuchos::ParameterList& mprgp, const char* doc) {
      auto& entry = mprgp.getEntry("Expansion step");
      entry.setValue<std::string>("projected CG", false, doc, entry.validator());
    };
    projectedCg(pl->sublist("MPRGP"), "FETI default: projected CG (the component's: fixed)");
    auto& smalbe = pl->sublist("SMALBE");
    smalbe.setParameters(*SmalbeSolMgr<Scalar, MultiVector, Operator>::getValidParameters());
    // Measured (docs/qp_solvers.md): rho = ||P F P|| needs up to 100 outer iterations on the
    // two-membrane problem; with the projected CG expansion rho = 10 ||P F P|| gives the fewest
    // multiplications (8192 subdomains: 117 against 157 at 100 ||P F P||; 101k-unknown
    // two-cylinder case: 306 against 587), at the price of more, cheap, outer iterations.
    smalbe.set("Penalty", 10.0,
               "rho = value * ||P F P|| (FETI default 10; the component's default is 1)",
               strict::positive());
    projectedCg(smalbe.sublist("MPRGP"), "FETI default: projected CG (the component's: fixed)");
    // The contact rows' gaps order the face of smooth convex bodies: the level search finds it in
    // about log2(rows) loose face solves where MPRGP's expansion steps open a row or two each
    // (docs/qp_solvers.md: two cylinders at 1M unknowns, 765 -> 143 multiplications). Used only
    // with "Face solve" = pcpg, and only for frictionless contact without a warm start.
    // Once the active set settles, the face PCPG replaces the tail of SMALBE's outer iterations
    // (docs/qp_solvers.md: two cylinders 101k-4M unknowns, 112-232 multiplications with the
    // level search against 223-1421 for SMALBE alone); the result is accepted only by SMALBE's
    // final test, so SMALBE alone remains the fallback.
    {
      auto& entry = smalbe.getEntry("Face solve");
      entry.setValue<std::string>("pcpg", false, "FETI default: pcpg (the component's: none)",
                                  entry.validator());
    }
    // With the loose verdicts a face tried after every outer iteration is cheap, and its
    // active-set steps settle the face faster than the outer iterations do (two membranes,
    // 8192 subdomains, H/h = 32: 11 -> 1 outer iteration, 111 -> 67 multiplications).
    smalbe.set("Face settle iterations", 0,
               "FETI default 0: a face solve after every outer iteration (the component's: 1)",
               strict::count(0));
    {
      auto& entry = smalbe.getEntry("Initial face");
      entry.setValue<std::string>("levels", false,
                                  "FETI default: levels, the contact rows' gaps (the component's: "
                                  "none)",
                                  entry.validator());
    }
    // One switch for MPRGP's preconditioner, alone or inside SMALBE: the FETI list's own
    // "Preconditioning in face" below (the sublists would only contradict it).
    pl->sublist("MPRGP").remove(kPreconditioningInFace);
    smalbe.sublist("MPRGP").remove(kPreconditioningInFace);
    // At rho = 10 ||P F P|| the outer iterations grow with the subdomains per side (25 at 64 x 64
    // per membrane, 35 at 88 x 88; 3-6 multiplications each): the component's limit of 100
    // would be reached near 250 x 250.
    smalbe.set("Maximum outer iterations", 1000,
               "limit on multiplier updates (FETI default 1000; the component's default is 100)",
               strict::count());
    auto& pen = pl->sublist("Penalty", false, "Dual solver = penalty");
    pen.set("Penalty", 1e4,
            "rho relative to the estimate of ||P F P||; the constraint error G lambda falls like "
            "1/rho (about 1e-5 relative at the default)",
            strict::positive());
    pen.set("Power iterations", 20, "power iterations for the estimate of ||P F P||",
            strict::count());
    pl->set(
        kPreconditioningInFace, true,
        "SMALBE / penalty: precondition MPRGP's conjugate gradient steps by P M P + Q / rho (M the "
        "chosen dual preconditioner) restricted to the free set");
    pl->set("Initial equality multiplier", "gap",
            "SMALBE's first multiplier of G lambda = e (unless warm-started): zero, or gap: Q c_I, "
            "the multiplier at which lambda = 0 is the solution when no load acts (c_I the gaps "
            "of the inequality rows; at the solution it is Q (c - B u), the gaps left open)",
            choice({"gap", "zero"}));
    pl->set("Keep subdomain matrices", true,
            "false: free each subdomain matrix K once its preconditioner is set up (a linear "
            "solve needs it no more; about 200 bytes per unknown in 2D); update() then cannot "
            "rebuild a preconditioner whose interface dofs changed");
    pl->set("Warm start", true,
            "SMALBE / penalty after update(): start from the multipliers of the previous solve "
            "(projected onto G lambda = e and the bounds) when the dual dimension is unchanged");
  }
  return pl;
}

FetiSolver::FetiSolver(const Teuchos::RCP<const Comm>& comm, int numSubdomains,
                       std::vector<SubdomainData> local, const Teuchos::ParameterList& params,
                       const std::vector<InequalityRow>& inequalities,
                       const std::vector<EqualityRow>& equalities)
    : comm_(comm),
      params_(params),
      numSubdomains_(numSubdomains),
      data_(std::move(local)),
      equalities_(equalities) {
  rejectMisplacedParameters(params_);
  applySolverAliases(params_);
  params_.validateParametersAndSetDefaults(*validParameters());
  // Subdomain matrices given as Tpetra::CrsMatrix become CSR arrays (checked with the rest).
  collectively(*comm_, [&] {
    for (auto& sd : data_) {
      if (sd.tpetraK.is_null()) continue;
      const std::string what = "subdomain " + std::to_string(sd.mesh.id) + ": tpetraK";
      if (sd.K.rows != 0 || !sd.K.rowPtr.empty())
        throw std::invalid_argument(what + " and K are both given; give one");
      sd.K = csrFromTpetra(*sd.tpetraK, what);
      sd.tpetraK = Teuchos::null;
    }
  });
  // Every size the solver indexes by, on every rank, before anything is built from it.
  checkSubdomainInput(*comm_, numSubdomains_, data_);
  // A rank may hold no subdomain; every rank must still agree on the dofs per node.
  int localDpn = data_.empty() ? 0 : data_.front().dofsPerNode;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 1, &localDpn, &dofsPerNode_);
  std::vector<std::vector<double>> coords;
  for (const auto& sd : data_) coords.push_back(sd.mesh.coords);
  buildSubdomains(coords);
  buildConstraints(inequalities, true);
  buildDualRhs();
}

void FetiSolver::buildSubdomains(const std::vector<std::vector<double>>& coords) {
  const Formulation formulation = parseFormulation(params_.get<std::string>("Formulation"));
  const std::string solver = params_.get<std::string>("Local solver");
  PhaseTimer t(*comm_, timings_.factorization, &memory_, "factorization");
  subdomains_.clear();
  // An error in one subdomain is reported on every rank (no rank left waiting in a collective).
  collectively(*comm_, [&] {
    for (std::size_t i = 0; i < data_.size(); ++i) {
      auto& sd = data_[i];
      KernelOptions kernel;
      kernel.dim = sd.mesh.dim;
      kernel.elements = sd.mesh.connectivity();
      kernel.kernel = sd.kernel;
      kernel.residualTolerance = params_.get<double>("Kernel tolerance");
      const std::vector<int> dirichletDofs = sd.mesh.dirichletDofs(sd.dofsPerNode);
      // K and f move into the subdomain (data_ keeps the mesh, the kernel and the sizes).
      subdomains_.push_back(std::make_shared<Subdomain>(sd.mesh.id, sd.dofsPerNode, coords[i],
                                                        kernel, std::move(sd.K), std::move(sd.f),
                                                        dirichletDofs, formulation, solver));
    }
  });
}

void FetiSolver::buildConstraints(const std::vector<InequalityRow>& inequalities,
                                  bool newSubdomains) {
  const Formulation formulation = parseFormulation(params_.get<std::string>("Formulation"));
  const PreconditionerType precType =
      parsePreconditioner(params_.get<std::string>("Preconditioner"));
  const std::string solver = params_.get<std::string>("Local solver");
  {
    PhaseTimer t(*comm_, timings_.tearing, &memory_, "tearing");
    TearingOptions opts;
    opts.formulation = formulation;
    const std::string gluing = params_.get<std::string>("Gluing");
    opts.gluing = gluing == "redundant" ? Gluing::Redundant
                  : gluing == "none"    ? Gluing::None
                                        : Gluing::NonRedundant;
    opts.gluingAtDirichletNodes = params_.get<bool>("Gluing at Dirichlet nodes");
    opts.inequalityScaling = params_.get<std::string>("Inequality row scaling") == "separate"
                                 ? TearingOptions::InequalityScaling::Separate
                                 : TearingOptions::InequalityScaling::Joined;
    std::vector<TearingInput> input;
    for (const auto& sd : data_) {
      TearingInput in;
      in.id = sd.mesh.id;
      in.numDofs = sd.mesh.numNodes() * sd.dofsPerNode;
      in.boundaryNodes = sd.mesh.boundaryNodes();
      const std::vector<int> dir = sd.mesh.dirichletMasks(sd.dofsPerNode);
      for (int n : in.boundaryNodes) {
        in.boundaryGlobal.push_back(sd.mesh.globalNode[n]);
        in.boundaryDirichlet.push_back(dir[n]);
      }
      input.push_back(std::move(in));
    }
    tearing_ =
        buildTearing(comm_, numSubdomains_, input, dofsPerNode_, opts, inequalities, equalities_);
    if (formulation == Formulation::FETI) requireNoRowOnEliminatedDofs();
  }
  {
    PhaseTimer t(*comm_, timings_.coarse, &memory_, "coarse");
    coarse_ = std::make_unique<CoarseSpace>(tearing_, subdomains_,
                                            params_.get<std::string>("Coarse solver"));
  }
  {
    PhaseTimer t(*comm_, timings_.preconditioner, &memory_, "preconditioner");
    collectively(*comm_, [&] {
      for (std::size_t i = 0; i < subdomains_.size(); ++i) {
        std::vector<int> dofs;
        for (const auto& e : tearing_.subdomainRows[i]) dofs.push_back(e.dof);
        std::sort(dofs.begin(), dofs.end());
        dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
        // Contact rows that move between iterations of a nonlinear solve mostly keep the same
        // dofs: the interior factorization is redone only when they change.
        if (newSubdomains || dofs != subdomains_[i]->interfaceDofs())
          subdomains_[i]->setupPreconditioner(dofs, precType, solver);
        // Freed one by one, so that K and the preconditioner's factors never coexist in full.
        if (!params_.get<bool>("Keep subdomain matrices")) subdomains_[i]->releaseStiffness();
      }
    });
    if (precType != PreconditionerType::None)
      M_ = Teuchos::rcp(new DualPreconditioner(tearing_, subdomains_));
  }
  Kplus_ = Teuchos::rcp(new PseudoInverseOperator(tearing_.primalMap, subdomains_));
  F_ = Teuchos::rcp(new DualOperator(tearing_.B, Kplus_));
}

void FetiSolver::buildDualRhs() {
  PhaseTimer t(*comm_, timings_.dualRhs, &memory_, "dual_rhs");
  f_ = Teuchos::rcp(new MultiVector(tearing_.primalMap, 1));
  {
    auto f = f_->getDataNonConst(0);
    std::size_t offset = 0;
    for (const auto& s : subdomains_) {
      for (int i = 0; i < s->numDofs(); ++i) f[offset + i] = s->load()[i];
      offset += s->numDofs();
    }
  }
  MultiVector Kf(tearing_.primalMap, 1);
  Kplus_->apply(*f_, Kf);
  d_ = Teuchos::rcp(new Vector(tearing_.multiplierMap));
  tearing_.B->apply(Kf, *d_);
  d_->update(-1.0, *tearing_.rhs, 1.0);  // d = B K+ f - c
  lambda0_ = Teuchos::rcp(new Vector(tearing_.multiplierMap));
  if (coarse_->dimension() > 0) {
    Vector e(coarse_->coarseMap());
    coarse_->applyKernelTranspose(*f_, e);
    coarse_->particularSolution(e, *lambda0_);
  }
}

void FetiSolver::update(const std::vector<std::vector<double>>& loads,
                        const std::vector<InequalityRow>& inequalities,
                        const std::vector<EqualityRow>& equalities) {
  equalities_ = equalities;
  update(loads, inequalities);
}

void FetiSolver::updateStiffness(std::vector<CsrMatrix> K,
                                 const std::vector<std::vector<double>>& coords,
                                 const std::vector<std::vector<double>>& loads,
                                 const std::vector<InequalityRow>& inequalities,
                                 const std::vector<EqualityRow>& equalities) {
  equalities_ = equalities;
  updateStiffness(std::move(K), coords, loads, inequalities);
}

void FetiSolver::update(const std::vector<std::vector<double>>& loads,
                        const std::vector<InequalityRow>& inequalities) {
  collectively(*comm_, [&] {
    if (loads.size() != subdomains_.size())
      throw std::invalid_argument("FetiSolver::update: " + std::to_string(loads.size()) +
                                  " load vectors for " + std::to_string(subdomains_.size()) +
                                  " local subdomains");
    for (std::size_t i = 0; i < subdomains_.size(); ++i) subdomains_[i]->setLoad(loads[i]);
  });
  previousLambda_ = lambda_;
  previousEqualityMultiplier_ = equalityMultiplier_;
  previousNorm_ = normEstimate_;
  buildConstraints(inequalities, false);
  buildDualRhs();
  u_vec_ = Teuchos::null;
  lambda_ = Teuchos::null;
  u_.clear();
}

void FetiSolver::updateStiffness(std::vector<CsrMatrix> K,
                                 const std::vector<std::vector<double>>& coords,
                                 const std::vector<std::vector<double>>& loads,
                                 const std::vector<InequalityRow>& inequalities) {
  collectively(*comm_, [&] {
    if (K.size() != data_.size() || coords.size() != data_.size() || loads.size() != data_.size())
      throw std::invalid_argument("FetiSolver::updateStiffness: expected " +
                                  std::to_string(data_.size()) +
                                  " matrices, coordinate sets and loads");
    for (std::size_t i = 0; i < data_.size(); ++i) {
      const std::string error = subdomainDataError(data_[i].mesh, coords[i], data_[i].dofsPerNode,
                                                   K[i], loads[i], {}, numSubdomains_);
      if (!error.empty()) throw std::invalid_argument("FetiSolver::updateStiffness: " + error);
    }
  });
  for (std::size_t i = 0; i < data_.size(); ++i) {
    data_[i].K = std::move(K[i]);
    data_[i].f = loads[i];
  }
  previousLambda_ = lambda_;
  previousEqualityMultiplier_ = equalityMultiplier_;
  previousNorm_ = 0.0;  // a new K: estimate ||P F P|| again
  buildSubdomains(coords);
  buildConstraints(inequalities, true);
  buildDualRhs();
  u_vec_ = Teuchos::null;
  lambda_ = Teuchos::null;
  u_.clear();
}

bool FetiSolver::inequalitiesTied(const Teuchos::ParameterList& feti) {
  return feti.isParameter("Inequality rows") &&
         feti.get<std::string>("Inequality rows") == "equalities";
}

std::string FetiSolver::dualSolverFor(const Teuchos::ParameterList& feti, GO inequalityRows) {
  // Tied inequality rows are equality rows: no bound constrains their multipliers.
  if (inequalitiesTied(feti)) inequalityRows = 0;
  std::string method = feti.get<std::string>("Dual solver");
  if (method == "auto") method = inequalityRows > 0 ? "SMALBE" : "PCPG";
  if (method == "PCPG" && inequalityRows > 0)
    throw std::invalid_argument(
        "FETI: \"Dual solver\" = PCPG handles equality constraints only, but the problem has " +
        std::to_string(inequalityRows) + " inequality (contact) rows: choose SMALBE or penalty");
  return method;
}

DualResult FetiSolver::solve() {
  const std::string method = dualSolverFor(params_, tearing_.numInequalityRows);
  const bool tied = inequalitiesTied(params_);
  lambda_ = Teuchos::rcp(new Vector(tearing_.multiplierMap));
  Vector g(tearing_.multiplierMap);
  DualResult result;
  if (method == "PCPG") {
    PhaseTimer t(*comm_, timings_.solve, &memory_, "solve");
    Tpetra::deep_copy(*lambda_, *lambda0_);
    Pcpg pcpg(F_, *coarse_, M_, params_.sublist("PCPG"));
    const long long before = F_->numApplies();
    pcpg.setOutputStream(out_);
    static_cast<PcpgResult&>(result) = pcpg.solve(*d_, *lambda_, g);
    result.method = "PCPG";
    // The same counters as the QP solvers, so that a tied and a contact solve compare directly.
    result.qp.hessianMultiplications = F_->numApplies() - before;
    result.qp.cgSteps = result.iterations;
    result.qp.converged = result.converged;
    result.qp.projectedGradientNorm = result.projectedGradientNorm;
  } else {
    result = solveQp(method);
  }
  {
    PhaseTimer t(*comm_, timings_.recovery, &memory_, "recovery");
    // u = K+ (f - B^T lambda) + R alpha, alpha fitted on the rows that hold with equality.
    MultiVector rhs(tearing_.primalMap, 1);
    u_vec_ = Teuchos::rcp(new MultiVector(tearing_.primalMap, 1));
    MultiVector& u = *u_vec_;
    Tpetra::deep_copy(rhs, *f_);
    tearing_.B->apply(*lambda_, rhs, Teuchos::TRANS, -1.0, 1.0);
    Kplus_->apply(rhs, u);
    // Nothing acts (no load, no multiplier, no prescribed value): u = 0 exactly. The fit below
    // would be singular when a body is held by contact alone and, unloaded, touches nothing;
    // of the rigid motions it leaves free, zero is the smallest.
    Teuchos::Array<double> fNorm(1);
    f_->normInf(fNorm());
    double acting[3] = {fNorm[0], lambda_->normInf(), 0.0}, anyActing[3];
    {
      auto c = tearing_.rhs->getData();
      const auto& map = *tearing_.multiplierMap;
      for (std::size_t i = 0; i < map.getNodeNumElements(); ++i)
        if (!tearing_.isInequality(map.getGlobalElement(static_cast<LO>(i))))
          acting[2] = std::max(acting[2], std::abs(c[i]));
    }
    Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 3, acting, anyActing);
    const bool unloaded = anyActing[0] == 0.0 && anyActing[1] == 0.0 && anyActing[2] == 0.0;
    if (coarse_->dimension() > 0 && !unloaded) {
      F_->apply(*lambda_, g);
      g.update(-1.0, *d_, 1.0);
      Vector alpha(coarse_->coarseMap());
      if (tearing_.numInequalityRows == 0 || tied) {
        coarse_->leastSquaresCoefficients(g, alpha);
      } else {
        // Inactive inequality rows (lambda_i = 0) have a gap: they must not enter the fit.
        Vector mask(tearing_.multiplierMap);
        auto m = mask.getDataNonConst();
        auto l = lambda_->getData();
        const auto& map = *tearing_.multiplierMap;
        // Likewise a friction row whose multiplier is at a bound (slip): only the rows with
        // the multiplier strictly inside its bounds hold with equality.
        for (std::size_t i = 0; i < map.getNodeNumElements(); ++i) {
          const GO row = map.getGlobalElement(static_cast<LO>(i));
          bool holds = true;
          if (tearing_.isInequality(row)) {
            const InequalityRow& r = tearing_.inequalityRows[row - tearing_.firstInequalityRow];
            holds = r.boundActive(l[i]) == 0;
          }
          m[i] = holds ? 1.0 : 0.0;
        }
        coarse_->leastSquaresOnRows(g, mask, alpha, params_.get<std::string>("Coarse solver"));
      }
      coarse_->addKernelCombination(alpha, u);
    }
    auto uv = u.getData(0);
    u_.assign(subdomains_.size(), {});
    std::size_t offset = 0;
    for (std::size_t i = 0; i < subdomains_.size(); ++i) {
      const int n = subdomains_[i]->numDofs();
      u_[i].assign(uv.getRawPtr() + offset, uv.getRawPtr() + offset + n);
      offset += n;
    }
  }
  return result;
}

DualResult FetiSolver::solveQp(const std::string& method) {
  using MV = MultiVector;
  using Qp = BoundConstrainedQp<Scalar, MV, Operator>;
  DualResult result;
  result.method = method;
  PhaseTimer t(*comm_, timings_.solve, &memory_, "solve");
  const auto map = tearing_.multiplierMap;
  // lambda = lambda~ + mu: b = P (d - F lambda~), bounds l_I - lambda~_I <= mu_I <= u_I -
  // lambda~_I (l = 0, u = +inf for the non-penetration rows; a box for friction rows).
  auto b = Teuchos::rcp(new Vector(map));
  F_->apply(*lambda0_, *b);
  b->update(1.0, *d_, -1.0);
  coarse_->project(*b, *b);
  auto lower = Teuchos::rcp(new Vector(map));
  auto upper = Teuchos::rcp(new Vector(map));
  int anyUpperLocal = 0, anyUpper = 0;
  {
    const double inf = std::numeric_limits<double>::infinity();
    auto lo = lower->getDataNonConst();
    auto up = upper->getDataNonConst();
    auto l0 = lambda0_->getData();
    const bool tied = inequalitiesTied(params_);
    for (std::size_t i = 0; i < map->getNodeNumElements(); ++i) {
      const GO row = map->getGlobalElement(static_cast<LO>(i));
      lo[i] = -inf;
      up[i] = inf;
      if (!tied && tearing_.isInequality(row)) {
        const InequalityRow& r = tearing_.inequalityRows[row - tearing_.firstInequalityRow];
        lo[i] = r.lowerBound - l0[i];
        up[i] = r.upperBound - l0[i];
        if (r.upperBound < inf) anyUpperLocal = 1;
      }
    }
  }
  // Without friction rows the QP keeps its lower bounds only (the solvers' one-sided path).
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 1, &anyUpperLocal, &anyUpper);
  // From 0, or (warm start) from P (lambda_previous - lambda~): in the kernel of G, projected
  // onto the bounds by MPRGP. The rows of a nonlinear iteration keep their canonical order as
  // long as each slave node keeps its segment; any start is valid, a close one is cheap.
  auto mu = Teuchos::rcp(new Vector(map));
  bool warm = params_.get<bool>("Warm start") && !previousLambda_.is_null() &&
              previousLambda_->getGlobalLength() == map->getGlobalNumElements() &&
              previousLambda_->getLocalLength() == map->getNodeNumElements();
  int warmAll = 0, warmLocal = warm ? 1 : 0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MIN, 1, &warmLocal, &warmAll);
  if (warmAll == 1) {
    auto m = mu->getDataNonConst();
    auto p = previousLambda_->getData();
    auto l0 = lambda0_->getData();
    for (std::size_t i = 0; i < map->getNodeNumElements(); ++i) m[i] = p[i] - l0[i];
    coarse_->project(*mu, *mu);
  }
  auto PFP = Teuchos::rcp(new ProjectedDualOperator(F_, *coarse_));
  auto Q = Teuchos::rcp(new ComplementProjector(map, *coarse_));
  using Mgr = MprgpSolMgr<Scalar, MV, Operator>;
  const long long before = F_->numApplies();
  // ||P F P|| sets the scale of rho (both methods) and of MPRGP's step length; estimated once.
  const bool smalbe = method == "SMALBE";
  Teuchos::ParameterList sp = params_.sublist("SMALBE"), mp = params_.sublist("MPRGP");
  const Teuchos::ParameterList& pen = params_.sublist("Penalty");
  double norm = smalbe ? sp.get<double>("Norm of A") : 0.0;
  // A warm start after update() keeps K, so ||P F P|| moves only with the contact rows: the
  // previous estimate (already enlarged by 5 %) is kept instead of new power iterations.
  if (norm <= 0.0 && warmAll == 1 && previousNorm_ > 0.0) norm = previousNorm_;
  if (norm <= 0.0) {
    const int its = smalbe ? sp.get<int>("Power iterations") : pen.get<int>("Power iterations");
    norm = Mgr::estimateNorm(*PFP, *b, its);
  }
  normEstimate_ = norm;
  result.rho = (smalbe ? sp.get<double>("Penalty") : pen.get<double>("Penalty")) * norm;
  // Preconditioning in face: P M P acts on range(P), where the Hessian is P F P; on range(Q) the
  // Hessian is rho I, so the preconditioner is P M P + Q / rho (singular without the Q part).
  Teuchos::RCP<const Operator> prec;
  if (params_.get<bool>(kPreconditioningInFace) && !M_.is_null())
    prec = Teuchos::rcp(new ProjectedPlusComplement(M_, *coarse_, 1.0 / result.rho));
  // P F P + rho Q sharing P x between its two terms: two coarse projections, not three.
  const auto H = Teuchos::rcp(new ProjectedPlusComplement(F_, *coarse_, result.rho));

  Qp qp;
  qp.b = b;
  qp.lower = lower;
  qp.x = mu;
  if (anyUpper == 1) qp.upper = upper;
  Belos::ReturnType ret;
  if (smalbe) {
    qp.A = PFP;
    sp.set("Norm of A", norm);
    sp.sublist("MPRGP").set(kPreconditioningInFace, !prec.is_null());
    SmalbeSolMgr<Scalar, MV, Operator> solver(qp, Q, sp, prec);
    solver.setOutputStream(out_);
    solver.setAugmentedHessian(H);
    // SMALBE's equality multiplier of the previous solve, moved into the new range(Q).
    // Otherwise, from the geometry: with lambda = lambda~ + mu, the KKT conditions read
    // P F P mu - b + nu = c - B u (zero on the equality rows and the active inequality rows, the
    // open gap elsewhere) with nu = Q (c - B u); u = 0 gives nu_0 = Q c_I. Without a load
    // (lambda~ = 0, b = P c) mu = 0 then meets them at once, so the result is the exact zero.
    if (warmAll != 1 && tearing_.numInequalityRows > 0 && !inequalitiesTied(params_) &&
        params_.get<std::string>("Initial equality multiplier") == "gap") {
      Vector gaps(map);
      {
        auto dst = gaps.getDataNonConst();
        auto c = tearing_.rhs->getData();
        for (std::size_t i = 0; i < map->getNodeNumElements(); ++i)
          dst[i] = tearing_.isInequality(map->getGlobalElement(static_cast<LO>(i))) ? c[i] : 0.0;
      }
      auto nu0 = Teuchos::rcp(new Vector(map));
      Q->apply(gaps, *nu0);
      solver.setInitialMultiplier(nu0);
    }
    // The gaps as the levels of SMALBE's "Initial face" = levels (frictionless contact only:
    // the tangential rows' boxes have no level), not for warm starts, which have their face.
    if (warmAll != 1 && tearing_.numInequalityRows > 0 && !inequalitiesTied(params_) &&
        anyUpper != 1) {
      auto levels = Teuchos::rcp(new Vector(map));
      auto dst = levels->getDataNonConst();
      auto c = tearing_.rhs->getData();
      for (std::size_t i = 0; i < map->getNodeNumElements(); ++i)
        dst[i] = tearing_.isInequality(map->getGlobalElement(static_cast<LO>(i)))
                     ? c[i]
                     : std::numeric_limits<double>::quiet_NaN();
      solver.setFaceLevels(levels);
    }
    if (warmAll == 1 && !previousEqualityMultiplier_.is_null()) {
      Vector previous(map);
      {
        auto dst = previous.getDataNonConst();
        auto src = previousEqualityMultiplier_->getData();
        for (std::size_t i = 0; i < map->getNodeNumElements(); ++i) dst[i] = src[i];
      }
      auto nu0 = Teuchos::rcp(new Vector(map));
      Q->apply(previous, *nu0);
      solver.setInitialMultiplier(nu0);
    }
    ret = solver.solve();
    result.qp = solver.counters();
    equalityMultiplier_ = Teuchos::rcp(new Vector(map));
    Tpetra::deep_copy(*equalityMultiplier_, *solver.getMultiplier()->getVector(0));
  } else {
    qp.A = H;
    // ||P F P + rho Q|| = max(||P F P||, rho): P and Q are complementary orthogonal projectors.
    if (mp.get<double>("Norm of A") == 0.0) mp.set("Norm of A", std::max(norm, result.rho));
    mp.set(kPreconditioningInFace, !prec.is_null());
    Mgr solver(qp, mp, prec);
    solver.setOutputStream(out_);
    ret = solver.solve();
    result.qp = solver.counters();
    Vector qmu(map);
    Q->apply(*mu, qmu);
    result.qp.equalityResidualNorm = qmu.norm2();
  }
  // Every application of the Hessian is one of F (the projections are coarse solves): count
  // them all, the norm estimate's included.
  result.qp.hessianMultiplications = F_->numApplies() - before;
  result.converged = ret == Belos::Converged && result.qp.converged;
  result.iterations =
      static_cast<int>(result.qp.cgSteps + result.qp.expansionSteps + result.qp.proportioningSteps);
  result.projectedGradientNorm = result.qp.projectedGradientNorm;
  result.relativeResidual =
      result.qp.rhsNorm > 0.0 ? result.qp.projectedGradientNorm / result.qp.rhsNorm : 0.0;
  result.history = result.qp.history;
  Tpetra::deep_copy(*lambda_, *lambda0_);
  lambda_->update(1.0, *mu, 1.0);
  return result;
}

std::vector<std::vector<double>> FetiSolver::multiplierForces() const {
  if (lambda_.is_null())
    throw std::logic_error("FetiSolver::multiplierForces: no solution (call solve() first)");
  MultiVector btl(tearing_.primalMap, 1);
  tearing_.B->apply(*lambda_, btl, Teuchos::TRANS);
  auto v = btl.getData(0);
  std::vector<std::vector<double>> out;
  std::size_t offset = 0;
  for (const auto& s : subdomains_) {
    out.emplace_back(v.getRawPtr() + offset, v.getRawPtr() + offset + s->numDofs());
    offset += s->numDofs();
  }
  return out;
}

ConstraintReport FetiSolver::constraintReport() const {
  ConstraintReport r;
  r.inequalityRows = tearing_.numInequalityRows;
  if (u_vec_.is_null()) return r;
  Vector bu(tearing_.multiplierMap);
  tearing_.B->apply(*u_vec_, bu);
  bu.update(-1.0, *tearing_.rhs, 1.0);  // B u - c
  auto v = bu.getData();
  auto l = lambda_->getData();
  const auto& map = *tearing_.multiplierMap;
  double mx[4] = {-std::numeric_limits<double>::infinity(), 0.0, 0.0,
                  -std::numeric_limits<double>::infinity()};  // penetration, compl, eq, -min l
  double sums[2] = {0.0, 0.0};                                // force, active rows
  double fr[4] = {0.0, 0.0, 0.0, 0.0};  // friction: bound excess, slip residual, rows, stick rows
  const bool tied = inequalitiesTied(params_);
  for (std::size_t i = 0; i < map.getNodeNumElements(); ++i) {
    const GO row = map.getGlobalElement(static_cast<LO>(i));
    if (tearing_.isInequality(row) &&
        !tearing_.inequalityRows[row - tearing_.firstInequalityRow].isNonPenetration()) {
      // A friction row: not one of the contact conditions above but its own: |lambda| within
      // the box, B u = c where inside (stick), B u - c of lambda's sign at a bound (slip).
      if (tied) mx[2] = std::max(mx[2], std::abs(v[i]));
      const InequalityRow& r = tearing_.inequalityRows[row - tearing_.firstInequalityRow];
      const int side = r.boundActive(l[i]);
      fr[0] = std::max({fr[0], r.lowerBound - l[i], l[i] - r.upperBound});
      // A degenerate box (l = u: an open node's zero Coulomb bound) holds lambda at both bounds
      // at once: any slip is admissible there.
      if (r.lowerBound != r.upperBound)
        fr[1] = std::max(fr[1], side == 0 ? std::abs(v[i]) : std::max(0.0, -side * v[i]));
      fr[2] += 1.0;
      fr[3] += side == 0 ? 1.0 : 0.0;
    } else if (tearing_.isInequality(row)) {
      if (tied) mx[2] = std::max(mx[2], std::abs(v[i]));
      mx[0] = std::max(mx[0], v[i]);
      mx[1] = std::max(mx[1], std::abs(l[i] * v[i]));
      mx[3] = std::max(mx[3], -l[i]);
      sums[0] += l[i];
      sums[1] += l[i] > 0.0 ? 1.0 : 0.0;
    } else {
      mx[2] = std::max(mx[2], std::abs(v[i]));
    }
  }
  double gmx[4], gsums[2];
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 4, mx, gmx);
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 2, sums, gsums);
  double gfr[2], gcount[2], counts[2] = {fr[2], fr[3]};
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 2, fr, gfr);
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 2, counts, gcount);
  r.frictionRows = static_cast<GO>(gcount[0]);
  r.stickRows = static_cast<GO>(gcount[1]);
  r.maxFrictionBoundExcess = gfr[0];
  r.maxFrictionSlipResidual = gfr[1];
  if (r.inequalityRows > 0) {
    r.maxPenetration = gmx[0];
    r.maxComplementarity = gmx[1];
    r.minMultiplier = -gmx[3];
  }
  r.equalityResidual = gmx[2];
  r.force = gsums[0];
  r.activeRows = static_cast<GO>(gsums[1]);
  return r;
}

std::vector<double> FetiSolver::multipliersOfRows(GO first, GO count) const {
  std::vector<double> mine;  // (row - first, lambda) pairs
  if (!lambda_.is_null()) {
    auto l = lambda_->getData();
    const auto& map = *tearing_.multiplierMap;
    for (std::size_t i = 0; i < map.getNodeNumElements(); ++i) {
      const GO row = map.getGlobalElement(static_cast<LO>(i));
      if (row >= first && row < first + count)
        mine.insert(mine.end(), {static_cast<double>(row - first), l[i]});
    }
  }
  const std::vector<double> all = allGather(*comm_, mine);
  std::vector<double> out(count, 0.0);
  for (std::size_t k = 0; k + 1 < all.size(); k += 2)
    out[static_cast<std::size_t>(all[k])] = all[k + 1];
  return out;
}

std::vector<double> FetiSolver::inequalityMultipliers() const {
  return multipliersOfRows(tearing_.firstInequalityRow, tearing_.numInequalityRows);
}

std::vector<double> FetiSolver::userEqualityMultipliers() const {
  return multipliersOfRows(tearing_.firstUserEqualityRow, tearing_.numUserEqualityRows);
}

void FetiSolver::requireNoRowOnEliminatedDofs() const {
  std::string error;
  for (std::size_t i = 0; i < data_.size() && error.empty(); ++i) {
    const std::vector<int> eliminated = data_[i].mesh.dirichletDofs(data_[i].dofsPerNode);
    for (const auto& e : tearing_.subdomainRows[i])
      if (tearing_.isUserEquality(e.row) &&
          std::binary_search(eliminated.begin(), eliminated.end(), e.dof)) {
        error = "FetiSolver: an equality row of the caller touches dof " + std::to_string(e.dof) +
                " of subdomain " + std::to_string(data_[i].mesh.id) +
                ", a Dirichlet dof that the FETI formulation eliminates (held at zero); use "
                "Formulation = TFETI or leave the node out of the mesh's Dirichlet nodes";
        break;
      }
  }
  throwIfAnyRankFailed(*comm_, error);
}

std::vector<std::vector<FetiSolver::InequalityOnDof>>
FetiSolver::inequalityMultipliersOnSubdomains() const {
  std::vector<std::vector<InequalityOnDof>> out(subdomains_.size());
  if (lambda_.is_null() || tearing_.numInequalityRows == 0) return out;
  // The rows touching a local subdomain may be owned elsewhere: bring them here.
  std::vector<GO> rows;
  for (const auto& list : tearing_.subdomainRows)
    for (const auto& e : list)
      if (tearing_.isInequality(e.row)) rows.push_back(e.row);
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  auto here = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                   Teuchos::ArrayView<const GO>(rows), 0, comm_));
  Vector local(here);
  local.doImport(*lambda_, Tpetra::Import<LO, GO, Node>(tearing_.multiplierMap, here),
                 Tpetra::INSERT);
  auto lv = local.getData();
  for (std::size_t i = 0; i < subdomains_.size(); ++i)
    for (const auto& e : tearing_.subdomainRows[i])
      if (tearing_.isInequality(e.row))
        out[i].push_back({e.dof, e.coef, lv[here->getLocalElement(e.row)]});
  return out;
}

double FetiSolver::timeDualApply(int repeats) const {
  Vector x(tearing_.multiplierMap), y(tearing_.multiplierMap);
  x.randomize();
  double seconds = 0.0;
  {
    PhaseTimer t(*comm_, seconds);
    for (int r = 0; r < repeats; ++r) F_->apply(x, y);
  }
  return seconds / repeats;
}

std::size_t FetiSolver::globalFactorBytes() const {
  unsigned long long mine = 0, all = 0;
  for (const auto& s : subdomains_) mine += s->factorBytes();
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 1, &mine, &all);
  return all;
}

std::size_t FetiSolver::globalPreconditionerFactorBytes() const {
  unsigned long long mine = 0, all = 0;
  for (const auto& s : subdomains_) mine += s->preconditionerFactorBytes();
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 1, &mine, &all);
  return all;
}

Teuchos::RCP<MultiVector> FetiSolver::solution(const Teuchos::RCP<const Map>& untornMap) const {
  TEUCHOS_TEST_FOR_EXCEPTION(u_.size() != data_.size(), std::logic_error,
                             "FetiSolver::solution: no solution yet (call solve() first)");
  std::vector<std::vector<GO>> nodes;
  for (const auto& sd : data_) nodes.push_back(sd.mesh.globalNode);
  return untornVector(untornMap, nodes, dofsPerNode_, u_);
}

}  // namespace tfeti
