// Unit tests of the Q1 element kernels (plasticity_Q1Assembly): element stiffness of the
// Laplacian and of plane-strain elasticity (symmetry, exact values, rigid body modes, rank,
// energy of linear fields), the patch test on a distorted 3x3 mesh, the consistent body load,
// and the rejection of degenerate and inverted elements.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "plasticity_ElasticLaw.hpp"
#include "plasticity_Q1Assembly.hpp"
#include "plasticity_TestUtils.hpp"
#include "tfeti_CsrMatrix.hpp"
#include "tfeti_DenseUtils.hpp"

namespace {
// The shared measures: dot, norm2, maxAbs, asymmetry, multiply, eigenvalues.
using namespace plasticity_test;  // NOLINT(build/namespaces)

using plasticity::ElasticLaw;
using plasticity::Field;
using plasticity::Q1Mesh;

// A single element with the given corners (counter-clockwise).
Q1Mesh singleElement(const std::vector<double>& xy) {
  Q1Mesh m;
  m.coords = xy;
  m.cells = {0, 1, 2, 3};
  return m;
}

// A genuinely distorted (non-parallelogram) element of area 0.5 * |d1 x d2|.
const std::vector<double> kDistorted = {0.0, 0.0, 2.0, 0.2, 1.8, 1.5, 0.3, 1.2};

// Area of a quadrilateral (shoelace).
double quadArea(const std::vector<double>& c) {
  double a = 0.0;
  const int n = static_cast<int>(c.size() / 2);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    a += c[2 * i] * c[2 * j + 1] - c[2 * j] * c[2 * i + 1];
  }
  return 0.5 * a;
}

// The unit square meshed by 3x3 elements whose 4 interior nodes are moved off the grid and whose
// boundary nodes slide along the sides: every element is a general (non-parallelogram) quad but
// the domain is still the unit square (area 1, centroid (0.5, 0.5)).
Q1Mesh distortedPatch() {
  Q1Mesh m;
  const double dx[4][4] = {{0, 0.05, -0.04, 0},
                           {0, 0.07, -0.06, 0},
                           {0, 0.05, -0.08, 0},
                           {0, -0.06, 0.03, 0}};  // [j][i]
  const double dy[4][4] = {
      {0, 0, 0, 0}, {0.04, -0.05, 0.08, -0.03}, {-0.05, 0.06, -0.04, 0.06}, {0, 0, 0, 0}};
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      m.coords.push_back(i / 3.0 + dx[j][i]);
      m.coords.push_back(j / 3.0 + dy[j][i]);
    }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const int n = 4 * j + i;
      m.cells.insert(m.cells.end(), {n, n + 1, n + 5, n + 4});
    }
  return m;
}

bool isInteriorPatchNode(int n) {
  const int i = n % 4, j = n / 4;
  return i > 0 && i < 3 && j > 0 && j < 3;
}

// Nodal values of the linear scalar field a + b x + c y.
std::vector<double> linearScalar(const Q1Mesh& m, double a, double b, double c) {
  std::vector<double> u(m.numNodes());
  for (int n = 0; n < m.numNodes(); ++n) u[n] = a + b * m.coords[2 * n] + c * m.coords[2 * n + 1];
  return u;
}

// Nodal values of the linear displacement u = t + A x (A row-major 2x2), interleaved.
std::vector<double> linearDisplacement(const Q1Mesh& m, const double t[2], const double A[4]) {
  std::vector<double> u(2 * m.numNodes());
  for (int n = 0; n < m.numNodes(); ++n) {
    const double x = m.coords[2 * n], y = m.coords[2 * n + 1];
    u[2 * n] = t[0] + A[0] * x + A[1] * y;
    u[2 * n + 1] = t[1] + A[2] * x + A[3] * y;
  }
  return u;
}

// Strain energy density (times 2) of the constant strain of u = t + A x: eps^T D eps.
double strainEnergy(const ElasticLaw& law, const double A[4], const double B[4]) {
  double D[9];
  law.planeStrainMatrix(D);
  const double ea[3] = {A[0], A[3], A[1] + A[2]}, eb[3] = {B[0], B[3], B[1] + B[2]};
  double s = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s += ea[i] * D[3 * i + j] * eb[j];
  return s;
}

