#include "contact_NonlinearIteration.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <utility>

#include "contact_ContactMaster.hpp"
#include "contact_PrescribedDisplacement.hpp"
#include "contact_TangentialRows.hpp"

namespace contact {

ResidualCheck checkResidual(const tfeti::Comm& comm, const Field& load,
                            const Field& multiplierForces, const Field& fint, const Field& u,
                            const Field& du, double loadNorm, const NonlinearOptions& options) {
  Field res(u.size());
  for (std::size_t i = 0; i < u.size(); ++i) {
    res[i].resize(u[i].size());
    for (std::size_t k = 0; k < u[i].size(); ++k)
      res[i][k] = load[i][k] - multiplierForces[i][k] - fint[i][k];
  }
  ResidualCheck c;
  c.solutionNorm = globalNorm(comm, u);
  c.relativeIncrement = c.solutionNorm > 0.0 ? globalNorm(comm, du) / c.solutionNorm : 0.0;
  // Without an applied load (an obstacle's prescribed motion) the internal forces, which then
  // balance the reactions, are the scale.
  const double scale = loadNorm > 0.0 ? loadNorm : globalNorm(comm, fint);
  c.relativeResidual = scale > 0.0 ? globalNorm(comm, res) / scale : 0.0;
  c.converged = c.relativeIncrement < options.eta1 && c.relativeResidual < options.eta2;
  return c;
}

LoadStepIteration::LoadStepIteration(const Teuchos::RCP<const tfeti::Comm>& comm,
                                     NonlinearModel& model, tfeti::FetiSolver& solver,
                                     const NonlinearOptions& options, double loadNorm)
    : comm_(comm), model_(model), solver_(solver), options_(options), loadNorm_(loadNorm) {}

void LoadStepIteration::moveFrozenGaps(const std::vector<double>& current) const {
  ElasticContactProblem& problem = model_.problem;
  std::vector<double> moved(current.size(), 0.0);
  for (std::size_t i = 0; i < current.size(); ++i)
    moved[i] = current[i] - (i < frozenAt_.size() ? frozenAt_[i] : 0.0);
  for (std::size_t k = 0; k < problem.contact.rows.size(); ++k)
    problem.contact.rows[k].gap =
        frozenGaps_[k] - applyRow(problem.contact.rows[k], problem.dim(), moved);
  setInequalitiesFromRows(problem, comm_->getRank());
}

namespace {

// Every rigid obstacle's master where its prescribed motion has taken it at load factor t (one
// obstacle at most moves: checkNonlinearOptionsFor), searching radiusFactor times its radius;
// without a motion only when `always` (a master searching another radius is put back).
void placeObstacles(ElasticContactProblem& problem, const NonlinearOptions& options, double t,
                    double radiusFactor, bool always) {
  if (options.obstacleDisplacement.empty() && !always) return;
  for (auto& pair : problem.pairs) {
    if (!pair.spec.obstacle) continue;
    ContactPairSpec at = pair.spec;
    if (!options.obstacleDisplacement.empty())
      for (int c = 0; c < at.obstacle->dim; ++c)
        at.obstacle->point[c] += t * options.obstacleDisplacement[c];
    ContactSearchOptions search;
    search.searchRadius = radiusFactor * pair.searchRadius;
    pair.master = makePairMaster(problem.mesh, at, search);
  }
}

// FNV-1a over each row's slave node, facet and entries' nodes: the rows' topology (their gaps
// and coefficients move with u every iteration).
std::size_t rowTopology(const std::vector<ContactRow>& rows) {
  std::size_t h = 1469598103934665603ull;
  const auto mix = [&](long long v) { h = (h ^ static_cast<std::size_t>(v)) * 1099511628211ull; };
  for (const ContactRow& row : rows) {
    mix(row.slaveNode);
    mix(row.facet);
    for (const NodeEntry& e : row.entries) mix(e.node);
  }
  return h;
}

}  // namespace

void searchContactAt(const tfeti::Comm& comm, NonlinearModel& model,
                     const NonlinearOptions& options, double t) {
  placeObstacles(model.problem, options, t, 1.0, false);
  contact::updateContact(model.problem, model.surfaceDisplacement(comm, model.u), comm.getRank());
}

void searchContactAtReference(ElasticContactProblem& problem, const NonlinearOptions& options,
                              double t, int rank) {
  placeObstacles(problem, options, t, 1.0, false);
  contact::updateContact(problem, {}, rank);
}

bool LoadStepIteration::keepsRowsInStep() const {
  const ElasticContactProblem& problem = model_.problem;
  if (problem.pairs.size() != 1 || friction.active()) return false;
  const ContactPairSpec& spec = problem.pairs.front().spec;
  // Frictionless only: a tied or bonded row holds at any gap. Mortar rows integrate the gap over
  // facets, where the radius does not only select rows.
  return spec.obstacle && spec.contactType == "frictionless" &&
         spec.discretization == "node_to_segment";
}

void LoadStepIteration::keepStepRows() const {
  ElasticContactProblem& problem = model_.problem;
  const double radius = problem.pairs.front().searchRadius;
  std::vector<ContactRow> kept;
  for (ContactRow& row : problem.contact.rows)
    if (std::abs(row.gap) <= radius ||
        std::binary_search(stepRowNodes_.begin(), stepRowNodes_.end(), row.slaveNode))
      kept.push_back(std::move(row));
    else
      ++problem.contact.beyondRadius;
  problem.contact.rows = std::move(kept);
  problem.rowPair.assign(problem.contact.rows.size(), 0);
  setInequalitiesFromRows(problem, comm_->getRank());
}

void LoadStepIteration::rememberStepRows() const {
  stepRowNodes_.clear();
  for (const ContactRow& row : model_.problem.contact.rows) stepRowNodes_.push_back(row.slaveNode);
  std::sort(stepRowNodes_.begin(), stepRowNodes_.end());
}

void LoadStepIteration::updateContact(const Field& u, double t) const {
  ElasticContactProblem& problem = model_.problem;
  const bool keeps = keepsRowsInStep();
  const bool keepRows = keeps && !contactFrozen_ && !stepRowNodes_.empty();
  placeObstacles(problem, options_, t, keepRows ? kKeptRowRadius : 1.0, keeps);
  const std::vector<double> current = model_.surfaceDisplacement(*comm_, u);
  if (contactFrozen_) {
    moveFrozenGaps(current);
  } else {
    contact::updateContact(problem, current, comm_->getRank());
    if (keepRows) keepStepRows();
    if (keeps) rememberStepRows();
  }
  contactAt_ = current;
  const std::size_t topology = rowTopology(problem.contact.rows);
  rowsMoved_ = rowsMoved_ || topology != rowTopology_;
  rowTopology_ = topology;
  if (friction.active()) {
    const std::vector<tfeti::InequalityRow> rows =
        frictionRows(problem, friction, frictionBounds,
                     model_.surfaceDisplacement(*comm_, model_.u), current, comm_->getRank());
    problem.inequalities.insert(problem.inequalities.end(), rows.begin(), rows.end());
  }
}

Field LoadStepIteration::incrementLoads(const Field& fint, double t) const {
  Field rhs = loadAt(model_.problem, t);
  for (std::size_t i = 0; i < fint.size(); ++i)
    for (std::size_t k = 0; k < rhs[i].size(); ++k) rhs[i][k] -= fint[i][k];
  return rhs;
}

std::vector<tfeti::EqualityRow> LoadStepIteration::prescribedIncrementRows(const Field& u,
                                                                           double t) const {
  // The increment du must take every prescribed component from where u has it to t times its
  // value: the rows du = t value - u (zero rows after the first iteration of a step).
  return equalityRowsAt(model_.problem, t, u);
}

LoadStepIteration::TangentPlan LoadStepIteration::planTangent(int iteration) const {
  TangentPlan plan;
  plan.refactor =
      options_.stiffness == "iteration" || (options_.stiffness == "step" && iteration == 1);
  if (!plan.refactor || options_.kinematics != plasticity::Kinematics::SmallStrain) return plan;
  // In small strain a subdomain's tangent with every point elastic is its elastic stiffness:
  // where the factor holds that already (the solver is built with it), the tangent is neither
  // assembled nor refactorized, and with no subdomain left to refactorize the solver only
  // updates its rows.
  const std::vector<char> loading = model_.plasticLoadingPerSubdomain();
  factorIsElastic_.resize(loading.size(), 1);
  plan.keep.resize(loading.size());
  int local = 0;
  for (std::size_t i = 0; i < loading.size(); ++i) {
    plan.keep[i] = !loading[i] && factorIsElastic_[i];
    local = plan.keep[i] ? local : 1;
  }
  int any = 0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 1, &local, &any);
  plan.refactor = any == 1;
  if (plan.refactor)
    for (std::size_t i = 0; i < loading.size(); ++i)
      if (!plan.keep[i]) factorIsElastic_[i] = !loading[i];
  // A solver that has freed its matrices ("Keep subdomain matrices" = false) cannot keep a K
  // it no longer holds: it gets the assembled one, whose factor it still keeps if unchanged.
  for (std::size_t i = 0; i < plan.keep.size(); ++i)
    if (plan.keep[i] && !solver_.subdomains()[i]->hasStiffness()) plan.keep[i] = 0;
  return plan;
}

