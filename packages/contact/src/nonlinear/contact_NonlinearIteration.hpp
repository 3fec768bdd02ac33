#pragma once
// One load step of the reference paper's loop, as its named steps. From the converged state u
// at load factor t, iterate:
//   contact update    B_I and the gaps g(u) on the current geometry X + u (a rigid obstacle at
//                     its position for t);
//   QP solve          the increment du: K du + B^T lambda = t f - f_int(u), B_E du = c_E,
//                     B_I du <= g(u), lambda_I >= 0 (TFETI, SMALBE/MPRGP, warm-started);
//   internal force    u += du, f_int(u) (the laws' trial history);
//   residual check    res = t f - B^T lambda - f_int(u); converged when ||du|| / ||u|| < eta1
//                     and ||res|| / ||t f|| < eta2 (||f_int|| when no load is applied: a
//                     prescribed obstacle motion alone).
// Options: inexact QPs whose tolerance follows the residual (forcing terms) and a backtracking
// line search on ||res||; a step then converges only on a full step of an exactly solved QP.
// Step control (contact_LoadStepControl.hpp) decides the load factors and the cut-backs.
// NonlinearOptions::solveAsBuilt and singleIncrement make it the one-step case of a linear
// problem: one increment from u = 0 with the solver's own loads and rows, no contact update, no
// f_int(0).
#include <functional>
#include <string>
#include <vector>

#include "contact_Friction.hpp"
#include "contact_NonlinearHistory.hpp"
#include "contact_NonlinearModel.hpp"
#include "contact_NonlinearOptions.hpp"
#include "contact_RigidObstacle.hpp"

namespace contact {

struct StepOutcome {
  bool converged = false;
  std::string reason;  // why not
  Field u;             // the trial displacement at the end
  std::vector<IterationRecord> iterations;
  tfeti::DualResult qp;  // the last QP solve of the attempt
};

struct ResidualCheck {
  double solutionNorm = 0.0, relativeIncrement = 0.0, relativeResidual = 0.0;
  bool converged = false;
};

// res = f(t) - B^T lambda - f_int and the stopping test against eta1, eta2 (collective).
// load = f(t), the external load at the step's load factor; loadNorm = ||f(t)||; when it is zero
// the residual is relative to ||f_int||.
ResidualCheck checkResidual(const tfeti::Comm& comm, const Field& load,
                            const Field& multiplierForces, const Field& fint, const Field& u,
                            const Field& du, double loadNorm, const NonlinearOptions& options);

// The contact update of an increment that starts from model.u and goes to load factor t, without
// friction rows or kept rows: every rigid obstacle where its prescribed motion has taken it, then
// the rows from the surface displacement (model.problem.contact and inequalities; collective).
// The run's solver is built with the first increment's rows, which its first iteration then
// finds again.
void searchContactAt(const tfeti::Comm& comm, NonlinearModel& model,
                     const NonlinearOptions& options, double t);
// The same search without a model, at the reference configuration (a run that does not restart
// starts there): what the dry run's check of the rigid motions sees of the first solve's rows.
void searchContactAtReference(ElasticContactProblem& problem, const NonlinearOptions& options,
                              double t, int rank);

class LoadStepIteration {
 public:
  // loadNorm: ||f|| at load factor 1 (0: no applied load). The contact pairs (their names for
  // errors, a rigid obstacle at load factor 0) are the model's problem's.
  LoadStepIteration(const Teuchos::RCP<const tfeti::Comm>& comm, NonlinearModel& model,
                    tfeti::FetiSolver& solver, const NonlinearOptions& options, double loadNorm);

  // Iterations at load factor t from the converged state model.u (the model's laws keep the
  // trial history of the last iteration: commit or revert it).
  StepOutcome attempt(int step, double t) const;

  // Friction on the contact pair: the tangential rows join the contact rows of every
  // iteration (contact_Friction.hpp), their slip measured from the step's start model.u.
  ModelFriction friction;
  SlipBounds frictionBounds;  // Coulomb: the slip bound per slave node (contact_FrictionStep)

  // Progress lines per iteration (Verbosity 2): called with the record of each iteration.
  std::function<void(const IterationRecord&)> onIteration;

  // Coulomb with its bounds inside the Newton loop (contact_FrictionStep.hpp): called after each
  // iteration's QP; it updates frictionBounds and says by how much they changed (relative) and
  // whether that is below its tolerance, which the step then needs besides Eta 1 and Eta 2.
  struct BoundsUpdate {
    bool settled = true;
    double change = 0.0, tolerance = 0.0;  // tolerance 0: no bounds to settle
  };
  std::function<BoundsUpdate()> updateBounds;

  // The named steps.
  void updateContact(const Field& u, double t) const;
  tfeti::DualResult solveIncrement(const Field& u, const Field& fint, double t,
                                   int iteration) const;

 private:
  // The right-hand sides of the increment's QP: t f - f_int(u) per subdomain. The gluing and
  // zero Dirichlet rows B_E du = 0 are FetiSolver's own.
  Field incrementLoads(const Field& fint, double t) const;
  // The prescribed displacements' rows of the increment, c_E(t) - B_E u, and the kinematic
  // couplings' rows.
  std::vector<tfeti::EqualityRow> prescribedIncrementRows(const Field& u, double t) const;

