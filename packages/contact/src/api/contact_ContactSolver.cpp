#include "contact_ContactSolver.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "contact_ContactOutput.hpp"
#include "contact_ContactParameters.hpp"
#include "contact_Driver.hpp"
#include "contact_FrictionStep.hpp"
#include "contact_LoadStepControl.hpp"
#include "contact_NonlinearIteration.hpp"
#include "contact_NonlinearModel.hpp"
#include "contact_NonlinearOptions.hpp"
#include "contact_NonlinearSetup.hpp"
#include "contact_NonlinearStepOutput.hpp"
#include "contact_PrescribedDisplacement.hpp"
#include "contact_RunSummary.hpp"

namespace contact {

using Teuchos::ParameterList;

namespace {

// The one-step case of the loop for elastic_contact: small strain, one increment at load
// factor 1, no cut-back; the contact zone measured as "Contact zone" says.
NonlinearOptions linearOptions(const ParameterList& params, int dim) {
  NonlinearOptions o;
  o.linear = true;
  o.kinematics = plasticity::Kinematics::SmallStrain;
  o.steps = 1;
  o.maxIterations = 1;
  o.maxCutbacks = 0;
  o.stiffness = "initial";
  o.vtuEveryStep = false;
  o.rule.line = lineContact(params, dim);
  return o;
}

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

// A 3D line contact (a plane-strain slab): the length of the contact line (the slave nodes'
// extent along z), the force per unit of it (to compare with a 2D run's force per unit
// thickness) and the half-width on each node plane, whose spread shows how far the solution is
// from independent of z.
SlabContact slabContact(const std::vector<ContactNode>& nodes, double force) {
  const std::vector<PlaneHalfWidth> planes = halfWidthPerPlane(nodes);
  SlabContact s;
  s.lineLength = planes.empty() ? 0.0 : planes.back().z - planes.front().z;
  s.forcePerUnitLength = s.lineLength > 0.0 ? force / s.lineLength : 0.0;
  s.nodePlanes = static_cast<int>(planes.size());
  for (std::size_t k = 0; k < planes.size(); ++k) {
    s.halfWidthMin = k ? std::min(s.halfWidthMin, planes[k].halfWidth) : planes[k].halfWidth;
    s.halfWidthMax = k ? std::max(s.halfWidthMax, planes[k].halfWidth) : planes[k].halfWidth;
  }
  return s;
}

}  // namespace

// The state of a set-up run.
struct ContactSolver::Run {
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  bool linear = false;  // elastic_contact: the one-step case
  bool solved = false;
  int verbosity = 1;
  ElasticContactSpec spec;
  ParameterList feti;
  NonlinearOptions options;
  std::unique_ptr<NonlinearModel> model;
  std::unique_ptr<tfeti::FetiSolver> solver;
  double loadNorm = 0.0, appliedForce = 0.0;
  double loadDirection[3] = {0.0, 0.0, 0.0};
  NonlinearHistory history;
  ModelFriction friction;
  FrictionHistory frictionHistory;  // read by a restart, kept up to date by the load steps
  std::vector<plasticity::StressField> stresses;  // elastic_contact: of the solution
  std::vector<ContactNode> nodes;                 // elastic_contact: of the solution