tfeti::DualResult LoadStepIteration::solveIncrement(const Field& u, const Field& fint, double t,
                                                    int iteration) const {
  if (options_.solveAsBuilt && iteration == 1) return solver_.solve();
  const Field rhs = incrementLoads(fint, t);
  const std::vector<tfeti::EqualityRow> prescribed = prescribedIncrementRows(u, t);
  const TangentPlan plan = planTangent(iteration);
  // Inexact solves and partial steps leave jumps in u: the next increment closes them.
  if (inexact()) solver_.setIncrementOrigin(u);
  if (plan.refactor)
    solver_.updateStiffness(model_.tangent(u, options_.kinematics, plan.keep),
                            model_.kernelCoordinates(u, options_.kinematics), rhs,
                            model_.problem.inequalities, prescribed);
  else
    solver_.update(rhs, model_.problem.inequalities, prescribed);
  return solver_.solve();
}

bool LoadStepIteration::inexact() const {
  return options_.inexactQpFactor > 1.0 || options_.lineSearch;
}

double LoadStepIteration::loadNormAt(const Field& load, double t) const {
  // With ramped loads the load's norm at t is the scale; proportional loading keeps t ||f||
  // (the same number, computed as it always was).
  return model_.problem.rampedLoads.empty() ? t * loadNorm_
         : loadNorm_ > 0.0                  ? globalNorm(*comm_, load)
                                            : 0.0;
}

