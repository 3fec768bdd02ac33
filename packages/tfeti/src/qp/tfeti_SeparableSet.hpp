#pragma once
// The feasible set of MPGP (Dostál's modified proportioning with gradient projections): a
// product of intervals l_i <= x_i <= u_i (the boxes of MPRGP, tfeti_BoundTraits.hpp) and discs
// |(x_i, x_{i+1})| <= r (3D friction: the two tangential multipliers of a contact node under the
// slip bound), |x - c| <= r with a centre c (the dual QP's shift by the particular
// multiplier). Without discs every operation is BoundTraits' on (l, u), the same operations in
// the same order, so MPRGP's steps are unchanged.
//
// The discs are given by one vector on x's map (BoundConstrainedQp::discs): r >= 0 at the first
// component i of a disc, a negative marker (-1) at its second component i + 1, NaN elsewhere.
// Both components of a disc are owned by one rank, consecutive there (checkDiscs says which
// disc is split), and have no interval bounds (l = -inf, u = +inf).
//
// On a disc with r > 0, x is active when |x| >= r (1 - kDiscTolerance): the projection scales x
// back onto the circle, which hits r only to rounding, so the test has a relative tolerance
// (boxes are tested exactly, as the projection sets x_i = l_i exactly). A disc with r = 0 is the
// point 0, always active and fixed (like l_i = u_i). With n = x / |x| the outward normal:
//  - free gradient phi: g on a free disc; on an active one its tangential part g - (n.g) n, the
//    direction in which x slides along the circle (the CG face of an active disc is its
//    tangent, as the free component of a box pair at one bound is free; MPGP's CG steps there
//    are followed by the projection back onto the circle);
//  - chopped gradient beta on an active disc: max(n.g, 0) n, the part that -g moves into the
//    disc (0 when -g points out); 0 when r = 0. phi + beta is the projection of g onto the
//    tangent cone, zero exactly at a KKT point;
//  - reduced free gradient: phi~ = (x - P(x - alphaBar phi)) / alphaBar (for an interval the
//    same as MPRGP's min((x - l) / alphaBar, phi) form);
//  - the feasible step along -p: the positive root of |x - alpha p| = r (CG steps leave out
//    the active discs, whose tangential move the projection follows).
#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_MultiVector.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "tfeti_BoundTraits.hpp"
#include "tfeti_QpProblem.hpp"

namespace tfeti {

// Relative tolerance of the active test on a disc (|x| >= r (1 - tol)) and of its feasibility
// (|x| <= r (1 + tol)).
constexpr double kDiscTolerance = 1e-12;

template <class S, class MV>
class SeparableSet;

template <class S, class LO, class GO, class Node>
class SeparableSet<S, Tpetra::MultiVector<S, LO, GO, Node>> {
 public:
  using MV = Tpetra::MultiVector<S, LO, GO, Node>;
  using BT = BoundTraits<S, MV>;

  // lower must outlive the set; upper and discs may be null (none). Collective.
  SeparableSet(const MV& lower, const MV* upper, const MV* discs, const MV* centers = nullptr)
      : l_(lower), u_(upper) {
    if (discs != nullptr) {
      checkDiscs(*discs, lower, upper);
      auto dv = discs->getData(0);
      Teuchos::ArrayRCP<const S> cv;
      if (centers != nullptr) cv = centers->getData(0);
      for (std::size_t i = 0; i < discs->getLocalLength(); ++i)
        if (dv[i] >= S(0)) {
          first_.push_back(static_cast<LO>(i));
          radius_.push_back(dv[i]);
          center_.push_back(cv.is_null() ? S(0) : cv[i]);
          center_.push_back(cv.is_null() ? S(0) : cv[i + 1]);
        }
    }
    int mine = first_.empty() ? 0 : 1, any = 0;
    Teuchos::reduceAll(*lower.getMap()->getComm(), Teuchos::REDUCE_MAX, 1, &mine, &any);
    hasDiscs_ = any == 1;
  }

