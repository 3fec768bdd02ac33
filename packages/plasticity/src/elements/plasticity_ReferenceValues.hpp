#pragma once
// Shape functions and their reference derivatives at a fixed set of reference points (a Gauss
// rule, then optionally the element's nodes), evaluated once per kernel launch: the polynomials
// are the same in every element of a mesh, only the map x(xi) differs, so the kernels map the
// tabulated derivatives (mappedGradients) instead of evaluating the polynomials per element and
// point (which took a third of the element work in a Newton iteration on Hex8).
#include <Kokkos_Core.hpp>

#include "plasticity_ElementTypes.hpp"

namespace plasticity {
namespace detail {

struct ReferenceValues {
  Kokkos::View<double**, Kokkos::HostSpace> N;    // (point, node)
  Kokkos::View<double***, Kokkos::HostSpace> dN;  // (point, node, kMaxDim), contiguous per point
  Kokkos::View<double*, Kokkos::HostSpace> w;     // the Gauss weights; 0 at the node points

  KOKKOS_INLINE_FUNCTION const double* shape(int p) const { return &N(p, 0); }
  KOKKOS_INLINE_FUNCTION auto derivatives(int p) const {
    return reinterpret_cast<const double(*)[kMaxDim]>(&dN(p, 0, 0));
  }
};

// The values at type t's Gauss points (points 0 .. numGaussPoints - 1) and, with nodes, at its
// reference nodes after them.
inline ReferenceValues referenceValues(ElementType t, bool nodes = false) {
  const int ngp = numGaussPoints(t), npe = nodesPerElement(t);
  const int points = ngp + (nodes ? npe : 0);
  ReferenceValues v;
  v.N = Kokkos::View<double**, Kokkos::HostSpace>("referenceN", points, kMaxElementNodes);
  v.dN =
      Kokkos::View<double***, Kokkos::HostSpace>("referenceDN", points, kMaxElementNodes, kMaxDim);
  v.w = Kokkos::View<double*, Kokkos::HostSpace>("referenceW", points);
  for (int p = 0; p < points; ++p) {
    double xi[kMaxDim] = {0, 0, 0}, w = 0;
    if (p < ngp)
      gaussPoint(t, p, xi, w);
    else
      referenceNode(t, p - ngp, xi);
    double N[kMaxElementNodes] = {}, dN[kMaxElementNodes][kMaxDim] = {};
    shapeFunctions(t, xi, N, dN);
    v.w(p) = w;
    for (int a = 0; a < npe; ++a) {
      v.N(p, a) = N[a];
      for (int j = 0; j < kMaxDim; ++j) v.dN(p, a, j) = dN[a][j];
    }
  }
  return v;
}

}  // namespace detail
}  // namespace plasticity
