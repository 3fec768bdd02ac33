#pragma once
// Elementwise operations of the bound-constrained QP solvers (MPRGP, SMALBE) that
// Belos::MultiVecTraits does not offer. The algorithms only touch vectors through
// Belos::MultiVecTraits and this class, so another vector type needs one more specialization.
//
// All vectors are single columns (column 0 is used). Lower bounds may be -infinity, upper bounds
// +infinity, which means "unconstrained" on that side. The upper bound vector is optional (a
// null pointer: no upper bounds); with it null or +infinity every function computes exactly what
// the lower-bound-only version computed, operation for operation, so lower-bound problems take
// the same steps. A component is free when l_i < x_i < u_i, active at its lower (upper) bound
// when x_i == l_i (x_i == u_i) exactly: the solvers keep x feasible by projecting after every
// step, so the tests are exact. A component with l_i == u_i is fixed: never free, its chopped
// gradient is zero. Every function returning a scalar or bool is collective (reduced over the
// vector's map).
#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_MultiVector.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

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
  static void project(MV& x, const MV& l, const MV* u = nullptr) {
    UndefinedBoundTraits<Scalar, MV>::notDefined();
  }
};

template <class S, class LO, class GO, class Node>
struct BoundTraits<S, Tpetra::MultiVector<S, LO, GO, Node>> {
  using MV = Tpetra::MultiVector<S, LO, GO, Node>;

  // x = min(max(x, l), u): the projection onto the feasible set.
  static void project(MV& x, const MV& l, const MV* u = nullptr) {
    auto xv = x.getDataNonConst(0);
    auto lv = l.getData(0);
    const std::size_t n = x.getLocalLength();
    for (std::size_t i = 0; i < n; ++i)
      if (xv[i] < lv[i]) xv[i] = lv[i];
    if (u == nullptr) return;
    auto uv = u->getData(0);
    for (std::size_t i = 0; i < n; ++i)
      if (xv[i] > uv[i]) xv[i] = uv[i];
  }

  // phi_i = g_i where l_i < x_i < u_i, else 0.
  static void freeGradient(const MV& x, const MV& l, const MV* u, const MV& g, MV& phi) {
    const Bounds b(x, l, u);
    auto gv = g.getData(0);
    auto pv = phi.getDataNonConst(0);
    for (std::size_t i = 0; i < b.n; ++i) pv[i] = b.isFree(i) ? gv[i] : S(0);
  }

  // beta_i = min(g_i, 0) where x_i == l_i < u_i, max(g_i, 0) where x_i == u_i > l_i, else 0
  // (free, or fixed by l_i == u_i): the part of the gradient that moving off the active bound
  // would decrease.
  static void choppedGradient(const MV& x, const MV& l, const MV* u, const MV& g, MV& beta) {
    const Bounds b(x, l, u);
    auto gv = g.getData(0);
    auto bv = beta.getDataNonConst(0);
    for (std::size_t i = 0; i < b.n; ++i) {
      if (b.isFree(i) || b.lv[i] == b.upper(i))
        bv[i] = S(0);
      else if (!(b.xv[i] > b.lv[i]))
        bv[i] = std::min(gv[i], S(0));
      else
        bv[i] = std::max(gv[i], S(0));
    }
  }

  // z_i = 0 where x_i is on a bound: restricts a direction to the current face.
  static void restrictToFree(const MV& x, const MV& l, const MV* u, MV& z) {
    const Bounds b(x, l, u);
    auto zv = z.getDataNonConst(0);
    for (std::size_t i = 0; i < b.n; ++i)
      if (!b.isFree(i)) zv[i] = S(0);
  }

  // phi~^T phi over free components with phi~_i = min((x_i - l_i) / alphaBar, phi_i) where
  // phi_i >= 0 and max((x_i - u_i) / alphaBar, phi_i) where phi_i < 0: the part of the free
  // gradient that a step of length alphaBar along -phi can use without hitting the bound it
  // moves towards.
  static S reducedFreeGradientDot(const MV& x, const MV& l, const MV* u, const MV& phi,
                                  S alphaBar) {
    const Bounds b(x, l, u);
    auto pv = phi.getData(0);
    S local = 0;
    for (std::size_t i = 0; i < b.n; ++i)
      if (b.isFree(i)) {
        const S reduced = pv[i] >= S(0) ? std::min((b.xv[i] - b.lv[i]) / alphaBar, pv[i])
                                        : std::max((b.xv[i] - b.upper(i)) / alphaBar, pv[i]);
        local += reduced * pv[i];
      }
    return sum(x, local);
  }

