#include "plasticity_TotalLagrangian.hpp"

#include <Kokkos_Core.hpp>

#include <string>

namespace plasticity {
namespace {

using ExecSpace = Kokkos::DefaultHostExecutionSpace;
using detail::HostView2;
using detail::HostView3;

constexpr int kMaxElementDofs = 2 * kMaxElementNodes;

// What one Gauss point contributes, in the reference configuration.
struct GaussKinematics {
  double N[kMaxElementNodes];
  double dNdX[kMaxElementNodes][2];
  double F[2][2];
  double detF;
  double wdetJ;                  // quadrature weight times reference Jacobian
  double B[3][kMaxElementDofs];  // dE (Voigt) / du_e
};

// Deformation gradient, Green-Lagrange strain and B_NL at Gauss point q of element e.
KOKKOS_INLINE_FUNCTION void kinematics(ElementType type, bool large, const double* xe,
                                       const double* ue, int q, GaussKinematics& g, double E[3]) {
  const int npe = nodesPerElement(type);
  double xi, eta, w;
  gaussPoint(type, q, xi, eta, w);
  g.wdetJ = w * physicalGradients(type, xe, xi, eta, g.N, g.dNdX);
  double H[2][2] = {{0, 0}, {0, 0}};  // du_i / dX_j
  for (int a = 0; a < npe; ++a)
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) H[i][j] += ue[2 * a + i] * g.dNdX[a][j];
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) g.F[i][j] = (i == j ? 1.0 : 0.0) + (large ? H[i][j] : 0.0);
  g.detF = g.F[0][0] * g.F[1][1] - g.F[0][1] * g.F[1][0];
  // Written with H rather than F^T F - I so that small strains lose no digits to cancellation.
  const double s = large ? 0.5 : 0.0;
  E[0] = H[0][0] + s * (H[0][0] * H[0][0] + H[1][0] * H[1][0]);
  E[1] = H[1][1] + s * (H[0][1] * H[0][1] + H[1][1] * H[1][1]);
  E[2] = H[0][1] + H[1][0] + 2 * s * (H[0][0] * H[0][1] + H[1][0] * H[1][1]);
  for (int a = 0; a < npe; ++a)
    for (int k = 0; k < 2; ++k) {
      g.B[0][2 * a + k] = g.F[k][0] * g.dNdX[a][0];
      g.B[1][2 * a + k] = g.F[k][1] * g.dNdX[a][1];
      g.B[2][2 * a + k] = g.F[k][0] * g.dNdX[a][1] + g.F[k][1] * g.dNdX[a][0];
    }
}

// Throws for the first element with det F <= 0 at some Gauss point (minDetF filled by a kernel).
void checkDeformation(const ElementMesh& mesh, const Kokkos::View<double*, Kokkos::HostSpace>& m) {
  for (int e = 0; e < mesh.numElements(); ++e)
    if (!(m(e) > 0.0))
      throw InvertedDeformationError(
          detail::elementLabel(mesh, e) +
          " is inverted by the displacement (det F = " + std::to_string(m(e)) + ")");
}

// Per element: the internal force vector (fe), or with Ke also the tangent. The law is not
// called at an inverted point, so that a rejected state leaves no trial history behind there.
void elementKernel(const ElementMesh& mesh, const MaterialLaw& law, const std::vector<double>& u,
                   Kinematics kin, bool initialStress, HostView2& fe, HostView3* Ke) {
  const bool large = kin == Kinematics::TotalLagrangian;
  const bool geometric = large && initialStress;
  const HostView2 xe = detail::checkedElementCoords(mesh);
  const HostView2 ue = detail::elementDisplacements(mesh, u);
  const int ne = mesh.numElements(), nd = 2 * nodesPerElement(mesh.type);
  const ElementType type = mesh.type;
  const MaterialLaw* lawPtr = &law;
  fe = HostView2("fe", ne, nd);
  const bool withTangent = Ke != nullptr;
  HostView3 K;
  if (withTangent) K = *Ke = HostView3("Ke", ne, nd, nd);
  Kokkos::View<double*, Kokkos::HostSpace> minDetF("minDetF", ne);
  Kokkos::parallel_for(
      "plasticity::total_lagrangian", Kokkos::RangePolicy<ExecSpace>(0, ne), KOKKOS_LAMBDA(int e) {
        double detMin = 1e300;
        for (int q = 0; q < numGaussPoints(type); ++q) {
          GaussKinematics g;
          double E[3];
          kinematics(type, large, &xe(e, 0), &ue(e, 0), q, g, E);
          detMin = g.detF < detMin ? g.detF : detMin;
          if (!(g.detF > 0.0)) continue;
          MaterialResponse r;
          lawPtr->evaluate(MaterialPointId{e, q}, E, r);
          const double* S = r.stress;
          for (int i = 0; i < nd; ++i)
            fe(e, i) += (g.B[0][i] * S[0] + g.B[1][i] * S[1] + g.B[2][i] * S[2]) * g.wdetJ;
          if (!withTangent) continue;
          const double* C = r.tangent;
          double CB[3][kMaxElementDofs];
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < nd; ++j)
              CB[i][j] = C[3 * i] * g.B[0][j] + C[3 * i + 1] * g.B[1][j] + C[3 * i + 2] * g.B[2][j];
          for (int i = 0; i < nd; ++i)
            for (int j = 0; j < nd; ++j)
              K(e, i, j) +=
                  (g.B[0][i] * CB[0][j] + g.B[1][i] * CB[1][j] + g.B[2][i] * CB[2][j]) * g.wdetJ;
          // Initial stress: the variation of B_NL with u, contracted with S; it couples only
          // like components, hence the identity in k.
          if (!geometric) continue;
          const int npe = nd / 2;
          for (int a = 0; a < npe; ++a)
            for (int b = 0; b < npe; ++b) {
              const double* ga = g.dNdX[a];
              const double* gb = g.dNdX[b];
              const double s =
                  (ga[0] * (S[0] * gb[0] + S[2] * gb[1]) + ga[1] * (S[2] * gb[0] + S[1] * gb[1])) *
                  g.wdetJ;
              K(e, 2 * a, 2 * b) += s;
              K(e, 2 * a + 1, 2 * b + 1) += s;
            }
        }
        minDetF(e) = detMin;
      });
  checkDeformation(mesh, minDetF);
}

}  // namespace

