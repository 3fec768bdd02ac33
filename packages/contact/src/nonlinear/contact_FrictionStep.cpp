#include "contact_FrictionStep.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "contact_ContactOutput.hpp"

namespace contact {

namespace {

// mu lambda_N of the solver's last multipliers per slave node of the Coulomb pairs (each its own
// mu), and the relative change from `bounds` (2-norm; a node that lost its row counts with its
// old bound).
SlipBounds coulombBounds(const tfeti::FetiSolver& solver, const ElasticContactProblem& problem,
                         const ContactExtentRule& rule, const ModelFriction& friction,
                         const SlipBounds& bounds, double& change) {
  SlipBounds next;
  double diff = 0.0, norm = 0.0;
  for (const ContactNode& n : contactNodes(problem, solver, rule, {})) {
    const FrictionSpec& f = friction.ofPair(n.pair);
    if (f.law != FrictionSpec::Law::Coulomb) continue;  // Tresca's bounds are given
    const double g = f.coefficient * std::max(n.lambda, 0.0);
    next[n.slaveNode] = g;
    const auto it = bounds.find(n.slaveNode);
    const double old = it == bounds.end() ? 0.0 : it->second;
    diff += (g - old) * (g - old);
    norm += g * g;
  }
  for (const auto& [node, g] : bounds)
    if (!next.count(node)) diff += g * g;
  change = norm > 0.0 ? std::sqrt(diff / norm) : (diff > 0.0 ? 1.0 : 0.0);
  return next;
}

// The bounds updated after every Newton iteration: one Newton loop whose stopping test also
// needs the bounds' change below the tolerance.
StepOutcome attemptInNewton(LoadStepIteration& iteration, const tfeti::FetiSolver& solver,
                            const ElasticContactProblem& problem, const ContactExtentRule& rule,
                            int step, double t, FixedPointRecord& record) {
  const ModelFriction& f = iteration.friction;
  const SlipBounds start = iteration.frictionBounds;
  iteration.updateBounds = [&]() {
    iteration.frictionBounds =
        coulombBounds(solver, problem, rule, f, iteration.frictionBounds, record.change);
    ++record.iterations;
    return LoadStepIteration::BoundsUpdate{record.change < f.fixedPointTolerance, record.change,
                                           f.fixedPointTolerance};
  };
  StepOutcome out = iteration.attempt(step, t);
  iteration.updateBounds = nullptr;
  if (!out.converged) {
    iteration.frictionBounds = start;
    std::ostringstream s;
    s << "Coulomb with its bounds in the Newton loop (last relative change of the slip bounds "
      << record.change << ", Fixed-point tolerance " << f.fixedPointTolerance
      << "): " << out.reason;
    out.reason = s.str();
  }
  return out;
}

}  // namespace

StepOutcome attemptFrictionalStep(LoadStepIteration& iteration, const tfeti::FetiSolver& solver,
                                  const ElasticContactProblem& problem,
                                  const ContactExtentRule& rule, int step, double t,
                                  FixedPointRecord& record) {
  record = FixedPointRecord();
  const ModelFriction& f = iteration.friction;
  if (!f.coulomb()) {
    record.iterations = 1;
    return iteration.attempt(step, t);
  }
  if (f.scheme == FrictionSpec::Scheme::InNewton)
    return attemptInNewton(iteration, solver, problem, rule, step, t, record);
  const SlipBounds start = iteration.frictionBounds;
  std::vector<IterationRecord> all;  // every fixed-point iteration's Newton iterations
  for (int k = 1; k <= f.maxFixedPointIterations; ++k) {
    StepOutcome out = iteration.attempt(step, t);
    all.insert(all.end(), out.iterations.begin(), out.iterations.end());
    record.iterations = k;
    if (!out.converged) {
      iteration.frictionBounds = start;
      out.iterations = all;
      out.reason = "Coulomb fixed-point iteration " + std::to_string(k) + ": " + out.reason;
      return out;
    }
    // The normal multipliers of the last solve (every rank has them all).
    iteration.frictionBounds =
        coulombBounds(solver, problem, rule, f, iteration.frictionBounds, record.change);
    if (record.change < f.fixedPointTolerance) {
      out.iterations = all;
      return out;
    }
  }
  iteration.frictionBounds = start;
  StepOutcome failed;
  failed.iterations = all;
  std::ostringstream s;
  s << "the Coulomb fixed point did not converge in " << f.maxFixedPointIterations
    << " iterations (relative change of the slip bounds " << record.change
    << " > Fixed-point tolerance " << f.fixedPointTolerance << ")";
  failed.reason = s.str();
  return failed;
}

}  // namespace contact
