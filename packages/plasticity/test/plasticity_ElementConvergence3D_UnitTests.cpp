// Measured energy-norm convergence of the 3D elements on a manufactured solution: the
// Papkovich-Neuber displacement u = grad phi + 4 (1 - nu) psi e_z - grad(z psi) with harmonic
// phi and psi solves the Navier equations without body force, so the finite element solution
// with u = exact on the boundary nodes of the (smoothly distorted) unit cube converges at
// rate 1 (Tet4, Hex8) and 2 (Tet10, Hex27) in the energy norm.
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>
#include <vector>

#include "plasticity_ElementTestMeshes3D.hpp"
#include "plasticity_Elements.hpp"
#include "plasticity_TestUtils.hpp"
#include "tfeti_LocalSolver.hpp"

namespace {

using plasticity::ElasticLaw;
using plasticity::ElementMesh;
using plasticity::ElementType;
using plasticity_test::CubeMesh;

constexpr double kNu = 0.3;

// phi = exp(sqrt 2 x) cos y cos z and psi = sinh(y) sin(z) + x: both harmonic.
void exactDisplacement(const double x[3], double u[3]) {
  const double r2 = std::sqrt(2.0);
  const double ex = std::exp(r2 * x[0]);
  const double gphi[3] = {r2 * ex * std::cos(x[1]) * std::cos(x[2]),
                          -ex * std::sin(x[1]) * std::cos(x[2]),
                          -ex * std::cos(x[1]) * std::sin(x[2])};
  const double psi = std::sinh(x[1]) * std::sin(x[2]) + x[0];
  const double gpsi[3] = {1.0, std::cosh(x[1]) * std::sin(x[2]), std::sinh(x[1]) * std::cos(x[2])};
  // grad(z psi) = z grad psi + psi e_z
  for (int i = 0; i < 3; ++i) u[i] = 0.1 * gphi[i] - 0.2 * x[2] * gpsi[i];
  u[2] += 0.2 * (4 * (1 - kNu) * psi - psi);
}

// Engineering strain (Voigt) of the exact field by central differences (error ~1e-10, far
// below the discretization errors measured).
void exactStrain(const double x[3], double e[plasticity::kNumVoigt]) {
  const double h = 1e-5;
  double G[3][3];  // du_i / dx_j
  for (int j = 0; j < 3; ++j) {
    double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]}, up[3], um[3];
    xp[j] += h, xm[j] -= h;
    exactDisplacement(xp, up), exactDisplacement(xm, um);
    for (int i = 0; i < 3; ++i) G[i][j] = (up[i] - um[i]) / (2 * h);
  }
  e[0] = G[0][0], e[1] = G[1][1], e[2] = G[2][2];
  e[3] = G[1][2] + G[2][1], e[4] = G[0][2] + G[2][0], e[5] = G[0][1] + G[1][0];
}

// Reference rule finer than the elements' own (their Gauss points may be superconvergent):
// 5^3 Gauss-Legendre points, collapsed onto the tetrahedron (Duffy) for simplices.
struct RefPoint {
  double xi[3], w;
};
std::vector<RefPoint> referenceRule(ElementType t) {
  const double p[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                       0.9061798459386640};
  const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                       0.4786286704993665, 0.2369268850561891};
  std::vector<RefPoint> rule;
  const bool simplex = plasticity::elementInfo(t).simplex;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 5; ++k) {
        if (!simplex) {
          rule.push_back({{p[i], p[j], p[k]}, w[i] * w[j] * w[k]});
          continue;
        }
        const double a = 0.5 * (1 + p[i]), b = 0.5 * (1 + p[j]), c = 0.5 * (1 + p[k]);
        rule.push_back({{a * (1 - b) * (1 - c), b * (1 - c), c},
                        0.125 * w[i] * w[j] * w[k] * (1 - b) * (1 - c) * (1 - c)});
      }
  return rule;
}