std::vector<double> internalForce(const ElementMesh& mesh, const MaterialLaw& law,
                                  const std::vector<double>& u, Kinematics kinematics) {
  HostView2 fe;
  elementKernel(mesh, law, u, kinematics, false, fe, nullptr);
  const int npe = nodesPerElement(mesh.type);
  std::vector<double> f(2 * static_cast<std::size_t>(mesh.numNodes()), 0.0);
  for (int e = 0; e < mesh.numElements(); ++e)
    for (int a = 0; a < npe; ++a) {
      const int n = mesh.connectivity[static_cast<std::size_t>(e) * npe + a];
      f[2 * n] += fe(e, 2 * a);
      f[2 * n + 1] += fe(e, 2 * a + 1);
    }
  return f;
}

tfeti::CsrMatrix tangentStiffness(const ElementMesh& mesh, const MaterialLaw& law,
                                  const std::vector<double>& u, Kinematics kinematics,
                                  bool initialStress) {
  HostView2 fe;
  HostView3 Ke;
  elementKernel(mesh, law, u, kinematics, initialStress, fe, &Ke);
  return detail::scatterStiffness(mesh, Ke);
}

StressField cauchyStress(const ElementMesh& mesh, const MaterialLaw& law,
                         const std::vector<double>& u, Kinematics kin) {
  const bool large = kin == Kinematics::TotalLagrangian;
  const HostView2 xe = detail::checkedElementCoords(mesh);
  const HostView2 ue = detail::elementDisplacements(mesh, u);
  const int ne = mesh.numElements(), npe = nodesPerElement(mesh.type);
  const int ngp = numGaussPoints(mesh.type);
  const ElementType type = mesh.type;
  const MaterialLaw* lawPtr = &law;
  HostView3 sg("cauchyStress", ne, ngp, 4), xg("deformedGaussCoords", ne, ngp, 2);
  Kokkos::View<double*, Kokkos::HostSpace> minDetF("minDetF", ne);
  Kokkos::parallel_for(
      "plasticity::cauchy_stress", Kokkos::RangePolicy<ExecSpace>(0, ne), KOKKOS_LAMBDA(int e) {
        double detMin = 1e300;
        for (int q = 0; q < ngp; ++q) {
          GaussKinematics g;
          double E[3];
          kinematics(type, large, &xe(e, 0), &ue(e, 0), q, g, E);
          detMin = g.detF < detMin ? g.detF : detMin;
          for (int a = 0; a < npe; ++a)
            for (int i = 0; i < 2; ++i)
              xg(e, q, i) += g.N[a] * (xe(e, 2 * a + i) + ue(e, 2 * a + i));
          if (!(g.detF > 0.0)) continue;
          MaterialResponse r;
          lawPtr->evaluate(MaterialPointId{e, q}, E, r);
          const double S[2][2] = {{r.stress[0], r.stress[2]}, {r.stress[2], r.stress[1]}};
          double sigma[2][2] = {{0, 0}, {0, 0}};
          for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j)
              for (int k = 0; k < 2; ++k)
                for (int l = 0; l < 2; ++l) sigma[i][j] += g.F[i][k] * S[k][l] * g.F[j][l];
          sg(e, q, 0) = sigma[0][0] / g.detF;
          sg(e, q, 1) = sigma[1][1] / g.detF;
          sg(e, q, 2) = sigma[0][1] / g.detF;
          sg(e, q, 3) = r.stress[3] / g.detF;
        }
        minDetF(e) = detMin;
      });
  checkDeformation(mesh, minDetF);
  return detail::stressField(mesh, sg, xg);
}

}  // namespace plasticity
