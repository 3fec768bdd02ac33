#include "plasticity_Elements.hpp"

#include <Kokkos_Core.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "plasticity_ReferenceValues.hpp"
#include "plasticity_TotalLagrangian.hpp"
#include "tfeti_Digest.hpp"

namespace plasticity {
namespace {

using ExecSpace = Kokkos::DefaultHostExecutionSpace;
using detail::checkedElementCoords;
using detail::elementLabel;
using detail::HostView2;
using detail::HostView3;

// Sizes and connectivity, checked before any kernel indexes with them.
void validateMesh(const ElementMesh& mesh) {
  const int dim = mesh.dim();
  if (dim < 2)
    throw std::invalid_argument(elementTypeName(mesh.type) +
                                " is a face type: a mesh of solids needs 2D or 3D elements");
  if (!elementInfo(mesh.type).complete)
    throw std::invalid_argument(elementTypeName(mesh.type) +
                                " elements are not assembled (serendipity: no shape functions)");
  if (mesh.coords.size() % dim != 0)
    throw std::invalid_argument("mesh of " + elementTypeName(mesh.type) + " elements has " +
                                std::to_string(mesh.coords.size()) +
                                " coordinates, not a multiple of its dimension " +
                                std::to_string(dim));
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

// Per-node values (dim per node) gathered per element into a View (ne, dim npe).
HostView2 gather(const ElementMesh& mesh, const std::vector<double>& nodal,
                 const std::string& label) {
  const int ne = mesh.numElements(), npe = nodesPerElement(mesh.type), dim = mesh.dim();
  HostView2 v(label, ne, dim * npe);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < npe; ++a) {
      const int n = mesh.connectivity[static_cast<std::size_t>(e) * npe + a];
      for (int i = 0; i < dim; ++i)
        v(e, dim * a + i) = nodal[static_cast<std::size_t>(dim) * n + i];
    }
  return v;
}

// Throws for the first element whose Jacobian is not positive everywhere: the smallest
// determinant over the Gauss points and the nodes (checking the nodes too catches a map that
// folds over near a corner or a misplaced mid-node while staying positive at every Gauss point).
void checkJacobians(const ElementMesh& mesh, const HostView2& xe) {
  const int ne = mesh.numElements(), npe = nodesPerElement(mesh.type), dim = mesh.dim();
  const detail::ReferenceValues ref = detail::referenceValues(mesh.type, true);
  const int points = static_cast<int>(ref.w.extent(0));
  Kokkos::View<double*, Kokkos::HostSpace> minDet("minDet", ne);
  Kokkos::parallel_for(
      "plasticity::element_jacobians", Kokkos::RangePolicy<ExecSpace>(0, ne), KOKKOS_LAMBDA(int e) {
        double dNdx[kMaxElementNodes][kMaxDim];
        double detMin = 1e300;
        for (int p = 0; p < points; ++p) {
          const double det = mappedGradients(npe, dim, &xe(e, 0), ref.derivatives(p), dNdx);
          detMin = det < detMin ? det : detMin;
        }
        minDet(e) = detMin;
      });
  for (int e = 0; e < ne; ++e)
    if (!(minDet(e) > 0.0))
      throw std::invalid_argument(elementLabel(mesh, e) +
                                  " is degenerate or inverted (Jacobian determinant " +
                                  std::to_string(minDet(e)) + ")");
}

// The digest of what the checks read: the type, the coordinates' bits and the connectivity.
std::array<std::uint64_t, 2> meshDigest(const ElementMesh& mesh) {
  tfeti::Digest d(static_cast<std::uint64_t>(mesh.type));
  d.add(mesh.coords.data(), mesh.coords.size() * sizeof(double));
  d.add(mesh.connectivity.data(), mesh.connectivity.size() * sizeof(int));
  return d.value();
}

}  // namespace

namespace detail {

std::string elementLabel(const ElementMesh& mesh, int e) {
  return elementTypeName(mesh.type) + " element " + std::to_string(e);
}

// The common prologue of every entry point. The checks are skipped for a mesh whose digest
// matches the one recorded when it last passed them.
HostView2 checkedElementCoords(const ElementMesh& mesh) {
  const std::array<std::uint64_t, 2> digest = meshDigest(mesh);
  const bool checked = mesh.checkedDigest == digest;
  if (!checked) validateMesh(mesh);
  HostView2 xe = gather(mesh, mesh.coords, "xe");
  if (!checked) checkJacobians(mesh, xe);
  mesh.checkedDigest = digest;
  return xe;
}

HostView2 elementDisplacements(const ElementMesh& mesh, const std::vector<double>& u) {
  const int dim = mesh.dim();
  if (u.size() != static_cast<std::size_t>(dim) * mesh.numNodes())
    throw std::invalid_argument("displacement vector has " + std::to_string(u.size()) +
                                " entries, expected " + std::to_string(dim) + " x " +
                                std::to_string(mesh.numNodes()) + " nodes");
  return gather(mesh, u, "ue");
}

// Node-to-node adjacency through elements, expanded to dim dofs per node: the rows of a node's
// dofs share one column list, each neighbour's dofs consecutive in it.
tfeti::CsrMatrix stiffnessPattern(const ElementMesh& mesh) {
  const int ne = mesh.numElements(), nn = mesh.numNodes(), npe = nodesPerElement(mesh.type);
  const int dim = mesh.dim();
  const int* conn = mesh.connectivity.data();
  std::vector<std::vector<int>> adj(nn);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < npe; ++a)
      for (int b = 0; b < npe; ++b) adj[conn[e * npe + a]].push_back(conn[e * npe + b]);
  tfeti::CsrMatrix K;
  K.rows = K.cols = dim * nn;
  K.rowPtr.assign(K.rows + 1, 0);
  for (int n = 0; n < nn; ++n) {
    auto& a = adj[n];
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
    for (int c = 0; c < dim; ++c) {
      for (int m : a)
        for (int d = 0; d < dim; ++d) K.colInd.push_back(dim * m + d);
      K.rowPtr[dim * n + c + 1] = static_cast<int>(K.colInd.size());
    }
  }
  K.values.assign(K.colInd.size(), 0.0);
  return K;
}

// Each element adds its block (atomics keep this correct should the execution space be
// threaded). One search per node pair: the pattern puts a neighbour's dim columns side by side,
// at the same offset in each of the node's dim rows.
void addElementMatrices(const ElementMesh& mesh, const HostView3& Ke, int first, int last,
                        tfeti::CsrMatrix& K) {
  const int npe = nodesPerElement(mesh.type), dim = mesh.dim();
  const int* conn = mesh.connectivity.data();
  Kokkos::View<double*, Kokkos::HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>> vals(
      K.values.data(), K.values.size());
  const tfeti::CsrMatrix& Kc = K;
  Kokkos::parallel_for(
      "plasticity::element_scatter", Kokkos::RangePolicy<ExecSpace>(first, last), [&](int e) {
        const int* en = conn + static_cast<std::size_t>(e) * npe;
        for (int a = 0; a < npe; ++a) {
          const int row0 = dim * en[a];
          for (int b = 0; b < npe; ++b) {
            const long at = Kc.find(row0, dim * en[b]) - Kc.rowPtr[row0];
            for (int c = 0; c < dim; ++c) {
              const long k = Kc.rowPtr[row0 + c] + at;
              for (int d = 0; d < dim; ++d)
                Kokkos::atomic_add(&vals(k + d), Ke(e - first, dim * a + c, dim * b + d));
            }
          }
        }
      });
}

std::vector<double> scatterVector(const ElementMesh& mesh, const HostView2& fe) {
  const int npe = nodesPerElement(mesh.type), dim = mesh.dim();
  std::vector<double> f(static_cast<std::size_t>(dim) * mesh.numNodes(), 0.0);
  for (int e = 0; e < mesh.numElements(); ++e)
    for (int a = 0; a < npe; ++a) {
      const int n = mesh.connectivity[static_cast<std::size_t>(e) * npe + a];
      for (int i = 0; i < dim; ++i) f[static_cast<std::size_t>(dim) * n + i] += fe(e, dim * a + i);
    }
  return f;
}

}  // namespace detail

