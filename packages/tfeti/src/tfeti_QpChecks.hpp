#pragma once
// Collective checks that the vectors and operators of a bound-constrained QP live on one map,
// before MPRGP or SMALBE touches them elementwise (a bound vector on a shorter map would be read
// past its end). Every rank reaches the same verdict and throws the same std::invalid_argument.
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Operator.hpp>

#include <stdexcept>
#include <string>

#include "tfeti_QpProblem.hpp"

namespace tfeti {

namespace qp_checks {

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

// Collective: b, the lower bounds, the operators A and (SMALBE) Q on the map of x.
template <class S, class MV, class OP>
void checkQpMaps(const BoundConstrainedQp<S, MV, OP>& qp, const std::string& solver,
                 const OP* Q = nullptr) {
  using namespace qp_checks;
  std::string e = vectorMismatch(*qp.b, *qp.x, "the right-hand side b");
  if (e.empty()) e = vectorMismatch(*qp.lower, *qp.x, "the lower bound vector");
  if (e.empty()) e = operatorMismatch(*qp.A, *qp.x, "A");
  if (e.empty() && Q != nullptr) e = operatorMismatch(*Q, *qp.x, "Q");
  if (!e.empty())
    throw std::invalid_argument(solver + ": " + e +
                                " (every vector and operator of the problem must be on the map "
                                "of the initial guess x)");
}

}  // namespace tfeti