  // Inexact QPs or partial steps: increments then also close the jumps left in u.
  bool inexact() const;
  // ||f(t)|| as the residual's scale (contact_NonlinearIteration.cpp).
  double loadNormAt(const Field& load, double t) const;
  // u + alpha du with the multipliers' forces moved by the same fraction, f_int and the residual.
  struct Trial {
    double alpha = 1.0;
    Field u, du, forces, fint;
    ResidualCheck check;
  };
  Trial tryStep(const Field& u, const Field& du, double alpha, const Field& forces,
                const Field& previousForces, double t) const;

  // A contact update that 2-cycles (the iterates alternate between two sets of rows: a slave
  // node whose closest point jumps between master facets with different normals, and back) is
  // stopped by freezing the rows: from then on the step keeps them and only moves their gaps
  // with the displacement, g = g_frozen - B (u - u_frozen), which is a linear problem for Newton.
  mutable bool contactFrozen_ = false;
  mutable std::vector<double> contactAt_;   // the surface displacement the rows are at
  mutable std::vector<double> frozenAt_;    // ... when they were frozen
  mutable std::vector<double> frozenGaps_;  // their gaps then
  // Within a step, a slave node of a rigid obstacle keeps its row while the iterations move its
  // gap beyond the Search radius (out to kKeptRowRadius times it): such a row is inactive, and
  // a row set that stays the same keeps the solver's tearing and coarse space instead of
  // building them again. For the only contact pair, a rigid obstacle with frictionless
  // node-wise rows, without friction (keepsRowsInStep). stepRowNodes_: the slave nodes of the
  // step's last update, empty at its start.
  static constexpr double kKeptRowRadius = 2.0;
  mutable std::vector<int> stepRowNodes_;
  bool keepsRowsInStep() const;
  void keepStepRows() const;      // the new rows within the radius, and the step's kept ones
  void rememberStepRows() const;  // stepRowNodes_ from the rows in force
  // Whether the last three iterations show the 2-cycle: u_k = u_(k-2) and |du_k| = |du_(k-1)|.
  static bool twoCycle(const std::vector<IterationRecord>& iterations);
  // Keeps the rows in force (their gaps at contactAt_) for the rest of the step, and says so.
  void freezeContact(int step, int iteration, double relativeIncrement) const;
  // Once the residual is below Eta 2, what is left of the step's test (||du||/||u|| against
  // Eta 1, Coulomb's bounds against their tolerance) should keep shrinking. Where it stops, it
  // has reached what the QPs' inexactness leaves: a penalty QP's multipliers at MPRGP's
  // tolerance move the bounds by about ten times it, and further iterations only repeat that.
  // After kStalls such iterations in a row (each no closer than kStallContraction times the
  // last), the rest of the attempt solves its QPs at kTighterQp times the configured tolerances,
  // once, and says so. (A tenth first, then a hundredth, took 18 Newton iterations on 2 ranks
  // where this takes 14: docs/qp_solvers.md.) A Newton loop that converges is never tightened.
  // Only iterations whose contact rows join the same nodes and facets as the last one's count:
  // where the rows move (a contact update that cycles, freezeContact's case), the stall is the
  // search's, not the QPs'.
  static constexpr int kStalls = 2;
  static constexpr double kStallContraction = 0.5, kTighterQp = 0.01;
  // A hash of the contact rows' slave nodes, facets and entries' nodes, and whether the last
  // contact update changed it (updateContact; the first update of an attempt always does).
  mutable std::size_t rowTopology_ = 0;
  mutable bool rowsMoved_ = true;
  struct StallWatch {
    int stalls = 0;  // iterations in a row that did not get closer
    double previousDistance = 0.0;
  };
  // This iteration is the kStalls-th in a row that stalled (collective).
  bool stalledAtQpAccuracy(const ResidualCheck& check, const BoundsUpdate& bounds, double factor,
                           StallWatch& watch) const;
  void tightenQps(int step, int iteration, double relativeIncrement, const BoundsUpdate& bounds,
                  double factor) const;
  // The frozen rows' gaps at the surface displacement `current`, and their dual rows.
  void moveFrozenGaps(const std::vector<double>& current) const;

  // Whether this iteration gives the solver a new tangent, and per local subdomain whether it
  // keeps its K instead (an empty matrix passed): updates factorIsElastic_ (collective).
  struct TangentPlan {
    bool refactor = false;
    std::vector<char> keep;
  };
  TangentPlan planTangent(int iteration) const;
  // Per local subdomain: the solver's factor is of the elastic stiffness (it is built with it; a
  // small-strain tangent with every point elastic is it again). Empty until the first tangent.
  mutable std::vector<char> factorIsElastic_;

  Teuchos::RCP<const tfeti::Comm> comm_;
  NonlinearModel& model_;
  tfeti::FetiSolver& solver_;
  const NonlinearOptions& options_;
  double loadNorm_;
};

}  // namespace contact
