#pragma once
// MPRGP (modified proportioning with reduced gradient projections; Dostál & Schöberl 2005,
// Dostál, "Optimal Quadratic Programming Algorithms", 2009) as a Belos::Iteration for
//   min 1/2 x^T A x - b^T x  subject to  l <= x <= u   (u optional: the box version).
//
// Notation (g = A x - b): the free gradient phi (g on the free set l_i < x_i < u_i), the
// chopped gradient beta (min(g_i, 0) where x_i = l_i, max(g_i, 0) where x_i = u_i, 0 where
// l_i = u_i), the projected gradient g^P = phi + beta (zero exactly at the solution), the reduced
// free gradient phi~_i = min((x_i - l_i) / alphaBar, phi_i) for phi_i >= 0 and
// max((x_i - u_i) / alphaBar, phi_i) for phi_i < 0. The feasible step along a direction stops at
// the first bound reached on either side, the projection is onto the box. Without u (or with
// u = +infinity) every step is the lower-bound-only algorithm's. Each step of iterate() is one of
//  - CG step: when x is proportional (||beta||^2 <= Gamma^2 phi~^T phi) and the CG step along p
//    stays feasible;
//  - expansion step: proportional, but the CG step would leave the feasible set: go to the bound
//    along p, then take the projected free-gradient step x = P(x - alphaBar phi) (it may add or
//    remove several active constraints at once) and restart CG;
//  - proportioning step: not proportional (the chopped gradient dominates): a minimizing step
//    along -beta, which releases constraints (with u: shortened to the first bound reached on
//    the other side of the box), and restart CG.
//
// Preconditioning in face: given an operator M (an approximate inverse of A, symmetric positive
// definite), the CG directions use z = R M R phi, R zeroing the active components, instead of
// phi: CG on the current face preconditioned by the face block of M. It changes neither the
// proportioning test nor the expansion step (which use phi), so the finite termination and the
// R-linear rate of MPRGP are kept; it pays off when M is a good approximation on every face (for
// example a diagonal scaling of a badly scaled A).
//
// MPGP (Dostál's modified proportioning with gradient projections; Kučera 2008, Dostál et al.
// 2012 for 3D friction): with disc constraints |(x_i, x_{i+1})| <= r (BoundConstrainedQp::discs)
// the same steps run on the product of intervals and discs (tfeti_SeparableSet.hpp): projection
// onto the discs, the feasible step to the circle, the reduced free gradient
// phi~ = (x - P(x - alphaBar phi)) / alphaBar. On an active disc (n the outward normal) the free
// gradient is g's tangential part and the chopped gradient max(n.g, 0) n: CG runs on the face
// that holds each active disc's tangent, as it holds the free component of a box pair at one
// bound. The circle is curved, so such a CG step is followed by the projection onto the circle
// and a fresh gradient (one more multiplication), its length uses p^T A p plus the circle's
// curvature sum nu_k |p_k|^2 / r_k (nu = max(-n.g, 0)), the next direction is moved onto the new
// tangents (and restarted when that leaves no descent), and a step that does not decrease f is
// replaced by the projected gradient step x = P(x - alphaBar g). Held out of the face (phi = 0
// on an active disc, the implementation before 2026-11-27) the discs moved along their circles
// by proportioning steps only, which on a badly conditioned A took thousands of steps. The
// proportioning step is MPRGP's along -beta, into the discs. Without discs nothing changes: MPRGP
// is MPGP on boxes, and one class runs both (MpgpIteration names it).
//
// The iteration works in place on the problem's x (projected onto the bounds by initialize()),
// so a status test can read the iterate through getProblem().getLHS().
#include <BelosIteration.hpp>
#include <BelosLinearProblem.hpp>
#include <BelosMultiVecTraits.hpp>
#include <BelosOperatorTraits.hpp>
#include <BelosStatusTest.hpp>
#include <Teuchos_RCP.hpp>

#include <iosfwd>
#include <vector>

#include "tfeti_QpProblem.hpp"

namespace tfeti {

template <class S, class MV>
class SeparableSet;

template <class S, class MV, class OP>
class MprgpIteration : public Belos::Iteration<S, MV, OP> {
 public:
  using magnitude_type = typename Teuchos::ScalarTraits<S>::magnitudeType;

  struct Options {
    S gamma = 1;     // proportioning parameter Gamma > 0
    S alphaBar = 0;  // fixed step length of the expansion step, in (0, 2 / ||A||]
    // Expansion along the free gradient with the step that minimizes f before the projection
    // (one more multiplication), falling back to alphaBar when the projected step does not
    // decrease f. Helps when ||A|| is dominated by a part of A the bounds do not touch (the
    // penalized dual Hessian P F P + rho Q, where alphaBar ~ 2/rho hardly moves x).
    bool optimalExpansion = false;
    // Expansion by the projected conjugate gradient step x = P(x - alphaCg p): the CG step
    // length of the (preconditioned) direction, which adds every constraint the step crosses at
    // once. Accepted when f does not exceed f at the feasible half step x - alphaFeasible p;
    // otherwise the fixed-length (or optimal) expansion from the half step is taken (one more
    // multiplication). The CG step length is set by the curvature along p, not by ||A||, so it
    // is not shortened by a large part of A the bounds do not see (rho Q in SMALBE).
    bool projectedCgExpansion = false;
    S printScale = 1;             // verbosity 2 prints ||g^P|| / printScale
    int verbosity = 0;            // >= 2: one line per step on rank 0
    std::ostream* out = nullptr;  // std::cout when null
  };

