// Unit tests of the Q1 kernels in 3D (trilinear hexahedra, plasticity_Q1Assembly): the kernel
// of the element matrices (constants; the six rigid body modes) and their rank, the patch test
// and the energy of linear fields on a distorted 2x2x2 mesh of the unit cube, the consistent
// body load, and the rejection of inverted elements and inconsistent meshes.
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "plasticity_ElasticLaw.hpp"
#include "plasticity_Q1Assembly.hpp"
#include "plasticity_TestUtils.hpp"
#include "tfeti_CsrMatrix.hpp"
#include "tfeti_StructuredMesh.hpp"

namespace {
using namespace plasticity_test;  // NOLINT(build/namespaces)

using plasticity::ElasticLaw;
using plasticity::Field;
using plasticity::Q1Mesh;

// The unit cube in 2x2x2 hexahedra with every node off the cube's edges moved within the faces
// it lies on (and the centre node freely): the cells are non-affine but fill the cube exactly,
// so volume integrals have closed forms.
Q1Mesh distortedCube() {
  const tfeti::StructuredMesh grid({0, 0, 0}, {1, 1, 1}, {1, 1, 1}, {2, 2, 2});
  const tfeti::SubdomainMesh m = grid.wholeMesh();
  Q1Mesh q{m.coords, grid.wholeCells(), 3};
  const double shift[3] = {0.09, -0.07, 0.05};
  for (int n = 0; n < q.numNodes(); ++n)
    for (int d = 0; d < 3; ++d) {
      const double x = q.coords[3 * n + d];
      // Coordinate d may move unless the node lies on a face normal to d.
      if (x != 0.0 && x != 1.0) q.coords[3 * n + d] += shift[d] * (1.0 + 0.3 * ((n + d) % 3));
    }
  return q;
}

std::vector<double> column(const std::vector<std::vector<double>>& R, int k) {
  return R[k];
}

// Translations and the rotations e_a x x at the given nodes.
std::vector<std::vector<double>> rigidModes3d(const std::vector<double>& x) {
  const std::size_t n = x.size() / 3;
  std::vector<std::vector<double>> R(6, std::vector<double>(3 * n, 0.0));
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) R[d][3 * i + d] = 1.0;
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, e = (a + 2) % 3;
      R[3 + a][3 * i + e] = x[3 * i + b];
      R[3 + a][3 * i + b] = -x[3 * i + e];
    }
  }
  return R;
}

// Nodes on the boundary of the unit cube.
bool onBoundary(const Q1Mesh& m, int n) {
  for (int d = 0; d < 3; ++d)
    if (m.coords[3 * n + d] == 0.0 || m.coords[3 * n + d] == 1.0) return true;
  return false;
}

TEUCHOS_UNIT_TEST(Q1Assembly3D, ElementKernelsAndRank) {
  // One distorted hexahedron (cell 0 of the distorted cube).
  const Q1Mesh cube = distortedCube();
  Q1Mesh m;
  m.dim = 3;
  for (int a = 0; a < 8; ++a) {
    const int n = cube.cells[a];
    m.coords.insert(m.coords.end(), cube.coords.begin() + 3 * n, cube.coords.begin() + 3 * n + 3);
    m.cells.push_back(a);
  }
  const tfeti::CsrMatrix L = plasticity::assembleStiffness(m, Field::Scalar, ElasticLaw());
  TEST_COMPARE(asymmetry(L), <, 1e-14);
  TEST_COMPARE(maxAbs(multiply(L, std::vector<double>(8, 1.0))) / L.maxAbs(), <, 1e-14);
  const std::vector<double> wl = eigenvalues(L);
  TEST_COMPARE(std::abs(wl[0]) / wl.back(), <, 1e-13);
  TEST_COMPARE(wl[1] / wl.back(), >, 1e-3);  // rank 7: only the constants

  const tfeti::CsrMatrix K =
      plasticity::assembleStiffness(m, Field::Elasticity, ElasticLaw(210, 0.3));
  TEST_EQUALITY(K.rows, 24);
  TEST_COMPARE(asymmetry(K), <, 1e-14);
  const auto R = rigidModes3d(m.coords);
  for (int k = 0; k < 6; ++k) {
    const double r = norm2(multiply(K, column(R, k))) / (K.maxAbs() * norm2(R[k]));
    out << "||K r_" << k << "|| / (max|K| ||r||) = " << r << "\n";
    TEST_COMPARE(r, <, 1e-14);
  }
  const std::vector<double> w = eigenvalues(K);
  for (int k = 0; k < 6; ++k) TEST_COMPARE(std::abs(w[k]) / w.back(), <, 1e-13);
  TEST_COMPARE(w[6] / w.back(), >, 1e-3);  // rank 18: exactly the six rigid modes
}