  // Throws std::runtime_error naming the first bad component (global index) when the disc
  // vector is malformed: a radius NaN-free but negative without a first component before it, a
  // first component whose second is on another rank, a radius that is +inf, or interval bounds
  // on a disc component. Collective.
  static void checkDiscs(const MV& discs, const MV& lower, const MV* upper) {
    const auto map = discs.getMap();
    auto dv = discs.getData(0);
    auto lv = lower.getData(0);
    Teuchos::ArrayRCP<const S> uv;
    if (upper != nullptr) uv = upper->getData(0);
    const std::size_t n = discs.getLocalLength();
    constexpr S inf = std::numeric_limits<S>::infinity();
    long long bad = std::numeric_limits<long long>::max();
    int why = 0;
    auto flag = [&](std::size_t i, int reason) {
      const long long gi = static_cast<long long>(map->getGlobalElement(static_cast<LO>(i)));
      if (gi < bad) bad = gi, why = reason;
    };
    for (std::size_t i = 0; i < n; ++i) {
      if (std::isnan(dv[i])) continue;
      if (lv[i] != -inf || (!uv.is_null() && uv[i] != inf)) flag(i, 1);
      if (dv[i] >= S(0)) {
        if (dv[i] == inf) flag(i, 2);
        const bool pairHere = i + 1 < n && dv[i + 1] < S(0) &&
                              map->getGlobalElement(static_cast<LO>(i + 1)) ==
                                  map->getGlobalElement(static_cast<LO>(i)) + 1;
        if (!pairHere) flag(i, 3);
      } else if (i == 0 || !(dv[i - 1] >= S(0))) {
        flag(i, 4);
      }
    }
    long long worst = bad;
    Teuchos::reduceAll(*map->getComm(), Teuchos::REDUCE_MIN, 1, &bad, &worst);
    int reason = worst == bad ? why : 0, r = 0;
    Teuchos::reduceAll(*map->getComm(), Teuchos::REDUCE_MAX, 1, &reason, &r);
    if (worst == std::numeric_limits<long long>::max()) return;
    const std::string at = "MPGP: disc constraint at component " + std::to_string(worst) + ": ";
    if (r == 1)
      throw std::runtime_error(at +
                               "a disc component has interval bounds (lower must be -Inf, "
                               "upper +Inf or absent)");
    if (r == 2) throw std::runtime_error(at + "the radius is +Inf (leave the pair unbounded)");
    if (r == 3)
      throw std::runtime_error(at +
                               "the first component of a disc (radius >= 0) must be followed "
                               "by its second (marker -1) on the same rank");
    throw std::runtime_error(at +
                             "a second component (negative marker) without a first one "
                             "(radius >= 0) at the index before it on the same rank");
  }

  bool hasDiscs() const { return hasDiscs_; }

  // x = P(x): the box projection, then every disc scaled back onto its circle.
  void project(MV& x) const {
    BT::project(x, l_, u_);
    if (first_.empty()) return;
    auto xv = x.getDataNonConst(0);
    for (std::size_t k = 0; k < first_.size(); ++k) {
      const S a = xv[first_[k]] - center_[2 * k], b = xv[first_[k] + 1] - center_[2 * k + 1];
      const S r = radius_[k], n2 = a * a + b * b;
      if (n2 <= r * r) continue;
      const S s = r > S(0) ? r / std::sqrt(n2) : S(0);
      xv[first_[k]] = center_[2 * k] + s * a;
      xv[first_[k] + 1] = center_[2 * k + 1] + s * b;
    }
  }

  void freeGradient(const MV& x, const MV& g, MV& phi) const {
    BT::freeGradient(x, l_, u_, g, phi);
    if (first_.empty()) return;
    auto xv = x.getData(0);
    auto gv = g.getData(0);
    auto pv = phi.getDataNonConst(0);
    for (std::size_t k = 0; k < first_.size(); ++k) {
      const LO i = first_[k];
      pv[i] = gv[i];
      pv[i + 1] = gv[i + 1];
      if (active(xv, k)) tangential(xv, k, pv[i], pv[i + 1]);
    }
  }

  void choppedGradient(const MV& x, const MV& g, MV& beta) const {
    BT::choppedGradient(x, l_, u_, g, beta);
    if (first_.empty()) return;
    auto xv = x.getData(0);
    auto gv = g.getData(0);
    auto bv = beta.getDataNonConst(0);
    for (std::size_t k = 0; k < first_.size(); ++k) {
      const LO i = first_[k];
      bv[i] = bv[i + 1] = S(0);
      if (!active(xv, k) || !(radius_[k] > S(0))) continue;
      S n0, n1;
      normal(xv, k, n0, n1);
      const S ng = std::max(n0 * gv[i] + n1 * gv[i + 1], S(0));
      bv[i] = ng * n0;
      bv[i + 1] = ng * n1;
    }
  }