  std::string elapsed() const {
    std::ostringstream s;
    s << std::fixed << std::setprecision(1)
      << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s";
    return s.str();
  }
};

ContactSolver::ContactSolver(Teuchos::RCP<const tfeti::Comm> comm) : comm_(std::move(comm)) {
  if (comm_.is_null()) throw std::invalid_argument("ContactSolver: the communicator is null");
}

ContactSolver::~ContactSolver() = default;

Teuchos::RCP<const ParameterList> ContactSolver::validParameters() {
  return validDriverParameters();
}

void ContactSolver::setParameters(const ParameterList& params, const std::string& source) {
  ParameterList p = params;
  validateDriverParameters(p, source);
  const std::string problem = p.get<std::string>("Problem");
  if (problem != "elastic_contact" && problem != "nonlinear_contact")
    throw std::invalid_argument(source + ": \"Problem\" is " + problem +
                                "; ContactSolver solves elastic_contact and nonlinear_contact");
  if (p.get<std::string>("Study") != "single")
    throw std::invalid_argument(source + ": ContactSolver runs \"Study\" = single");
  applyOutputVerbosity(p);
  params_ = std::move(p);
  source_ = source;
  haveParameters_ = true;
  run_.reset();
}

const ParameterList& ContactSolver::parameters() const {
  return params_;
}

void ContactSolver::setOutputDirectory(const std::string& dir) {
  dir_ = dir;
}

void ContactSolver::setup() {
  if (!haveParameters_) throw std::logic_error("ContactSolver::setup: setParameters first");
  auto run = std::make_unique<Run>();
  Run& r = *run;
  const ParameterList& params = params_;
  r.linear = params.get<std::string>("Problem") == "elastic_contact";
  r.verbosity = params.sublist("Output").get<int>("Verbosity");
  if (!r.linear) checkNonlinearParameters(params);
  if (!r.linear) r.options = nonlinearOptionsFrom(params);
  r.spec = r.linear ? elasticContactSpec(params) : nonlinearContactSpec(params);
  // Small strain reads a height-function obstacle at the reference positions: the gap is then
  // linear in u, as the kinematics are.
  int obstacles = 0;
  for (ContactPairSpec& pair : r.spec.pairs)
    if (pair.obstacle) {
      ++obstacles;
      if (!r.linear)
        pair.obstacle->heightAtReference =
            r.options.kinematics == plasticity::Kinematics::SmallStrain;
    }
  r.friction = modelFriction(params, r.spec.pairs);
  r.feti = fetiParameters(params, r.spec);
  if (!dir_.empty() && comm_->getRank() == 0) std::filesystem::create_directories(dir_);

  // The bodies, their laws and the state; the dimension is the mesh's.
  r.model = std::make_unique<NonlinearModel>(
      makeNonlinearModel(buildElasticContactProblem(r.spec, *comm_), r.spec.bodies));
  NonlinearModel& model = *r.model;
  ElasticContactProblem& problem = model.problem;
  const int dim = problem.dim();
  if (r.linear) {
    r.options = linearOptions(params, dim);
    Field f;
    for (const auto& s : problem.local) f.push_back(s.f);
    r.loadNorm = globalNorm(*comm_, f);  // the residual's scale; an unloaded problem is valid
  } else {
    checkNonlinearOptionsFor(r.options, dim, obstacles);
    r.loadNorm = requireLoadOrMotion(*comm_, problem.local, r.options, !problem.prescribed.empty());
  }
  const double* F = problem.appliedForce;
  r.appliedForce = dim == 3 ? std::hypot(F[0], F[1], F[2]) : std::hypot(F[0], F[1]);
  // The contact force is reported along the applied load, or along the obstacle's motion.
  if (r.appliedForce > 0.0) {
    for (int c = 0; c < dim; ++c) r.loadDirection[c] = F[c] / r.appliedForce;
  } else if (!r.options.obstacleDisplacement.empty()) {
    double n = 0.0;
    for (double v : r.options.obstacleDisplacement) n += v * v;
    for (int c = 0; c < dim; ++c)
      r.loadDirection[c] = r.options.obstacleDisplacement[c] / std::sqrt(n);
  } else if (!r.spec.prescribed.empty()) {
    // Driven by prescribed boundary displacements: the force along their direction (the sum of
    // the prescribed vectors), as a load in that direction would be reported.
    double n = 0.0;
    for (const PrescribedDisplacement& p : r.spec.prescribed)
      r.loadDirection[p.component] += p.value;
    for (int c = 0; c < dim; ++c) n += r.loadDirection[c] * r.loadDirection[c];
    for (int c = 0; c < dim && n > 0.0; ++c) r.loadDirection[c] /= std::sqrt(n);
  }

  r.history.stepSize = 1.0 / r.options.steps;
  if (r.options.restart) {
    if (dir_.empty())
      throw std::invalid_argument(
          "Nonlinear: \"Restart\" reads OUTPUT/restart: set the output directory");
    std::vector<SubdomainRestart> saved;
    r.history = readRestart(dir_ + "/restart", problem, saved,
                            r.friction.active() ? &r.frictionHistory : nullptr);
    for (std::size_t i = 0; i < problem.local.size(); ++i) {
      model.u[i] = saved[i].displacement;
      if (model.plastic[i]) model.plastic[i]->setCommittedHistory(saved[i].history);
    }
    if (comm_->getRank() == 0 && r.verbosity > 0)
      std::cout << "nonlinear_contact: restart from step " << r.history.step << " (load factor "
                << r.history.loadFactor << ")\n";
  }
  if (!r.linear && !dir_.empty() && comm_->getRank() == 0)
    std::filesystem::create_directories(dir_ + "/restart");

  // K of the undeformed bodies, factorized once; loads and rows change per iteration. The
  // one-step case builds the solver with its only increment's loads f and rows (the contact
  // rows of the reference geometry, the prescribed rows at their full value), so that its
  // increment is solved as built. The nonlinear loop sets the prescribed rows per increment
  // (LoadStepIteration); here at the state the run starts from, so that they exist from the
  // start.
  r.solver = std::make_unique<tfeti::FetiSolver>(
      comm_, problem.numSubdomains(), problem.local, r.feti, problem.inequalities,
      r.linear ? problem.equalities : equalityRowsAt(problem, r.history.loadFactor, model.u));
  for (auto& sd : problem.local) sd.K = tfeti::CsrMatrix();  // the solver holds its own copy
  run_ = std::move(run);
}

const ElasticContactProblem& ContactSolver::problem() const {
  if (!run_) throw std::logic_error("ContactSolver::problem: setup first");
  return run_->model->problem;
}

const std::vector<std::vector<double>>& ContactSolver::displacement() const {
  if (!run_ || !run_->solved) throw std::logic_error("ContactSolver::displacement: solve first");
  return run_->model->u;
}

const std::vector<plasticity::StressField>& ContactSolver::stresses() const {
  if (!run_ || !run_->solved) throw std::logic_error("ContactSolver::stresses: solve first");
  return run_->stresses;
}

// The state of solve()'s load steps: the iteration that solves a step, the output of the
// converged ones, the step control, and how the loop ended.
struct ContactSolver::LoadSteps {
  LoadSteps(const Teuchos::RCP<const tfeti::Comm>& comm, Run& r, const std::string& dir)
      : iteration(comm, *r.model, *r.solver, r.options, r.loadNorm),
        output(comm, *r.model, *r.solver, r.options, dir),
        control(r.history, r.options.steps, r.options.maxCutbacks, r.options.stopAfter) {}

