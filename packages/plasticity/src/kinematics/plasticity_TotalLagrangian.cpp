#include "plasticity_TotalLagrangian.hpp"

#include <Kokkos_Core.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "plasticity_ReferenceValues.hpp"

namespace plasticity {
namespace {

using ExecSpace = Kokkos::DefaultHostExecutionSpace;
using detail::HostView2;
using detail::HostView3;

constexpr int kMaxElementDofs = kMaxDim * kMaxElementNodes;

// The Voigt components a mesh of dimension dim strains: (xx, yy, xy) in plane strain, all six
// in 3D. The kernels' B matrices have one row per active component, in this order.
KOKKOS_INLINE_FUNCTION int activeComponents(int dim, int comp[kNumVoigt]) {
  if (dim == 2) {
    comp[0] = kXX, comp[1] = kYY, comp[2] = kXY;
    return 3;
  }
  for (int c = 0; c < kNumVoigt; ++c) comp[c] = c;
  return kNumVoigt;
}
// Tensor indices (i, j) of Voigt component c, and the Voigt component of (i, j).
KOKKOS_INLINE_FUNCTION void voigtPair(int c, int& i, int& j) {
  const int p[kNumVoigt][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
  i = p[c][0], j = p[c][1];
}
KOKKOS_INLINE_FUNCTION int voigtIndex(int i, int j) {
  const int v[3][3] = {{kXX, kXY, kXZ}, {kXY, kYY, kYZ}, {kXZ, kYZ, kZZ}};
  return v[i][j];
}

// An assembled element type's node count, dimension and Gauss point count as compile-time
// constants, for the kernels' loop bounds.
template <int Npe, int Dim, int Ngp>
struct ElementShape {
  static constexpr int npe = Npe, dim = Dim, ngp = Ngp;
};

// f(ElementShape<...>{}) for type t; throws for a type the kernels do not assemble (faces and
// the serendipity types, which the mesh checks reject first).
template <class F>
void forElementShape(ElementType t, F&& f) {
  auto call = [&](auto shape) {
    using S = decltype(shape);
    if (nodesPerElement(t) != S::npe || spatialDimension(t) != S::dim ||
        numGaussPoints(t) != S::ngp)
      throw std::logic_error("element kernels: the shape constants of " + elementTypeName(t) +
                             " disagree with the element catalogue");
    f(shape);
  };
  using T = ElementType;
  switch (t) {
    case T::Tri3:
      return call(ElementShape<3, 2, 1>{});
    case T::Quad4:
      return call(ElementShape<4, 2, 4>{});
    case T::Tri6:
      return call(ElementShape<6, 2, 3>{});
    case T::Quad9:
      return call(ElementShape<9, 2, 9>{});
    case T::Tet4:
      return call(ElementShape<4, 3, 1>{});
    case T::Tet10:
      return call(ElementShape<10, 3, 4>{});
    case T::Hex8:
      return call(ElementShape<8, 3, 8>{});
    case T::Hex27:
      return call(ElementShape<27, 3, 27>{});
    default:
      throw std::invalid_argument(elementTypeName(t) + " elements are not assembled");
  }
}

// What one Gauss point contributes, in the reference configuration.
struct GaussKinematics {
  int dim;
  int nv;  // active Voigt components
  int comp[kNumVoigt];
  double N[kMaxElementNodes];
  double dNdX[kMaxElementNodes][kMaxDim];
  double F[3][3];  // 3x3 also in 2D, with F_zz = 1 (plane strain)
  double detF;
  double wdetJ;                          // quadrature weight times reference Jacobian
  double B[kNumVoigt][kMaxElementDofs];  // d E (active components) / d u_e
};

// Deformation gradient, strain and B_NL at Gauss point q of element e. The strain is the
// Green-Lagrange one (large) or B u (small: F = I in B, the linearized strain); it has all six
// Voigt components, zero where the dimension does not strain.
// Npe and Dim are the element type's (forElementShape): with the loop bounds known at compile
// time, the Hex8 kernels of step-42's 64^3 elastic run took 1.9 s of rank 0 instead of 3.2 s
// (docs/benchmarks.md, "Packed supernodal solves").
template <int Npe, int Dim>
KOKKOS_INLINE_FUNCTION void kinematics(const detail::ReferenceValues& ref, bool large,
                                       const double* xe, const double* ue, int q,
                                       GaussKinematics& g, double E[kNumVoigt]) {
  constexpr int npe = Npe, dim = Dim, nd = dim * npe;
  g.dim = dim;
  g.nv = activeComponents(dim, g.comp);
  constexpr int nv = dim == 2 ? 3 : kNumVoigt;  // activeComponents' count
  const double* N = ref.shape(q);
  for (int a = 0; a < npe; ++a) g.N[a] = N[a];
  g.wdetJ = ref.w(q) * mappedGradients(npe, dim, xe, ref.derivatives(q), g.dNdX);
  double H[3][3] = {};  // du_i / dX_j
  for (int a = 0; a < npe; ++a)
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j) H[i][j] += ue[dim * a + i] * g.dNdX[a][j];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) g.F[i][j] = (i == j ? 1.0 : 0.0) + (large ? H[i][j] : 0.0);
  const double(&F)[3][3] = g.F;
  g.detF = F[0][0] * (F[1][1] * F[2][2] - F[1][2] * F[2][1]) -
           F[0][1] * (F[1][0] * F[2][2] - F[1][2] * F[2][0]) +
           F[0][2] * (F[1][0] * F[2][1] - F[1][1] * F[2][0]);
  for (int r = 0; r < nv; ++r) {
    int i, j;
    voigtPair(g.comp[r], i, j);
    for (int a = 0; a < npe; ++a)
      for (int k = 0; k < dim; ++k)
        g.B[r][dim * a + k] =
            i == j ? F[k][i] * g.dNdX[a][i] : F[k][i] * g.dNdX[a][j] + F[k][j] * g.dNdX[a][i];
  }
  for (int c = 0; c < kNumVoigt; ++c) E[c] = 0;
  for (int r = 0; r < nv; ++r) {
    const int c = g.comp[r];
    if (!large) {
      for (int j = 0; j < nd; ++j) E[c] += g.B[r][j] * ue[j];
      continue;
    }
    // Written with H rather than F^T F - I so that small strains lose no digits to cancellation.
    int i, j;
    voigtPair(c, i, j);
    double hh = 0;
    for (int k = 0; k < dim; ++k) hh += H[k][i] * H[k][j];
    E[c] = i == j ? H[i][i] + 0.5 * hh : H[i][j] + H[j][i] + 2 * 0.5 * hh;
  }
}

// Throws for the first element with det F <= 0 at some Gauss point (minDetF filled by a kernel
// for the elements from first on).
void checkDeformation(const ElementMesh& mesh, const Kokkos::View<double*, Kokkos::HostSpace>& m,
                      int first = 0) {
  for (int k = 0; k < static_cast<int>(m.extent(0)); ++k)
    if (!(m(k) > 0.0))
      throw InvertedDeformationError(
          detail::elementLabel(mesh, first + k) +
          " is inverted by the displacement (det F = " + std::to_string(m(k)) + ")");
}

// What the element kernels of one call share: the element coordinates and displacements, the
// reference values of the Gauss rule.
struct ElementInputs {
  HostView2 xe, ue;
  detail::ReferenceValues ref;
};

ElementInputs elementInputs(const ElementMesh& mesh, const std::vector<double>& u) {
  ElementInputs in;
  in.xe = detail::checkedElementCoords(mesh);
  in.ue = detail::elementDisplacements(mesh, u);
  in.ref = detail::referenceValues(mesh.type);
  return in;
}

// Per element of [first, last): the internal force vector (into fe, indexed by element) or the
// tangent (into Ke, indexed by e - first), whichever is given. The law is not called at an
// inverted point, so that a rejected state leaves no trial history behind there.
template <class Shape>
void elementKernel(Shape, const ElementMesh& mesh, const MaterialLaw& law, const ElementInputs& in,
                   Kinematics kin, bool initialStress, int first, int last, HostView2* fe,
                   HostView3* Ke) {
  constexpr int npe = Shape::npe, dim = Shape::dim, ngp = Shape::ngp, nd = dim * npe;
  const bool large = kin == Kinematics::TotalLagrangian;
  const bool geometric = large && initialStress;
  const HostView2 xe = in.xe, ue = in.ue;
  const detail::ReferenceValues ref = in.ref;
  const MaterialLaw* lawPtr = &law;  // captured by value: the lambda copies the pointer only
  const bool withForce = fe != nullptr, withTangent = Ke != nullptr;
  HostView2 f;
  if (withForce) f = *fe;
  HostView3 K;
  if (withTangent) K = *Ke;
  Kokkos::View<double*, Kokkos::HostSpace> minDetF("minDetF", last - first);
  Kokkos::parallel_for(
      "plasticity::element_kernel", Kokkos::RangePolicy<ExecSpace>(first, last),
      KOKKOS_LAMBDA(int e) {
        double detMin = 1e300;
        for (int q = 0; q < ngp; ++q) {
          GaussKinematics g;
          double E[kNumVoigt];
          kinematics<npe, dim>(ref, large, &xe(e, 0), &ue(e, 0), q, g, E);
          detMin = g.detF < detMin ? g.detF : detMin;
          if (!(g.detF > 0.0)) continue;
          MaterialResponse r;
          lawPtr->evaluate(MaterialPointId{e, q}, E, r);
          const double* S = r.stress;
          constexpr int nv = dim == 2 ? 3 : kNumVoigt;  // g.nv
          if (withForce)
            for (int i = 0; i < nd; ++i) {
              double s = 0;
              for (int k = 0; k < nv; ++k) s += g.B[k][i] * S[g.comp[k]];
              f(e, i) += s * g.wdetJ;
            }
          if (!withTangent) continue;
          const int ke = e - first;
          // Material part B^T C B over the active components.
          double CB[kNumVoigt][kMaxElementDofs];
          for (int k = 0; k < nv; ++k)
            for (int j = 0; j < nd; ++j) {
              double s = 0;
              for (int l = 0; l < nv; ++l)
                s += r.tangent[kNumVoigt * g.comp[k] + g.comp[l]] * g.B[l][j];
              CB[k][j] = s;
            }
          // The upper triangle only (the laws' tangents are symmetric, as the local solvers,
          // which read one triangle, assume); mirrored once the element is done.
          for (int i = 0; i < nd; ++i)
            for (int j = i; j < nd; ++j) {
              double s = 0;
              for (int k = 0; k < nv; ++k) s += g.B[k][i] * CB[k][j];
              K(ke, i, j) += s * g.wdetJ;
            }
          // Initial stress: the variation of B_NL with u, contracted with S; it couples only
          // like components, hence the identity in k.
          if (!geometric) continue;
          for (int a = 0; a < npe; ++a)
            for (int b = 0; b < npe; ++b) {
              const double* ga = g.dNdX[a];
              const double* gb = g.dNdX[b];
              double s = 0;
              for (int i = 0; i < dim; ++i) {
                double t = 0;
                for (int j = 0; j < dim; ++j) t += S[voigtIndex(i, j)] * gb[j];
                s += ga[i] * t;
              }
              s *= g.wdetJ;
              for (int k = 0; k < dim; ++k) K(ke, dim * a + k, dim * b + k) += s;
            }
        }
        if (withTangent)
          for (int i = 0; i < nd; ++i)
            for (int j = 0; j < i; ++j) K(e - first, i, j) = K(e - first, j, i);
        minDetF(e - first) = detMin;
      });
  checkDeformation(mesh, minDetF, first);
}

void elementKernel(const ElementMesh& mesh, const MaterialLaw& law, const ElementInputs& in,
                   Kinematics kin, bool initialStress, int first, int last, HostView2* fe,
                   HostView3* Ke) {
  forElementShape(mesh.type, [&](auto shape) {
    elementKernel(shape, mesh, law, in, kin, initialStress, first, last, fe, Ke);
  });
}

// Elements per chunk of the tangent: the element matrices of one chunk at a time (Hex8: 4.7 MB),
// not of the whole mesh (Hex8 at 64^3 cells on 2 ranks: 600 MB a rank, zeroed and written once).
constexpr int kTangentChunk = 1024;

}  // namespace