  void restrictToFree(const MV& x, MV& z) const {
    BT::restrictToFree(x, l_, u_, z);
    restrictToCircleTangents(x, z);
  }

  // z on each active disc replaced by its tangential part (0 where r = 0); the rest untouched.
  void restrictToCircleTangents(const MV& x, MV& z) const {
    if (first_.empty()) return;
    auto xv = x.getData(0);
    auto zv = z.getDataNonConst(0);
    for (std::size_t k = 0; k < first_.size(); ++k)
      if (active(xv, k)) tangential(xv, k, zv[first_[k]], zv[first_[k] + 1]);
  }

  // Whether some active disc has a non-zero p (a step along p then slides on a circle, which
  // the projection follows: x is no longer linear in the step). Collective.
  bool slidesOnCircles(const MV& x, const MV& p) const {
    if (!hasDiscs_) return false;
    auto xv = x.getData(0);
    auto pv = p.getData(0);
    int mine = 0;
    for (std::size_t k = 0; k < first_.size(); ++k)
      if (radius_[k] > S(0) && active(xv, k) &&
          (pv[first_[k]] != S(0) || pv[first_[k] + 1] != S(0)))
        mine = 1;
    int any = mine;
    Teuchos::reduceAll(*x.getMap()->getComm(), Teuchos::REDUCE_MAX, 1, &mine, &any);
    return any == 1;
  }

  // Ap += K p with K = (nu / r) I on the tangent of each active disc, nu = max(-n.g, 0) the
  // multiplier that holds x on the circle: the circle's curvature in f along the circle,
  // f(P(x - t p)) = f(x) - t g^T p + t^2 / 2 (p^T A p + sum nu |p_k|^2 / r) + O(t^3) for a
  // tangential p. Without it a CG step on the tangent overshoots by the ratio of the two.
  void addCircleCurvature(const MV& x, const MV& g, const MV& p, MV& Ap) const {
    if (first_.empty()) return;
    auto xv = x.getData(0);
    auto gv = g.getData(0);
    auto pv = p.getData(0);
    auto av = Ap.getDataNonConst(0);
    for (std::size_t k = 0; k < first_.size(); ++k) {
      const LO i = first_[k];
      if (!(radius_[k] > S(0)) || !active(xv, k)) continue;
      S n0, n1;
      normal(xv, k, n0, n1);
      const S nu = std::max(-(n0 * gv[i] + n1 * gv[i + 1]), S(0));
      av[i] += nu / radius_[k] * pv[i];
      av[i + 1] += nu / radius_[k] * pv[i + 1];
    }
  }

  // phi~^T phi over the free components (collective).
  S reducedFreeGradientDot(const MV& x, const MV& phi, S alphaBar) const {
    if (!hasDiscs_) return BT::reducedFreeGradientDot(x, l_, u_, phi, alphaBar);
    // The intervals' part with the disc components of phi zeroed (they are unbounded there).
    if (work_.is_null() || !work_->getMap()->isSameAs(*phi.getMap()))
      work_ = Teuchos::rcp(new MV(phi.getMap(), 1));
    Tpetra::deep_copy(*work_, phi);
    auto wv = work_->getDataNonConst(0);
    for (const LO i : first_) wv[i] = wv[i + 1] = S(0);
    wv = Teuchos::null;
    const S boxes = BT::reducedFreeGradientDot(x, l_, u_, *work_, alphaBar);
    auto xv = x.getData(0);
    auto pv = phi.getData(0);
    S local = 0;
    for (std::size_t k = 0; k < first_.size(); ++k) {
      const LO i = first_[k];
      if (!(radius_[k] > S(0))) continue;
      // y = P(x - alphaBar phi) - c, x - c: the disc's coordinates about its centre.
      const S x0 = xv[i] - center_[2 * k], x1 = xv[i + 1] - center_[2 * k + 1];
      S y0 = x0 - alphaBar * pv[i], y1 = x1 - alphaBar * pv[i + 1];
      const S r = radius_[k], n2 = y0 * y0 + y1 * y1;
      if (n2 > r * r) {
        const S s = r / std::sqrt(n2);
        y0 *= s;
        y1 *= s;
      }
      local += ((x0 - y0) * pv[i] + (x1 - y1) * pv[i + 1]) / alphaBar;
    }
    return boxes + sum(x, local);
  }