namespace {

// Extrapolation from Gauss points to nodes, E[a * ngp + q]: the polynomial through the Gauss
// point values is the interpolant of a smaller (or equal) element whose nodes are the Gauss
// points, so it is that element's shape functions at the node mapped into Gauss-point
// coordinates p' = c + s (p - c): for Tri6/Tet10 the linear simplex shrunk about the centroid
// (s = 2 in 2D, sqrt 5 in 3D), for the tensor products the element itself shrunk to the Gauss
// points (s = 1 / Gauss abscissa).
std::vector<double> extrapolationMatrix(ElementType t) {
  const ElementInfo info = elementInfo(t);
  const int npe = info.nodes, ngp = info.gaussPoints, dim = info.dim;
  std::vector<double> E(static_cast<std::size_t>(npe) * ngp, 0.0);
  if (ngp == 1) {
    std::fill(E.begin(), E.end(), 1.0);
    return E;
  }
  ElementType g = t;
  double c = 0.0, s = 1.0;
  if (info.simplex) {
    g = info.linear, c = 1.0 / (dim + 1), s = dim == 2 ? 2.0 : std::sqrt(5.0);
  } else {
    s = info.order == 1 ? std::sqrt(3.0) : std::sqrt(5.0 / 3.0);
  }
  // Which node of g each Gauss point becomes.
  std::vector<int> nodeOf(ngp, -1);
  for (int q = 0; q < ngp; ++q) {
    double xi[kMaxDim], w;
    gaussPoint(t, q, xi, w);
    for (int j = 0; j < dim; ++j) xi[j] = c + s * (xi[j] - c);
    for (int a = 0; a < nodesPerElement(g); ++a) {
      double r[kMaxDim];
      referenceNode(g, a, r);
      bool same = true;
      for (int j = 0; j < dim; ++j) same = same && std::abs(r[j] - xi[j]) < 1e-12;
      if (same) nodeOf[q] = a;
    }
    if (nodeOf[q] < 0) throw std::logic_error("extrapolationMatrix: unmatched Gauss point");
  }
  for (int a = 0; a < npe; ++a) {
    double xi[kMaxDim];
    referenceNode(t, a, xi);
    for (int j = 0; j < dim; ++j) xi[j] = c + s * (xi[j] - c);
    double N[kMaxElementNodes], dN[kMaxElementNodes][kMaxDim];
    shapeFunctions(g, xi, N, dN);
    for (int q = 0; q < ngp; ++q) E[a * ngp + q] = N[nodeOf[q]];
  }
  return E;
}

// Whether the face nodes `fn` (face-type order) sit on element e's face where that order puts
// them: the affine map taking the face's reference corners 0, 1 and (last corner) to the
// element reference positions of those nodes must take every face node to its own.
bool faceOrderMatches(ElementType elemType, const int* elemNodes, ElementType ft, const int* fn) {
  const ElementInfo fi = elementInfo(ft), ei = elementInfo(elemType);
  auto elementRef = [&](int node, double X[]) {
    for (int a = 0; a < ei.nodes; ++a)
      if (elemNodes[a] == node) return referenceNode(elemType, a, X);
  };
  double X0[kMaxDim], A[kMaxDim][kMaxDim - 1], f0[kMaxDim];
  elementRef(fn[0], X0);
  referenceNode(ft, 0, f0);
  const int axisNode[2] = {1, fi.corners - 1};
  for (int j = 0; j < fi.dim; ++j) {
    double Xj[kMaxDim], fj[kMaxDim];
    elementRef(fn[axisNode[j]], Xj);
    referenceNode(ft, axisNode[j], fj);
    for (int i = 0; i < ei.dim; ++i) A[i][j] = (Xj[i] - X0[i]) / (fj[j] - f0[j]);
  }
  for (int a = 0; a < fi.nodes; ++a) {
    double X[kMaxDim], f[kMaxDim];
    elementRef(fn[a], X);
    referenceNode(ft, a, f);
    for (int i = 0; i < ei.dim; ++i) {
      double y = X0[i];
      for (int j = 0; j < fi.dim; ++j) y += A[i][j] * (f[j] - f0[j]);
      if (std::abs(y - X[i]) > 1e-12) return false;
    }
  }
  return true;
}

// Throws unless every face of `faces` is a face of some element in a valid node order.
void checkFaces(const ElementMesh& mesh, const std::vector<int>& faces) {
  const ElementType ft = faceType(mesh.type);
  const int npf = nodesPerElement(ft), npe = nodesPerElement(mesh.type);
  const std::string word = mesh.dim() == 2 ? "edge" : "face";
  if (faces.size() % npf != 0)
    throw std::invalid_argument(word + " list of " + std::to_string(faces.size()) +
                                " nodes is not a multiple of the " + std::to_string(npf) +
                                " nodes of a " + elementTypeName(mesh.type) + " " + word);
  // Element faces by their sorted node set, with the element holding them.
  std::map<std::vector<int>, int> owner;
  for (int e = 0; e < mesh.numElements(); ++e)
    for (int f = 0; f < facesPerElement(mesh.type); ++f) {
      std::vector<int> key;
      for (int a : facetNodes(mesh.type, f))
        key.push_back(mesh.connectivity[static_cast<std::size_t>(e) * npe + a]);
      std::sort(key.begin(), key.end());
      owner.emplace(key, e);
    }
  for (std::size_t k = 0; k < faces.size() / npf; ++k) {
    const int* fn = &faces[k * npf];
    std::vector<int> key(fn, fn + npf);
    std::sort(key.begin(), key.end());
    const auto it = owner.find(key);
    if (it == owner.end() ||
        !faceOrderMatches(mesh.type, &mesh.connectivity[static_cast<std::size_t>(it->second) * npe],
                          ft, fn)) {
      std::string nodes;
      for (int a = 0; a < npf; ++a) nodes += (a ? ", " : "") + std::to_string(fn[a]);
      throw std::invalid_argument(word + " " + std::to_string(k) + " (nodes " + nodes +
                                  ") is not " + (mesh.dim() == 2 ? "an " : "a ") + word +
                                  " of any " + elementTypeName(mesh.type) + " element");
    }
  }
}

}  // namespace

