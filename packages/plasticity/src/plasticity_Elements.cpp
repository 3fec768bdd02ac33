#include "plasticity_Elements.hpp"

#include <Kokkos_Core.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace plasticity {
namespace {

using ExecSpace = Kokkos::DefaultHostExecutionSpace;
using detail::checkedElementCoords;
using detail::elementDisplacements;
using detail::elementLabel;
using detail::HostView2;
using detail::HostView3;
using detail::scatterStiffness;

constexpr int kMaxElementDofs = 2 * kMaxElementNodes;

// Sizes and connectivity, checked before any kernel indexes with them.
void validateMesh(const ElementMesh& mesh) {
  if (mesh.coords.size() % 2 != 0)
    throw std::invalid_argument("mesh has an odd number of coordinates (" +
                                std::to_string(mesh.coords.size()) + ")");
  const int npe = nodesPerElement(mesh.type);
  if (mesh.connectivity.size() % npe != 0)
    throw std::invalid_argument("connectivity of " + std::to_string(mesh.connectivity.size()) +
                                " entries is not a multiple of the " + std::to_string(npe) +
                                " nodes of a " + elementTypeName(mesh.type));
  const int nn = mesh.numNodes();
  for (int e = 0; e < mesh.numElements(); ++e)
    for (int a = 0; a < npe; ++a) {
      const int n = mesh.connectivity[static_cast<std::size_t>(e) * npe + a];
      if (n < 0 || n >= nn)
        throw std::invalid_argument(elementLabel(mesh, e) + " references node " +
                                    std::to_string(n) + " (local " + std::to_string(a) +
                                    "), outside [0, " + std::to_string(nn) + ")");
    }
}

// Element coordinates gathered into a View so that the kernels see plain arrays.
HostView2 elementCoords(const ElementMesh& mesh) {
  const int ne = mesh.numElements(), npe = nodesPerElement(mesh.type);
  HostView2 xe("xe", ne, 2 * npe);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < npe; ++a) {
      const int n = mesh.connectivity[static_cast<std::size_t>(e) * npe + a];
      xe(e, 2 * a) = mesh.coords[2 * n];
      xe(e, 2 * a + 1) = mesh.coords[2 * n + 1];
    }
  return xe;
}

// Smallest Jacobian determinant over the Gauss points and the nodes: checking the nodes too
// catches a map that folds over near a corner or a misplaced mid-node while staying positive
// at every Gauss point.
KOKKOS_INLINE_FUNCTION double minJacobian(ElementType t, const double* x) {
  double N[kMaxElementNodes], dNdx[kMaxElementNodes][2];
  double detMin = 1e300;
  for (int q = 0; q < numGaussPoints(t); ++q) {
    double xi, eta, w;
    gaussPoint(t, q, xi, eta, w);
    const double det = physicalGradients(t, x, xi, eta, N, dNdx);
    detMin = det < detMin ? det : detMin;
  }
  for (int a = 0; a < nodesPerElement(t); ++a) {
    double xi, eta;
    referenceNode(t, a, xi, eta);
    const double det = physicalGradients(t, x, xi, eta, N, dNdx);
    detMin = det < detMin ? det : detMin;
  }
  return detMin;
}

// Throws for the first element whose Jacobian is not positive everywhere.
void checkJacobians(const ElementMesh& mesh, const HostView2& xe) {
  const int ne = mesh.numElements();
  const ElementType type = mesh.type;
  Kokkos::View<double*, Kokkos::HostSpace> minDet("minDet", ne);
  Kokkos::parallel_for(
      "plasticity::element_jacobians", Kokkos::RangePolicy<ExecSpace>(0, ne),
      KOKKOS_LAMBDA(int e) { minDet(e) = minJacobian(type, &xe(e, 0)); });
  for (int e = 0; e < ne; ++e)
    if (!(minDet(e) > 0.0))
      throw std::invalid_argument(elementLabel(mesh, e) +
                                  " is degenerate or inverted (Jacobian determinant " +
                                  std::to_string(minDet(e)) + ")");
}

}  // namespace