LoadStepIteration::Trial LoadStepIteration::tryStep(const Field& u, const Field& du, double alpha,
                                                    const Field& forces,
                                                    const Field& previousForces, double t) const {
  Trial trial;
  trial.alpha = alpha;
  trial.u = u;
  trial.du = du;
  trial.forces = forces;
  for (std::size_t i = 0; i < u.size(); ++i)
    for (std::size_t k = 0; k < u[i].size(); ++k) {
      trial.du[i][k] *= alpha;
      trial.u[i][k] += trial.du[i][k];
      // The multipliers move with the step: B^T lambda from the previous iteration's towards
      // this QP's.
      if (alpha != 1.0)
        trial.forces[i][k] = previousForces[i][k] + alpha * (forces[i][k] - previousForces[i][k]);
    }
  trial.fint = model_.internalForce(trial.u, options_.kinematics);
  const Field load = loadAt(model_.problem, t);
  trial.check = checkResidual(*comm_, load, trial.forces, trial.fint, trial.u, trial.du,
                              loadNormAt(load, t), options_);
  return trial;
}

bool LoadStepIteration::twoCycle(const std::vector<IterationRecord>& it) {
  const std::size_t n = it.size();
  if (n < 4) return false;
  const IterationRecord &a = it[n - 3], &b = it[n - 2], &c = it[n - 1];
  return std::abs(c.solutionNorm - a.solutionNorm) <= 1e-9 * c.solutionNorm &&
         std::abs(c.relativeIncrement - b.relativeIncrement) <= 1e-3 * c.relativeIncrement &&
         c.relativeIncrement > 0.0;
}

void LoadStepIteration::freezeContact(int step, int iteration, double relativeIncrement) const {
  contactFrozen_ = true;
  frozenAt_ = contactAt_;
  frozenGaps_.clear();
  for (const ContactRow& row : model_.problem.contact.rows) frozenGaps_.push_back(row.gap);
  if (comm_->getRank() == 0)
    std::cout << "  step " << step << " iteration " << iteration
              << ": the contact update alternates between two states (||du||/||u|| = "
              << relativeIncrement
              << " twice, u back where it was): its rows are kept for the rest of the step"
              << std::endl;
}

void LoadStepIteration::tightenQps(int step, int iteration, double relativeIncrement,
                                   const BoundsUpdate& bounds, double factor) const {
  if (comm_->getRank() != 0) return;
  std::cout << "  step " << step << " iteration " << iteration
            << ": with the residual below Eta 2, ||du||/||u|| = " << relativeIncrement;
  if (bounds.tolerance > 0.0)
    std::cout << " and the slip bounds' relative change " << bounds.change;
  std::cout << " stopped decreasing (the QPs' accuracy): the step's next QPs stop at " << factor
            << " times the configured tolerances" << std::endl;
}

bool LoadStepIteration::stalledAtQpAccuracy(const ResidualCheck& check, const BoundsUpdate& bounds,
                                            double factor, StallWatch& watch) const {
  // How far from the step's test the residual's equilibrium leaves it (above 1: not there).
  const double distance = std::max(check.relativeIncrement / options_.eta1,
                                   bounds.tolerance > 0.0 ? bounds.change / bounds.tolerance : 0.0);
  // Every rank finds the same rows; the decision sets every rank's QP tolerance, so it is made
  // collectively all the same.
  int moved = rowsMoved_ ? 1 : 0, anyMoved = 0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 1, &moved, &anyMoved);
  rowsMoved_ = false;
  const bool stalled = check.relativeResidual < options_.eta2 && factor <= 1.0 && anyMoved == 0 &&
                       distance > kStallContraction * watch.previousDistance;
  watch.stalls = stalled ? watch.stalls + 1 : 0;
  watch.previousDistance = distance;
  return watch.stalls == kStalls;
}

