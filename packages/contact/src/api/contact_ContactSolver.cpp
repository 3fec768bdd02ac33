#include "contact_ContactSolver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "contact_ContactOutput.hpp"
#include "contact_ContactParameters.hpp"
#include "contact_ContactRun.hpp"
#include "contact_Driver.hpp"
#include "contact_FrictionStep.hpp"
#include "contact_NonlinearSetup.hpp"
#include "contact_RecoveredFields.hpp"
#include "contact_RunPolicy.hpp"
#include "contact_RunSummary.hpp"

namespace contact {

using Teuchos::ParameterList;

namespace {

// The subdomains as the solver takes them: K moved out of the problem (which needs no stiffness
// after setup; a copy would hold every K twice until the solver had factorized it), the rest
// copied.
std::vector<tfeti::SubdomainData> handOverStiffness(std::vector<tfeti::SubdomainData>& local) {
  std::vector<tfeti::SubdomainData> out;
  out.reserve(local.size());
  for (auto& sd : local) {
    tfeti::CsrMatrix K = std::move(sd.K);
    sd.K = tfeti::CsrMatrix();
    out.push_back(sd);
    out.back().K = std::move(K);
  }
  return out;
}

// The applied load's resultant and the direction the contact force is reported along: the
// applied load's, else the obstacle's motion, else the sum of the prescribed displacements.
void setLoadDirection(ContactRun& r, int dim) {
  const double* F = r.model->problem.appliedForce;
  r.appliedForce = dim == 3 ? std::hypot(F[0], F[1], F[2]) : std::hypot(F[0], F[1]);
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
}

// Nonlinear/Restart: the history, the displacement, the committed plastic history and the
// friction state of the last saved step, from DIR/restart.
void restoreRestart(ContactRun& r, const std::string& dir) {
  if (dir.empty())
    throw std::invalid_argument(
        "Nonlinear: \"Restart\" reads OUTPUT/restart: set the output directory");
  NonlinearModel& model = *r.model;
  ElasticContactProblem& problem = model.problem;
  std::vector<SubdomainRestart> saved;
  r.history = readRestart(dir + "/restart", problem, saved,
                          r.friction.active() ? &r.frictionHistory : nullptr);
  for (std::size_t i = 0; i < problem.local.size(); ++i) {
    model.u[i] = saved[i].displacement;
    if (model.plastic[i]) model.plastic[i]->setCommittedHistory(saved[i].history);
  }
  if (r.comm->getRank() == 0 && r.verbosity > 0)
    std::cout << "nonlinear_contact: restart from step " << r.history.step << " (load factor "
              << r.history.loadFactor << ")\n";
}

}  // namespace

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
  auto run = std::make_unique<ContactRun>();
  ContactRun& r = *run;
  const ParameterList& params = params_;
  r.comm = comm_;
  r.policy = RunPolicy::forProblem(params.get<std::string>("Problem"));
  const RunPolicy& policy = *r.policy;
  r.verbosity = params.sublist("Output").get<int>("Verbosity");
  r.vtu = params.sublist("Output").get<bool>("VTU");
  r.spec = policy.readParameters(params, r.options);
  int obstacles = 0;
  for (const ContactPairSpec& pair : r.spec.pairs)
    if (pair.obstacle) ++obstacles;
  r.friction = modelFriction(params, r.spec.pairs);
  r.feti = fetiParameters(params, r.spec);
  if (!dir_.empty() && comm_->getRank() == 0) std::filesystem::create_directories(dir_);

  // The bodies, their laws and the state; the dimension is the mesh's.
  r.model = std::make_unique<NonlinearModel>(
      makeNonlinearModel(buildElasticContactProblem(r.spec, *comm_), r.spec.bodies));
  NonlinearModel& model = *r.model;
  ElasticContactProblem& problem = model.problem;
  const int dim = problem.dim();
  policy.fitOptions(params, dim, obstacles, r.options);
  r.loadNorm = policy.loadNorm(*comm_, problem, r.options);
  // Hertz's reference is made after the solve: its input is checked before it (in the dry
  // run's order).
  checkHertzInput(params, dim, contactBodyLaws(r.spec, problem));
  setLoadDirection(r, dim);

  r.history.stepSize = 1.0 / r.options.steps;
  if (r.options.restart) restoreRestart(r, dir_);
  if (policy.savesSteps() && !dir_.empty() && comm_->getRank() == 0)
    std::filesystem::create_directories(dir_ + "/restart");