namespace detail {

std::string elementLabel(const ElementMesh& mesh, int e) {
  return elementTypeName(mesh.type) + " element " + std::to_string(e);
}

// The common prologue of every entry point.
HostView2 checkedElementCoords(const ElementMesh& mesh) {
  validateMesh(mesh);
  HostView2 xe = elementCoords(mesh);
  checkJacobians(mesh, xe);
  return xe;
}

}  // namespace detail

namespace {

// Strain-displacement matrix (3 x 2 npe) from the physical gradients; gamma_xy engineering.
KOKKOS_INLINE_FUNCTION void strainMatrix(int npe, const double dNdx[][2],
                                         double B[3][kMaxElementDofs]) {
  for (int a = 0; a < npe; ++a) {
    B[0][2 * a] = dNdx[a][0], B[0][2 * a + 1] = 0;
    B[1][2 * a] = 0, B[1][2 * a + 1] = dNdx[a][1];
    B[2][2 * a] = dNdx[a][1], B[2][2 * a + 1] = dNdx[a][0];
  }
}

}  // namespace

namespace detail {

HostView2 elementDisplacements(const ElementMesh& mesh, const std::vector<double>& u) {
  if (u.size() != 2 * static_cast<std::size_t>(mesh.numNodes()))
    throw std::invalid_argument("displacement vector has " + std::to_string(u.size()) +
                                " entries, expected 2 x " + std::to_string(mesh.numNodes()) +
                                " nodes");
  const int ne = mesh.numElements(), npe = nodesPerElement(mesh.type);
  HostView2 ue("ue", ne, 2 * npe);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < npe; ++a) {
      const int n = mesh.connectivity[static_cast<std::size_t>(e) * npe + a];
      ue(e, 2 * a) = u[2 * n];
      ue(e, 2 * a + 1) = u[2 * n + 1];
    }
  return ue;
}

}  // namespace detail

namespace {

// Element tangent stiffness sum_q B^T C_q B w_q det J_q, with C_q the law's tangent at the
// strain of ue (zero strain when ue is empty: the linear stiffness). Keeping the displacement
// here is what lets a J2 or total Lagrangian tangent reuse the kernel unchanged.
HostView3 elementStiffness(const ElementMesh& mesh, const HostView2& xe, const MaterialLaw& law,
                           const HostView2& ue) {
  const int ne = mesh.numElements(), npe = nodesPerElement(mesh.type), nd = 2 * npe;
  const ElementType type = mesh.type;
  const MaterialLaw* lawPtr = &law;  // captured by value: the lambda copies the pointer only
  const bool withDisplacement = ue.extent(0) > 0;
  HostView3 Ke("Ke", ne, nd, nd);
  Kokkos::parallel_for(
      "plasticity::element_stiffness", Kokkos::RangePolicy<ExecSpace>(0, ne), KOKKOS_LAMBDA(int e) {
        for (int q = 0; q < numGaussPoints(type); ++q) {
          double xi, eta, w;
          gaussPoint(type, q, xi, eta, w);
          double N[kMaxElementNodes], dNdx[kMaxElementNodes][2];
          const double det = physicalGradients(type, &xe(e, 0), xi, eta, N, dNdx);
          double B[3][kMaxElementDofs];
          strainMatrix(npe, dNdx, B);
          double strain[3] = {0, 0, 0};
          if (withDisplacement)
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < nd; ++j) strain[i] += B[i][j] * ue(e, j);
          MaterialResponse r;
          lawPtr->evaluate(MaterialPointId{e, q}, strain, r);
          double CB[3][kMaxElementDofs];
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < nd; ++j)
              CB[i][j] = r.tangent[3 * i] * B[0][j] + r.tangent[3 * i + 1] * B[1][j] +
                         r.tangent[3 * i + 2] * B[2][j];
          const double wd = w * det;
          for (int i = 0; i < nd; ++i)
            for (int j = 0; j < nd; ++j)
              Ke(e, i, j) += (B[0][i] * CB[0][j] + B[1][i] * CB[1][j] + B[2][i] * CB[2][j]) * wd;
        }
      });
  return Ke;
}

}  // namespace