tfeti::CsrMatrix assembleStiffness(const ElementMesh& mesh, const MaterialLaw& law) {
  validateMesh(mesh);
  const std::vector<double> zero(static_cast<std::size_t>(mesh.dim()) * mesh.numNodes(), 0.0);
  return tangentStiffness(mesh, law, zero, Kinematics::SmallStrain, false);
}

tfeti::CsrMatrix assembleStiffness(const ElementMesh& mesh, const ElasticLaw& law) {
  return assembleStiffness(mesh, LinearElasticMaterial(law));
}

std::vector<double> assembleBodyForce(const ElementMesh& mesh, const double b[]) {
  const HostView2 xe = checkedElementCoords(mesh);
  const int ne = mesh.numElements(), npe = nodesPerElement(mesh.type), dim = mesh.dim();
  const ElementType type = mesh.type;
  // Per element, integral of N_a: the body force only scales it.
  HostView2 w("nodalWeights", ne, npe);
  Kokkos::parallel_for(
      "plasticity::element_body_force", Kokkos::RangePolicy<ExecSpace>(0, ne),
      KOKKOS_LAMBDA(int e) {
        for (int q = 0; q < numGaussPoints(type); ++q) {
          double xi[kMaxDim], wq;
          gaussPoint(type, q, xi, wq);
          double N[kMaxElementNodes], dNdx[kMaxElementNodes][kMaxDim];
          const double det = physicalGradients(type, &xe(e, 0), xi, N, dNdx);
          for (int a = 0; a < npe; ++a) w(e, a) += N[a] * wq * det;
        }
      });
  std::vector<double> f(static_cast<std::size_t>(dim) * mesh.numNodes(), 0.0);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < npe; ++a) {
      const int n = mesh.connectivity[static_cast<std::size_t>(e) * npe + a];
      for (int i = 0; i < dim; ++i) f[static_cast<std::size_t>(dim) * n + i] += w(e, a) * b[i];
    }
  return f;
}