  // qp.A, qp.b, qp.lower and qp.x must be set, qp.upper may; M (optional) enables
  // preconditioning in face.
  MprgpIteration(const BoundConstrainedQp<S, MV, OP>& qp, Teuchos::RCP<const OP> M,
                 Teuchos::RCP<Belos::StatusTest<S, MV, OP>> tester, const Options& options);

  // Belos::Iteration.
  // Runs MPRGP steps until the status test returns Passed (Belos convention: Failed and
  // Undefined mean "not yet"), or the projected gradient is exactly zero. Throws
  // std::runtime_error when the Hessian is not positive definite on the free set or a
  // non-finite value appears.
  void iterate() override;
  // Projects x onto the bounds, checks the data for NaN/Inf, computes g = A x - b, phi, beta
  // and p. Called by iterate() when needed.
  void initialize() override;
  int getNumIters() const override { return iter_; }
  void resetNumIters(int iter = 0) override { iter_ = iter; }
  // norms[0] = ||g^P||; returns null (there is no residual vector).
  Teuchos::RCP<const MV> getNativeResiduals(std::vector<magnitude_type>* norms) const override;
  // The iterate is updated in place: there is no separate update.
  Teuchos::RCP<MV> getCurrentUpdate() const override { return Teuchos::null; }
  const Belos::LinearProblem<S, MV, OP>& getProblem() const override { return *problem_; }
  int getBlockSize() const override { return 1; }
  void setBlockSize(int blockSize) override;
  bool isInitialized() override { return initialized_; }

  // Extras.
  // Throws std::runtime_error naming the culprit (and the component of a bound) when b, x or the
  // bounds contain NaN or Inf (lower bounds may be -Inf, upper bounds +Inf), or when a lower
  // bound exceeds the upper bound. Collective.
  static void checkProblemData(const BoundConstrainedQp<S, MV, OP>& qp);
  void setPrintScale(S scale) { opts_.printScale = scale; }
  // g = A x - b at the (feasible) initial x: initialize() copies it instead of multiplying.
  void setInitialGradient(Teuchos::RCP<const MV> g) { g0_ = std::move(g); }
  magnitude_type projectedGradientNorm() const { return gpNorm_; }
  // g = A x - b of the current iterate (updated recursively between restarts).
  Teuchos::RCP<const MV> getGradient() const { return g_; }
  // Step and multiplication counts and the history of ||g^P|| (absolute; the other fields are
  // left alone).
  const QpCounters& counters() const { return counters_; }
  // True when iterate() stopped because g^P = 0 exactly, not because of the status test.
  bool reachedStationaryPoint() const { return stationary_; }
  // The last search direction had a curvature p^T A p at the level of rounding: no further
  // progress is possible in floating point (the status tests judge whether that suffices).
  bool stalledAtRounding() const { return stalled_; }

 private:
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;

  void applyA(const MV& in, MV& out);
  // g = A x - b afresh (one multiplication).
  void computeGradient();
  // phi, beta, ||g^P|| and the proportioning test quantities from x and g.
  void updateGradientSplit();
  // p (or z) = the CG restart direction from phi.
  void precondition(MV& z);
  const char* cgStep(S alphaCg);  // returns the step's name
  // Returns the kind of expansion taken, for the verbose output.
  const char* expansionStep(S alphaFeasible, S alphaCg);
  bool tryProjectedCgExpansion(S alphaFeasible, S alphaCg);
  bool tryOptimalExpansion();
  S energy() const;
  void proportioningStep();
  void record(const char* kind);

  BoundConstrainedQp<S, MV, OP> qp_;
  const MV* upper_ = nullptr;                    // qp_.upper when it has a finite entry, else null
  Teuchos::RCP<const SeparableSet<S, MV>> set_;  // the intervals and discs of x
  Teuchos::RCP<const OP> M_;
  Teuchos::RCP<Belos::StatusTest<S, MV, OP>> tester_;
  Options opts_;
  Teuchos::RCP<Belos::LinearProblem<S, MV, OP>> problem_;
  Teuchos::RCP<MV> g_, p_, Ap_, phi_, beta_, z_, xHalf_, gHalf_;
  Teuchos::RCP<const MV> g0_;
  magnitude_type gpNorm_ = 0, betaNorm2_ = 0;
  S phiTildePhi_ = 0;
  int iter_ = 0;
  bool initialized_ = false, stationary_ = false, stalled_ = false, root_ = false;
  QpCounters counters_;
};

// MPGP: the same iteration, for problems with disc constraints.
template <class S, class MV, class OP>
using MpgpIteration = MprgpIteration<S, MV, OP>;

}  // namespace tfeti
