#pragma once
// A load step of a frictional nonlinear run. Tresca: the step as it is (its bounds are fixed).
// Coulomb: the fixed point on the slip bound g_i = mu lambda_N,i (contact_Friction.hpp): each
// fixed-point iteration solves the whole step (LoadStepIteration::attempt, from the step's start)
// with the bounds of the previous iterate, then sets them to mu times the normal multipliers of
// its last solve; it stops when the relative change ||g_new - g|| / ||g_new|| is below the
// Fixed-point tolerance (0 / 0, no node in contact or mu = 0, counts as converged), and the step
// is rejected (cut back by the step control) after Fixed-point iterations without. With
// `Coulomb scheme` = in_newton the bounds are set to mu lambda_N after every Newton iteration's
// QP instead, and the one Newton loop stops when Eta 1, Eta 2 and the Fixed-point tolerance hold
// together (its Maximum iterations bound it): one Newton loop per step instead of one per
// fixed-point iteration.
#include "contact_NonlinearIteration.hpp"

namespace contact {

struct FixedPointRecord {
  int iterations = 0;   // fixed-point iterations of the step (1 for Tresca; in_newton: updates)
  double change = 0.0;  // the last relative change of the slip bounds (Coulomb)
};

// iteration.frictionBounds is the fixed point's state: the converged step leaves its final
// bounds there (the next step starts from them), a rejected one restores those it started with.
StepOutcome attemptFrictionalStep(LoadStepIteration& iteration, const tfeti::FetiSolver& solver,
                                  const ElasticContactProblem& problem,
                                  const ContactExtentRule& rule, int step, double t,
                                  FixedPointRecord& record);

}  // namespace contact
