// Convergence of the plane-strain elements to a smooth exact solution of elasticity without body
// force on the unit square (Dirichlet data interpolated on the whole boundary), on a family of
// smoothly distorted meshes: the energy-norm error must fall like h for the linear elements and
// like h^2 for the quadratic ones.
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "plasticity_ElementTestMeshes.hpp"
#include "plasticity_Elements.hpp"
#include "plasticity_TestUtils.hpp"
#include "tfeti_CsrMatrix.hpp"
#include "tfeti_LocalSolver.hpp"

namespace {

using plasticity::ElasticLaw;
using plasticity::ElementMesh;
using plasticity::ElementType;
using plasticity_test::LatticeMesh;

// u = grad Phi + beta (-y g_x, (3 - 4 nu) g - y g_y) with Phi = sinh(a x) sin(a y) / a^2 and
// g = exp(a x) cos(a y) / a, both harmonic. The first part is divergence-free and satisfies
// Navier's equations for any moduli; the second is the Papkovich-Neuber solution of a harmonic
// potential (0, g) and carries volume change, so the Poisson ratio matters.
struct ExactSolution {
  double a = 2.0, beta = 0.5, nu = 0.3;

  void displacement(double x, double y, double u[2]) const {
    const double ex = std::exp(a * x), c = std::cos(a * y), s = std::sin(a * y);
    u[0] = std::cosh(a * x) * s / a - beta * y * ex * c;
    u[1] = std::sinh(a * x) * c / a + beta * ((3 - 4 * nu) * ex * c / a + y * ex * s);
  }
  // (eps_xx, eps_yy, gamma_xy).
  void strain(double x, double y, double e[3]) const {
    const double ex = std::exp(a * x), c = std::cos(a * y), s = std::sin(a * y);
    const double gx = ex * c, gy = -ex * s, gxx = a * ex * c, gxy = -a * ex * s, gyy = -a * ex * c;
    const double sh = std::sinh(a * x) * s;
    e[0] = sh - beta * y * gxx;
    e[1] = -sh + beta * ((2 - 4 * nu) * gy - y * gyy);
    e[2] = 2 * std::cosh(a * x) * c + beta * ((2 - 4 * nu) * gx - 2 * y * gxy);
  }
};

// Reference quadrature, finer than the elements' own: their Gauss points are superconvergent
// stress points of quadrilaterals and would flatter the error.
struct RefPoint {
  double xi, eta, w;
};
std::vector<RefPoint> referenceRule(ElementType type) {
  const double p[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                       0.9061798459386640};
  const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                       0.4786286704993665, 0.2369268850561891};
  std::vector<RefPoint> rule;
  const bool tri = plasticity::cornersPerElement(type) == 3;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      if (!tri) {
        rule.push_back({p[i], p[j], w[i] * w[j]});
      } else {
        // The square collapsed onto the triangle (Duffy): xi = u (1 - v), eta = v.
        const double u = 0.5 * (1 + p[i]), v = 0.5 * (1 + p[j]);
        rule.push_back({u * (1 - v), v, 0.25 * w[i] * w[j] * (1 - v)});
      }
    }
  return rule;
}

struct Errors {
  double energy = 0.0, l2 = 0.0;
};

// Energy-norm and L2 errors of the discrete displacement against the exact solution.
Errors errors(const ElementMesh& m, const ElasticLaw& law, const std::vector<double>& uh,
              const ExactSolution& ex) {
  double D[9];
  law.planeStrainMatrix(D);
  const int npe = plasticity::nodesPerElement(m.type);
  const std::vector<RefPoint> rule = referenceRule(m.type);
  double energy = 0.0, l2 = 0.0;
  for (int e = 0; e < m.numElements(); ++e) {
    const int* en = &m.connectivity[e * npe];
    for (const RefPoint& r : rule) {
      double N[plasticity::kMaxElementNodes], dN[plasticity::kMaxElementNodes][plasticity::kMaxDim];
      const double xi[2] = {r.xi, r.eta};
      plasticity::shapeFunctions(m.type, xi, N, dN);
      double J[2][2] = {{0, 0}, {0, 0}}, x[2] = {0, 0}, u[2] = {0, 0}, G[2][2] = {{0, 0}, {0, 0}};
      for (int a = 0; a < npe; ++a)
        for (int i = 0; i < 2; ++i) {
          x[i] += N[a] * m.coords[2 * en[a] + i];
          u[i] += N[a] * uh[2 * en[a] + i];
          for (int j = 0; j < 2; ++j) {
            J[i][j] += m.coords[2 * en[a] + i] * dN[a][j];
            G[i][j] += uh[2 * en[a] + i] * dN[a][j];  // d u_i / d xi_j
          }
        }
      const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
      const double inv[2][2] = {{J[1][1] / det, -J[0][1] / det}, {-J[1][0] / det, J[0][0] / det}};
      double du[2][2];  // d u_i / d x_k
      for (int i = 0; i < 2; ++i)
        for (int k = 0; k < 2; ++k) du[i][k] = G[i][0] * inv[0][k] + G[i][1] * inv[1][k];
      double eps[3], ue[2];
      ex.strain(x[0], x[1], eps);
      ex.displacement(x[0], x[1], ue);
      const double d[3] = {eps[0] - du[0][0], eps[1] - du[1][1], eps[2] - du[0][1] - du[1][0]};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) energy += d[i] * D[3 * i + j] * d[j] * r.w * det;
      l2 += ((ue[0] - u[0]) * (ue[0] - u[0]) + (ue[1] - u[1]) * (ue[1] - u[1])) * r.w * det;
    }
  }
  return {std::sqrt(energy), std::sqrt(l2)};
}