std::string thrownMessage(const Q1Mesh& m, Field field) {
  try {
    plasticity::assembleStiffness(m, field, ElasticLaw(1.0, 0.3));
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// ---------------------------------------------------------------- element stiffness: Laplacian

TEUCHOS_UNIT_TEST(Q1Laplacian, UnitSquareElementMatchesClosedForm) {
  // K = 1/6 [4 -1 -2 -1; -1 4 -1 -2; -2 -1 4 -1; -1 -2 -1 4] on the unit square.
  const Q1Mesh m = singleElement({0, 0, 1, 0, 1, 1, 0, 1});
  const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, Field::Scalar, ElasticLaw());
  TEST_EQUALITY(K.rows, 4);
  TEST_EQUALITY(K.cols, 4);
  TEST_EQUALITY(static_cast<int>(K.nnz()), 16);
  const double ref[4][4] = {{4, -1, -2, -1}, {-1, 4, -1, -2}, {-2, -1, 4, -1}, {-1, -2, -1, 4}};
  double err = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const long k = K.find(i, j);
      TEST_COMPARE(k, >=, 0);
      if (k >= 0) err = std::max(err, std::abs(K.values[k] - ref[i][j] / 6.0));
    }
  TEST_COMPARE(err, <, 1e-14);
}

TEUCHOS_UNIT_TEST(Q1Laplacian, DistortedElementSymmetricWithConstantKernelOfRankThree) {
  const Q1Mesh m = singleElement(kDistorted);
  const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, Field::Scalar, ElasticLaw());
  TEST_EQUALITY(K.rows, 4);
  TEST_COMPARE(asymmetry(K), <=, 1e-14);
  const std::vector<double> ones(4, 1.0);
  TEST_COMPARE(norm2(multiply(K, ones)) / (K.frobeniusNorm() * norm2(ones)), <, 1e-12);
  // Exactly one zero eigenvalue; the other three clearly positive.
  const std::vector<double> w = eigenvalues(K);
  TEST_COMPARE(std::abs(w[0]), <, 1e-12 * w[3]);
  TEST_COMPARE(w[1], >, 1e-2 * w[3]);
}

TEUCHOS_UNIT_TEST(Q1Laplacian, EnergyOfLinearFieldsIsExact) {
  // v^T K u = area * grad u . grad v for linear u, v (bilinear interpolation and 2x2 Gauss are
  // exact for them), on a distorted element.
  const Q1Mesh m = singleElement(kDistorted);
  const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, Field::Scalar, ElasticLaw());
  const double area = quadArea(kDistorted);
  const std::vector<double> u = linearScalar(m, 0.3, 1.7, -0.4);
  const std::vector<double> v = linearScalar(m, -2.0, 0.25, 0.9);
  TEST_FLOATING_EQUALITY(dot(v, multiply(K, u)), area * (1.7 * 0.25 + -0.4 * 0.9), 1e-13);
  TEST_FLOATING_EQUALITY(dot(u, multiply(K, u)), area * (1.7 * 1.7 + 0.4 * 0.4), 1e-13);
}

// ------------------------------------------------------ element stiffness: plane-strain elasticity

TEUCHOS_UNIT_TEST(Q1Elasticity, DistortedElementSymmetricWithRigidBodyKernelOfRankFive) {
  const Q1Mesh m = singleElement(kDistorted);
  const tfeti::CsrMatrix K =
      plasticity::assembleStiffness(m, Field::Elasticity, ElasticLaw(210.0, 0.3));
  TEST_EQUALITY(K.rows, 8);
  TEST_EQUALITY(static_cast<int>(K.nnz()), 64);
  TEST_COMPARE(asymmetry(K), <=, 1e-14);
  for (const auto& r : rigidModes(m.coords))
    TEST_COMPARE(norm2(multiply(K, r)) / (K.frobeniusNorm() * norm2(r)), <, 1e-12);
  // Full 2x2 integration: exactly the 3 rigid body modes are zero-energy, no hourglass modes.
  const std::vector<double> w = eigenvalues(K);
  for (int i = 0; i < 3; ++i) TEST_COMPARE(std::abs(w[i]), <, 1e-12 * w[7]);
  TEST_COMPARE(w[3], >, 1e-3 * w[7]);
}

TEUCHOS_UNIT_TEST(Q1Elasticity, EnergyOfLinearDisplacementsIsExact) {
  const Q1Mesh m = singleElement(kDistorted);
  const ElasticLaw law(3.0, 0.25);
  const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, Field::Elasticity, law);
  const double area = quadArea(kDistorted);
  const double tu[2] = {0.1, -0.3}, Au[4] = {0.7, -0.2, 0.5, 1.1};
  const double tv[2] = {2.0, 0.4}, Av[4] = {-0.3, 0.8, 0.6, 0.2};
  const std::vector<double> u = linearDisplacement(m, tu, Au), v = linearDisplacement(m, tv, Av);
  TEST_FLOATING_EQUALITY(dot(v, multiply(K, u)), area * strainEnergy(law, Av, Au), 1e-13);
  TEST_FLOATING_EQUALITY(dot(u, multiply(K, u)), area * strainEnergy(law, Au, Au), 1e-13);
  // Uniaxial stretch of the unit square in plane strain: energy (lambda + 2 mu) * e^2.
  const Q1Mesh sq = singleElement({0, 0, 1, 0, 1, 1, 0, 1});
  const tfeti::CsrMatrix Ks = plasticity::assembleStiffness(sq, Field::Elasticity, law);
  const double t0[2] = {0, 0}, stretch[4] = {1e-2, 0, 0, 0};
  const std::vector<double> s = linearDisplacement(sq, t0, stretch);
  TEST_FLOATING_EQUALITY(dot(s, multiply(Ks, s)), (law.lambda() + 2 * law.mu()) * 1e-4, 1e-13);
}