  LoadStepIteration iteration;
  NonlinearStepOutput output;
  LoadStepControl control;
  std::vector<FixedPointStep> fixedPointSteps;  // Coulomb, per converged step
  tfeti::DualResult lastQp;
  bool failed = false, stopped = false, qpFailed = false;
  std::string failure;
};

ContactResult ContactSolver::solve() {
  if (!run_) setup();
  if (run_->solved) throw std::logic_error("ContactSolver::solve: once per setup()");
  run_->solved = true;
  LoadSteps steps(comm_, *run_, dir_);
  prepareLoadSteps(steps);
  runLoadSteps(steps);
  evaluateFinalState(steps);
  ContactResult res = fillResult(steps);
  measureContact(res, steps);
  measureFinalState(res, steps);
  writeResultFiles(res, steps);
  reportResult(res, steps);
  return res;
}

void ContactSolver::prepareLoadSteps(LoadSteps& s) {
  Run& r = *run_;
  // Friction (nonlinear_contact only): tangential rows beside the contact rows of every iteration.
  s.iteration.friction = r.friction;
  // A restart continues the friction state of the step it starts from.
  s.iteration.frictionBounds = r.frictionHistory.bounds;
  if (comm_->getRank() == 0 && r.verbosity > 1 && !r.linear)
    s.iteration.onIteration = [&r](const IterationRecord& rec) {
      std::cout << "  step " << rec.step << " (t = " << rec.loadFactor << ") iteration "
                << rec.iteration << ": ||res||/||f|| = " << rec.relativeResidual
                << ", ||du||/||u|| = " << rec.relativeIncrement << ", "
                << rec.hessianMultiplications << " Hessian multiplications [" << r.elapsed()
                << "]\n";
    };
  s.output.friction = s.iteration.friction;
  s.output.accumulatedSlip = r.frictionHistory.slip;
}

void ContactSolver::writeTables() const {
  if (comm_->getRank() != 0 || dir_.empty() || run_->linear) return;
  writeIterationsCsv(dir_ + "/iterations.csv", run_->history);
  writeStepsCsv(dir_ + "/steps.csv", run_->history);
}

// The load steps: attempt, then accept (commit, report, save) or cut back.
void ContactSolver::runLoadSteps(LoadSteps& s) {
  Run& r = *run_;
  NonlinearHistory& history = r.history;
  while (!s.control.finished()) {
    if (s.control.stopRequested()) {
      s.stopped = true;
      break;
    }
    const double t = s.control.nextLoadFactor();
    const int step = s.control.nextStep();
    FixedPointRecord fixedPoint;
    StepOutcome out = attemptFrictionalStep(s.iteration, *r.solver, r.model->problem,
                                            r.options.rule, step, t, fixedPoint);
    s.lastQp = out.qp;
    // The one-step case keeps the state of a QP that did not converge (reported, not retried).
    if (r.linear && !out.converged) {
      s.qpFailed = true;
      s.failure = out.reason;
    }
    for (auto& it : out.iterations) it.accepted = out.converged || r.linear;
    history.iterations.insert(history.iterations.end(), out.iterations.begin(),
                              out.iterations.end());
    if (!out.converged && !r.linear) {
      if (!rejectStep(s, step, t, out.reason)) break;
      continue;
    }
    acceptStep(s, step, t, out, fixedPoint);
    if (r.linear) break;
    saveStep(s, history.steps.back());
  }
}

// A step that did not converge: revert it and cut back; false when no cut-back is left.
bool ContactSolver::rejectStep(LoadSteps& s, int step, double t, const std::string& reason) {
  Run& r = *run_;
  r.model->revert();
  if (comm_->getRank() == 0 && r.verbosity > 0)
    std::cout << "nonlinear_contact: step " << step << " at load factor " << t
              << " rejected: " << reason << " [" << r.elapsed() << "]\n";
  const int cutbacks = s.control.cutbacks();
  if (!s.control.reject()) {
    s.failed = true;
    std::ostringstream msg;
    msg << "load step " << step << " (load factor " << t << ") did not converge after " << cutbacks
        << " cut-backs: " << reason;
    s.failure = msg.str();
    return false;
  }
  writeTables();
  return true;
}

// A converged step: commit the state and record the step's figures.
void ContactSolver::acceptStep(LoadSteps& s, int step, double t, StepOutcome& out,
                               const FixedPointRecord& fixedPoint) {
  Run& r = *run_;
  NonlinearModel& model = *r.model;
  if (!r.linear) s.output.evaluate(out.u);
  model.commit();
  model.u = std::move(out.u);
  StepRecord rec;
  rec.step = step;
  rec.loadFactor = t;
  rec.outerIterations = static_cast<int>(out.iterations.size());
  rec.cutbacks = s.control.cutbacks();
  for (const auto& it : out.iterations) {
    rec.mprgpIterations += it.mprgpIterations;
    rec.hessianMultiplications += it.hessianMultiplications;
    rec.residuals.push_back(it.relativeResidual);
    rec.increments.push_back(it.relativeIncrement);
  }
  if (r.linear)
    evaluateLinearSolution(rec);
  else
    s.output.fill(rec, r.loadDirection);
  if (s.iteration.friction.coulomb())
    s.fixedPointSteps.push_back({step, fixedPoint.iterations, fixedPoint.change});
  r.history.steps.push_back(rec);
  s.control.accept();
}

// The one-step case's evaluation of its solution: the stresses of the linear laws and the
// contact nodes on the reference geometry, as the elastic problem reports them.
void ContactSolver::evaluateLinearSolution(StepRecord& rec) {
  Run& r = *run_;
  NonlinearModel& model = *r.model;
  const ElasticContactProblem& problem = model.problem;
  const tfeti::FetiSolver& solver = *r.solver;
  Field solution;
  for (std::size_t i = 0; i < problem.local.size(); ++i) solution.push_back(solver.solution(i));
  r.nodes = contactNodes(problem, solver, r.options.rule, {},
                         model.surfaceDisplacement(*comm_, solution));
  double vm = 0.0;
  r.stresses.clear();
  for (std::size_t i = 0; i < problem.local.size(); ++i) {
    r.stresses.push_back(
        plasticity::recoverStresses(problem.localElements[i], *model.laws[i], model.u[i]));
    const auto& st = r.stresses.back();
    for (int e = 0; e < problem.localElements[i].numElements(); ++e)
      for (int q = 0; q < st.gaussPointsPerElement; ++q)
        vm = std::max(vm, st.atGaussPoint(e, q, plasticity::kVonMises));
  }
  rec.pMax = maxPressure(r.nodes);
  rec.contactExtent = contactExtent(r.nodes, r.options.rule, problem.dim());
  rec.maxVonMises = globalMax(*comm_, vm);
  // The elastic problem's contact force: the sum of the multipliers (forces along each row's
  // normal), the figure its summary has always reported.
  rec.contactForce = 0.0;
  for (const auto& n : r.nodes) rec.contactForce += n.lambda;
}

// A converged nonlinear step's files (VTU, contact CSV, tables, restart) and progress line.
void ContactSolver::saveStep(LoadSteps& s, const StepRecord& rec) {
  Run& r = *run_;
  const bool files = !dir_.empty();
  const int step = rec.step;
  const std::string base = stepBaseName(step);
  if (files && r.options.vtuEveryStep) {
    s.output.writeVtu(base, r.model->u);
    if (comm_->getRank() == 0) writePvd(dir_ + "/steps.pvd", stepCollection(r.history));
  }
  if (files) s.output.writeContactCsv(dir_ + "/contact_pressure_" + base + ".csv");
  writeTables();
  if (r.friction.active()) {
    s.output.commitSlip();
    r.frictionHistory = {s.output.accumulatedSlip, s.iteration.frictionBounds};
  }
  if (files)
    saveRestart(*comm_, dir_ + "/restart", r.history, *r.model,
                r.friction.active() ? &r.frictionHistory : nullptr);
  if (comm_->getRank() == 0 && r.verbosity > 0)
    std::cout << "nonlinear_contact: step " << step << " converged at load factor "
              << rec.loadFactor << " in " << rec.outerIterations << " iterations ("
              << rec.hessianMultiplications << " Hessian multiplications); p_max " << rec.pMax
              << ", contact extent " << rec.contactExtent << ", max von Mises " << rec.maxVonMises
              << ", max plastic strain " << rec.maxPlasticStrain << ", contact force "
              << rec.contactForce
              << (s.fixedPointSteps.empty() || s.fixedPointSteps.back().step != step
                      ? std::string()
                      : ", " + std::to_string(s.fixedPointSteps.back().iterations) +
                            " Coulomb fixed-point iterations")
              << " [" << r.elapsed() << "]\n";
}

// The final state is the last converged step; its contact rows and multipliers need one solve
// at its load factor when this run converged no step (a restart that stops at once or fails at
// its first step).
void ContactSolver::evaluateFinalState(LoadSteps& s) {
  Run& r = *run_;
  if (!r.linear && !r.history.steps.empty() && !s.output.evaluated()) {
    const StepOutcome again = s.iteration.attempt(r.history.step, r.history.loadFactor);
    r.model->revert();
    if (again.converged) s.output.evaluate(again.u);
  }
}

// The run's description: the problem, the FETI dimensions, the last QP, the history and how
// the run ended.
ContactResult ContactSolver::fillResult(const LoadSteps& s) const {
  const Run& r = *run_;
  const ElasticContactProblem& problem = r.model->problem;
  const tfeti::FetiSolver& solver = *r.solver;
  const NonlinearOptions& opt = r.options;
  ContactResult res;
  res.problem = r.linear ? "elastic_contact" : "nonlinear_contact";
  res.ranks = comm_->getSize();
  res.subdomains = problem.numSubdomains();
  res.nodes = problem.mesh.numNodes();
  res.dimension = problem.dim();
  res.feti = fetiDimensions(solver, r.feti);
  res.qp = s.lastQp;
  res.contactType = r.spec.bonded ? "bonded" : r.spec.tied ? "tied" : "frictionless";
  // The pairs' discretization, or "mixed" when they differ (contact.pairs names each).
  res.contactDiscretization = r.spec.pairs.front().discretization;
  for (const auto& pair : r.spec.pairs)
    if (pair.discretization != res.contactDiscretization) res.contactDiscretization = "mixed";
  res.history = r.history;
  res.converged = r.linear ? !s.qpFailed : !s.failed && !s.stopped;
  res.exitCode = s.failed ? 3 : s.qpFailed ? 2 : 0;
  res.message = s.failure;
  if (s.stopped && res.message.empty())
    res.message = "stopped after step " + std::to_string(r.history.step) + " (Stop after step)";
  const NonlinearOutcome o{opt.kinematics == plasticity::Kinematics::TotalLagrangian,
                           opt.stiffness,
                           opt.eta1,
                           opt.eta2,
                           s.stopped,
                           opt.restart};
  res.nonlinear = o;
  res.materials = r.spec.bodies;
  res.friction = s.iteration.friction;
  res.fixedPoint = s.fixedPointSteps;
  return res;
}

// The contact zone of the final state: p_max, extent, force against the applied load and the
// supports' reaction, Hertz where it applies.
void ContactSolver::measureContact(ContactResult& res, const LoadSteps& s) const {
  const Run& r = *run_;
  const ElasticContactProblem& problem = r.model->problem;
  const NonlinearOptions& opt = r.options;
  const NonlinearHistory& history = r.history;
  const int dim = problem.dim();
  const bool haveStep = !history.steps.empty();
  ContactMeasures& c = res.contact;
  const std::vector<ContactNode>& nodes = r.linear ? r.nodes : s.output.nodes();
  res.haveContact = haveStep && (r.linear || s.output.evaluated());
  if (haveStep) {
    const StepRecord& last = history.steps.back();
    c.constraints = r.solver->constraintReport();
    c.pMax = last.pMax;
    c.extent = last.contactExtent;
    c.extentKey = dim == 3 && !opt.rule.line ? "contact_radius"
                  : opt.rule.angle           ? "angle"
                                             : "half_width";
    c.force = last.contactForce;
    c.appliedForce = r.linear ? std::hypot(problem.appliedForce[0], problem.appliedForce[1],
                                           problem.appliedForce[2])
                     : problem.rampedLoads.empty()
                         ? history.loadFactor * r.appliedForce
                         : [&]() {  // ramped tractions: the resultant at the load factor
                             const auto F = appliedForceAt(problem, history.loadFactor);
                             double n = 0.0;
                             for (double v : F) n += v * v;
                             return std::sqrt(n);
                           }();
    c.forceRelativeError =
        c.appliedForce > 0.0 ? std::abs(c.force - c.appliedForce) / c.appliedForce : 0.0;
    if (r.linear && dim == 3 && opt.rule.line) c.slab = slabContact(nodes, c.force);
    if (r.linear || history.loadFactor > 1.0 - 1e-12)
      c.hertz = hertzReference(params_, c.pMax, c.extent, dim, contactBodyLaws(r.spec, problem));
    if (!r.linear) {
      // The reaction of the fixed boundaries balances the contact force (and the load).
      c.supportForce = supportForce(*comm_, *r.solver, problem, r.loadDirection);
      c.supportRelativeError =
          last.contactForce != 0.0
              ? std::abs(c.supportForce - last.contactForce) / last.contactForce
              : 0.0;
      c.lastMaxAbsIncrement = maxAbsSolution(*comm_, *r.solver);
    }
    res.maxVonMises = last.maxVonMises;
    res.maxPlasticStrain = last.maxPlasticStrain;
  }
  res.contactNodes = nodes;
  if (problem.namedPairs && res.haveContact) res.pairs = pairForces(problem, nodes);
}

// The final state's stresses and largest displacement, the reactions of the prescribed entries
// and the coupled boundaries' common values, the solver's timings.
void ContactSolver::measureFinalState(ContactResult& res, const LoadSteps& s) {
  Run& r = *run_;
  const NonlinearModel& model = *r.model;
  const ElasticContactProblem& problem = model.problem;
  const bool haveStep = !r.history.steps.empty();
  if (!r.linear && s.output.evaluated()) {
    r.stresses.clear();
    for (std::size_t i = 0; i < model.u.size(); ++i)
      r.stresses.push_back(plasticity::cauchyStress(problem.localElements[i], *model.laws[i],
                                                    model.u[i], r.options.kinematics));
  }
  {
    double mx = 0.0;
    for (const auto& x : model.u)
      for (double v : x) mx = std::max(mx, std::abs(v));
    res.maxAbsU = globalMax(*comm_, mx);
  }
  const auto nodesOfBoundary = [&](const std::string& name) {
    const auto ids = boundaryNodeIds(problem.mesh, name);
    return std::vector<long long>(ids.begin(), ids.end());
  };
  // The multipliers of the last solve are the total constraint forces, also in the nonlinear
  // loop.
  if (!r.spec.prescribed.empty() && (r.linear || s.output.evaluated())) {
    res.prescribedRows =
        static_cast<long long>(r.solver->userEqualityRows()) - problem.couplingRowCount;
    res.prescribed = prescribedSummary(*r.solver, r.spec.prescribed, nodesOfBoundary);
  }
  if (!r.spec.couplings.empty() && haveStep) {
    res.couplingRows = problem.couplingRowCount;
    res.couplings =
        couplingSummary(*comm_, r.spec.couplings, problem.local, model.u, nodesOfBoundary);
  }
  res.timings = r.solver->timings();
}

// The files of the final state: the contact pressure and VTU, the tables, summary.json.
void ContactSolver::writeResultFiles(ContactResult& res, LoadSteps& s) {
  Run& r = *run_;
  const ElasticContactProblem& problem = r.model->problem;
  const bool files = !dir_.empty();
  if (files) {
    res.contactCsv = dir_ + "/contact_pressure.csv";
    if (r.linear) {
      writeContactCsv(*comm_, res.contactCsv, res.contactNodes, problem.dim());
      if (params_.sublist("Output").get<bool>("VTU")) {
        std::vector<SubdomainFields> fields;
        for (std::size_t i = 0; i < problem.local.size(); ++i) {
          fields.push_back({&problem.localElements[i],
                            problem.local[i].mesh.id,
                            &r.model->u[i],
                            &r.stresses[i],
                            {}});
          if (problem.namedPairs)
            fields.back().extra.push_back(
                contactPairField(res.contactNodes, problem.local[i].mesh.globalNode));
        }
        const std::vector<std::string> names = problem.namedPairs
                                                   ? std::vector<std::string>{"contact_pair"}
                                                   : std::vector<std::string>{};
        res.vtu = writeVtu(*comm_, dir_, "solution", stressPiece(fields, names));
      }
    } else {
      if (!r.history.steps.empty() && s.output.evaluated()) {
        s.output.writeContactCsv(res.contactCsv);
        if (params_.sublist("Output").get<bool>("VTU")) s.output.writeVtu("solution", r.model->u);
      }
      res.iterationsCsv = dir_ + "/iterations.csv";
      res.stepsCsv = dir_ + "/steps.csv";
    }
  }
  res.wallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - r.start).count();
  res.peakRssMb = peakRssMb(*comm_);
  if (files) {
    writeTables();
    writeSummary(*comm_, dir_, summaryJson(res), params_);
  }
}

