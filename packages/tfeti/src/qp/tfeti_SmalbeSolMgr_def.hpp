#pragma once
#include <Teuchos_Assert.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "tfeti_BoundTraits.hpp"
#include "tfeti_FacePcpg.hpp"
#include "tfeti_MprgpSolMgr_def.hpp"
#include "tfeti_OperatorSum.hpp"
#include "tfeti_QpChecks.hpp"
#include "tfeti_QpStatusTests.hpp"
#include "tfeti_SmalbeSolMgr_decl.hpp"
#include "tfeti_StrictParameters.hpp"
#include "tfeti_TimedOperator.hpp"

namespace tfeti {

template <class S, class MV, class OP>
Teuchos::RCP<const Teuchos::ParameterList> SmalbeSolMgr<S, MV, OP>::getValidParameters() {
  static Teuchos::RCP<Teuchos::ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::rcp(new Teuchos::ParameterList("SMALBE"));
    pl->set("Relative tolerance", 1e-6, "stop when ||g^P|| <= tolerance * ||b|| ...",
            strict::positive());
    pl->set("Equality tolerance", 1e-6, "... and ||A|| ||Q x|| <= tolerance * ||b||",
            strict::positive());
    pl->set("Maximum outer iterations", 100, "limit on multiplier updates", strict::count());
    pl->set("Penalty", 1.0, "rho = Penalty * ||A||", strict::positive());
    pl->set("Initial M", 1.0, "M_0 = value * ||A||", strict::positive());
    pl->set("Beta", 10.0, "M is divided by Beta when the Lagrangian does not increase enough",
            strict::between(1.0, std::numeric_limits<double>::infinity(), true, true));
    pl->set("Lagrangian test", "Dostal",
            "Dostal: L(x_k, mu_k) < L(x_{k-1}, mu_{k-1}) + rho/2 ||Q x_k||^2 divides M by Beta "
            "(SMALBE-M as published); shifted: the same with L(x_k, mu_{k+1}) and "
            "L(x_{k-1}, mu_k), the multipliers after the update (the earlier implementation, "
            "which demands an increase of about rho ||Q x_{k-1}||^2 and fails almost always)",
            Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
                Teuchos::tuple<std::string>("Dostal", "shifted"), "Lagrangian test")));
    pl->set("Eta", 0.1, "eta = value * ||b||: inner precision bound", strict::positive());
    pl->set("Reuse gradient", true,
            "start each inner solve from the last inner gradient plus rho Q x (the multiplier "
            "change) instead of a multiplication; false: recompute it (the earlier behaviour)");
    pl->set("Norm of A", 0.0, "||A||; 0: estimate by power iterations", strict::nonNegative());
    pl->set("Power iterations", 20, "power iterations for estimating ||A||", strict::count());
    pl->set("Verbosity", 0,
            "0 silent, 1 summary, 2 every outer iteration (rank 0), or a sum of Belos::MsgType "
            "values (Warnings 1, IterationDetails 2, FinalSummary 8, TimingDetails 16, "
            "StatusTestDetails 32)",
            strict::intBetween(0, kAllMsgTypes));
    pl->set("Face solve", "none",
            "none: SMALBE-M alone; pcpg: once the active set is unchanged over \"Face settle "
            "iterations\" outer iterations, solve on that face (active rows held at their bounds, "
            "Q x = 0 by a projector) by projected preconditioned CG and accept the result only "
            "if it passes SMALBE's final test; otherwise a primal-dual active-set step and a new "
            "face, and after \"Maximum face solves\" back to SMALBE's own iterate",
            Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
                Teuchos::tuple<std::string>("none", "pcpg"), "Face solve")));
    pl->set("Face settle iterations", 1,
            "a face solve follows an outer iteration whose active set equals that of this many "
            "outer iterations before it (0: after every outer iteration)",
            strict::count(0));
    pl->set("Initial face", "none",
            "with Face solve = pcpg: none: the first face is the settled active set of the outer "
            "iterations; levels: before the first outer iteration, a bisection over the level "
            "sets {i : level_i > tau} of the levels the caller gives (FETI: the contact rows' "
            "gaps, open rows held at their bounds) for the face whose loose solve neither leaves "
            "the box nor has multipliers of the wrong sign, then a face solve from it",
            Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
                Teuchos::tuple<std::string>("none", "levels"), "Initial face")));
    pl->set("Maximum face solves", 10,
            "limit on face solves (active-set corrections included) in one SMALBE solve",
            strict::count());
    pl->set("Face maximum iterations", 1000, "limit on the CG steps of one face solve",
            strict::count());
    pl->set("Face relative tolerance", kFaceRelativeTolerance,
            "the face CG stops at ||P_F g|| <= value * \"Relative tolerance\" * ||b||; ||P_F g|| "
            "is the residual of the rows that hold with equality (for FETI ||B u - c|| over the "
            "gluing and contact rows), which SMALBE alone ends well below its tolerance",
            strict::between(0.0, 1.0, true, false));
    pl->sublist("MPRGP", false, "inner solver (MPRGP) parameters")
        .setParameters(*MprgpSolMgr<S, MV, OP>::getValidParameters());
  }
  return pl;
}