StepOutcome LoadStepIteration::attempt(int step, double t) const {
  contactFrozen_ = false;
  stepRowNodes_.clear();
  rowsMoved_ = true;
  StepOutcome out;
  out.u = model_.u;
  Field& u = out.u;
  try {
    // The increment the solver was built with has its loads (f - f_int(0) = f) already.
    Field fint = options_.solveAsBuilt ? Field() : model_.internalForce(u, options_.kinematics);
    // Inexact Newton: the first QP of a step at the loosest tolerance, later ones from the
    // residual they start from.
    double factor = options_.inexactQpFactor;
    // An exact QP's factor: 1 unless the step's test stalls (tightenQps).
    double exactFactor = 1.0;
    StallWatch stall;
    Field previousForces;
    double previousResidual = 0.0;
    for (int it = 1; it <= options_.maxIterations; ++it) {
      if (!(options_.solveAsBuilt && it == 1)) updateContact(u, t);
      solver_.setToleranceFactor(factor);
      // The step's first QP starts from the last step's solution, under another load.
      solver_.setLoadStepStart(it == 1);
      out.qp = solveIncrement(u, fint, t, it);
      solver_.setLoadStepStart(false);
      const tfeti::DualResult& qp = out.qp;
      IterationRecord rec;
      rec.step = step;
      rec.loadFactor = t;
      rec.iteration = it;
      rec.mprgpIterations = qp.iterations;
      rec.hessianMultiplications = qp.qp.hessianMultiplications;
      rec.qpToleranceFactor = factor;
      if (!qp.converged && !options_.singleIncrement) {
        out.iterations.push_back(rec);
        out.reason = "the contact QP did not converge in iteration " + std::to_string(it) + " (" +
                     qp.qp.message + ")";
        return out;
      }
      Field du(u.size());
      for (std::size_t i = 0; i < u.size(); ++i) du[i] = solver_.solution(i);
      const Field forces = solver_.multiplierForces();
      Trial trial = tryStep(u, du, 1.0, forces, forces, t);
      // Backtracking (not on a step's first iteration, which has no residual to compare with,
      // nor once the residual is below Eta 2, where it is rounding): the first halving that
      // decreases ||res||, else the smallest residual tried.
      if (options_.lineSearch && it > 1 && trial.check.relativeResidual >= previousResidual &&
          trial.check.relativeResidual >= options_.eta2) {
        Trial best = trial;
        double alpha = 1.0;
        for (int cut = 1; cut <= options_.lineSearchCuts; ++cut) {
          alpha *= 0.5;
          Trial half = tryStep(u, du, alpha, forces, previousForces, t);
          const bool decreases = half.check.relativeResidual < previousResidual;
          if (half.check.relativeResidual < best.check.relativeResidual) best = std::move(half);
          if (decreases) break;
        }
        trial = std::move(best);
      }
      u = std::move(trial.u);
      fint = std::move(trial.fint);
      const ResidualCheck& check = trial.check;
      rec.solutionNorm = check.solutionNorm;
      rec.relativeIncrement = check.relativeIncrement;
      rec.relativeResidual = check.relativeResidual;
      rec.lineSearchStep = trial.alpha;
      out.iterations.push_back(rec);
      if (onIteration) onIteration(rec);
      if (options_.singleIncrement) {  // its state is kept and reported either way
        out.converged = qp.converged;
        if (!qp.converged) out.reason = "the contact QP did not converge (" + qp.qp.message + ")";
        return out;
      }
      const BoundsUpdate bounds = updateBounds ? updateBounds() : BoundsUpdate();
      // Only a full step of an exact QP ends a step: the multipliers reported are that QP's.
      if (check.converged && bounds.settled && factor <= 1.0 && trial.alpha == 1.0) {
        out.converged = true;
        return out;
      }
      if (!contactFrozen_ && !check.converged && twoCycle(out.iterations))
        freezeContact(step, it, check.relativeIncrement);
      if (stalledAtQpAccuracy(check, bounds, factor, stall) && exactFactor == 1.0) {
        exactFactor = kTighterQp;
        tightenQps(step, it, check.relativeIncrement, bounds, exactFactor);
      }
      factor =
          check.converged || options_.inexactQpFactor == 1.0
              ? exactFactor
              : std::clamp(check.relativeResidual / options_.eta2, 1.0, options_.inexactQpFactor);
      previousForces = std::move(trial.forces);
      previousResidual = check.relativeResidual;
    }
    out.reason = "no convergence in " + std::to_string(options_.maxIterations) + " iterations";
  } catch (const plasticity::InvertedDeformationError& e) {
    out.reason = e.what();
  }
  return out;
}

}  // namespace contact