namespace detail {

// Pattern: node-to-node adjacency through elements, expanded to 2 dofs per node; then each
// element adds its block (atomics keep this correct should the execution space be threaded).
tfeti::CsrMatrix scatterStiffness(const ElementMesh& mesh, const HostView3& Ke) {
  const int ne = mesh.numElements(), nn = mesh.numNodes(), npe = nodesPerElement(mesh.type);
  const int* conn = mesh.connectivity.data();
  std::vector<std::vector<int>> adj(nn);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < npe; ++a)
      for (int b = 0; b < npe; ++b) adj[conn[e * npe + a]].push_back(conn[e * npe + b]);
  tfeti::CsrMatrix K;
  K.rows = K.cols = 2 * nn;
  K.rowPtr.assign(K.rows + 1, 0);
  for (int n = 0; n < nn; ++n) {
    auto& a = adj[n];
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
    for (int c = 0; c < 2; ++c) {
      for (int m : a) K.colInd.insert(K.colInd.end(), {2 * m, 2 * m + 1});
      K.rowPtr[2 * n + c + 1] = static_cast<int>(K.colInd.size());
    }
  }
  K.values.assign(K.colInd.size(), 0.0);

  Kokkos::View<double*, Kokkos::HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>> vals(
      K.values.data(), K.values.size());
  const tfeti::CsrMatrix& Kc = K;
  Kokkos::parallel_for("plasticity::element_scatter", Kokkos::RangePolicy<ExecSpace>(0, ne),
                       [&](int e) {
                         for (int a = 0; a < npe; ++a)
                           for (int c = 0; c < 2; ++c) {
                             const int row = 2 * conn[e * npe + a] + c;
                             for (int b = 0; b < npe; ++b)
                               for (int d = 0; d < 2; ++d) {
                                 const long k = Kc.find(row, 2 * conn[e * npe + b] + d);
                                 Kokkos::atomic_add(&vals(k), Ke(e, 2 * a + c, 2 * b + d));
                               }
                           }
                       });
  return K;
}

}  // namespace detail

namespace {

// Extrapolation from Gauss points to nodes, E[a * ngp + q]: the polynomial through the Gauss
// point values is the interpolant of a smaller (or equal) element whose nodes are the Gauss
// points, so it is that element's shape functions at the node mapped into Gauss-point
// coordinates p' = c + s (p - c).
std::vector<double> extrapolationMatrix(ElementType t) {
  const int npe = nodesPerElement(t), ngp = numGaussPoints(t);
  std::vector<double> E(static_cast<std::size_t>(npe) * ngp, 0.0);
  if (t == ElementType::Tri3) {
    std::fill(E.begin(), E.end(), 1.0);
    return E;
  }
  ElementType g = t;
  double c = 0.0, s = 1.0;
  if (t == ElementType::Tri6) {
    g = ElementType::Tri3, c = 1.0 / 3.0, s = 2.0;  // Gauss triangle: halved about the centroid
  } else if (t == ElementType::Quad4) {
    s = std::sqrt(3.0);
  } else {
    s = std::sqrt(5.0 / 3.0);
  }
  // Which node of g each Gauss point becomes.
  std::vector<int> nodeOf(ngp, -1);
  for (int q = 0; q < ngp; ++q) {
    double xi, eta, w;
    gaussPoint(t, q, xi, eta, w);
    xi = c + s * (xi - c), eta = c + s * (eta - c);
    for (int a = 0; a < nodesPerElement(g); ++a) {
      double ra, sa;
      referenceNode(g, a, ra, sa);
      if (std::abs(ra - xi) < 1e-12 && std::abs(sa - eta) < 1e-12) nodeOf[q] = a;
    }
    if (nodeOf[q] < 0) throw std::logic_error("extrapolationMatrix: unmatched Gauss point");
  }
  for (int a = 0; a < npe; ++a) {
    double xi, eta;
    referenceNode(t, a, xi, eta);
    double N[kMaxElementNodes], dN[kMaxElementNodes][2];
    shapeFunctions(g, c + s * (xi - c), c + s * (eta - c), N, dN);
    for (int q = 0; q < ngp; ++q) E[a * ngp + q] = N[nodeOf[q]];
  }
  return E;
}

}  // namespace

