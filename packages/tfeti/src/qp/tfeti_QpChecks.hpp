#pragma once
// Collective checks that the vectors and operators of a bound-constrained QP live on one map,
// before MPRGP or SMALBE touches them elementwise (a bound vector on a shorter map would be read
// past its end). Every rank reaches the same verdict and throws the same std::invalid_argument.
// And the KKT conditions of a computed solution (qpKkt), for tests and diagnostics.
#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Operator.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "tfeti_QpProblem.hpp"

namespace tfeti {

namespace qp_checks {

// T in a context where template arguments are not deduced.
template <class T>
struct Identity {
  using type = T;
};

// Empty when `v` is on `map`; otherwise what differs, in the user's terms. Collective.
template <class Map>
std::string mapMismatch(const Map& map, const Map& other, const std::string& what,
                        const std::string& reference) {
  if (map.isSameAs(other)) return "";
  const auto n = other.getGlobalNumElements(), m = map.getGlobalNumElements();
  if (n != m)
    return what + " has " + std::to_string(n) + " entries, " + reference + " has " +
           std::to_string(m);
  return what + " has the " + std::to_string(n) + " entries of " + reference +
         " but another map (other global indices or another distribution over the ranks)";
}

// Operators other than Tpetra's expose no maps: nothing to compare.
template <class OP, class MV>
std::string operatorMismatch(const OP&, const MV&, const std::string&) {
  return "";
}

template <class S, class LO, class GO, class N>
std::string operatorMismatch(const Tpetra::Operator<S, LO, GO, N>& A,
                             const Tpetra::MultiVector<S, LO, GO, N>& x, const std::string& what) {
  const auto domain = A.getDomainMap(), range = A.getRangeMap();
  if (domain.is_null() || range.is_null()) return what + " has no domain or range map";
  std::string e = mapMismatch(*x.getMap(), *domain, "the domain of " + what, "x");
  if (e.empty()) e = mapMismatch(*x.getMap(), *range, "the range of " + what, "x");
  return e;
}

template <class MV>
std::string vectorMismatch(const MV& v, const MV& x, const std::string& what) {
  return "";
}

template <class S, class LO, class GO, class N>
std::string vectorMismatch(const Tpetra::MultiVector<S, LO, GO, N>& v,
                           const Tpetra::MultiVector<S, LO, GO, N>& x, const std::string& what) {
  return mapMismatch(*x.getMap(), *v.getMap(), what, "x");
}

}  // namespace qp_checks

// Collective: b, the lower and (when given) upper bounds, the operators A and (SMALBE) Q on the map
// of x.
template <class S, class MV, class OP>
void checkQpMaps(const BoundConstrainedQp<S, MV, OP>& qp, const std::string& solver,
                 const OP* Q = nullptr) {
  using namespace qp_checks;
  std::string e = vectorMismatch(*qp.b, *qp.x, "the right-hand side b");
  if (e.empty()) e = vectorMismatch(*qp.lower, *qp.x, "the lower bound vector");
  if (e.empty() && qp.upper != Teuchos::null)
    e = vectorMismatch(*qp.upper, *qp.x, "the upper bound vector");
  if (e.empty()) e = operatorMismatch(*qp.A, *qp.x, "A");
  if (e.empty() && Q != nullptr) e = operatorMismatch(*Q, *qp.x, "Q");
  if (!e.empty())
    throw std::invalid_argument(solver + ": " + e +
                                " (every vector and operator of the problem must be on the map "
                                "of the initial guess x)");
}

// The KKT conditions of min 1/2 x^T A x - b^T x subject to l <= x <= u (and Q x = 0 with the
// multiplier mu, the gradient then being g = A x - b + mu), as maxima over the components. The
// gradient splits into the multipliers of the two sides, g = lambda_l - lambda_u: where both
// bounds are finite lambda_l = max(g, 0) and lambda_u = max(-g, 0); with one finite bound its
// multiplier is the whole gradient (g, or -g at an upper bound), so that a gradient of the wrong
// sign off the bound shows up in the complementarity as well as in the free gradient. A fixed
// component (l_i = u_i) takes any multiplier.
struct QpKkt {
  double infeasibility = 0;       // max(l_i - x_i, x_i - u_i, 0)
  double freeGradient = 0;        // |g_i| where l_i < x_i < u_i (stationarity)
  double negativeMultiplier = 0;  // max(-g_i, 0) where x_i = l_i < u_i, max(g_i, 0) where
                                  // x_i = u_i > l_i (the sign of the active side's multiplier)
  double complementarity = 0;     // |(x_i - l_i) lambda_l,i|, |(u_i - x_i) lambda_u,i| (finite)
  double equalityResidual = 0;    // ||Q x|| (0 without Q)
  double gapRange = 0;            // max |x_i - l_i|, |u_i - x_i| over finite bounds (the scale
                                  // of the complementarity)
};

// Collective; u, mu and Q may be null (no upper bounds, no equality constraint). The scalar and
// ordinal types come from A alone, so that Tpetra::Vector arguments and null pointers convert.
template <class S, class LO, class GO, class N>
QpKkt qpKkt(
    const Tpetra::Operator<S, LO, GO, N>& A,
    const typename qp_checks::Identity<Tpetra::MultiVector<S, LO, GO, N>>::type& b,
    const typename qp_checks::Identity<Tpetra::MultiVector<S, LO, GO, N>>::type& l,
    const typename qp_checks::Identity<Tpetra::MultiVector<S, LO, GO, N>>::type* u,
    const typename qp_checks::Identity<Tpetra::MultiVector<S, LO, GO, N>>::type& x,
    const typename qp_checks::Identity<Tpetra::MultiVector<S, LO, GO, N>>::type* mu = nullptr,
    const Tpetra::Operator<S, LO, GO, N>* Q = nullptr) {
  using MV = Tpetra::MultiVector<S, LO, GO, N>;
  MV g(x.getMap(), 1);
  A.apply(x, g);
  g.update(-1.0, b, 1.0);
  if (mu != nullptr) g.update(1.0, *mu, 1.0);
  auto xv = x.getData(0);
  auto lv = l.getData(0);
  auto gv = g.getData(0);
  Teuchos::ArrayRCP<const S> uv;
  if (u != nullptr) uv = u->getData(0);
  const double inf = std::numeric_limits<double>::infinity();
  double m[5] = {0, 0, 0, 0, 0};  // the fields of QpKkt but the equality residual, in order
  for (std::size_t i = 0; i < x.getLocalLength(); ++i) {
    const double xi = xv[i], li = lv[i], ui = uv.is_null() ? inf : uv[i], gi = gv[i];
    const bool hasL = std::isfinite(li), hasU = std::isfinite(ui);
    m[0] = std::max({m[0], li - xi, xi - ui});
    if (xi > li && xi < ui)
      m[1] = std::max(m[1], std::abs(gi));
    else if (li < ui)
      m[2] = std::max(m[2], xi <= li ? -gi : gi);
    if (hasL) {
      const double lambdaL = hasU ? std::max(gi, 0.0) : gi;
      m[3] = std::max(m[3], std::abs((xi - li) * lambdaL));
      m[4] = std::max(m[4], std::abs(xi - li));
    }
    if (hasU) {
      const double lambdaU = hasL ? std::max(-gi, 0.0) : -gi;
      m[3] = std::max(m[3], std::abs((ui - xi) * lambdaU));
      m[4] = std::max(m[4], std::abs(ui - xi));
    }
  }
  double global[5];
  Teuchos::reduceAll(*x.getMap()->getComm(), Teuchos::REDUCE_MAX, 5, m, global);
  QpKkt k;
  k.infeasibility = global[0];
  k.freeGradient = global[1];
  k.negativeMultiplier = global[2];
  k.complementarity = global[3];
  k.gapRange = global[4];
  if (Q != nullptr) {
    MV qx(x.getMap(), 1);
    Q->apply(x, qx);
    std::vector<S> n(1);
    qx.norm2(Teuchos::arrayViewFromVector(n));
    k.equalityResidual = n[0];
  }
  return k;
}

}  // namespace tfeti
