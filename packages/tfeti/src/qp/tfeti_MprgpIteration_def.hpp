#pragma once
#include <Teuchos_Assert.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "tfeti_BoundTraits.hpp"
#include "tfeti_MprgpIteration_decl.hpp"
#include "tfeti_SeparableSet.hpp"

namespace tfeti {

template <class S, class MV, class OP>
MprgpIteration<S, MV, OP>::MprgpIteration(const BoundConstrainedQp<S, MV, OP>& qp,
                                          Teuchos::RCP<const OP> M,
                                          Teuchos::RCP<Belos::StatusTest<S, MV, OP>> tester,
                                          const Options& options)
    : qp_(qp), M_(std::move(M)), tester_(std::move(tester)), opts_(options) {
  TEUCHOS_TEST_FOR_EXCEPTION(
      qp_.A.is_null() || qp_.b.is_null() || qp_.lower.is_null() || qp_.x.is_null(),
      std::invalid_argument, "MprgpIteration: A, b, lower and x of the problem must all be set");
  TEUCHOS_TEST_FOR_EXCEPTION(tester_.is_null(), std::invalid_argument,
                             "MprgpIteration: a status test is required");
  TEUCHOS_TEST_FOR_EXCEPTION(!(opts_.alphaBar > S(0)) || !(opts_.gamma > S(0)),
                             std::invalid_argument,
                             "MprgpIteration: the step length alphaBar and Gamma must be > 0");
  TEUCHOS_TEST_FOR_EXCEPTION(MVT::GetNumberVecs(*qp_.x) != 1 || MVT::GetNumberVecs(*qp_.b) != 1 ||
                                 MVT::GetNumberVecs(*qp_.lower) != 1 ||
                                 (!qp_.upper.is_null() && MVT::GetNumberVecs(*qp_.upper) != 1),
                             std::invalid_argument,
                             "MprgpIteration: x, b, lower and upper must be single vectors");
  // An upper bound vector without a finite entry changes nothing: drop it, so that such a
  // problem takes the lower-bound-only path (no extra reduction in the proportioning step).
  if (!qp_.upper.is_null() && BoundTraits<S, MV>::anyFinite(*qp_.upper)) upper_ = qp_.upper.get();
  set_ = Teuchos::rcp(
      new SeparableSet<S, MV>(*qp_.lower, upper_, qp_.discs.get(), qp_.discCenters.get()));
  // Built directly, not through setProblem, which would compute residuals and shuffle columns
  // for Belos' block solvers; status tests only need A, b and the iterate.
  problem_ = Teuchos::rcp(new Belos::LinearProblem<S, MV, OP>(qp_.A, qp_.x, qp_.b));
  g_ = MVT::Clone(*qp_.x, 1);
  p_ = MVT::Clone(*qp_.x, 1);
  Ap_ = MVT::Clone(*qp_.x, 1);
  phi_ = MVT::Clone(*qp_.x, 1);
  beta_ = MVT::Clone(*qp_.x, 1);
  if (!M_.is_null()) z_ = MVT::Clone(*qp_.x, 1);
  const bool discs = set_->hasDiscs();
  if (opts_.optimalExpansion || opts_.projectedCgExpansion || discs) xHalf_ = MVT::Clone(*qp_.x, 1);
  if (opts_.projectedCgExpansion || discs) gHalf_ = MVT::Clone(*qp_.x, 1);
  root_ = BoundTraits<S, MV>::commRank(*qp_.x) == 0;
}

template <class S, class MV, class OP>
void MprgpIteration<S, MV, OP>::setBlockSize(int blockSize) {
  TEUCHOS_TEST_FOR_EXCEPTION(blockSize != 1, std::invalid_argument,
                             "MprgpIteration: the block size is always 1");
}

template <class S, class MV, class OP>
Teuchos::RCP<const MV> MprgpIteration<S, MV, OP>::getNativeResiduals(
    std::vector<magnitude_type>* norms) const {
  if (norms != nullptr) {
    if (norms->size() < 1) norms->resize(1);
    (*norms)[0] = gpNorm_;
  }
  return Teuchos::null;
}

template <class S, class MV, class OP>
void MprgpIteration<S, MV, OP>::applyA(const MV& in, MV& out) {
  OPT::Apply(*qp_.A, in, out);
  ++counters_.hessianMultiplications;
}

template <class S, class MV, class OP>
void MprgpIteration<S, MV, OP>::computeGradient() {
  applyA(*qp_.x, *g_);
  MVT::MvAddMv(S(1), *g_, S(-1), *qp_.b, *g_);
}

template <class S, class MV, class OP>
void MprgpIteration<S, MV, OP>::updateGradientSplit() {
  set_->freeGradient(*qp_.x, *g_, *phi_);
  set_->choppedGradient(*qp_.x, *g_, *beta_);
  std::vector<magnitude_type> n(1);
  MVT::MvNorm(*phi_, n);
  const magnitude_type phiNorm = n[0];
  MVT::MvNorm(*beta_, n);
  betaNorm2_ = n[0] * n[0];
  gpNorm_ = std::sqrt(phiNorm * phiNorm + betaNorm2_);
  phiTildePhi_ = set_->reducedFreeGradientDot(*qp_.x, *phi_, opts_.alphaBar);
  if (!std::isfinite(gpNorm_))
    throw std::runtime_error(
        "MPRGP: the gradient A x - b contains NaN or Inf (the operator A produced a non-finite "
        "value)");
}

template <class S, class MV, class OP>
void MprgpIteration<S, MV, OP>::precondition(MV& z) {
  if (M_.is_null()) {
    MVT::Assign(*phi_, z);
    return;
  }
  OPT::Apply(*M_, *phi_, z);
  set_->restrictToFree(*qp_.x, z);
}

template <class S, class MV, class OP>
void MprgpIteration<S, MV, OP>::checkProblemData(const BoundConstrainedQp<S, MV, OP>& qp) {
  using BT = BoundTraits<S, MV>;
  if (!BT::allFinite(*qp.b))
    throw std::runtime_error("MPRGP: the right-hand side b contains NaN or Inf");
  const auto value = [](const MV& v, long long i) {
    std::ostringstream os;
    os << BT::valueAt(v, i);
    return os.str();
  };
  const long long badLower = BT::firstNonFinite(*qp.lower, true, false);
  if (badLower >= 0)
    throw std::runtime_error("MPRGP: the lower bounds contain NaN or +Inf: component " +
                             std::to_string(badLower) + " is " + value(*qp.lower, badLower) +
                             " (use -Inf for a component without lower bound)");
  if (!qp.upper.is_null()) {
    const long long badUpper = BT::firstNonFinite(*qp.upper, false, true);
    if (badUpper >= 0)
      throw std::runtime_error("MPRGP: the upper bounds contain NaN or -Inf: component " +
                               std::to_string(badUpper) + " is " + value(*qp.upper, badUpper) +
                               " (use +Inf for a component without upper bound)");
    const long long crossing = BT::firstCrossing(*qp.lower, *qp.upper);
    if (crossing >= 0)
      throw std::runtime_error("MPRGP: the bounds cross at component " + std::to_string(crossing) +
                               ": lower " + value(*qp.lower, crossing) + " > upper " +
                               value(*qp.upper, crossing) + " (the feasible set is empty)");
  }
  if (!BT::allFinite(*qp.x))
    throw std::runtime_error("MPRGP: the initial guess x contains NaN or Inf");
  if (!qp.discs.is_null()) SeparableSet<S, MV>::checkDiscs(*qp.discs, *qp.lower, qp.upper.get());
}

template <class S, class MV, class OP>
void MprgpIteration<S, MV, OP>::initialize() {
  using BT = BoundTraits<S, MV>;
  checkProblemData(qp_);
  set_->project(*qp_.x);
  if (!g0_.is_null()) {
    MVT::Assign(*g0_, *g_);
  } else {
    computeGradient();
  }
  if (!BT::allFinite(*g_))
    throw std::runtime_error("MPRGP: A x contains NaN or Inf for the initial guess x");
  updateGradientSplit();
  precondition(*p_);
  iter_ = 0;
  stationary_ = false;
  stalled_ = false;
  initialized_ = true;
  counters_.history.assign(1, gpNorm_);
}

template <class S, class MV, class OP>
void MprgpIteration<S, MV, OP>::iterate() {
  if (!initialized_) initialize();
  while (tester_->checkStatus(this) != Belos::Passed) {
    if (gpNorm_ == magnitude_type(0)) {
      // x is the exact solution: every step below would divide by zero.
      stationary_ = true;
      break;
    }
    if (betaNorm2_ <= opts_.gamma * opts_.gamma * phiTildePhi_) {
      applyA(*p_, *Ap_);
      // MPGP: the curvature of the circles p slides along (zero without active discs).
      if (set_->hasDiscs()) set_->addCircleCurvature(*qp_.x, *g_, *p_, *Ap_);
      std::vector<S> d(1);
      MVT::MvDot(*p_, *Ap_, d);
      const S pAp = d[0];
      if (!(pAp > S(0))) {
        std::vector<magnitude_type> n(1);
        MVT::MvNorm(*p_, n);
        // A curvature at the level of rounding in A p (|p^T A p| ~ eps ||A|| ||p||^2) means the
        // direction is numerically zero: x is as stationary as floating point can tell.
        const magnitude_type normA = opts_.alphaBar > 0 ? magnitude_type(2) / opts_.alphaBar : 0;
        if (std::isfinite(pAp) && n[0] > 0 &&
            -pAp <= magnitude_type(1e3) * std::numeric_limits<magnitude_type>::epsilon() * normA *
                        n[0] * n[0]) {
          stalled_ = true;
          break;
        }
        std::ostringstream os;
        if (!std::isfinite(pAp))
          os << "MPRGP: p^T A p is " << pAp << " (A produced NaN or Inf)";
        else if (n[0] == magnitude_type(0))
          os << "MPRGP: the preconditioner in face returned a zero direction for a non-zero "
                "free gradient (it is singular on the free set)";
        else
          os << "MPRGP: the Hessian is not positive definite on the free set (p^T A p = " << pAp
             << " for a non-zero direction p at step " << iter_ << ")";
        throw std::runtime_error(os.str());
      }
      // g^T p = phi^T p in the face; with discs phi's, which rounding in g's normal part on the
      // circles (the multipliers, much larger than phi near the solution) cannot reach.
      MVT::MvDot(set_->hasDiscs() ? *phi_ : *g_, *p_, d);
      const S alphaCg = d[0] / pAp;
      const S alphaF = set_->maxFeasibleStep(*qp_.x, *p_, true);
      if (alphaCg <= alphaF) {
        record(cgStep(alphaCg));
      } else {
        record(expansionStep(alphaF, alphaCg));
      }
    } else {
      proportioningStep();
      record("proportioning");
    }
    ++iter_;
  }
}

template <class S, class MV, class OP>
const char* MprgpIteration<S, MV, OP>::cgStep(S alphaCg) {
  const bool discs = set_->hasDiscs();
  // MPGP: a step along the tangent of an active disc leaves the circle; the projection brings
  // x back, no longer linear in alpha, so the gradient is computed afresh (one more
  // multiplication), and the step is kept only when f decreased: f(y) - f(x) =
  // 1/2 (y - x)^T (g(x) + g(y)) exactly for a quadratic.
  const bool slides = discs && set_->slidesOnCircles(*qp_.x, *p_);
  if (slides) {
    MVT::Assign(*qp_.x, *xHalf_);
    MVT::Assign(*g_, *gHalf_);
  }
  MVT::MvAddMv(S(1), *qp_.x, -alphaCg, *p_, *qp_.x);
  // Mathematically feasible; the projection only removes rounding below the bounds (and puts
  // sliding discs back on their circles).
  set_->project(*qp_.x);
  if (slides) {
    computeGradient();
    MVT::MvAddMv(S(1), *qp_.x, S(-1), *xHalf_, *phi_);
    MVT::MvAddMv(S(1), *g_, S(1), *gHalf_, *beta_);
    std::vector<S> change(1);
    MVT::MvDot(*phi_, *beta_, change);
    // Rounding must not decide (nor the order of summation, which depends on the rank count):
    // the projection puts x on the circle to eps r, which moves f by eps r nu per disc, so an
    // increase below 100 eps |x| |g(x) + g(y)| counts as none. Near the solution the steps'
    // true changes are below that, and they are taken.
    std::vector<magnitude_type> xn(1), gs(1);
    MVT::MvNorm(*qp_.x, xn);
    MVT::MvNorm(*beta_, gs);
    const magnitude_type slack =
        magnitude_type(100) * std::numeric_limits<magnitude_type>::epsilon() * xn[0] * gs[0];
    if (!(change[0] <= slack)) {
      // The circles' curvature beyond second order spoiled the step: the projected gradient
      // step from x instead, which decreases f for alphaBar < 2 / ||A||; CG restarts.
      MVT::MvAddMv(S(1), *xHalf_, -opts_.alphaBar, *gHalf_, *qp_.x);
      set_->project(*qp_.x);
      computeGradient();
      updateGradientSplit();
      precondition(*p_);
      ++counters_.expansionSteps;
      return "expansion (sliding fall-back)";
    }
  } else {
    MVT::MvAddMv(S(1), *g_, -alphaCg, *Ap_, *g_);
  }
  updateGradientSplit();
  // p = z - (z^T A p / p^T A p) p keeps the new direction A-conjugate to the previous one.
  MV& z = M_.is_null() ? *phi_ : *z_;
  if (!M_.is_null()) precondition(z);
  std::vector<S> zAp(1), pAp(1);
  MVT::MvDot(z, *Ap_, zAp);
  MVT::MvDot(*p_, *Ap_, pAp);
  MVT::MvAddMv(S(1), z, -zAp[0] / pAp[0], *p_, *p_);
  if (discs) {
    // The circles' tangents turned with x: p moved onto the new ones (conjugacy then holds
    // only approximately), and restarted as z when that left it no descent direction.
    set_->restrictToCircleTangents(*qp_.x, *p_);
    std::vector<S> gp(1);
    MVT::MvDot(*phi_, *p_, gp);
    if (!(gp[0] > S(0))) MVT::Assign(z, *p_);
  }
  ++counters_.cgSteps;
  return "CG";
}

template <class S, class MV, class OP>
S MprgpIteration<S, MV, OP>::energy() const {
  // f(x) = 1/2 x^T A x - b^T x = 1/2 x^T (g - b) with g = A x - b: no multiplication.
  std::vector<S> xg(1), xb(1);
  MVT::MvDot(*qp_.x, *g_, xg);
  MVT::MvDot(*qp_.x, *qp_.b, xb);
  return S(0.5) * (xg[0] - xb[0]);
}

template <class S, class MV, class OP>
bool MprgpIteration<S, MV, OP>::tryOptimalExpansion() {
  // phi holds the free gradient at the half step x; phi^T g = phi^T phi.
  applyA(*phi_, *Ap_);
  std::vector<S> phiAphi(1), phiPhi(1);
  MVT::MvDot(*phi_, *Ap_, phiAphi);
  MVT::MvDot(*phi_, *phi_, phiPhi);
  if (!(phiAphi[0] > S(0))) return false;
  const S fHalf = energy();
  MVT::Assign(*qp_.x, *xHalf_);
  MVT::MvAddMv(S(1), *qp_.x, -phiPhi[0] / phiAphi[0], *phi_, *qp_.x);
  set_->project(*qp_.x);
  computeGradient();
  if (energy() <= fHalf) {
    updateGradientSplit();
    precondition(*p_);
    return true;
  }
  // The projection spoiled the step: back to the half step, whose gradient is recomputed by
  // the fixed-length step that follows.
  MVT::Assign(*xHalf_, *qp_.x);
  return false;
}

template <class S, class MV, class OP>
bool MprgpIteration<S, MV, OP>::tryProjectedCgExpansion(S alphaFeasible, S alphaCg) {
  using BT = BoundTraits<S, MV>;
  // The feasible half step and its energy, kept for the fall-back (no multiplication).
  MVT::MvAddMv(S(1), *qp_.x, -alphaFeasible, *p_, *xHalf_);
  set_->project(*xHalf_);
  MVT::MvAddMv(S(1), *g_, -alphaFeasible, *Ap_, *gHalf_);
  std::vector<S> xg(1), xb(1);
  MVT::MvDot(*xHalf_, *gHalf_, xg);
  MVT::MvDot(*xHalf_, *qp_.b, xb);
  const S fHalf = S(0.5) * (xg[0] - xb[0]);
  MVT::MvAddMv(S(1), *qp_.x, -alphaCg, *p_, *qp_.x);
  set_->project(*qp_.x);
  computeGradient();
  if (BT::allFinite(*g_) && energy() <= fHalf) {
    updateGradientSplit();
    precondition(*p_);
    return true;
  }
  MVT::Assign(*xHalf_, *qp_.x);
  MVT::Assign(*gHalf_, *g_);
  return false;
}

template <class S, class MV, class OP>
const char* MprgpIteration<S, MV, OP>::expansionStep(S alphaFeasible, S alphaCg) {
  // MPGP: where p slides on circles the half step's gradient g - alpha (A + K) p is the
  // curvature model's, not A x - b at the projected half step; it only chooses the direction
  // (and the projected CG variant's comparison), and every path below ends with g = A x - b.
  if (opts_.projectedCgExpansion) {
    if (tryProjectedCgExpansion(alphaFeasible, alphaCg)) {
      ++counters_.expansionSteps;
      return "expansion (CG)";
    }
    // x and g are the half step's: continue with the projected gradient step.
    alphaFeasible = 0;
  }
  MVT::MvAddMv(S(1), *qp_.x, -alphaFeasible, *p_, *qp_.x);
  set_->project(*qp_.x);
  MVT::MvAddMv(S(1), *g_, -alphaFeasible, *Ap_, *g_);
  set_->freeGradient(*qp_.x, *g_, *phi_);
  if (opts_.optimalExpansion && tryOptimalExpansion()) {
    ++counters_.expansionSteps;
    return "expansion (opt)";
  }
  MVT::MvAddMv(S(1), *qp_.x, -opts_.alphaBar, *phi_, *qp_.x);
  set_->project(*qp_.x);
  // The projection changed x non-linearly: recompute the gradient, which also stops the
  // recursive update from drifting.
  computeGradient();
  updateGradientSplit();
  precondition(*p_);
  ++counters_.expansionSteps;
  return opts_.projectedCgExpansion ? "expansion (fixed, fall-back)" : "expansion";
}

template <class S, class MV, class OP>
void MprgpIteration<S, MV, OP>::proportioningStep() {
  // d = beta lives on the active set, beta <= 0 at lower and >= 0 at upper bounds, so
  // x - alpha d (alpha > 0) only moves components off their bounds into the box; with lower
  // bounds only that is always feasible. g^T d = ||beta||^2 > 0.
  applyA(*beta_, *Ap_);
  std::vector<S> dAd(1);
  MVT::MvDot(*beta_, *Ap_, dAd);
  if (!(dAd[0] > S(0))) {
    std::ostringstream os;
    if (!std::isfinite(dAd[0]))
      os << "MPRGP: d^T A d is " << dAd[0] << " (A produced NaN or Inf)";
    else
      os << "MPRGP: the Hessian is not positive definite on the free set (d^T A d = " << dAd[0]
         << " along the chopped gradient at step " << iter_ << ")";
    throw std::runtime_error(os.str());
  }
  S alpha = betaNorm2_ / dAd[0];
  if (upper_ != nullptr || set_->hasDiscs()) {
    // With two bounds the step may carry a component from one bound past the other: stop at
    // the first one reached (f still decreases, alpha <= the minimizing length), and project
    // away the rounding, as in a CG step. On an active disc -beta points along -n, into the
    // disc: the step may cross it to the far side of the circle at most.
    alpha = std::min(alpha, set_->maxFeasibleStep(*qp_.x, *beta_));
    MVT::MvAddMv(S(1), *qp_.x, -alpha, *beta_, *qp_.x);
    set_->project(*qp_.x);
  } else {
    MVT::MvAddMv(S(1), *qp_.x, -alpha, *beta_, *qp_.x);
  }
  MVT::MvAddMv(S(1), *g_, -alpha, *Ap_, *g_);
  updateGradientSplit();
  precondition(*p_);
  ++counters_.proportioningSteps;
}

template <class S, class MV, class OP>
void MprgpIteration<S, MV, OP>::record(const char* kind) {
  counters_.history.push_back(gpNorm_);
  if (opts_.verbosity < 2) return;
  // Collective: every rank counts, rank 0 prints.
  const std::size_t active = set_->activeIndices(*qp_.x).size();
  if (root_) {
    // Formatted apart: the target stream's precision and flags stay the caller's.
    std::ostringstream os;
    os << "  MPRGP " << std::setw(5) << iter_ + 1 << "  " << std::left << std::setw(28) << kind
       << std::right << " ||g^P||/||b|| = " << std::scientific << std::setprecision(3)
       << gpNorm_ / opts_.printScale << "  active " << active << "\n";
    (opts_.out != nullptr ? *opts_.out : std::cout) << os.str() << std::flush;
  }
}

}  // namespace tfeti