std::string elementTypeName(ElementType t) {
  switch (t) {
    case ElementType::Tri3:
      return "Tri3";
    case ElementType::Quad4:
      return "Quad4";
    case ElementType::Tri6:
      return "Tri6";
    case ElementType::Quad9:
      return "Quad9";
  }
  return "unknown";
}

tfeti::CsrMatrix assembleStiffness(const ElementMesh& mesh, const MaterialLaw& law) {
  const HostView2 xe = checkedElementCoords(mesh);
  return scatterStiffness(mesh, elementStiffness(mesh, xe, law, HostView2()));
}

tfeti::CsrMatrix assembleStiffness(const ElementMesh& mesh, const ElasticLaw& law) {
  return assembleStiffness(mesh, LinearElasticMaterial(law));
}

std::vector<double> assembleBodyForce(const ElementMesh& mesh, const double b[2]) {
  const HostView2 xe = checkedElementCoords(mesh);
  const int ne = mesh.numElements(), npe = nodesPerElement(mesh.type);
  const ElementType type = mesh.type;
  // Per element, integral of N_a: the body force only scales it.
  HostView2 w("nodalWeights", ne, npe);
  Kokkos::parallel_for(
      "plasticity::element_body_force", Kokkos::RangePolicy<ExecSpace>(0, ne),
      KOKKOS_LAMBDA(int e) {
        for (int q = 0; q < numGaussPoints(type); ++q) {
          double xi, eta, wq;
          gaussPoint(type, q, xi, eta, wq);
          double N[kMaxElementNodes], dNdx[kMaxElementNodes][2];
          const double det = physicalGradients(type, &xe(e, 0), xi, eta, N, dNdx);
          for (int a = 0; a < npe; ++a) w(e, a) += N[a] * wq * det;
        }
      });
  std::vector<double> f(2 * static_cast<std::size_t>(mesh.numNodes()), 0.0);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < npe; ++a) {
      const int n = mesh.connectivity[static_cast<std::size_t>(e) * npe + a];
      f[2 * n] += w(e, a) * b[0];
      f[2 * n + 1] += w(e, a) * b[1];
    }
  return f;
}

