#pragma once
// SmalbeSolMgr: SMALBE-M (Dostál, "Optimal Quadratic Programming Algorithms", 2009: the
// semi-monotonic augmented Lagrangian method for bound and equality constraints with a fixed
// penalty rho and an adaptive precision control M) for
//   min 1/2 x^T A x - b^T x  subject to  l <= x <= u  and  Q x = 0   (u optional),
// Q an orthogonal projector (Q = Q^T = Q^2) onto the range of the equality-constraint rows, so
// ||Q x|| is the equality residual. With the multiplier mu in range(Q), the augmented Lagrangian
//   L(x, mu, rho) = 1/2 x^T (A + rho Q) x - b^T x + mu^T x
// is minimized subject to l <= x <= u by MPRGP (Hessian H = A + rho Q applied as an OperatorSum),
// warm-started from the previous x, to the precision
//   ||g^P(x, mu_k)|| <= min(M_k ||Q x||, eta)
// (or until SMALBE's final test holds, see below); then mu_{k+1} = mu_k + rho Q x_k, and M is
// divided by beta when L did not increase enough (k > 0; each L at the multiplier of its own
// inner solve, as published; a shortfall below the rounding level of L does not count):
//   L(x_k, mu_k, rho) < L(x_{k-1}, mu_{k-1}, rho) + rho/2 ||Q x_k||^2   =>   M_{k+1} = M_k / beta.
// The next inner solve starts at x_k with the gradient g_k + rho Q x_k (no multiplication).
// SMALBE stops when ||g^P|| <= tol ||b|| and ||A|| ||Q x|| <= tolE ||b||; g = A x - b + mu with
// the final mu (getMultiplier), the gradient of the Lagrangian, so the KKT conditions read
// g^P = 0 and Q x = 0.
//
// Parameters (getValidParameters(); unknown names throw). ||A|| is the given "Norm of A" or the
// power-iteration estimate, which makes every parameter below invariant to scaling A, b or x:
//  "Relative tolerance"        1e-6  ||g^P|| <= tol * ||b||
//  "Equality tolerance"        1e-6  ||A|| * ||Q x|| <= tolE * ||b|| (||A|| Q x has the units
//                                    of b)
//  "Maximum outer iterations"  100   limit on the multiplier updates
//  "Penalty"                   1.0   rho = Penalty * ||A||
//  "Initial M"                 1.0   M_0 = value * ||A||
//  "Beta"                      10.0  M is divided by Beta when the Lagrangian does not increase
//                                    enough (> 1)
//  "Lagrangian test"           "Dostal"  the test above; "shifted": L(x_k, mu_{k+1}) against
//                                    L(x_{k-1}, mu_k), the earlier implementation, which asks for
//                                    about rho ||Q x_{k-1}||^2 and fails almost always
//  "Reuse gradient"            true  start the inner solves from g_k + rho Q x_k; false: one
//                                    multiplication per outer iteration (the earlier behaviour)
//  "Eta"                       0.1   eta = value * ||b||
//  "Norm of A"                 0.0   ||A|| of the unaugmented Hessian; 0: power iterations
//  "Power iterations"          20    for the estimate of ||A||
//  "Verbosity"                 0     0 silent, 1 summary, 2 every outer iteration (rank 0)
//  sublist "MPRGP"                   the inner solver's parameters (MprgpSolMgr); SMALBE replaces
//                                    its stopping test by the rule above and its "Norm of A" by
//                                    ||A|| + rho (an upper bound of ||A + rho Q||, no power
//                                    iterations); "Maximum iterations" limits each inner solve.
// When b = 0, ||b|| in the tolerances is replaced by ||A P(0)|| as in MPRGP.
#include <BelosTypes.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>

#include "tfeti_QpProblem.hpp"

namespace tfeti {

template <class S, class MV, class OP>
class SmalbeSolMgr {
 public:
  using magnitude_type = typename Teuchos::ScalarTraits<S>::magnitudeType;

  // qp.A is the unaugmented Hessian; qp.x holds the initial guess and receives the solution.
  // The preconditioner goes to MPRGP (used with "Preconditioning in face" in the sublist).
  SmalbeSolMgr(const BoundConstrainedQp<S, MV, OP>& qp, Teuchos::RCP<const OP> Q,
               const Teuchos::ParameterList& params,
               Teuchos::RCP<const OP> preconditioner = Teuchos::null);

  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
  const Teuchos::ParameterList& getCurrentParameters() const { return params_; }

  // The augmented Hessian A + rho Q applied by the caller's own operator (e.g. one that shares
  // work between A and Q) instead of the OperatorSum of the two; its rho must be
  // penaltyFor(||A||), the "Penalty" parameter times the "Norm of A" given.
  void setAugmentedHessian(Teuchos::RCP<const OP> H) { augmented_ = std::move(H); }
  // Starting multiplier (in range(Q); default zero).
  void setInitialMultiplier(Teuchos::RCP<const MV> mu0) { mu0_ = std::move(mu0); }
  // Progress lines of SMALBE and its inner MPRGP (Verbosity >= 1, rank 0) go here, e.g. a
  // Teuchos::FancyOStream; null: std::cout. Its format state is never changed.
  void setOutputStream(Teuchos::RCP<std::ostream> os) { out_.setStream(std::move(os)); }

  // Converged, or Unconverged with counters().message saying why. Throws like MPRGP.
  Belos::ReturnType solve();

  // Counters summed over all inner solves; history: ||g^P|| / ||b|| per outer iteration.
  const QpCounters& counters() const { return counters_; }
  // The equality multiplier mu (in range(Q)): A x - b + mu is the Lagrangian's gradient.
  Teuchos::RCP<const MV> getMultiplier() const { return mu_; }
  long long projectorApplications() const { return qApplies_; }
  magnitude_type getNormOfA() const { return normA_; }
  magnitude_type getPenalty() const { return rho_; }
  magnitude_type getM() const { return M_; }

 private:
  BoundConstrainedQp<S, MV, OP> qp_;
  Teuchos::RCP<const OP> Q_, P_, augmented_;
  Teuchos::ParameterList params_;
  Teuchos::RCP<const MV> mu0_;
  Teuchos::RCP<MV> mu_;
  QpCounters counters_;
  long long qApplies_ = 0;
  magnitude_type normA_ = 0, rho_ = 0, M_ = 0;
  SolverOutput out_;
};

}  // namespace tfeti