std::vector<double> internalForce(const ElementMesh& mesh, const MaterialLaw& law,
                                  const std::vector<double>& u, Kinematics kinematics) {
  const ElementInputs in = elementInputs(mesh, u);
  HostView2 fe("fe", mesh.numElements(), mesh.dim() * nodesPerElement(mesh.type));
  elementKernel(mesh, law, in, kinematics, false, 0, mesh.numElements(), &fe, nullptr);
  return detail::scatterVector(mesh, fe);
}

tfeti::CsrMatrix tangentStiffness(const ElementMesh& mesh, const MaterialLaw& law,
                                  const std::vector<double>& u, Kinematics kinematics,
                                  bool initialStress) {
  const ElementInputs in = elementInputs(mesh, u);
  const int ne = mesh.numElements(), nd = mesh.dim() * nodesPerElement(mesh.type);
  tfeti::CsrMatrix K = detail::stiffnessPattern(mesh);
  HostView3 Ke("Ke", std::min(ne, kTangentChunk), nd, nd);
  for (int first = 0; first < ne; first += kTangentChunk) {
    const int last = std::min(ne, first + kTangentChunk);
    if (first > 0) Kokkos::deep_copy(Ke, 0.0);
    elementKernel(mesh, law, in, kinematics, initialStress, first, last, nullptr, &Ke);
    detail::addElementMatrices(mesh, Ke, first, last, K);
  }
  return K;
}