std::vector<double> assembleEdgeTraction(const ElementMesh& mesh, const std::vector<int>& edges,
                                         const double t[2]) {
  validateMesh(mesh);
  const int npe = nodesPerElement(mesh.type), nc = cornersPerElement(mesh.type);
  const int npd = nodesPerEdge(mesh.type);
  const bool quadratic = isQuadratic(mesh.type);
  if (edges.size() % npd != 0)
    throw std::invalid_argument("edge list of " + std::to_string(edges.size()) +
                                " nodes is not a multiple of the " + std::to_string(npd) +
                                " nodes of a " + elementTypeName(mesh.type) + " edge");
  // Element edges by their (sorted) end nodes, with the middle node (-1 for linear elements).
  std::map<std::pair<int, int>, int> elementEdges;
  for (int e = 0; e < mesh.numElements(); ++e) {
    const int* en = &mesh.connectivity[static_cast<std::size_t>(e) * npe];
    for (int k = 0; k < nc; ++k) {
      const int a = en[k], b = en[(k + 1) % nc];
      elementEdges[{std::min(a, b), std::max(a, b)}] = quadratic ? en[nc + k] : -1;
    }
  }
  const int nEdges = static_cast<int>(edges.size()) / npd;
  for (int k = 0; k < nEdges; ++k) {
    const int* en = &edges[static_cast<std::size_t>(k) * npd];
    const auto it = elementEdges.find({std::min(en[0], en[1]), std::max(en[0], en[1])});
    if (it == elementEdges.end() || (quadratic && it->second != en[2])) {
      std::string nodes;
      for (int a = 0; a < npd; ++a) nodes += (a ? ", " : "") + std::to_string(en[a]);
      throw std::invalid_argument("edge " + std::to_string(k) + " (nodes " + nodes +
                                  ") is not an edge of any " + elementTypeName(mesh.type) +
                                  " element");
    }
  }

  Kokkos::View<double**, Kokkos::HostSpace> xk("edgeCoords", nEdges, 2 * npd);
  for (int k = 0; k < nEdges; ++k)
    for (int a = 0; a < npd; ++a)
      for (int i = 0; i < 2; ++i) xk(k, 2 * a + i) = mesh.coords[2 * edges[k * npd + a] + i];
  // Per edge, integral of N_a ds with 1D Lagrange functions on [-1, 1] (ends at -1, +1, middle
  // at 0): 2 Gauss points are exact for a straight linear edge, 3 for a quadratic one whose
  // middle node is off-centre (ds then varies linearly).
  HostView2 w("edgeWeights", nEdges, npd);
  Kokkos::View<double*, Kokkos::HostSpace> minLength("minLength", nEdges);
  Kokkos::parallel_for(
      "plasticity::edge_traction", Kokkos::RangePolicy<ExecSpace>(0, nEdges), KOKKOS_LAMBDA(int k) {
        const double g2 = 0.57735026918962576451, g3 = 0.77459666924148337704;
        const double p2[2] = {-g2, g2}, w2[2] = {1, 1};
        const double p3[3] = {-g3, 0, g3}, w3[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
        double jMin = 1e300;
        for (int q = 0; q < npd; ++q) {
          const double s = npd == 2 ? p2[q] : p3[q], wq = npd == 2 ? w2[q] : w3[q];
          double N[3], dN[3];
          if (npd == 2) {
            N[0] = 0.5 * (1 - s), N[1] = 0.5 * (1 + s);
            dN[0] = -0.5, dN[1] = 0.5;
          } else {
            N[0] = 0.5 * s * (s - 1), N[1] = 0.5 * s * (s + 1), N[2] = 1 - s * s;
            dN[0] = s - 0.5, dN[1] = s + 0.5, dN[2] = -2 * s;
          }
          double dx = 0, dy = 0;
          for (int a = 0; a < npd; ++a) dx += dN[a] * xk(k, 2 * a), dy += dN[a] * xk(k, 2 * a + 1);
          const double ds = std::sqrt(dx * dx + dy * dy);
          jMin = ds < jMin ? ds : jMin;
          for (int a = 0; a < npd; ++a) w(k, a) += N[a] * wq * ds;
        }
        minLength(k) = jMin;
      });
  for (int k = 0; k < nEdges; ++k)
    if (!(minLength(k) > 0.0))
      throw std::invalid_argument("edge " + std::to_string(k) + " has zero length");
  std::vector<double> f(2 * static_cast<std::size_t>(mesh.numNodes()), 0.0);
  for (int k = 0; k < nEdges; ++k)
    for (int a = 0; a < npd; ++a) {
      const int n = edges[k * npd + a];
      f[2 * n] += w(k, a) * t[0];
      f[2 * n + 1] += w(k, a) * t[1];
    }
  return f;
}

StressField recoverStresses(const ElementMesh& mesh, const MaterialLaw& law,
                            const std::vector<double>& u) {
  const HostView2 xe = checkedElementCoords(mesh);
  const HostView2 ue = elementDisplacements(mesh, u);
  const int ne = mesh.numElements(), npe = nodesPerElement(mesh.type), nd = 2 * npe;
  const int ngp = numGaussPoints(mesh.type);
  const ElementType type = mesh.type;
  const MaterialLaw* lawPtr = &law;

  HostView3 sg("gaussStress", ne, ngp, 4), xg("gaussCoords", ne, ngp, 2);
  Kokkos::parallel_for(
      "plasticity::element_stress", Kokkos::RangePolicy<ExecSpace>(0, ne), KOKKOS_LAMBDA(int e) {
        for (int q = 0; q < ngp; ++q) {
          double xi, eta, w;
          gaussPoint(type, q, xi, eta, w);
          double N[kMaxElementNodes], dNdx[kMaxElementNodes][2];
          physicalGradients(type, &xe(e, 0), xi, eta, N, dNdx);
          double B[3][kMaxElementDofs];
          strainMatrix(npe, dNdx, B);
          double strain[3] = {0, 0, 0};
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < nd; ++j) strain[i] += B[i][j] * ue(e, j);
          MaterialResponse r;
          lawPtr->evaluate(MaterialPointId{e, q}, strain, r);
          for (int c = 0; c < 4; ++c) sg(e, q, c) = r.stress[c];
          for (int a = 0; a < npe; ++a) {
            xg(e, q, 0) += N[a] * xe(e, 2 * a);
            xg(e, q, 1) += N[a] * xe(e, 2 * a + 1);
          }
        }
      });
  return detail::stressField(mesh, sg, xg);
}

