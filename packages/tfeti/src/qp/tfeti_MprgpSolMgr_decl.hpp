#pragma once
// MprgpSolMgr: the MPRGP solver for  min 1/2 x^T A x - b^T x  subject to  l <= x <= u  (see
// tfeti_MprgpIteration_decl.hpp for the algorithm), set up like Belos' solver managers: a
// validated parameter list, status tests (Belos::StatusTestMaxIters OR the projected-gradient
// test), an iteration object, and solve() returning Belos::Converged or Belos::Unconverged.
// A problem with disc constraints (BoundConstrainedQp::discs) is solved by MPGP, the same
// iteration on intervals and discs; MpgpSolMgr names it.
//
// Parameters (getValidParameters() lists them with these defaults; unknown names throw):
//  "Relative tolerance"   1e-6   stop when ||g^P|| <= tol * ||b|| (when b = 0: tol * ||A P(0)||,
//                                the gradient at the feasible point nearest 0; if that is 0 too,
//                                x = P(0) solves the problem)
//  "Maximum iterations"   10000  limit on MPRGP steps (CG + expansion + proportioning)
//  "Gamma"                1.0    proportioning parameter: x is proportional when
//                                ||beta||^2 <= Gamma^2 phi~^T phi
//  "Step length factor"   1.9    alphaBar = factor / ||A||, in (0, 2]
//  "Expansion step"       "fixed"  fixed: P(x - alphaBar phi) after the feasible half step;
//                                optimal: the line-search length along -phi, falling back to
//                                alphaBar; projected CG: P(x - alphaCg p), falling back to the
//                                fixed step when f is above f at the feasible half step
//  "Norm of A"            0.0    ||A|| (an upper bound is best); 0: estimate by power iterations
//  "Power iterations"     20     power iterations for the estimate of ||A||
//  "Preconditioning in face" false  CG directions M phi restricted to the free set (needs the
//                                constructor's preconditioner M ~ A^{-1})
//  "Verbosity"            0      0 silent, 1 summary, 2 every step (rank 0, std::cout or the
//                                stream given), or a Belos::MsgType mask: FinalSummary (the
//                                summary), IterationDetails (every step), Warnings (a line when
//                                not converged), TimingDetails (the solve's and the Hessian's
//                                time), StatusTestDetails (the status tests at the end)
// Belos's names are accepted as aliases: "Convergence Tolerance" = "Relative tolerance",
// "Maximum Iterations" = "Maximum iterations" (tfeti_SolverConventions.hpp). Timers (Teuchos::
// TimeMonitor): "tfeti: MPRGP solve" per solve, "tfeti: Hessian apply" per multiplication by A
// (Tpetra operators), the power iterations included.
//
// The estimate of ||A||: ||A v_k|| for the k-th normalized power iterate v_k, started from a
// deterministic vector that depends only on global indices (the same on any number of ranks),
// times 1.05, because power iteration approaches ||A|| from below and alphaBar must not exceed
// 2 / ||A||. It costs "Power iterations" multiplications, which are counted.
#include <BelosStatusTest.hpp>
#include <BelosTypes.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>

#include "tfeti_QpProblem.hpp"
#include "tfeti_SolverConventions.hpp"
#include "tfeti_SolverOutput.hpp"

namespace tfeti {

template <class S, class MV, class OP>
class MprgpSolMgr {
 public:
  using magnitude_type = typename Teuchos::ScalarTraits<S>::magnitudeType;

  // qp.x holds the initial guess (projected onto the bounds if infeasible) and receives the
  // solution; qp.upper (optional) adds upper bounds. The preconditioner is used only with
  // "Preconditioning in face" = true.
  MprgpSolMgr(const BoundConstrainedQp<S, MV, OP>& qp, const Teuchos::ParameterList& params,
              Teuchos::RCP<const OP> preconditioner = Teuchos::null);
  // Belos's way: construct, then setProblem and setParameters (defaults until then).
  MprgpSolMgr();