StressField cauchyStress(const ElementMesh& mesh, const MaterialLaw& law,
                         const std::vector<double>& u, Kinematics kin) {
  return detail::gaussPointStresses(mesh, law, u, kin, true);
}

namespace detail {

namespace {

// The Cauchy stresses (into sg) and the Gauss points' positions (into xg) of every element;
// returns the smallest det F of each element.
template <class Shape>
Kokkos::View<double*, Kokkos::HostSpace> stressKernel(Shape, const ElementMesh& mesh,
                                                      const MaterialLaw& law, const HostView2& xe,
                                                      const HostView2& ue, Kinematics kin,
                                                      bool deformedPositions, HostView3 sg,
                                                      HostView3 xg) {
  constexpr int npe = Shape::npe, dim = Shape::dim, ngp = Shape::ngp;
  const bool large = kin == Kinematics::TotalLagrangian;
  const detail::ReferenceValues ref = detail::referenceValues(mesh.type);
  const int ne = mesh.numElements();
  const MaterialLaw* lawPtr = &law;
  const double moved = deformedPositions ? 1.0 : 0.0;
  Kokkos::View<double*, Kokkos::HostSpace> minDetF("minDetF", ne);
  Kokkos::parallel_for(
      "plasticity::cauchy_stress", Kokkos::RangePolicy<ExecSpace>(0, ne), KOKKOS_LAMBDA(int e) {
        double detMin = 1e300;
        for (int q = 0; q < ngp; ++q) {
          GaussKinematics g;
          double E[kNumVoigt];
          kinematics<npe, dim>(ref, large, &xe(e, 0), &ue(e, 0), q, g, E);
          detMin = g.detF < detMin ? g.detF : detMin;
          for (int a = 0; a < npe; ++a)
            for (int i = 0; i < dim; ++i)
              xg(e, q, i) += g.N[a] * (xe(e, dim * a + i) + moved * ue(e, dim * a + i));
          if (!(g.detF > 0.0)) continue;
          MaterialResponse r;
          lawPtr->evaluate(MaterialPointId{e, q}, E, r);
          for (int c = 0; c < kNumVoigt; ++c) {
            int i, j;
            voigtPair(c, i, j);
            double sigma = 0;  // (F S F^T)_ij
            for (int k = 0; k < 3; ++k)
              for (int l = 0; l < 3; ++l)
                sigma += g.F[i][k] * r.stress[voigtIndex(k, l)] * g.F[j][l];
            sg(e, q, c) = sigma / g.detF;
          }
        }
        minDetF(e) = detMin;
      });
  return minDetF;
}

}  // namespace

StressField gaussPointStresses(const ElementMesh& mesh, const MaterialLaw& law,
                               const std::vector<double>& u, Kinematics kin,
                               bool deformedPositions) {
  const HostView2 xe = detail::checkedElementCoords(mesh);
  const HostView2 ue = detail::elementDisplacements(mesh, u);
  const int ne = mesh.numElements(), ngp = numGaussPoints(mesh.type);
  HostView3 sg("cauchyStress", ne, ngp, kNumVoigt), xg("gaussCoords", ne, ngp, mesh.dim());
  forElementShape(mesh.type, [&](auto shape) {
    checkDeformation(mesh, stressKernel(shape, mesh, law, xe, ue, kin, deformedPositions, sg, xg));
  });
  return detail::stressField(mesh, sg, xg);
}

}  // namespace detail

}  // namespace plasticity