  // The largest alpha with x - alpha p in the set (collective); +infinity when unbounded. With
  // alongCircles the active discs are left out: a CG step moves them along their tangent and
  // the projection keeps them on the circle.
  S maxFeasibleStep(const MV& x, const MV& p, bool alongCircles = false) const {
    const S boxes = BT::maxFeasibleStep(x, l_, u_, p);
    if (!hasDiscs_) return boxes;
    auto xv = x.getData(0);
    auto pv = p.getData(0);
    S local = std::numeric_limits<S>::infinity();
    for (std::size_t k = 0; k < first_.size(); ++k) {
      const LO i = first_[k];
      if (alongCircles && radius_[k] > S(0) && active(xv, k)) continue;
      const S a = pv[i] * pv[i] + pv[i + 1] * pv[i + 1];
      if (!(a > S(0))) continue;
      const S r = radius_[k];
      const S x0 = xv[i] - center_[2 * k], x1 = xv[i + 1] - center_[2 * k + 1];
      const S b = x0 * pv[i] + x1 * pv[i + 1];
      const S c = std::max(r * r - (x0 * x0 + x1 * x1), S(0));
      const S root = std::sqrt(b * b + a * c);
      // The positive root of a alpha^2 - 2 b alpha - c = 0, without cancellation.
      const S alpha = b >= S(0) ? (b + root) / a : (root - b > S(0) ? c / (root - b) : S(0));
      local = std::min(local, alpha);
    }
    S global = local;
    Teuchos::reduceAll(*x.getMap()->getComm(), Teuchos::REDUCE_MIN, 1, &local, &global);
    return std::min(boxes, global);
  }

  // Exactly feasible in the intervals, within the tolerance in the discs (collective).
  bool isFeasible(const MV& x) const {
    const bool boxes = BT::isFeasible(x, l_, u_);
    if (!hasDiscs_) return boxes;
    auto xv = x.getData(0);
    int bad = 0;
    for (std::size_t k = 0; k < first_.size(); ++k)
      if (!(norm(xv, k) <= radius_[k] * (S(1) + S(kDiscTolerance)))) bad = 1;
    int any = bad;
    Teuchos::reduceAll(*x.getMap()->getComm(), Teuchos::REDUCE_MAX, 1, &bad, &any);
    return boxes && any == 0;
  }

  // A disc with r > 0 on its circle as a row of a face (SMALBE's face solve, tfeti_FaceProjector
  // .hpp): the global index of its first component, the outward unit normal n at x, the radius
  // and the centre. The face holds n . (x - c) = r and lets x move along the tangent.
  struct Circle {
    long long index;
    S n0, n1, radius, c0, c1;
  };
  // The discs with r > 0 whose first component is in `among` (sorted global indices), with their
  // normals at x, sorted by index, on every rank. A disc whose x is at its centre has no normal
  // and is left out. Collective.
  std::vector<Circle> circles(const MV& x, const std::vector<long long>& among) const {
    std::vector<S> mine;
    if (!first_.empty()) {
      const auto map = x.getMap();
      auto xv = x.getData(0);
      for (std::size_t k = 0; k < first_.size(); ++k) {
        const long long gi = static_cast<long long>(map->getGlobalElement(first_[k]));
        if (!(radius_[k] > S(0)) || !std::binary_search(among.begin(), among.end(), gi)) continue;
        if (!(norm(xv, k) > S(0))) continue;
        S n0, n1;
        normal(xv, k, n0, n1);
        for (S v : {static_cast<S>(gi), n0, n1, radius_[k], center_[2 * k], center_[2 * k + 1]})
          mine.push_back(v);
      }
    }
    // Gathered as six numbers per disc (the index is exact in a double below 2^53).
    const auto& comm = *x.getMap()->getComm();
    long long count = static_cast<long long>(mine.size()), most = 0;
    Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &count, &most);
    mine.resize(static_cast<std::size_t>(most), S(-1));
    std::vector<S> all(static_cast<std::size_t>(most) * comm.getSize());
    if (most > 0)
      Teuchos::gatherAll(comm, static_cast<int>(most), mine.data(), static_cast<int>(all.size()),
                         all.data());
    std::vector<Circle> out;
    for (std::size_t i = 0; i + 5 < all.size(); i += 6)
      if (all[i] >= S(0))
        out.push_back({static_cast<long long>(all[i]), all[i + 1], all[i + 2], all[i + 3],
                       all[i + 4], all[i + 5]});
    std::sort(out.begin(), out.end(),
              [](const Circle& a, const Circle& b) { return a.index < b.index; });
    return out;
  }