// The run's last line on rank 0.
void ContactSolver::reportResult(const ContactResult& res, const LoadSteps& s) const {
  const Run& r = *run_;
  if (comm_->getRank() != 0 || r.verbosity <= 0) return;
  const ContactMeasures& c = res.contact;
  if (r.linear) {
    std::cout << "elastic_contact: " << r.model->problem.numSubdomains() << " subdomains, primal "
              << res.feti.primal << ", dual " << res.feti.dual << " (" << res.feti.contactRows
              << " contact rows), " << res.qp.method << ": " << res.qp.qp.hessianMultiplications
              << " Hessian multiplications (" << (res.converged ? "converged" : "NOT CONVERGED")
              << "); p_max " << c.pMax
              << (r.options.rule.line ? ", half-width " : ", contact radius ") << c.extent
              << ", force " << c.force << " (applied " << c.appliedForce << "), max von Mises "
              << res.maxVonMises << "\n";
  } else if (!s.failed) {
    const IterationTotals totals = iterationTotals(r.history);
    std::cout << "nonlinear_contact: " << (s.stopped ? "stopped after" : "finished") << " step "
              << r.history.step << " at load factor " << r.history.loadFactor << ", "
              << totals.iterations << " iterations, " << totals.hessianMultiplications
              << " Hessian multiplications [" << r.elapsed() << "]\n";
  }
}

int runContactProblem(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                      const std::string& dir) {
  ContactSolver solver(comm);
  solver.setParameters(params, "tfeti_contact parameters");
  solver.setOutputDirectory(dir);
  const ContactResult result = solver.solve();
  if (comm->getRank() == 0) {
    if (result.exitCode == 2)
      std::cerr << "tfeti_contact: " << result.qp.method << " did not converge ("
                << result.qp.qp.message << "); results written to " << dir << "\n";
    if (result.exitCode == 3)
      std::cerr << "tfeti_contact: " << result.message
                << "; results up to the last converged step (" << result.history.step
                << ", load factor " << result.history.loadFactor << ") are in " << dir << "\n";
  }
  return result.exitCode;
}

}  // namespace contact