// Finite element solution with u = exact on the boundary nodes and no body force.
std::vector<double> solveDirichlet(const LatticeMesh& L, const ElasticLaw& law,
                                   const ExactSolution& ex) {
  const ElementMesh& m = L.mesh;
  const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, law);
  std::vector<double> u(2 * m.numNodes(), 0.0);
  std::vector<int> free;
  for (int n = 0; n < m.numNodes(); ++n) {
    if (L.onBoundary(n))
      ex.displacement(m.coords[2 * n], m.coords[2 * n + 1], &u[2 * n]);
    else
      free.insert(free.end(), {2 * n, 2 * n + 1});
  }
  plasticity_test::solveFreeDofs(K, free, u);
  return u;
}

}  // namespace

TEUCHOS_UNIT_TEST(ElementConvergence, ExactSolutionStrainsAreItsDerivatives) {
  // The error measure trusts the hand-derived strains: check them by central differences.
  const ExactSolution ex;
  const double h = 1e-5;
  const double pts[3][2] = {{0.3, 0.7}, {0.9, 0.1}, {0.55, 0.45}};
  for (const auto& p : pts) {
    double e[3], xp[2], xm[2], yp[2], ym[2];
    ex.strain(p[0], p[1], e);
    ex.displacement(p[0] + h, p[1], xp), ex.displacement(p[0] - h, p[1], xm);
    ex.displacement(p[0], p[1] + h, yp), ex.displacement(p[0], p[1] - h, ym);
    TEST_FLOATING_EQUALITY(e[0], (xp[0] - xm[0]) / (2 * h), 1e-8);
    TEST_FLOATING_EQUALITY(e[1], (yp[1] - ym[1]) / (2 * h), 1e-8);
    TEST_FLOATING_EQUALITY(e[2], (yp[0] - ym[0] + xp[1] - xm[1]) / (2 * h), 1e-8);
  }
}

TEUCHOS_UNIT_TEST(ElementConvergence, EnergyErrorRatesAreOneForLinearAndTwoForQuadratic) {
  const ElasticLaw law(1.0, 0.3);
  const ExactSolution ex;
  struct Case {
    ElementType type;
    int n0;
    double rate;
  };
  // Equal node counts per level for linear and quadratic elements.
  const Case cases[] = {{ElementType::Tri3, 8, 1.0},
                        {ElementType::Quad4, 8, 1.0},
                        {ElementType::Tri6, 4, 2.0},
                        {ElementType::Quad9, 4, 2.0}};
  for (const Case& c : cases) {
    std::vector<double> energy, l2;
    for (int level = 0; level < 3; ++level) {
      const int n = c.n0 << level;
      const LatticeMesh L =
          plasticity_test::latticeMesh(c.type, n, plasticity_test::smoothVertices(0.04));
      const Errors err = errors(L.mesh, law, solveDirichlet(L, law, ex), ex);
      energy.push_back(err.energy);
      l2.push_back(err.l2);
    }
    out << plasticity::elementTypeName(c.type) << ": energy errors";
    for (double e : energy) out << " " << e;
    out << ", rates";
    for (int k = 0; k < 2; ++k) out << " " << std::log2(energy[k] / energy[k + 1]);
    out << "; L2 rates";
    for (int k = 0; k < 2; ++k) out << " " << std::log2(l2[k] / l2[k + 1]);
    out << "\n";
    for (int k = 0; k < 2; ++k) {
      const double rate = std::log2(energy[k] / energy[k + 1]);
      TEST_COMPARE(std::abs(rate - c.rate), <, 0.1);
    }
  }
}