TEUCHOS_UNIT_TEST(Q1Assembly3D, PoissonPatchTestAndEnergy) {
  const Q1Mesh m = distortedCube();
  const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, Field::Scalar, ElasticLaw());
  // u = g . x + c: K u vanishes at the interior node, and u^T K u = |g|^2 |cube|.
  const double g[3] = {0.7, -1.1, 0.4};
  std::vector<double> u(m.numNodes());
  for (int n = 0; n < m.numNodes(); ++n)
    u[n] = 0.3 + g[0] * m.coords[3 * n] + g[1] * m.coords[3 * n + 1] + g[2] * m.coords[3 * n + 2];
  const std::vector<double> Ku = multiply(K, u);
  int interior = 0;
  for (int n = 0; n < m.numNodes(); ++n)
    if (!onBoundary(m, n)) {
      ++interior;
      TEST_COMPARE(std::abs(Ku[n]) / K.maxAbs(), <, 1e-14);
    }
  TEST_EQUALITY(interior, 1);
  TEST_FLOATING_EQUALITY(dot(u, Ku), g[0] * g[0] + g[1] * g[1] + g[2] * g[2], 1e-13);
}

TEUCHOS_UNIT_TEST(Q1Assembly3D, ElasticityPatchTestAndEnergy) {
  const Q1Mesh m = distortedCube();
  const ElasticLaw law(3.0, 0.27);
  const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, Field::Elasticity, law);
  TEST_COMPARE(asymmetry(K), <, 1e-14);
  // u = A x: constant strain eps = sym(A), energy density lambda tr(eps)^2 + 2 mu eps:eps.
  const double A[3][3] = {{0.1, -0.3, 0.2}, {0.25, -0.15, 0.05}, {-0.2, 0.35, 0.3}};
  std::vector<double> u(3 * m.numNodes());
  for (int n = 0; n < m.numNodes(); ++n)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) u[3 * n + i] += A[i][j] * m.coords[3 * n + j];
  const std::vector<double> Ku = multiply(K, u);
  for (int n = 0; n < m.numNodes(); ++n)
    if (!onBoundary(m, n))
      for (int i = 0; i < 3; ++i) TEST_COMPARE(std::abs(Ku[3 * n + i]) / K.maxAbs(), <, 1e-14);
  double trace = 0.0, eps2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    trace += A[i][i];
    for (int j = 0; j < 3; ++j) eps2 += std::pow(0.5 * (A[i][j] + A[j][i]), 2);
  }
  TEST_FLOATING_EQUALITY(dot(u, Ku), law.lambda() * trace * trace + 2.0 * law.mu() * eps2, 1e-13);
  // The rigid modes of the whole patch.
  const auto R = rigidModes3d(m.coords);
  for (int k = 0; k < 6; ++k)
    TEST_COMPARE(norm2(multiply(K, R[k])) / (K.maxAbs() * norm2(R[k])), <, 1e-14);
}

TEUCHOS_UNIT_TEST(Q1Assembly3D, BodyLoadIntegratesTheSource) {
  const Q1Mesh m = distortedCube();
  const double s = 2.5;
  const std::vector<double> f = plasticity::assembleBodyLoad(m, Field::Scalar, &s);
  double sum = 0.0, moment = 0.0;
  for (int n = 0; n < m.numNodes(); ++n) {
    sum += f[n];
    moment += f[n] * m.coords[3 * n];  // exact: the shape functions reproduce x
  }
  TEST_FLOATING_EQUALITY(sum, s * 1.0, 1e-14);
  TEST_FLOATING_EQUALITY(moment, s * 0.5, 1e-14);
  const double b[3] = {0.5, -1.5, 2.0};
  const std::vector<double> fe = plasticity::assembleBodyLoad(m, Field::Elasticity, b);
  for (int d = 0; d < 3; ++d) {
    double total = 0.0;
    for (int n = 0; n < m.numNodes(); ++n) total += fe[3 * n + d];
    TEST_FLOATING_EQUALITY(total, b[d], 1e-14);
  }
}

TEUCHOS_UNIT_TEST(Q1Assembly3D, InvertedAndInconsistentMeshesThrow) {
  Q1Mesh m = distortedCube();
  // Cell 5 with its bottom and top faces swapped: inside out.
  std::swap_ranges(m.cells.begin() + 40, m.cells.begin() + 44, m.cells.begin() + 44);
  try {
    plasticity::assembleStiffness(m, Field::Elasticity, ElasticLaw());
    TEST_ASSERT(false);
  } catch (const std::exception& e) {
    out << e.what() << "\n";
    TEST_INEQUALITY(std::string(e.what()).find("element 5 "), std::string::npos);
  }
  Q1Mesh bad = distortedCube();
  bad.cells.pop_back();  // not a multiple of 8 nodes
  TEST_THROW(plasticity::assembleStiffness(bad, Field::Scalar, ElasticLaw()),
             std::invalid_argument);
  bad = distortedCube();
  bad.cells[3] = bad.numNodes();  // a node that does not exist
  TEST_THROW(plasticity::assembleBodyLoad(bad, Field::Scalar, std::vector<double>(8, 1.0)),
             std::invalid_argument);
}

}  // namespace