std::vector<double> assembleSurfaceTraction(const ElementMesh& mesh, const std::vector<int>& faces,
                                            const double t[]) {
  validateMesh(mesh);
  checkFaces(mesh, faces);
  const ElementType ft = faceType(mesh.type);
  const int npf = nodesPerElement(ft), dim = mesh.dim();
  const int nFaces = static_cast<int>(faces.size()) / npf;
  Kokkos::View<double**, Kokkos::HostSpace> xk("faceCoords", nFaces, dim * npf);
  for (int k = 0; k < nFaces; ++k)
    for (int a = 0; a < npf; ++a)
      for (int i = 0; i < dim; ++i)
        xk(k, dim * a + i) = mesh.coords[static_cast<std::size_t>(dim) * faces[k * npf + a] + i];
  // Per face, integral of N_a dA with the face type's shape functions and Gauss rule; dA is the
  // norm of the normal dx/dxi x dx/deta (in 2D of the tangent dx/dxi rotated by 90 degrees).
  HostView2 w("faceWeights", nFaces, npf);
  Kokkos::View<double*, Kokkos::HostSpace> minArea("minArea", nFaces);
  Kokkos::parallel_for(
      "plasticity::surface_traction", Kokkos::RangePolicy<ExecSpace>(0, nFaces),
      KOKKOS_LAMBDA(int k) {
        double jMin = 1e300;
        for (int q = 0; q < numGaussPoints(ft); ++q) {
          double xi[kMaxDim], wq, N[kMaxElementNodes], dN[kMaxElementNodes][kMaxDim];
          gaussPoint(ft, q, xi, wq);
          shapeFunctions(ft, xi, N, dN);
          double T[2][kMaxDim] = {};  // T[j][i] = d x_i / d xi_j
          for (int a = 0; a < npf; ++a)
            for (int j = 0; j < dim - 1; ++j)
              for (int i = 0; i < dim; ++i) T[j][i] += dN[a][j] * xk(k, dim * a + i);
          const double dA = dim == 2
                                ? std::sqrt(T[0][0] * T[0][0] + T[0][1] * T[0][1])
                                : std::sqrt(std::pow(T[0][1] * T[1][2] - T[0][2] * T[1][1], 2) +
                                            std::pow(T[0][2] * T[1][0] - T[0][0] * T[1][2], 2) +
                                            std::pow(T[0][0] * T[1][1] - T[0][1] * T[1][0], 2));
          jMin = dA < jMin ? dA : jMin;
          for (int a = 0; a < npf; ++a) w(k, a) += N[a] * wq * dA;
        }
        minArea(k) = jMin;
      });
  for (int k = 0; k < nFaces; ++k)
    if (!(minArea(k) > 0.0))
      throw std::invalid_argument((dim == 2 ? "edge " : "face ") + std::to_string(k) +
                                  (dim == 2 ? " has zero length" : " has zero area"));
  std::vector<double> f(static_cast<std::size_t>(dim) * mesh.numNodes(), 0.0);
  for (int k = 0; k < nFaces; ++k)
    for (int a = 0; a < npf; ++a) {
      const int n = faces[k * npf + a];
      for (int i = 0; i < dim; ++i) f[static_cast<std::size_t>(dim) * n + i] += w(k, a) * t[i];
    }
  return f;
}