// ------------------------------------------------------------------------------- patch tests

TEUCHOS_UNIT_TEST(Q1Laplacian, PatchTestOnDistortedMesh) {
  const Q1Mesh m = distortedPatch();
  const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, Field::Scalar, ElasticLaw());
  TEST_EQUALITY(K.rows, 16);
  TEST_COMPARE(asymmetry(K), <=, 1e-14);
  const std::vector<double> u = linearScalar(m, 0.5, 2.0, -3.0);
  const std::vector<double> f = multiply(K, u);
  const double scale = K.maxAbs() * maxAbs(u);
  double interior = 0.0, boundary = 0.0;
  for (int n = 0; n < 16; ++n) {
    double& slot = isInteriorPatchNode(n) ? interior : boundary;
    slot = std::max(slot, std::abs(f[n]));
  }
  TEST_COMPARE(interior / scale, <, 1e-12);
  TEST_COMPARE(boundary / scale, >, 1e-2);  // the boundary carries the flux
  // Energy over the whole patch: area 1.
  const std::vector<double> v = linearScalar(m, 1.0, -1.0, 0.5);
  TEST_FLOATING_EQUALITY(dot(v, f), 2.0 * -1.0 + -3.0 * 0.5, 1e-13);
  // A quadratic field is not reproduced: interior forces are those of its Laplacian (-2 * dA).
  const std::vector<double> q = [&] {
    std::vector<double> x(16);
    for (int n = 0; n < 16; ++n) x[n] = m.coords[2 * n] * m.coords[2 * n];
    return x;
  }();
  const std::vector<double> fq = multiply(K, q);
  for (int n = 0; n < 16; ++n)
    if (isInteriorPatchNode(n)) TEST_COMPARE(fq[n], <, -0.05);
}

TEUCHOS_UNIT_TEST(Q1Elasticity, PatchTestOnDistortedMesh) {
  const Q1Mesh m = distortedPatch();
  const ElasticLaw law(1.0, 0.3);
  const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, Field::Elasticity, law);
  TEST_EQUALITY(K.rows, 32);
  TEST_COMPARE(asymmetry(K), <=, 1e-14);
  for (const auto& r : rigidModes(m.coords))
    TEST_COMPARE(norm2(multiply(K, r)) / (K.frobeniusNorm() * norm2(r)), <, 1e-12);
  const double t[2] = {0.2, -0.1}, A[4] = {0.3, -0.7, 0.4, -0.2};
  const std::vector<double> u = linearDisplacement(m, t, A);
  const std::vector<double> f = multiply(K, u);
  const double scale = K.maxAbs() * maxAbs(u);
  double interior = 0.0, boundary = 0.0;
  for (int n = 0; n < 16; ++n)
    for (int c = 0; c < 2; ++c) {
      double& slot = isInteriorPatchNode(n) ? interior : boundary;
      slot = std::max(slot, std::abs(f[2 * n + c]));
    }
  TEST_COMPARE(interior / scale, <, 1e-12);
  TEST_COMPARE(boundary / scale, >, 1e-2);
  const double tv[2] = {0, 0}, Av[4] = {1.0, 0.5, -0.5, 2.0};
  const std::vector<double> v = linearDisplacement(m, tv, Av);
  TEST_FLOATING_EQUALITY(dot(v, f), strainEnergy(law, Av, A), 1e-13);
}

// -------------------------------------------------------------------------------- body load