namespace detail {

StressField stressField(const ElementMesh& mesh, const HostView3& sg, const HostView3& xg) {
  const int ne = mesh.numElements(), npe = nodesPerElement(mesh.type);
  const int ngp = numGaussPoints(mesh.type);
  const std::vector<double> Ehost = extrapolationMatrix(mesh.type);
  Kokkos::View<const double*, Kokkos::HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>> E(
      Ehost.data(), Ehost.size());
  HostView3 sn("nodeStress", ne, npe, 4);
  Kokkos::parallel_for(
      "plasticity::stress_extrapolation", Kokkos::RangePolicy<ExecSpace>(0, ne),
      KOKKOS_LAMBDA(int e) {
        for (int a = 0; a < npe; ++a)
          for (int c = 0; c < 4; ++c) {
            double s = 0;
            for (int q = 0; q < ngp; ++q) s += E(a * ngp + q) * sg(e, q, c);
            sn(e, a, c) = s;
          }
      });

  StressField out;
  out.gaussPointsPerElement = ngp;
  out.gauss.resize(static_cast<std::size_t>(ne) * ngp * kNumStressComponents);
  out.gaussCoords.resize(static_cast<std::size_t>(ne) * ngp * 2);
  for (int e = 0; e < ne; ++e)
    for (int q = 0; q < ngp; ++q) {
      double* s = &out.gauss[(static_cast<std::size_t>(e) * ngp + q) * kNumStressComponents];
      for (int c = 0; c < 4; ++c) s[c] = sg(e, q, c);
      s[kVonMises] = vonMises(s[kSxx], s[kSyy], s[kSxy], s[kSzz]);
      for (int i = 0; i < 2; ++i)
        out.gaussCoords[(static_cast<std::size_t>(e) * ngp + q) * 2 + i] = xg(e, q, i);
    }
  const int nn = mesh.numNodes();
  out.nodal.assign(static_cast<std::size_t>(nn) * kNumStressComponents, 0.0);
  std::vector<int> count(nn, 0);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < npe; ++a) {
      const int n = mesh.connectivity[static_cast<std::size_t>(e) * npe + a];
      ++count[n];
      for (int c = 0; c < 4; ++c) out.nodal[n * kNumStressComponents + c] += sn(e, a, c);
    }
  for (int n = 0; n < nn; ++n) {
    double* s = &out.nodal[static_cast<std::size_t>(n) * kNumStressComponents];
    if (count[n] > 0)
      for (int c = 0; c < 4; ++c) s[c] /= count[n];
    s[kVonMises] = vonMises(s[kSxx], s[kSyy], s[kSxy], s[kSzz]);
  }
  return out;
}

}  // namespace detail

}  // namespace plasticity