  // The problem to solve (A, b, lower and x must be set); the next solve() starts from qp.x.
  void setProblem(const BoundConstrainedQp<S, MV, OP>& qp);
  const BoundConstrainedQp<S, MV, OP>& getProblem() const { return qp_; }
  // M ~ A^{-1} for "Preconditioning in face".
  void setPreconditioner(Teuchos::RCP<const OP> preconditioner);
  // Changes the parameters given (Belos aliases resolved) and keeps the others as they are.
  void setParameters(const Teuchos::ParameterList& params);
  void setParameters(const Teuchos::RCP<Teuchos::ParameterList>& params) { setParameters(*params); }
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
  // The parameters in use, defaults filled in, under the package's names.
  const Teuchos::ParameterList& getCurrentParameters() const { return params_; }
  // Resolves the Belos aliases in params, validates it against getValidParameters() (defaults
  // filled in) and checks the values; throws std::invalid_argument naming the parameter.
  static void checkParameters(Teuchos::ParameterList& params);
  // Forgets the results of the last solve (counters, gradient, the initial gradient given) and,
  // with Belos::Problem, the estimate of ||A|| (the problem changed). Settings stay.
  void reset(Belos::ResetType type = Belos::Problem);

  // An extra convergence test, ORed with the projected-gradient test, or (replaceDefault) used
  // instead of it. "Maximum iterations" always applies. Converged means this test (or the
  // default one) passed.
  void setConvergenceTest(Teuchos::RCP<Belos::StatusTest<S, MV, OP>> test,
                          bool replaceDefault = false);
  // ||A|| (> 0) to use instead of "Norm of A" and the power iterations.
  void setNormOfA(magnitude_type normA);
  // ||A|| used by the last solve (or set).
  magnitude_type getNormOfA() const { return normA_; }
  // g = A x - b at the initial guess x, known to the caller (SMALBE: the last inner gradient
  // plus the multiplier change); saves the first multiplication. Ignored when x is infeasible.
  void setInitialGradient(Teuchos::RCP<const MV> g) { g0_ = std::move(g); }
  // Progress lines (Verbosity >= 1, rank 0) go here, e.g. a Teuchos::FancyOStream; null:
  // std::cout. Its format state is never changed.
  void setOutputStream(Teuchos::RCP<std::ostream> os) { out_.setStream(std::move(os)); }

  // Throws std::runtime_error for a Hessian that is not positive definite on a free set and for
  // NaN/Inf in the data; otherwise Converged, or Unconverged with counters().message saying why.
  Belos::ReturnType solve();

  const QpCounters& counters() const { return counters_; }
  // g = A x - b at the solution (recursively updated between restarts of MPRGP).
  Teuchos::RCP<const MV> getGradient() const { return g_; }
  int getNumIters() const { return numIters_; }
  // ||g^P|| / ||b|| reached by the last solve (the quantity "Relative tolerance" bounds).
  magnitude_type achievedTol() const { return achievedTol_; }

  // ||A v_k|| * 1.05 after k power iterations from a deterministic start (see above); adds the k
  // multiplications to *multiplications when given. start (optional, like's map): a non-zero
  // start replaces the deterministic one; on return it holds the last unit iterate v_k (to
  // start the estimate of a nearby operator from).
  static magnitude_type estimateNorm(const OP& A, const MV& like, int iterations,
                                     long long* multiplications = nullptr, MV* start = nullptr);

 private:
  BoundConstrainedQp<S, MV, OP> qp_;
  Teuchos::RCP<const OP> M_;
  Teuchos::ParameterList params_;
  Teuchos::RCP<Belos::StatusTest<S, MV, OP>> userTest_;
  bool replaceDefault_ = false;
  magnitude_type normA_ = 0;
  bool normGiven_ = false;
  QpCounters counters_;
  Teuchos::RCP<const MV> g_, g0_;
  int numIters_ = 0;
  magnitude_type achievedTol_ = 0;
  SolverOutput out_;
  void checkReady() const;
  Belos::ReturnType solveTimed();
};

// MPGP for problems with disc constraints: the same solver manager.
template <class S, class MV, class OP>
using MpgpSolMgr = MprgpSolMgr<S, MV, OP>;

}  // namespace tfeti