  // K of the undeformed bodies, factorized once; loads and rows change per iteration.
  policy.initialContact(*comm_, model, r.options,
                        std::min(1.0, r.history.loadFactor + r.history.stepSize));
  // Friction rows with a bound from the start hold the bodies from the first solve: the solver
  // is built with them, as the first iteration will have them; then what holds every body is
  // checked, before any factorization.
  const InitialFriction friction = addInitialFrictionRows(
      r.spec, problem, r.friction, r.frictionHistory.bounds, problem.inequalities, *comm_);
  r.frictionHistory.bounds = friction.bounds;
  r.frictionSticks = friction.sticks;
  r.frictionLimit = friction.limit;
  // A load the rows hold at no load factor fails every step: said before any factorization. A
  // restart's state is not the reference geometry the limit is of.
  if (!r.options.restart) requireLoadHeld(friction.limit);
  if (r.frictionSticks && r.verbosity > 0 && comm_->getRank() == 0)
    std::cout << "nonlinear_contact: Coulomb friction alone holds a body along the contact "
                 "surface: every load step starts sticking, then takes mu lambda_N\n";
  if (r.frictionLimit && r.frictionLimit->loadFactor < 1.0 && r.verbosity > 0 &&
      comm_->getRank() == 0)
    std::cout << "nonlinear_contact: " << frictionLimitText(*r.frictionLimit) << "\n";
  r.solver = std::make_unique<tfeti::FetiSolver>(
      comm_, problem.numSubdomains(), handOverStiffness(problem.local), r.feti,
      problem.inequalities, policy.initialEqualityRows(problem, r.history.loadFactor, model.u));
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
  // Computed at the first request (the model keeps its final state after solve()).
  if (run_->stressesPending) {
    run_->policy->finalStresses(*run_);
    run_->stressesPending = false;
  }
  return run_->stresses;
}

ContactResult ContactSolver::solve() {
  if (!run_) setup();
  if (run_->solved) throw std::logic_error("ContactSolver::solve: once per setup()");
  run_->solved = true;
  const RunPolicy& policy = *run_->policy;
  LoadSteps steps(*run_, dir_);
  prepareLoadSteps(steps);
  runLoadSteps(steps);
  policy.evaluateFinalState(*run_, steps);
  ContactResult res = fillResult(steps);
  measureContact(res);
  measureFinalState(res);
  writeResultFiles(res, steps);
  if (comm_->getRank() == 0 && run_->verbosity > 0) policy.report(res, *run_, steps);
  return res;
}

void ContactSolver::prepareLoadSteps(LoadSteps& s) {
  ContactRun& r = *run_;
  // Friction (nonlinear_contact only): tangential rows beside the contact rows of every iteration.
  s.iteration.friction = r.friction;
  // A restart continues the friction state of the step it starts from.
  s.iteration.frictionBounds = r.frictionHistory.bounds;
  if (comm_->getRank() == 0 && r.verbosity > 1 && r.policy->printsIterations())
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
  if (comm_->getRank() != 0 || dir_.empty() || !run_->policy->savesSteps()) return;
  writeIterationsCsv(dir_ + "/iterations.csv", run_->history);
  writeStepsCsv(dir_ + "/steps.csv", run_->history);
}

// The load steps: attempt, then accept (commit, record, save) or cut back.
void ContactSolver::runLoadSteps(LoadSteps& s) {
  ContactRun& r = *run_;
  NonlinearHistory& history = r.history;
  while (!s.control.finished()) {
    if (s.control.stopRequested()) {
      s.stopped = true;
      break;
    }
    const double t = s.control.nextLoadFactor();
    const int step = s.control.nextStep();
    FixedPointRecord fixedPoint;
    if (r.frictionSticks)
      s.iteration.frictionBounds = stickingBounds(r.spec, r.model->problem, r.friction);
    StepOutcome out = attemptFrictionalStep(s.iteration, *r.solver, r.model->problem,
                                            r.options.rule, step, t, fixedPoint);
    s.lastQp = out.qp;
    const bool kept = out.converged || r.policy->keepsUnconvergedStep();
    if (!out.converged && kept) {  // reported as its QP's failure (exit code 2), not retried
      s.qpFailed = true;
      s.failure = out.reason;
    }
    for (auto& it : out.iterations) it.accepted = kept;
    history.iterations.insert(history.iterations.end(), out.iterations.begin(),
                              out.iterations.end());
    if (!kept) {
      if (!rejectStep(s, step, t, out.reason)) break;
      continue;
    }
    acceptStep(s, step, t, out, fixedPoint);
    if (r.policy->savesSteps()) saveStep(s, history.steps.back());
  }
}

// A step that did not converge: revert it and cut back; false when no cut-back is left.
bool ContactSolver::rejectStep(LoadSteps& s, int step, double t, const std::string& reason) {
  ContactRun& r = *run_;
  r.model->revert();
  if (comm_->getRank() == 0 && r.verbosity > 0)
    std::cout << "nonlinear_contact: step " << step << " at load factor " << t
              << " rejected: " << reason << " [" << r.elapsed() << "]\n";
  const int cutbacks = s.control.cutbacks();
  if (!s.control.reject()) {
    s.failed = true;
    std::ostringstream msg;
    msg << "load step " << step << " (load factor " << t << ") did not converge after " << cutbacks
        << " cut-backs";
    if (s.control.belowSmallest())
      msg << " (a smaller increment would fall below the smallest allowed, the nominal one / 2^"
             "Maximum cutbacks = "
          << s.control.smallestIncrement() << ")";
    msg << ": " << reason;
    if (r.frictionLimit && t > r.frictionLimit->loadFactor)
      msg << " (" << frictionLimitText(*r.frictionLimit) << ")";
    s.failure = msg.str();
    return false;
  }
  writeTables();
  return true;
}