  // The largest alpha with l <= x - alpha p <= u: the minimum of (x_i - l_i) / p_i over p_i > 0
  // and of (x_i - u_i) / p_i over p_i < 0 (finite bounds only), or +infinity.
  static S maxFeasibleStep(const MV& x, const MV& l, const MV* u, const MV& p) {
    const Bounds b(x, l, u);
    auto pv = p.getData(0);
    constexpr S inf = std::numeric_limits<S>::infinity();
    S local = inf;
    for (std::size_t i = 0; i < b.n; ++i) {
      if (pv[i] > S(0) && b.lv[i] > -inf) local = std::min(local, (b.xv[i] - b.lv[i]) / pv[i]);
      if (pv[i] < S(0) && b.upper(i) < inf) local = std::min(local, (b.xv[i] - b.upper(i)) / pv[i]);
    }
    S global = local;
    Teuchos::reduceAll(*x.getMap()->getComm(), Teuchos::REDUCE_MIN, 1, &local, &global);
    return global;
  }

  // True when no entry is NaN or +-infinity; allowMinusInfinity accepts -inf (lower bounds).
  static bool allFinite(const MV& v, bool allowMinusInfinity = false) {
    return firstNonFinite(v, allowMinusInfinity, false) < 0;
  }

  // The smallest global index whose entry is NaN, or +-infinity where not allowed; -1 if none.
  static long long firstNonFinite(const MV& v, bool allowMinusInfinity, bool allowPlusInfinity) {
    auto vv = v.getData(0);
    const auto map = v.getMap();
    const std::size_t n = v.getLocalLength();
    constexpr S inf = std::numeric_limits<S>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      const bool allowed =
          (allowMinusInfinity && vv[i] == -inf) || (allowPlusInfinity && vv[i] == inf);
      if (!std::isfinite(vv[i]) && !allowed)
        return firstIndex(v, static_cast<long long>(map->getGlobalElement(static_cast<LO>(i))));
    }
    return firstIndex(v, -1);
  }

  // The smallest global index with l_i > u_i (the bounds cross); -1 if none.
  static long long firstCrossing(const MV& l, const MV& u) {
    auto lv = l.getData(0);
    auto uv = u.getData(0);
    const auto map = l.getMap();
    const std::size_t n = l.getLocalLength();
    for (std::size_t i = 0; i < n; ++i)
      if (lv[i] > uv[i])
        return firstIndex(l, static_cast<long long>(map->getGlobalElement(static_cast<LO>(i))));
    return firstIndex(l, -1);
  }

  // v at global index `index` (which must exist), on every rank.
  static S valueAt(const MV& v, long long index) {
    const auto map = v.getMap();
    const LO local = map->getLocalElement(static_cast<GO>(index));
    // Exactly one rank owns the index: the sum of its value and zeros is that value.
    S mine = local == Teuchos::OrdinalTraits<LO>::invalid() ? S(0) : v.getData(0)[local];
    return sum(v, mine);
  }

  // True when l_i <= x_i <= u_i for all i (exactly).
  static bool isFeasible(const MV& x, const MV& l, const MV* u = nullptr) {
    const Bounds b(x, l, u);
    int bad = 0;
    for (std::size_t i = 0; i < b.n && !bad; ++i)
      if (!(b.xv[i] >= b.lv[i]) || b.xv[i] > b.upper(i)) bad = 1;
    return max(x, bad) == 0;
  }

  // The face of x (the face solve of SMALBE): the global indices of the components at a bound
  // (x_i == l_i or x_i == u_i exactly, fixed components included), sorted, on every rank. The
  // order is that of the global indices, so it does not depend on the rank count.
  static std::vector<long long> activeIndices(const MV& x, const MV& l, const MV* u) {
    const Bounds b(x, l, u);
    const auto map = x.getMap();
    std::vector<long long> mine;
    for (std::size_t i = 0; i < b.n; ++i)
      if (!b.isFree(i)) mine.push_back(map->getGlobalElement(static_cast<LO>(i)));
    return gatherIndices(*map, std::move(mine));
  }

  // The global indices of the finite components of v, sorted, on every rank.
  static std::vector<long long> finiteIndices(const MV& v) {
    auto vv = v.getData(0);
    const auto map = v.getMap();
    std::vector<long long> mine;
    for (std::size_t i = 0; i < v.getLocalLength(); ++i)
      if (std::isfinite(vv[i])) mine.push_back(map->getGlobalElement(static_cast<LO>(i)));
    return gatherIndices(*map, std::move(mine));
  }

  // The number of components of x outside [l, u].
  static long long countOutside(const MV& x, const MV& l, const MV* u) {
    const Bounds b(x, l, u);
    long long mine = 0, all = 0;
    for (std::size_t i = 0; i < b.n; ++i)
      if (b.xv[i] < b.lv[i] || b.xv[i] > b.upper(i)) ++mine;
    Teuchos::reduceAll(*x.getMap()->getComm(), Teuchos::REDUCE_SUM, 1, &mine, &all);
    return all;
  }

  // The union of every rank's indices `mine`, sorted, on every rank (collective).
  template <class Map>
  static std::vector<long long> gatherIndices(const Map& map, std::vector<long long> mine) {
    const auto& comm = *map.getComm();
    long long count = static_cast<long long>(mine.size()), most = 0;
    Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &count, &most);
    mine.resize(static_cast<std::size_t>(most), -1);  // padded: gatherAll takes equal counts
    std::vector<long long> all(static_cast<std::size_t>(most) * comm.getSize());
    if (most > 0)
      Teuchos::gatherAll(comm, static_cast<int>(most), mine.data(), static_cast<int>(all.size()),
                         all.data());
    all.erase(std::remove(all.begin(), all.end(), -1LL), all.end());
    std::sort(all.begin(), all.end());
    return all;
  }

  // v at the sorted global indices idx, on every rank (each index owned by one rank).
  static std::vector<S> gatherAt(const MV& v, const std::vector<long long>& idx) {
    std::vector<S> mine(idx.size(), S(0)), all(idx.size(), S(0));
    auto vv = v.getData(0);
    const auto map = v.getMap();
    for (std::size_t k = 0; k < idx.size(); ++k) {
      const LO local = map->getLocalElement(static_cast<GO>(idx[k]));
      if (local != Teuchos::OrdinalTraits<LO>::invalid()) mine[k] = vv[local];
    }
    if (!idx.empty())
      Teuchos::reduceAll(*map->getComm(), Teuchos::REDUCE_SUM, static_cast<int>(idx.size()),
                         mine.data(), all.data());
    return all;
  }

  // v_{idx[k]} += alpha * values[k] where this rank owns idx[k] (v += alpha E^T values).
  static void addAt(const std::vector<long long>& idx, const std::vector<S>& values, S alpha,
                    MV& v) {
    auto vv = v.getDataNonConst(0);
    const auto map = v.getMap();
    for (std::size_t k = 0; k < idx.size(); ++k) {
      const LO local = map->getLocalElement(static_cast<GO>(idx[k]));
      if (local != Teuchos::OrdinalTraits<LO>::invalid()) vv[local] += alpha * values[k];
    }
  }

  // v_{idx[k]} = values[k] where this rank owns idx[k].
  static void setAt(const std::vector<long long>& idx, const std::vector<S>& values, MV& v) {
    auto vv = v.getDataNonConst(0);
    const auto map = v.getMap();
    for (std::size_t k = 0; k < idx.size(); ++k) {
      const LO local = map->getLocalElement(static_cast<GO>(idx[k]));
      if (local != Teuchos::OrdinalTraits<LO>::invalid()) vv[local] = values[k];
    }
  }

  // True when some u_i is finite: the problem has upper bounds at all.
  static bool anyFinite(const MV& u) {
    auto uv = u.getData(0);
    const std::size_t n = u.getLocalLength();
    int found = 0;
    for (std::size_t i = 0; i < n && !found; ++i)
      if (std::isfinite(uv[i])) found = 1;
    return max(u, found) == 1;
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
  // Local views of x, l and (when given) u; upper(i) is +infinity without u.
  struct Bounds {
    Teuchos::ArrayRCP<const S> xv, lv, uv;
    std::size_t n;
    Bounds(const MV& x, const MV& l, const MV* u)
        : xv(x.getData(0)), lv(l.getData(0)), n(x.getLocalLength()) {
      if (u != nullptr) uv = u->getData(0);
    }
    S upper(std::size_t i) const {
      return uv.is_null() ? std::numeric_limits<S>::infinity() : uv[i];
    }
    bool isFree(std::size_t i) const { return xv[i] > lv[i] && xv[i] < upper(i); }
  };
  static long long firstIndex(const MV& v, long long local) {
    long long mine = local < 0 ? std::numeric_limits<long long>::max() : local, global = mine;
    Teuchos::reduceAll(*v.getMap()->getComm(), Teuchos::REDUCE_MIN, 1, &mine, &global);
    return global == std::numeric_limits<long long>::max() ? -1 : global;
  }
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