// Energy-norm error sqrt(int (e - e_h) : C : (e - e_h)).
double energyError(const ElementMesh& m, const ElasticLaw& law, const std::vector<double>& uh) {
  double C[36];
  law.voigtMatrix(C);
  const int npe = plasticity::nodesPerElement(m.type);
  const std::vector<RefPoint> rule = referenceRule(m.type);
  double energy = 0.0;
  for (int e = 0; e < m.numElements(); ++e) {
    double xe[3 * plasticity::kMaxElementNodes], ue[3 * plasticity::kMaxElementNodes];
    for (int a = 0; a < npe; ++a)
      for (int i = 0; i < 3; ++i) {
        const int n = m.connectivity[e * npe + a];
        xe[3 * a + i] = m.coords[3 * n + i];
        ue[3 * a + i] = uh[3 * n + i];
      }
    for (const RefPoint& r : rule) {
      double N[plasticity::kMaxElementNodes],
          dNdx[plasticity::kMaxElementNodes][plasticity::kMaxDim];
      const double det = plasticity::physicalGradients(m.type, xe, r.xi, N, dNdx);
      double x[3] = {0, 0, 0}, G[3][3] = {};
      for (int a = 0; a < npe; ++a)
        for (int i = 0; i < 3; ++i) {
          x[i] += N[a] * xe[3 * a + i];
          for (int j = 0; j < 3; ++j) G[i][j] += ue[3 * a + i] * dNdx[a][j];
        }
      double ex[6];
      exactStrain(x, ex);
      const double d[6] = {ex[0] - G[0][0],           ex[1] - G[1][1],
                           ex[2] - G[2][2],           ex[3] - G[1][2] - G[2][1],
                           ex[4] - G[0][2] - G[2][0], ex[5] - G[0][1] - G[1][0]};
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) energy += d[i] * C[6 * i + j] * d[j] * r.w * det;
    }
  }
  return std::sqrt(energy);
}

std::vector<double> solveDirichlet(const CubeMesh& C, const ElasticLaw& law) {
  const ElementMesh& m = C.mesh;
  const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, law);
  std::vector<double> u(3 * m.numNodes(), 0.0);
  std::vector<int> free;
  for (int n = 0; n < m.numNodes(); ++n) {
    if (C.onBoundary(n))
      exactDisplacement(&m.coords[3 * n], &u[3 * n]);
    else
      free.insert(free.end(), {3 * n, 3 * n + 1, 3 * n + 2});
  }
  plasticity_test::solveFreeDofs(K, free, u);
  return u;
}

}  // namespace

TEUCHOS_UNIT_TEST(ElementConvergence3D, EnergyErrorRatesAreOneForLinearAndTwoForQuadratic) {
  const ElasticLaw law(1.0, kNu);
  struct Case {
    ElementType type;
    int n0;
    double rate;
  };
  // Equal node counts per level for linear and quadratic elements (up to 17^3 nodes).
  const Case cases[] = {{ElementType::Tet4, 4, 1.0},
                        {ElementType::Hex8, 4, 1.0},
                        {ElementType::Tet10, 2, 2.0},
                        {ElementType::Hex27, 2, 2.0}};
  for (const Case& c : cases) {
    std::vector<double> energy;
    for (int level = 0; level < 3; ++level) {
      const CubeMesh C =
          plasticity_test::cubeMesh(c.type, c.n0 << level, plasticity_test::smoothVertices3(0.04));
      energy.push_back(energyError(C.mesh, law, solveDirichlet(C, law)));
    }
    out << plasticity::elementTypeName(c.type) << ": energy errors";
    for (double e : energy) out << " " << e;
    out << ", rates";
    for (int k = 0; k < 2; ++k) out << " " << std::log2(energy[k] / energy[k + 1]);
    out << "\n";
    for (int k = 0; k < 2; ++k)
      TEST_COMPARE(std::abs(std::log2(energy[k] / energy[k + 1]) - c.rate), <, 0.1);
  }
}
