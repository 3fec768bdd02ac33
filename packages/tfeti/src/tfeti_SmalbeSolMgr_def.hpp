#pragma once
#include <Teuchos_Assert.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "tfeti_BoundTraits.hpp"
#include "tfeti_MprgpSolMgr_def.hpp"
#include "tfeti_OperatorSum.hpp"
#include "tfeti_QpChecks.hpp"
#include "tfeti_QpStatusTests.hpp"
#include "tfeti_SmalbeSolMgr_decl.hpp"
#include "tfeti_StrictParameters.hpp"

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
    pl->set("Verbosity", 0, "0 silent, 1 summary, 2 every outer iteration (rank 0)",
            strict::intBetween(0, 2));
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
    : qp_(qp), Q_(std::move(Q)), P_(std::move(preconditioner)), params_(params) {
  params_.validateParametersAndSetDefaults(*getValidParameters());
  auto fail = [](bool bad, const std::string& what) {
    TEUCHOS_TEST_FOR_EXCEPTION(bad, std::invalid_argument, "SMALBE: parameter " << what);
  };
  fail(!(params_.get<double>("Relative tolerance") >= 0.0), "\"Relative tolerance\" must be >= 0");
  fail(!(params_.get<double>("Equality tolerance") >= 0.0), "\"Equality tolerance\" must be >= 0");
  fail(params_.get<int>("Maximum outer iterations") < 1,
       "\"Maximum outer iterations\" must be >= 1");
  fail(!(params_.get<double>("Penalty") > 0.0), "\"Penalty\" must be > 0");
  fail(!(params_.get<double>("Initial M") > 0.0), "\"Initial M\" must be > 0");
  fail(!(params_.get<double>("Beta") > 1.0), "\"Beta\" must be > 1");
  fail(!(params_.get<double>("Eta") > 0.0), "\"Eta\" must be > 0");
  fail(!(params_.get<double>("Norm of A") >= 0.0), "\"Norm of A\" must be >= 0 (0: estimate)");
  fail(params_.get<int>("Power iterations") < 1, "\"Power iterations\" must be >= 1");
  const int verbosity = params_.get<int>("Verbosity");
  fail(verbosity < 0 || verbosity > 2, "\"Verbosity\" must be 0, 1 or 2");
  TEUCHOS_TEST_FOR_EXCEPTION(
      qp_.A.is_null() || qp_.b.is_null() || qp_.lower.is_null() || qp_.x.is_null() || Q_.is_null(),
      std::invalid_argument, "SMALBE: A, b, lower, x and Q must all be set");
  // Validates the inner parameters now rather than at the first inner solve.
  MprgpSolMgr<S, MV, OP> check(qp_, params_.sublist("MPRGP"), P_);
}

template <class S, class MV, class OP>
Belos::ReturnType SmalbeSolMgr<S, MV, OP>::solve() {
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;
  using BT = BoundTraits<S, MV>;
  counters_ = QpCounters{};
  qApplies_ = 0;
  checkQpMaps(qp_, "SMALBE", Q_.get());
  MprgpIteration<S, MV, OP>::checkProblemData(qp_);
  const int verbosity = params_.get<int>("Verbosity");
  const bool root = BT::commRank(*qp_.x) == 0;
  const auto start = std::chrono::steady_clock::now();

  normA_ = params_.get<double>("Norm of A");
  if (!(normA_ > 0))
    normA_ = MprgpSolMgr<S, MV, OP>::estimateNorm(
        *qp_.A, *qp_.x, params_.get<int>("Power iterations"), &counters_.hessianMultiplications);
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
    OPT::Apply(*qp_.A, *y, *Ay);
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

  S lagrangianPrev = 0;
  magnitude_type noisePrev = 0;
  bool converged = false, innerFailed = false;
  magnitude_type gp = 0, qxNorm = 0;
  int k = 0;
  for (; k < maxOuter; ++k) {
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
    if (verbosity >= 2 && root) {
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
    if (reduceM) M_ /= beta;
    if (reuseGradient) {
      // The next inner gradient at the same x: H x - b + mu_{k+1} = g + rho Q x.
      MVT::MvAddMv(S(1), *mprgp.getGradient(), S(rho_), *Qx, *gNext);
    }
    lagrangianPrev = lagrangian;
    noisePrev = noise;
  }
  qApplies_ += innerTest->projectorApplications();
  counters_.outerIterations = k;
  counters_.projectedGradientNorm = gp;
  counters_.equalityResidualNorm = qxNorm;
  counters_.converged = converged;
  std::ostringstream msg;
  msg << std::scientific << std::setprecision(3);
  if (converged)
    msg << "converged after " << k << " outer iterations: ||g^P||/||b|| = " << gp / scale
        << ", ||A|| ||Qx||/||b|| = " << normA_ * qxNorm / scale;
  else
    msg << "not converged: the limit of " << maxOuter
        << " outer iterations was reached with ||g^P||/||b|| = " << gp / scale << " (tolerance "
        << params_.get<double>("Relative tolerance")
        << "), ||A|| ||Qx||/||b|| = " << normA_ * qxNorm / scale << " (tolerance "
        << params_.get<double>("Equality tolerance") << ")";
  if (innerFailed)
    msg << "; some inner MPRGP solves hit their \"Maximum iterations\" before reaching the "
           "inner precision";
  counters_.message = msg.str();
  if (verbosity >= 1 && root) {
    auto line = SolverOutput::line();
    line << "SMALBE: " << counters_.message << "; " << counters_.cgSteps << " CG, "
         << counters_.expansionSteps << " expansion, " << counters_.proportioningSteps
         << " proportioning steps, " << counters_.hessianMultiplications
         << " Hessian multiplications, rho = " << rho_ << ", final M = " << M_ << "\n";
    out_.write(line);
  }
  return converged ? Belos::Converged : Belos::Unconverged;
}

}  // namespace tfeti