  // The global indices of both components of every disc of radius 0 (a point, always active),
  // sorted, on every rank (collective).
  std::vector<long long> pointComponents(const MV& x) const {
    const auto map = x.getMap();
    std::vector<long long> mine;
    for (std::size_t k = 0; k < first_.size(); ++k)
      if (!(radius_[k] > S(0))) {
        const long long gi = static_cast<long long>(map->getGlobalElement(first_[k]));
        mine.push_back(gi);
        mine.push_back(gi + 1);
      }
    return BT::gatherIndices(*map, std::move(mine));
  }

  // The global indices of the active components (both of an active disc), sorted, on every
  // rank.
  std::vector<long long> activeIndices(const MV& x) const {
    std::vector<long long> boxes = BT::activeIndices(x, l_, u_);
    if (!hasDiscs_) return boxes;
    const auto map = x.getMap();
    auto xv = x.getData(0);
    std::vector<long long> mine;
    for (std::size_t k = 0; k < first_.size(); ++k)
      if (active(xv, k)) {
        const long long gi = static_cast<long long>(map->getGlobalElement(first_[k]));
        mine.push_back(gi);
        mine.push_back(gi + 1);
      }
    const std::vector<long long> discs = BT::gatherIndices(*map, std::move(mine));
    std::vector<long long> all;
    std::merge(boxes.begin(), boxes.end(), discs.begin(), discs.end(), std::back_inserter(all));
    return all;
  }

 private:
  // |x - c| on disc k.
  template <class View>
  S norm(const View& xv, std::size_t k) const {
    return std::hypot(xv[first_[k]] - center_[2 * k], xv[first_[k] + 1] - center_[2 * k + 1]);
  }
  template <class View>
  bool active(const View& xv, std::size_t k) const {
    const S r = radius_[k];
    return !(r > S(0)) || norm(xv, k) >= r * (S(1) - S(kDiscTolerance));
  }
  // The outward normal at an active disc with r > 0 (x != 0 there).
  template <class View>
  void normal(const View& xv, std::size_t k, S& n0, S& n1) const {
    const S len = norm(xv, k);
    n0 = (xv[first_[k]] - center_[2 * k]) / len;
    n1 = (xv[first_[k] + 1] - center_[2 * k + 1]) / len;
  }
  // (v0, v1) on active disc k replaced by its tangential part; 0 where r = 0.
  template <class View>
  void tangential(const View& xv, std::size_t k, S& v0, S& v1) const {
    if (!(radius_[k] > S(0))) {
      v0 = v1 = S(0);
      return;
    }
    // (t.v) t with the unit tangent t = (-n1, n0), not v - (n.v) n: where v is mostly normal
    // (g on a sliding disc: its multiplier nu >> its tangential part near the solution) the
    // difference leaves a normal residue of eps |v|, which in g^T p would outweigh the
    // tangential part; (t.v) t is tangential to eps relative to itself.
    S n0, n1;
    normal(xv, k, n0, n1);
    const S tv = n0 * v1 - n1 * v0;
    v0 = -n1 * tv;
    v1 = n0 * tv;
  }
  static S sum(const MV& x, S local) {
    S global = local;
    Teuchos::reduceAll(*x.getMap()->getComm(), Teuchos::REDUCE_SUM, 1, &local, &global);
    return global;
  }

  const MV& l_;
  const MV* u_;
  std::vector<LO> first_;  // local index of each disc's first component; the second is next
  std::vector<S> radius_;
  std::vector<S> center_;  // per disc: the centre's two components
  bool hasDiscs_ = false;
  mutable Teuchos::RCP<MV> work_;
};

// The feasible set of a problem: its intervals and discs.
template <class S, class MV, class OP>
SeparableSet<S, MV> feasibleSet(const BoundConstrainedQp<S, MV, OP>& qp) {
  return SeparableSet<S, MV>(*qp.lower, qp.upper.get(), qp.discs.get(), qp.discCenters.get());
}

}  // namespace tfeti