TEUCHOS_UNIT_TEST(Q1BodyLoad, ScalarTotalEqualsAreaTimesSource) {
  const Q1Mesh m = distortedPatch();
  const double s = 3.5;
  const std::vector<double> f = plasticity::assembleBodyLoad(m, Field::Scalar, &s);
  TEST_EQUALITY(static_cast<int>(f.size()), 16);
  double total = 0.0, momentX = 0.0, momentY = 0.0;
  for (int n = 0; n < 16; ++n) {
    total += f[n];
    momentX += f[n] * m.coords[2 * n];
    momentY += f[n] * m.coords[2 * n + 1];
    TEST_COMPARE(f[n], >, 0.0);
  }
  TEST_FLOATING_EQUALITY(total, s * 1.0, 1e-14);
  // First moments: s * integral of x (resp. y) over the unit square = s / 2.
  TEST_FLOATING_EQUALITY(momentX, s * 0.5, 1e-14);
  TEST_FLOATING_EQUALITY(momentY, s * 0.5, 1e-14);
  // One distorted element on its own.
  const Q1Mesh e = singleElement(kDistorted);
  const std::vector<double> fe = plasticity::assembleBodyLoad(e, Field::Scalar, &s);
  TEST_FLOATING_EQUALITY(fe[0] + fe[1] + fe[2] + fe[3], s * quadArea(kDistorted), 1e-14);
}

TEUCHOS_UNIT_TEST(Q1BodyLoad, ElasticityTotalEqualsAreaTimesBodyForce) {
  const Q1Mesh m = distortedPatch();
  const double b[2] = {0.7, -1.3};
  const std::vector<double> f = plasticity::assembleBodyLoad(m, Field::Elasticity, b);
  TEST_EQUALITY(static_cast<int>(f.size()), 32);
  double fx = 0.0, fy = 0.0;
  for (int n = 0; n < 16; ++n) {
    fx += f[2 * n];
    fy += f[2 * n + 1];
    // Each component is the scalar load scaled by the body force component.
    TEST_FLOATING_EQUALITY(f[2 * n + 1] / f[2 * n], b[1] / b[0], 1e-13);
  }
  TEST_FLOATING_EQUALITY(fx, b[0] * 1.0, 1e-14);
  TEST_FLOATING_EQUALITY(fy, b[1] * 1.0, 1e-14);
}

// ------------------------------------------------------------------------------- bad elements

TEUCHOS_UNIT_TEST(Q1Assembly, InvertedElementThrowsNamingIt) {
  // Three unit squares in a row; element 2 has clockwise node order.
  Q1Mesh m;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) m.coords.insert(m.coords.end(), {double(i), double(j)});
  m.cells = {0, 1, 5, 4, 1, 2, 6, 5, 2, 6, 7, 3};
  for (Field field : {Field::Scalar, Field::Elasticity}) {
    const std::string msg = thrownMessage(m, field);
    TEST_INEQUALITY(msg, std::string(""));
    TEST_INEQUALITY(msg.find("element 2"), std::string::npos);
    TEST_INEQUALITY(msg.find("inverted"), std::string::npos);
  }
  // The same mesh with the orientation repaired assembles.
  m.cells = {0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6};
  TEST_NOTHROW(plasticity::assembleStiffness(m, Field::Elasticity, ElasticLaw()));
}

TEUCHOS_UNIT_TEST(Q1Assembly, DegenerateElementThrowsNamingIt) {
  // Element 1 has all four nodes on the line y = 0 (zero area).
  Q1Mesh m;
  m.coords = {0, 0, 1, 0, 1, 1, 0, 1, 2, 0, 3, 0, 1.5, 0};
  m.cells = {0, 1, 2, 3, 1, 4, 5, 6};
  for (Field field : {Field::Scalar, Field::Elasticity}) {
    const std::string msg = thrownMessage(m, field);
    TEST_INEQUALITY(msg, std::string(""));
    TEST_INEQUALITY(msg.find("element 1"), std::string::npos);
    TEST_EQUALITY(msg.find("element 0"), std::string::npos);
  }
  // Two coincident nodes collapse the element to zero area too.
  m.coords = {0, 0, 1, 0, 1, 1, 0, 1, 2, 0};
  m.cells = {0, 1, 2, 3, 1, 4, 4, 1};
  TEST_INEQUALITY(thrownMessage(m, Field::Scalar).find("element 1"), std::string::npos);
}

TEUCHOS_UNIT_TEST(Q1Assembly, NonConvexElementThrowsNamingIt) {
  // A dart: node 2 pushed inside the triangle of the other three. det J is linear in (xi, eta)
  // with corner values 1, 0.45, -0.1, 0.45: the map folds over near node 2 (positive at all
  // four Gauss points, negative at the corner), so the element is invalid.
  const Q1Mesh m = singleElement({0, 0, 2, 0, 0.9, 0.9, 0, 2});
  for (Field field : {Field::Scalar, Field::Elasticity}) {
    const std::string msg = thrownMessage(m, field);
    TEST_INEQUALITY(msg.find("element 0"), std::string::npos);
  }
}