StressField recoverStresses(const ElementMesh& mesh, const MaterialLaw& law,
                            const std::vector<double>& u) {
  return detail::gaussPointStresses(mesh, law, u, Kinematics::SmallStrain, false);
}

namespace detail {

StressField stressField(const ElementMesh& mesh, const HostView3& sg, const HostView3& xg) {
  const int ne = mesh.numElements(), npe = nodesPerElement(mesh.type), dim = mesh.dim();
  const int ngp = numGaussPoints(mesh.type);
  const std::vector<double> Ehost = extrapolationMatrix(mesh.type);
  Kokkos::View<const double*, Kokkos::HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>> E(
      Ehost.data(), Ehost.size());
  HostView3 sn("nodeStress", ne, npe, kNumVoigt);
  Kokkos::parallel_for(
      "plasticity::stress_extrapolation", Kokkos::RangePolicy<ExecSpace>(0, ne),
      KOKKOS_LAMBDA(int e) {
        for (int a = 0; a < npe; ++a)
          for (int c = 0; c < kNumVoigt; ++c) {
            double s = 0;
            for (int q = 0; q < ngp; ++q) s += E(a * ngp + q) * sg(e, q, c);
            sn(e, a, c) = s;
          }
      });

  StressField out;
  out.gaussPointsPerElement = ngp;
  out.gauss.resize(static_cast<std::size_t>(ne) * ngp * kNumStressComponents);
  out.gaussCoords.resize(static_cast<std::size_t>(ne) * ngp * dim);
  for (int e = 0; e < ne; ++e)
    for (int q = 0; q < ngp; ++q) {
      double* s = &out.gauss[(static_cast<std::size_t>(e) * ngp + q) * kNumStressComponents];
      for (int c = 0; c < kNumVoigt; ++c) s[c] = sg(e, q, c);
      s[kVonMises] = vonMises(s);
      for (int i = 0; i < dim; ++i)
        out.gaussCoords[(static_cast<std::size_t>(e) * ngp + q) * dim + i] = xg(e, q, i);
    }
  const int nn = mesh.numNodes();
  out.nodal.assign(static_cast<std::size_t>(nn) * kNumStressComponents, 0.0);
  std::vector<int> count(nn, 0);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < npe; ++a) {
      const int n = mesh.connectivity[static_cast<std::size_t>(e) * npe + a];
      ++count[n];
      for (int c = 0; c < kNumVoigt; ++c) out.nodal[n * kNumStressComponents + c] += sn(e, a, c);
    }
  for (int n = 0; n < nn; ++n) {
    double* s = &out.nodal[static_cast<std::size_t>(n) * kNumStressComponents];
    if (count[n] > 0)
      for (int c = 0; c < kNumVoigt; ++c) s[c] /= count[n];
    s[kVonMises] = vonMises(s);
  }
  return out;
}

}  // namespace detail

}  // namespace plasticity
