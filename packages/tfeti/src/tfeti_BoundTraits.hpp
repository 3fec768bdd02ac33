#pragma once
// Elementwise operations of the bound-constrained QP solvers (MPRGP, SMALBE) that
// Belos::MultiVecTraits does not offer. The algorithms only touch vectors through
// Belos::MultiVecTraits and this class, so another vector type needs one more specialization.
//
// All vectors are single columns (column 0 is used). Lower bounds may be -infinity, which means
// "unconstrained"; such components are always free. A component is active when x_i == l_i
// exactly: the solvers keep x feasible by projecting after every step, so the test is exact.
// Every function returning a scalar or bool is collective (reduced over the vector's map).
#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_MultiVector.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace tfeti {

template <class Scalar, class MV>
struct UndefinedBoundTraits {
  // Instantiating this means BoundTraits has no specialization for MV.
  static inline void notDefined() {
    return MV::this_type_is_missing_a_BoundTraits_specialization();
  }
};

template <class Scalar, class MV>
struct BoundTraits {
  static void project(MV& x, const MV& l) { UndefinedBoundTraits<Scalar, MV>::notDefined(); }
};

template <class S, class LO, class GO, class Node>
struct BoundTraits<S, Tpetra::MultiVector<S, LO, GO, Node>> {
  using MV = Tpetra::MultiVector<S, LO, GO, Node>;

  // x = max(x, l): the projection onto the feasible set.
  static void project(MV& x, const MV& l) {
    auto xv = x.getDataNonConst(0);
    auto lv = l.getData(0);
    const std::size_t n = x.getLocalLength();
    for (std::size_t i = 0; i < n; ++i)
      if (xv[i] < lv[i]) xv[i] = lv[i];
  }

  // phi_i = g_i where x_i > l_i, else 0.
  static void freeGradient(const MV& x, const MV& l, const MV& g, MV& phi) {
    auto xv = x.getData(0);
    auto lv = l.getData(0);
    auto gv = g.getData(0);
    auto pv = phi.getDataNonConst(0);
    const std::size_t n = x.getLocalLength();
    for (std::size_t i = 0; i < n; ++i) pv[i] = xv[i] > lv[i] ? gv[i] : S(0);
  }

  // beta_i = min(g_i, 0) where x_i == l_i, else 0.
  static void choppedGradient(const MV& x, const MV& l, const MV& g, MV& beta) {
    auto xv = x.getData(0);
    auto lv = l.getData(0);
    auto gv = g.getData(0);
    auto bv = beta.getDataNonConst(0);
    const std::size_t n = x.getLocalLength();
    for (std::size_t i = 0; i < n; ++i) bv[i] = xv[i] > lv[i] ? S(0) : std::min(gv[i], S(0));
  }

  // z_i = 0 where x_i is on its bound: restricts a direction to the current face.
  static void restrictToFree(const MV& x, const MV& l, MV& z) {
    auto xv = x.getData(0);
    auto lv = l.getData(0);
    auto zv = z.getDataNonConst(0);
    const std::size_t n = x.getLocalLength();
    for (std::size_t i = 0; i < n; ++i)
      if (!(xv[i] > lv[i])) zv[i] = S(0);
  }

  // phi~^T phi with phi~_i = min((x_i - l_i) / alphaBar, phi_i) on free components: the part of
  // the free gradient that a step of length alphaBar can use without hitting the bounds.
  static S reducedFreeGradientDot(const MV& x, const MV& l, const MV& phi, S alphaBar) {
    auto xv = x.getData(0);
    auto lv = l.getData(0);
    auto pv = phi.getData(0);
    const std::size_t n = x.getLocalLength();
    S local = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (xv[i] > lv[i]) local += std::min((xv[i] - lv[i]) / alphaBar, pv[i]) * pv[i];
    return sum(x, local);
  }

  // The largest alpha with x - alpha p >= l: min over p_i > 0 of (x_i - l_i) / p_i, or +infinity.
  static S maxFeasibleStep(const MV& x, const MV& l, const MV& p) {
    auto xv = x.getData(0);
    auto lv = l.getData(0);
    auto pv = p.getData(0);
    const std::size_t n = x.getLocalLength();
    S local = std::numeric_limits<S>::infinity();
    for (std::size_t i = 0; i < n; ++i)
      if (pv[i] > S(0) && lv[i] > -std::numeric_limits<S>::infinity())
        local = std::min(local, (xv[i] - lv[i]) / pv[i]);
    S global = local;
    Teuchos::reduceAll(*x.getMap()->getComm(), Teuchos::REDUCE_MIN, 1, &local, &global);
    return global;
  }

  // True when no entry is NaN or +-infinity; allowMinusInfinity accepts -inf (lower bounds).
  static bool allFinite(const MV& v, bool allowMinusInfinity = false) {
    auto vv = v.getData(0);
    const std::size_t n = v.getLocalLength();
    int bad = 0;
    for (std::size_t i = 0; i < n && !bad; ++i) {
      const bool minusInf = vv[i] == -std::numeric_limits<S>::infinity();
      if (!std::isfinite(vv[i]) && !(allowMinusInfinity && minusInf)) bad = 1;
    }
    return max(v, bad) == 0;
  }

  // True when x_i >= l_i for all i (exactly).
  static bool isFeasible(const MV& x, const MV& l) {
    auto xv = x.getData(0);
    auto lv = l.getData(0);
    const std::size_t n = x.getLocalLength();
    int bad = 0;
    for (std::size_t i = 0; i < n && !bad; ++i)
      if (!(xv[i] >= lv[i])) bad = 1;
    return max(x, bad) == 0;
  }

  // A start vector for power iterations that depends only on the global index, so the estimate
  // (and everything downstream) is the same on any number of ranks. Values in [0.5, 1.5): no
  // cancellation with the dominant eigenvector is likely.
  static void fillDeterministic(MV& v) {
    auto vv = v.getDataNonConst(0);
    const auto map = v.getMap();
    const std::size_t n = v.getLocalLength();
    for (std::size_t i = 0; i < n; ++i) {
      std::uint64_t h = static_cast<std::uint64_t>(map->getGlobalElement(static_cast<LO>(i)));
      h = (h + 0x9E3779B97F4A7C15ull) * 0xBF58476D1CE4E5B9ull;
      h ^= h >> 31;
      vv[i] = S(0.5) + S(h % 1000003ull) / S(1000003.0);
    }
  }

  static int commRank(const MV& v) { return v.getMap()->getComm()->getRank(); }

 private:
  static S sum(const MV& v, S local) {
    S global = local;
    Teuchos::reduceAll(*v.getMap()->getComm(), Teuchos::REDUCE_SUM, 1, &local, &global);
    return global;
  }
  static int max(const MV& v, int local) {
    int global = local;
    Teuchos::reduceAll(*v.getMap()->getComm(), Teuchos::REDUCE_MAX, 1, &local, &global);
    return global;
  }
};

}  // namespace tfeti
