// nonlinear_contact as the load-stepped case of the loop: the "Nonlinear" sublist's options, a
// step that did not converge reverted and cut back, every converged step saved (its VTU and
// contact CSV, iterations.csv and steps.csv, the restart files) and reported, the figures of the
// step output (contact force along the load, the supports' reaction, plastic strain).
#include <Teuchos_CommHelpers.hpp>

#include <cmath>
#include <iostream>

#include "contact_ContactRun.hpp"
#include "contact_NonlinearSetup.hpp"
#include "contact_PrescribedDisplacement.hpp"
#include "contact_RunPolicy.hpp"
#include "contact_RunSummary.hpp"

namespace contact {

namespace {

// The resultant of the multiplier forces B^T lambda of the last solve on the nodes of the Fixed
// boundaries, along `direction` (dim entries): the support's reaction. Gluing rows cancel in the
// sum over a node's copies, so it is the Dirichlet rows' force; in equilibrium it balances the
// applied load plus the force a rigid obstacle exerts.
double supportForce(const tfeti::Comm& comm, const tfeti::FetiSolver& solver,
                    const ElasticContactProblem& problem, const double direction[]) {
  const int dim = problem.dim();
  const Field btl = solver.multiplierForces();
  double local = 0.0, global = 0.0;
  for (std::size_t i = 0; i < btl.size(); ++i)
    for (int n : problem.local[i].mesh.dirichletNodes)
      for (int c = 0; c < dim; ++c) local += direction[c] * btl[i][dim * n + c];
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &local, &global);
  return global;
}

class NonlinearContactPolicy final : public RunPolicy {
 public:
  std::string name() const override { return "nonlinear_contact"; }

  ElasticContactSpec readParameters(const Teuchos::ParameterList& params,
                                    NonlinearOptions& options) const override {
    checkNonlinearParameters(params);
    options = nonlinearOptionsFrom(params);
    ElasticContactSpec spec = nonlinearContactSpec(params);
    // Small strain reads a height-function obstacle at the reference positions: the gap is then
    // linear in u, as the kinematics are.
    for (ContactPairSpec& pair : spec.pairs)
      if (pair.obstacle)
        pair.obstacle->heightAtReference =
            options.kinematics == plasticity::Kinematics::SmallStrain;
    return spec;
  }

  void fitOptions(const Teuchos::ParameterList&, int dim, int rigidObstacles,
                  NonlinearOptions& options) const override {
    checkNonlinearOptionsFor(options, dim, rigidObstacles);
  }

  double loadNorm(const tfeti::Comm& comm, const ElasticContactProblem& problem,
                  const NonlinearOptions& options) const override {
    return requireLoadOrMotion(comm, problem.local, options, !problem.prescribed.empty());
  }

  // The loop sets the prescribed rows per increment (LoadStepIteration); here at the state the
  // run starts from, so that they exist from the start.
  std::vector<tfeti::EqualityRow> initialEqualityRows(const ElasticContactProblem& problem,
                                                      double t, const Field& u) const override {
    return equalityRowsAt(problem, t, u);
  }

  // The first increment's own contact update (a rigid obstacle moved to t): the solver is built
  // with its rows, so that the first iteration keeps the tearing instead of building another.
  void initialContact(const tfeti::Comm& comm, NonlinearModel& model,
                      const NonlinearOptions& options, double t) const override {
    searchContactAt(comm, model, options, t);
  }

  bool printsIterations() const override { return true; }
  bool keepsUnconvergedStep() const override { return false; }
  bool savesSteps() const override { return true; }

  // The trial state: the laws' trial history and the slip from the step's start are only there
  // before the model commits.
  void evaluateStep(ContactRun& r, LoadSteps& s, const Field& u, StepRecord& rec) const override {
    s.output.evaluate(u);
    s.output.fill(rec, r.loadDirection);
  }

  // The final state is the last converged step; its contact rows and multipliers need one solve
  // at its load factor when this run converged no step (a restart that stops at once or fails
  // at its first step).
  void evaluateFinalState(ContactRun& r, LoadSteps& s) const override {
    NonlinearModel& model = *r.model;
    if (!r.history.steps.empty() && !s.output.evaluated()) {
      const StepOutcome again = s.iteration.attempt(r.history.step, r.history.loadFactor);
      model.revert();
      if (again.converged) s.output.evaluate(again.u);
    }
    r.evaluated = s.output.evaluated();
    if (!r.evaluated) return;
    r.nodes = s.output.nodes();
    r.maxVonMisesNodal = s.output.maxVonMisesNodal();
    // Only the C++ API reads the committed state's stresses (the files hold the last step's):
    // they cost one more pass of the element kernels over the mesh, 0.5 s of a 20 s step-42
    // run at 64^3, so they wait until asked for.
    r.stresses.clear();
    r.stressesPending = true;
  }

  void finalStresses(ContactRun& r) const override {
    const NonlinearModel& model = *r.model;
    r.stresses.clear();
    for (std::size_t i = 0; i < model.u.size(); ++i)
      r.stresses.push_back(plasticity::cauchyStress(model.problem.localElements[i], *model.laws[i],
                                                    model.u[i], r.options.kinematics));
  }

  double appliedForce(const ContactRun& r) const override {
    const ElasticContactProblem& problem = r.model->problem;
    const double t = r.history.loadFactor;
    if (problem.rampedLoads.empty()) return t * r.appliedForce;
    // Ramped tractions: the resultant at the load factor.
    const auto F = appliedForceAt(problem, t);
    double n = 0.0;
    for (double v : F) n += v * v;
    return std::sqrt(n);
  }

  // The reaction of the fixed boundaries balances the contact force (and the load).
  void addContactMeasures(ContactMeasures& c, const ContactRun& r) const override {
    c.supportForce = supportForce(*r.comm, *r.solver, r.model->problem, r.loadDirection);
    c.supportRelativeError = c.force != 0.0 ? std::abs(c.supportForce - c.force) / c.force : 0.0;
    c.lastMaxAbsIncrement = maxAbsSolution(*r.comm, *r.solver);
  }

  void writeFinalState(ContactResult& res, const ContactRun& r, const LoadSteps& s,
                       const std::string&) const override {
    if (r.history.steps.empty() || !s.output.evaluated()) return;
    s.output.writeContactCsv(res.contactCsv);
    if (r.vtu) s.output.writeVtu("solution", r.model->u);
  }

  // A run that failed has reported its rejected steps.
  void report(const ContactResult&, const ContactRun& r, const LoadSteps& s) const override {
    if (s.failed) return;
    const IterationTotals totals = iterationTotals(r.history);
    std::cout << "nonlinear_contact: " << (s.stopped ? "stopped after" : "finished") << " step "
              << r.history.step << " at load factor " << r.history.loadFactor << ", "
              << totals.iterations << " iterations, " << totals.hessianMultiplications
              << " Hessian multiplications [" << r.elapsed() << "]\n";
  }
};

}  // namespace

std::unique_ptr<const RunPolicy> nonlinearContactPolicy() {
  return std::make_unique<NonlinearContactPolicy>();
}

}  // namespace contact