template <class S, class MV, class OP>
SmalbeSolMgr<S, MV, OP>::SmalbeSolMgr(const BoundConstrainedQp<S, MV, OP>& qp,
                                      Teuchos::RCP<const OP> Q,
                                      const Teuchos::ParameterList& params,
                                      Teuchos::RCP<const OP> preconditioner)
    : P_(std::move(preconditioner)) {
  setParameters(params);
  setProblem(qp, std::move(Q));
  // Validates the inner solver's use of the preconditioner now rather than at the first solve.
  MprgpSolMgr<S, MV, OP> check(qp_, params_.sublist("MPRGP"), P_);
}

template <class S, class MV, class OP>
SmalbeSolMgr<S, MV, OP>::SmalbeSolMgr() {
  setParameters(Teuchos::ParameterList("SMALBE"));
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::setProblem(const BoundConstrainedQp<S, MV, OP>& qp,
                                         Teuchos::RCP<const OP> Q) {
  TEUCHOS_TEST_FOR_EXCEPTION(
      qp.A.is_null() || qp.b.is_null() || qp.lower.is_null() || qp.x.is_null() || Q.is_null(),
      std::invalid_argument, "SMALBE: A, b, lower, x and Q must all be set");
  qp_ = qp;
  Q_ = std::move(Q);
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::reset(Belos::ResetType) {
  counters_ = QpCounters{};
  face_ = FaceCounters{};
  mu_ = Teuchos::null;
  qApplies_ = 0;
  achievedTol_ = achievedEqualityTol_ = 0;
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::setParameters(const Teuchos::ParameterList& params) {
  // Aliases resolved within the list given (see MprgpSolMgr::setParameters), also in the inner
  // solver's sublist.
  Teuchos::ParameterList given = params;
  applyParameterAliases(given, "SMALBE", belosAliases("Maximum outer iterations"));
  if (given.isSublist("MPRGP"))
    applyParameterAliases(given.sublist("MPRGP"), "SMALBE/MPRGP",
                          belosAliases("Maximum iterations"));
  Teuchos::ParameterList merged = params_.numParams() == 0 ? given : params_;
  if (params_.numParams() != 0) merged.setParameters(given);
  merged.validateParametersAndSetDefaults(*getValidParameters());
  auto fail = [](bool bad, const std::string& what) {
    TEUCHOS_TEST_FOR_EXCEPTION(bad, std::invalid_argument, "SMALBE: parameter " << what);
  };
  fail(!(merged.get<double>("Relative tolerance") >= 0.0), "\"Relative tolerance\" must be >= 0");
  fail(!(merged.get<double>("Equality tolerance") >= 0.0), "\"Equality tolerance\" must be >= 0");
  fail(merged.get<int>("Maximum outer iterations") < 1,
       "\"Maximum outer iterations\" must be >= 1");
  fail(!(merged.get<double>("Penalty") > 0.0), "\"Penalty\" must be > 0");
  fail(!(merged.get<double>("Initial M") > 0.0), "\"Initial M\" must be > 0");
  fail(!(merged.get<double>("Beta") > 1.0), "\"Beta\" must be > 1");
  fail(!(merged.get<double>("Eta") > 0.0), "\"Eta\" must be > 0");
  fail(!(merged.get<double>("Norm of A") >= 0.0), "\"Norm of A\" must be >= 0 (0: estimate)");
  fail(merged.get<int>("Power iterations") < 1, "\"Power iterations\" must be >= 1");
  const int mask = verbosityMask(merged.get<int>("Verbosity"), "SMALBE");
  MprgpSolMgr<S, MV, OP>::checkParameters(merged.sublist("MPRGP"));
  params_ = merged;
  out_.setMask(mask);
}

template <class S, class MV, class OP>
Belos::ReturnType SmalbeSolMgr<S, MV, OP>::solve() {
  Teuchos::TimeMonitor monitor(*solverTimer("tfeti: SMALBE solve"));
  const bool root = qp_.x.is_null() || BoundTraits<S, MV>::commRank(*qp_.x) == 0;
  return out_.reportingErrors("SMALBE", root, [&] { return solveTimed(); });
}

template <class S, class MV, class OP>
Belos::ReturnType SmalbeSolMgr<S, MV, OP>::solveTimed() {
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;
  using BT = BoundTraits<S, MV>;
  TEUCHOS_TEST_FOR_EXCEPTION(qp_.A.is_null(), std::invalid_argument,
                             "SMALBE: no problem to solve (setProblem was not called)");
  counters_ = QpCounters{};
  face_ = FaceCounters{};
  qApplies_ = 0;
  checkQpMaps(qp_, "SMALBE", Q_.get());
  MprgpIteration<S, MV, OP>::checkProblemData(qp_);
  const bool root = BT::commRank(*qp_.x) == 0;
  const auto start = std::chrono::steady_clock::now();

  normA_ = params_.get<double>("Norm of A");
  if (!(normA_ > 0))
    normA_ = MprgpSolMgr<S, MV, OP>::estimateNorm(
        *TimedOperator<S, MV, OP>::wrap(qp_.A, solverTimer("tfeti: Hessian apply")), *qp_.x,
        params_.get<int>("Power iterations"), &counters_.hessianMultiplications);
  rho_ = params_.get<double>("Penalty") * normA_;
  M_ = params_.get<double>("Initial M") * normA_;
  const magnitude_type beta = params_.get<double>("Beta");
  const bool shiftedTest = params_.get<std::string>("Lagrangian test") == "shifted";
  const bool reuseGradient = params_.get<bool>("Reuse gradient");
  auto gNext = MVT::Clone(*qp_.x, 1);

  std::vector<magnitude_type> n(1);
  MVT::MvNorm(*qp_.b, n);
  counters_.rhsNorm = n[0];
  magnitude_type scale = n[0];
  if (scale == magnitude_type(0)) {
    auto y = MVT::Clone(*qp_.x, 1);
    auto Ay = MVT::Clone(*qp_.x, 1);
    MVT::MvInit(*y, S(0));
    BT::project(*y, *qp_.lower, qp_.upper.get());
    OPT::Apply(*TimedOperator<S, MV, OP>::wrap(qp_.A, solverTimer("tfeti: Hessian apply")), *y,
               *Ay);
    ++counters_.hessianMultiplications;
    MVT::MvNorm(*Ay, n);
    scale = n[0] > magnitude_type(0) ? n[0] : magnitude_type(1);
  }
  const magnitude_type gTol = params_.get<double>("Relative tolerance") * scale;
  const magnitude_type eTol = params_.get<double>("Equality tolerance") * scale / normA_;
  const magnitude_type eta = params_.get<double>("Eta") * scale;

  mu_ = MVT::Clone(*qp_.x, 1);
  if (mu0_.is_null())
    MVT::MvInit(*mu_, S(0));
  else
    MVT::Assign(*mu0_, *mu_);
  auto bInner = MVT::Clone(*qp_.x, 1);
  auto Qx = MVT::Clone(*qp_.x, 1);
  const Teuchos::RCP<const OP> H =
      augmented_.is_null() ? OperatorSum<S, MV, OP>::build(qp_.A, S(1), Q_, S(rho_)) : augmented_;
  BoundConstrainedQp<S, MV, OP> inner{H, bInner, qp_.lower, qp_.x, qp_.upper};
  Teuchos::ParameterList innerParams = params_.sublist("MPRGP");
  auto innerTest = Teuchos::rcp(new StatusTestSmalbeInner<S, MV, OP>(Q_, M_, eta, gTol, eTol));
  const int maxOuter = params_.get<int>("Maximum outer iterations");

  const bool faceMode = params_.get<std::string>("Face solve") == "pcpg";
  // The faces' columns of Q, shared by all faces of this solve (every bound component a
  // candidate).
  gramian_ = Teuchos::null;
  if (faceMode) {
    std::vector<long long> bounded = BT::finiteIndices(*qp_.lower);
    if (!qp_.upper.is_null()) {
      const std::vector<long long> up = BT::finiteIndices(*qp_.upper);
      std::vector<long long> both;
      std::set_union(bounded.begin(), bounded.end(), up.begin(), up.end(),
                     std::back_inserter(both));
      bounded = std::move(both);
    }
    gramian_ = Teuchos::rcp(new FaceGramian<S, MV, OP>(Q_, std::move(bounded), *qp_.x));
  }
  const int settleRequired = params_.get<int>("Face settle iterations");
  std::vector<long long> activePrev;
  int settled = 0;
  S lagrangianPrev = 0;
  magnitude_type noisePrev = 0;
  bool converged = false, innerFailed = false;
  magnitude_type gp = 0, qxNorm = 0;
  int k = 0;
  if (faceMode && params_.get<std::string>("Initial face") == "levels" && !levels_.is_null()) {
    // The active set from the levels (for contact: the gap, whose sublevel sets are the contact
    // zones of smooth convex bodies) instead of from MPRGP's expansion steps, which on fine
    // meshes open a few rows at a time.
    BT::project(*qp_.x, *qp_.lower, qp_.upper.get());
    // An initial iterate that already passes the final test (no load: x = 0 with the gap
    // multiplier, FetiSolver) is the answer, as SMALBE's first inner solve would return it; the
    // loose face solves of the search would only replace it by rounding.
    {
      auto g = MVT::Clone(*qp_.x, 1), phi = MVT::Clone(*qp_.x, 1), chopped = MVT::Clone(*qp_.x, 1);
      OPT::Apply(*H, *qp_.x, *g);
      ++counters_.hessianMultiplications;
      MVT::MvAddMv(S(1), *g, S(-1), *qp_.b, *g);
      MVT::MvAddMv(S(1), *g, S(1), *mu_, *g);
      BT::freeGradient(*qp_.x, *qp_.lower, qp_.upper.get(), *g, *phi);
      BT::choppedGradient(*qp_.x, *qp_.lower, qp_.upper.get(), *g, *chopped);
      MVT::MvAddMv(S(1), *phi, S(1), *chopped, *phi);
      MVT::MvNorm(*phi, n);
      gp = n[0];
      OPT::Apply(*Q_, *qp_.x, *Qx);
      ++qApplies_;
      MVT::MvNorm(*Qx, n);
      qxNorm = n[0];
      converged = gp <= gTol && qxNorm <= eTol;
    }
    if (!converged) {
      auto x = MVT::CloneCopy(*qp_.x);
      bool found = false;
      std::vector<long long> active = levelFace(kLevelTolerance * scale, *x, found);
      if (found) converged = faceSolve(std::move(active), gTol, eTol, scale, gp, qxNorm, x.get());
    }
  }
  for (; k < maxOuter && !converged; ++k) {
    MVT::MvAddMv(S(1), *qp_.b, S(-1), *mu_, *bInner);  // L's linear term: b - mu
    innerTest->setM(M_);
    MprgpSolMgr<S, MV, OP> mprgp(inner, innerParams, P_);
    mprgp.setOutputStream(out_.getStream());
    mprgp.setNormOfA(normA_ + rho_);
    if (reuseGradient && k > 0) mprgp.setInitialGradient(gNext);
    mprgp.setConvergenceTest(innerTest, true);
    const Belos::ReturnType innerResult = mprgp.solve();
    const QpCounters& ic = mprgp.counters();
    counters_.hessianMultiplications += ic.hessianMultiplications;
    counters_.cgSteps += ic.cgSteps;
    counters_.expansionSteps += ic.expansionSteps;
    counters_.proportioningSteps += ic.proportioningSteps;
    if (innerResult != Belos::Converged) innerFailed = true;

    OPT::Apply(*Q_, *qp_.x, *Qx);
    ++qApplies_;
    MVT::MvNorm(*Qx, n);
    qxNorm = n[0];
    gp = ic.projectedGradientNorm;
    counters_.history.push_back(gp / scale);
    converged = gp <= gTol && qxNorm <= eTol;

    // L(x_k, mu_k) = 1/2 x^T (g - b + mu) with g = H x - b + mu_k the inner gradient.
    std::vector<S> d(1);
    auto w = MVT::CloneCopy(*mprgp.getGradient());
    MVT::MvAddMv(S(1), *w, S(-1), *qp_.b, *w);
    MVT::MvAddMv(S(1), *w, S(1), *mu_, *w);
    MVT::MvDot(*qp_.x, *w, d);
    const S lagrangianK = S(0.5) * d[0];
    // The rounding level of that dot product: Lagrangian changes below it carry no information.
    std::vector<magnitude_type> nx(1), nw(1);
    MVT::MvNorm(*qp_.x, nx);
    MVT::MvNorm(*w, nw);
    const magnitude_type noise =
        magnitude_type(1e3) * std::numeric_limits<magnitude_type>::epsilon() * nx[0] * nw[0];
    // mu_{k+1} = mu_k + rho Q x_k: even after convergence, so that A x - b + mu is the
    // gradient the inner solver drove to zero.
    MVT::MvAddMv(S(1), *mu_, S(rho_), *Qx, *mu_);
    // SMALBE-M compares L(x_k, mu_k) with L(x_{k-1}, mu_{k-1}), each at the multiplier of its
    // own inner solve; "shifted" compares L(x_k, mu_{k+1}) = L(x_k, mu_k) + rho ||Q x_k||^2
    // with L(x_{k-1}, mu_k), which asks for an increase of about rho ||Q x_{k-1}||^2.
    const S lagrangian = shiftedTest ? lagrangianK + S(rho_) * qxNorm * qxNorm : lagrangianK;
    const S required = S(0.5) * S(rho_) * qxNorm * qxNorm;
    // M is reduced only when the shortfall exceeds the rounding level of L (otherwise the
    // decision, and with it the iteration, would depend on the order of the reductions).
    const bool reduceM =
        !converged && k > 0 && lagrangian + std::max(noise, noisePrev) < lagrangianPrev + required;
    if (out_.wants(Belos::IterationDetails) && root) {
      auto line = SolverOutput::line();
      line << "SMALBE " << std::setw(4) << k + 1 << "  ||g^P||/||b|| = " << std::scientific
           << std::setprecision(3) << gp / scale
           << "  ||A|| ||Qx||/||b|| = " << normA_ * qxNorm / scale << "  M/||A|| = " << M_ / normA_
           << "  MPRGP steps " << mprgp.getNumIters() << "  L increase "
           << (k > 0 ? lagrangian - lagrangianPrev : S(0)) << " (needed " << required
           << (reduceM ? ", M reduced)" : ")") << std::fixed << std::setprecision(2) << "  [QP "
           << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
           << " s]\n";
      out_.write(line);
    }
    if (converged) {
      ++k;
      break;
    }
    // The face phase: once the active set has settled, solve on that face like the tied
    // problem; accepted only when the result passes the final test above.
    {
      std::vector<long long> active = BT::activeIndices(*qp_.x, *qp_.lower, qp_.upper.get());
      if (k > 0 && active != activePrev) ++face_.activeSetChanges;
      settled = k > 0 && active == activePrev ? settled + 1 : 0;
      activePrev = active;
      if (faceMode && settled >= settleRequired &&
          face_.solves < params_.get<int>("Maximum face solves")) {
        if (faceSolve(std::move(active), gTol, eTol, scale, gp, qxNorm)) {
          converged = true;
          ++k;
          break;
        }
        settled = 0;
      }
    }
    if (reduceM) M_ /= beta;
    if (reuseGradient) {
      // The next inner gradient at the same x: H x - b + mu_{k+1} = g + rho Q x.
      MVT::MvAddMv(S(1), *mprgp.getGradient(), S(rho_), *Qx, *gNext);
    }
    lagrangianPrev = lagrangian;
    noisePrev = noise;
  }
  qApplies_ += innerTest->projectorApplications();
  if (!gramian_.is_null()) qApplies_ += gramian_->projectorApplications();
  gramian_ = Teuchos::null;  // its columns belong to this solve's Q
  counters_.outerIterations = k;
  counters_.projectedGradientNorm = gp;
  counters_.equalityResidualNorm = qxNorm;
  counters_.converged = converged;
  std::ostringstream msg;
  msg << std::scientific << std::setprecision(3);
  if (converged)
    msg << "converged after " << k << " outer iterations"
        << (face_.accepted ? " (the last a face solve)" : "") << ": ||g^P||/||b|| = " << gp / scale
        << ", ||A|| ||Qx||/||b|| = " << normA_ * qxNorm / scale;
  else
    msg << "not converged: the limit of " << maxOuter
        << " outer iterations was reached with ||g^P||/||b|| = " << gp / scale << " (tolerance "
        << params_.get<double>("Relative tolerance")
        << "), ||A|| ||Qx||/||b|| = " << normA_ * qxNorm / scale << " (tolerance "
        << params_.get<double>("Equality tolerance") << ")";
  if (faceMode)
    msg << "; face solve: " << face_.solves << " face solves, " << face_.iterations
        << " face CG steps, " << face_.activeSetChanges << " active-set changes";
  if (face_.levelSolves > 0)
    msg << ", " << face_.levelSolves << " level-search face solves (their CG steps included)";
  if (innerFailed)
    msg << "; some inner MPRGP solves hit their \"Maximum iterations\" before reaching the "
           "inner precision";
  counters_.message = msg.str();
  achievedTol_ = gp / scale;
  achievedEqualityTol_ = normA_ * qxNorm / scale;
  if (out_.wants(Belos::FinalSummary) && root) {
    auto line = SolverOutput::line();
    line << "SMALBE: " << counters_.message << "; " << counters_.cgSteps << " CG, "
         << counters_.expansionSteps << " expansion, " << counters_.proportioningSteps
         << " proportioning steps, " << counters_.hessianMultiplications
         << " Hessian multiplications, rho = " << rho_ << ", final M = " << M_ << "\n";
    out_.write(line);
  } else if (!converged && out_.wants(Belos::Warnings) && root) {
    out_.write("SMALBE: warning: " + counters_.message + "\n");
  }
  if (out_.wants(Belos::TimingDetails) && root) {
    auto line = SolverOutput::line();
    line << "SMALBE: solve " << std::scientific << std::setprecision(3)
         << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
         << " s\n";
    out_.write(line);
  }
  if (out_.wants(Belos::StatusTestDetails) && root) {
    auto line = SolverOutput::line();
    line << "SMALBE: final test: ||g^P|| = " << std::scientific << std::setprecision(3) << gp
         << (gp <= gTol ? " <= " : " > ") << gTol << " and ||Q x|| = " << qxNorm
         << (qxNorm <= eTol ? " <= " : " > ") << eTol << (converged ? ": Passed" : ": Failed")
         << "\n";
    out_.write(line);
  }
  return converged ? Belos::Converged : Belos::Unconverged;
}

template <class S, class MV, class OP>
bool SmalbeSolMgr<S, MV, OP>::faceSolve(std::vector<long long> active, magnitude_type gTol,
                                        magnitude_type eTol, magnitude_type scale,
                                        magnitude_type& gp, magnitude_type& qxNorm,
                                        const MV* start) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;
  using BT = BoundTraits<S, MV>;
  const bool root = BT::commRank(*qp_.x) == 0;
  const auto A = TimedOperator<S, MV, OP>::wrap(qp_.A, solverTimer("tfeti: Hessian apply"));
  const Teuchos::RCP<const OP> M =
      params_.sublist("MPRGP").get<bool>("Preconditioning in face") ? P_ : Teuchos::null;
  const MV* upper = qp_.upper.get();
  auto x = MVT::CloneCopy(start != nullptr ? *start : *qp_.x);
  auto g = MVT::Clone(*qp_.x, 1), t = MVT::Clone(*qp_.x, 1), mu = MVT::Clone(*qp_.x, 1);
  auto phi = MVT::Clone(*qp_.x, 1), chopped = MVT::Clone(*qp_.x, 1);
  std::vector<magnitude_type> n(1);
  const S inf = std::numeric_limits<S>::infinity();
  // The primal-dual active-set step: the rows at a bound of the projected iterate xp, less the
  // face's own rows whose multiplier sigma has the wrong sign (a lower bound is held by sigma
  // >= 0, an upper one by sigma <= 0). A row that has just left the box joins whatever its
  // gradient at the projected point (which is not a multiplier: judging it would undo most of
  // the step, a few rows joining per face).
  const auto pdasStep = [&](const MV& xp, const std::vector<long long>& face,
                            const std::vector<S>& sigma) {
    const std::vector<long long> now = BT::activeIndices(xp, *qp_.lower, upper);
    const std::vector<S> xn = BT::gatherAt(xp, now), ln = BT::gatherAt(*qp_.lower, now);
    std::vector<S> un(now.size(), inf);
    if (upper != nullptr) un = BT::gatherAt(*upper, now);
    std::vector<long long> next;
    for (std::size_t i = 0; i < now.size(); ++i) {
      const auto it = std::lower_bound(face.begin(), face.end(), now[i]);
      bool release = false;
      if (it != face.end() && *it == now[i] && ln[i] < un[i]) {
        const S si = sigma[static_cast<std::size_t>(it - face.begin())];
        release = xn[i] <= ln[i] ? si < S(0) : si > S(0);
      }
      if (!release) next.push_back(now[i]);
    }
    return next;
  };
  // Faces whose loose verdict already moved the active set: a verdict that leads back to one of
  // them (rows near a bound judged by a loose solution) is settled by the tight solve instead.
  std::vector<std::vector<long long>> visited;
  const S tightTol = S(params_.get<double>("Face relative tolerance")) * gTol;
  const S looseTol =
      std::max(tightTol, std::min(S(kFaceVerdictFactor) * gTol, S(kLevelTolerance) * scale));
  const int maxIterations = params_.get<int>("Face maximum iterations");
  while (face_.solves < params_.get<int>("Maximum face solves")) {
    ++face_.solves;
    FaceProjector<S, MV, OP> face(Q_, active, *x, gramian_.get());
    qApplies_ += face.projectorApplications();
    if (!face.valid()) {
      if (out_.wants(Belos::IterationDetails) && root)
        out_.write(
            "SMALBE face: the active rows are dependent on the equality rows; no face "
            "solve\n");
      break;
    }
    // The active rows' bound values: the upper bound where x reached it, else the lower one
    // (rows that an active-set step added from outside the box go to the bound they crossed).
    const std::vector<S> xa = BT::gatherAt(*x, active), la = BT::gatherAt(*qp_.lower, active);
    std::vector<S> ua(active.size(), inf);
    if (upper != nullptr) ua = BT::gatherAt(*upper, active);
    std::vector<S> r(active.size());
    for (std::size_t i = 0; i < active.size(); ++i) r[i] = xa[i] >= ua[i] ? ua[i] : la[i];
    face.projectAffine(r, *x);
    OPT::Apply(*A, *x, *g);
    MVT::MvAddMv(S(1), *g, S(-1), *qp_.b, *g);
    ++counters_.hessianMultiplications;
    // First to a loose tolerance (kFaceVerdictFactor): enough to tell whether the face holds (no
    // free row leaves the box, no active row pulls). Only a face that holds is solved to the
    // tight tolerance, from there; the active-set corrections before it cost loose solves only.
    int steps = 0;
    if (looseTol > tightTol) {
      FacePcpg<S, MV, OP> loose(A, M, face, looseTol, maxIterations);
      const FacePcpgResult<S> lr = loose.solve(*x, *g);
      steps += lr.iterations;
      counters_.hessianMultiplications += lr.iterations;
      face_.iterations += lr.iterations;
      auto xp = MVT::CloneCopy(*x);
      BT::setAt(active, r, *xp);
      BT::project(*xp, *qp_.lower, upper);
      std::vector<long long> next = pdasStep(*xp, active, face.activeMultipliers(*g));
      const bool seen = std::find(visited.begin(), visited.end(), next) != visited.end();
      // An unconverged loose solve gives no verdict; the tight one below judges the face.
      if (lr.converged && next != active && !seen) {
        if (out_.wants(Belos::IterationDetails) && root) {
          auto line = SolverOutput::line();
          line << "SMALBE face " << face_.solves << ": " << active.size() << " active rows, "
               << lr.iterations << " CG steps to the loose tolerance, next face " << next.size()
               << " active rows\n";
          out_.write(line);
        }
        visited.push_back(active);
        ++face_.activeSetChanges;
        active = std::move(next);
        MVT::Assign(*xp, *x);
        continue;
      }
    }
    // "Face maximum iterations" limits the face's loose and tight steps together.
    FacePcpg<S, MV, OP> pcpg(A, M, face, tightTol, maxIterations - steps);
    const FacePcpgResult<S> res = pcpg.solve(*x, *g);
    steps += res.iterations;
    counters_.hessianMultiplications += res.iterations;
    face_.iterations += res.iterations;
    // The active components exactly at their bounds (P_F leaves rounding errors there, which
    // would make them free, with their multiplier counted as a free gradient).
    BT::setAt(active, r, *x);
    // The result as SMALBE's: feasible (projected onto the box), the gradient recomputed, the
    // equality multiplier mu = -Q (g - E_A^T sigma) that leaves g + mu = P_F g + E_A^T sigma
    // (zero on the free rows up to the tolerance, sigma on the active ones), then the final test.
    BT::project(*x, *qp_.lower, upper);
    OPT::Apply(*A, *x, *g);
    MVT::MvAddMv(S(1), *g, S(-1), *qp_.b, *g);
    ++counters_.hessianMultiplications;
    OPT::Apply(*Q_, *x, *t);
    ++qApplies_;
    MVT::MvNorm(*t, n);
    const magnitude_type qx = n[0];
    const std::vector<S> sigma = face.activeMultipliers(*g);
    MVT::Assign(*g, *t);
    BT::addAt(active, sigma, S(-1), *t);
    OPT::Apply(*Q_, *t, *mu);
    ++qApplies_;
    MVT::MvScale(*mu, S(-1));
    MVT::MvAddMv(S(1), *g, S(1), *mu, *t);  // the Lagrangian's gradient
    BT::freeGradient(*x, *qp_.lower, upper, *t, *phi);
    BT::choppedGradient(*x, *qp_.lower, upper, *t, *chopped);
    MVT::MvAddMv(S(1), *phi, S(1), *chopped, *phi);
    MVT::MvNorm(*phi, n);
    const magnitude_type gpFace = n[0];
    const bool passed = gpFace <= gTol && qx <= eTol;
    std::vector<long long> next;
    if (!passed) next = pdasStep(*x, active, sigma);
    if (out_.wants(Belos::IterationDetails) && root) {
      auto line = SolverOutput::line();
      line << "SMALBE face " << face_.solves << ": " << active.size() << " active rows, " << steps
           << " CG steps" << (res.converged ? "" : " (not converged)") << std::scientific
           << std::setprecision(3) << ", ||g^P||/||b|| = " << gpFace / scale
           << "  ||A|| ||Qx||/||b|| = " << normA_ * qx / scale
           << (passed ? ": accepted" : ": rejected");
      if (!passed) line << ", next face " << next.size() << " active rows";
      line << "\n";
      out_.write(line);
    }
    if (passed) {
      MVT::Assign(*x, *qp_.x);
      MVT::Assign(*mu, *mu_);
      gp = gpFace;
      qxNorm = qx;
      counters_.history.push_back(gp / scale);
      face_.accepted = true;
      return true;
    }
    if (next == active) break;  // the same face again would give the same result
    visited.push_back(active);
    ++face_.activeSetChanges;
    active = std::move(next);
  }
  return false;  // SMALBE goes on from its own iterate (qp_.x and mu_ untouched)
}

template <class S, class MV, class OP>
typename SmalbeSolMgr<S, MV, OP>::FaceVerdict SmalbeSolMgr<S, MV, OP>::trialFace(
    const std::vector<long long>& active, magnitude_type tol, MV& x) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;
  using BT = BoundTraits<S, MV>;
  FaceVerdict v;
  ++face_.levelSolves;
  FaceProjector<S, MV, OP> face(Q_, active, x, gramian_.get());
  qApplies_ += face.projectorApplications();
  if (!face.valid()) return v;
  v.valid = true;
  face.projectAffine(BT::gatherAt(*qp_.lower, active), x);
  const auto A = TimedOperator<S, MV, OP>::wrap(qp_.A, solverTimer("tfeti: Hessian apply"));
  auto g = MVT::Clone(x, 1);
  OPT::Apply(*A, x, *g);
  MVT::MvAddMv(S(1), *g, S(-1), *qp_.b, *g);
  ++counters_.hessianMultiplications;
  const Teuchos::RCP<const OP> M =
      params_.sublist("MPRGP").get<bool>("Preconditioning in face") ? P_ : Teuchos::null;
  FacePcpg<S, MV, OP> pcpg(A, M, face, S(tol), params_.get<int>("Face maximum iterations"));
  const FacePcpgResult<S> res = pcpg.solve(x, *g);
  counters_.hessianMultiplications += res.iterations;
  face_.iterations += res.iterations;
  BT::setAt(active, BT::gatherAt(*qp_.lower, active), x);
  v.leftBox = BT::countOutside(x, *qp_.lower, qp_.upper.get());
  // A lower bound is held by a multiplier pushing x up: sigma >= 0 (g = sigma on the row).
  for (const S s : face.activeMultipliers(*g))
    if (s < S(0)) ++v.wrongSign;
  if (out_.wants(Belos::IterationDetails) && BT::commRank(x) == 0) {
    auto line = SolverOutput::line();
    line << "SMALBE level face: " << active.size() << " active rows, " << res.iterations
         << " CG steps, " << v.leftBox << " free rows outside the box, " << v.wrongSign
         << " active rows with a multiplier of the wrong sign\n";
    out_.write(line);
  }
  return v;
}

template <class S, class MV, class OP>
std::vector<long long> SmalbeSolMgr<S, MV, OP>::levelFace(magnitude_type tol, MV& x, bool& found) {
  using BT = BoundTraits<S, MV>;
  // The candidates and their levels, the same on every rank and rank count.
  const std::vector<long long> rows = BT::finiteIndices(*levels_);
  const std::vector<S> level = BT::gatherAt(*levels_, rows);
  std::vector<S> tau = level;
  std::sort(tau.begin(), tau.end());
  tau.erase(std::unique(tau.begin(), tau.end()), tau.end());
  const auto faceAbove = [&](std::size_t k) {
    std::vector<long long> a;
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (level[i] > tau[k]) a.push_back(rows[i]);
    return a;  // sorted: rows is
  };
  // One level (the two membranes: every gap zero) says nothing about the face.
  found = tau.size() > 1;
  if (!found) return {};
  // Level k holds the rows at or below tau[k] free: the larger k, the more free rows. Too many
  // free rows leave the box (tension on a closed contact row), too few leave active rows with
  // a multiplier of the wrong sign (penetration): bisect between the two.
  std::size_t lo = 0, hi = tau.size() - 1;
  while (lo < hi) {
    const std::size_t k = lo + (hi - lo) / 2;
    const FaceVerdict v = trialFace(faceAbove(k), tol, x);
    if (!v.valid || (v.wrongSign > 0 && v.leftBox == 0)) {
      lo = k + 1;  // too few free rows (or not enough to carry Q's rows)
    } else if (v.leftBox > 0 && v.wrongSign == 0) {
      hi = k;  // too many
    } else {
      return faceAbove(k);  // neither (the face) or both (the primal-dual steps go on from it)
    }
  }
  return faceAbove(lo);
}

}  // namespace tfeti