// An accepted step: record its figures, commit the state.
void ContactSolver::acceptStep(LoadSteps& s, int step, double t, StepOutcome& out,
                               const FixedPointRecord& fixedPoint) {
  ContactRun& r = *run_;
  NonlinearModel& model = *r.model;
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
  r.policy->evaluateStep(r, s, out.u, rec);
  model.commit();
  model.u = std::move(out.u);
  if (s.iteration.friction.coulomb())
    s.fixedPointSteps.push_back({step, fixedPoint.iterations, fixedPoint.change});
  r.history.steps.push_back(rec);
  s.control.accept();
}

// A converged step's files (VTU, contact CSV, tables, restart) and progress line.
void ContactSolver::saveStep(LoadSteps& s, const StepRecord& rec) {
  ContactRun& r = *run_;
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

// The run's description: the problem, the FETI dimensions, the last QP, the history and how
// the run ended.
ContactResult ContactSolver::fillResult(const LoadSteps& s) const {
  const ContactRun& r = *run_;
  const ElasticContactProblem& problem = r.model->problem;
  const tfeti::FetiSolver& solver = *r.solver;
  const NonlinearOptions& opt = r.options;
  ContactResult res;
  res.problem = r.policy->name();
  res.ranks = comm_->getSize();
  res.subdomains = problem.numSubdomains();
  res.distribution = problem.distribution;
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
  res.converged = !s.failed && !s.stopped && !s.qpFailed;
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
  res.frictionLimit = r.frictionLimit;
  return res;
}

// The contact zone of the final state: p_max, extent, force against the applied load, Hertz
// where it applies, and what the policy adds.
void ContactSolver::measureContact(ContactResult& res) const {
  const ContactRun& r = *run_;
  const ElasticContactProblem& problem = r.model->problem;
  const NonlinearOptions& opt = r.options;
  const NonlinearHistory& history = r.history;
  const int dim = problem.dim();
  const bool haveStep = !history.steps.empty();
  ContactMeasures& c = res.contact;
  res.haveContact = haveStep && r.evaluated;
  if (haveStep) {
    const StepRecord& last = history.steps.back();
    c.constraints = r.solver->constraintReport();
    c.pMax = last.pMax;
    c.extent = last.contactExtent;
    c.extentKey = dim == 3 && !opt.rule.line ? "contact_radius"
                  : opt.rule.angle           ? "angle"
                                             : "half_width";
    c.force = last.contactForce;
    c.appliedForce = r.policy->appliedForce(r);
    c.forceRelativeError =
        c.appliedForce > 0.0 ? std::abs(c.force - c.appliedForce) / c.appliedForce : 0.0;
    // Hertz is of the full load (the one-step case's only step is at load factor 1).
    if (history.loadFactor > 1.0 - 1e-12)
      c.hertz = hertzReference(params_, c.pMax, c.extent, dim, contactBodyLaws(r.spec, problem));
    c.pMaxRecovered = maxRecoveredPressure(r.nodes);
    res.maxVonMises = last.maxVonMises;
    res.maxVonMisesNodal = r.maxVonMisesNodal;
    if (c.hertz)
      addRecoveredErrors(*c.hertz, c.pMaxRecovered, res.maxVonMises, res.maxVonMisesNodal);
    r.policy->addContactMeasures(c, r);
    res.maxPlasticStrain = last.maxPlasticStrain;
  }
  res.contactNodes = r.nodes;
  if (problem.namedPairs && res.haveContact) res.pairs = pairForces(problem, r.nodes);
}

// The final state's largest displacement, the reactions of the prescribed entries and the
// coupled boundaries' common values, the solver's timings.
void ContactSolver::measureFinalState(ContactResult& res) {
  const ContactRun& r = *run_;
  const NonlinearModel& model = *r.model;
  const ElasticContactProblem& problem = model.problem;
  const bool haveStep = !r.history.steps.empty();
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
  if (!r.spec.prescribed.empty() && r.evaluated) {
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
void ContactSolver::writeResultFiles(ContactResult& res, const LoadSteps& s) {
  const ContactRun& r = *run_;
  const bool files = !dir_.empty();
  if (files) {
    res.contactCsv = dir_ + "/contact_pressure.csv";
    r.policy->writeFinalState(res, r, s, dir_);
    if (r.policy->savesSteps()) {
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
