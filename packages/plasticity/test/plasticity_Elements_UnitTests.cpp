// Unit tests of the general plane-strain elements (plasticity_Elements) on distorted meshes of
// the unit square, for every element type: the linear patch test (stresses at Gauss points and
// nodes, K u against the boundary tractions), rigid body modes, symmetry and the rank of one
// element's stiffness, the quadratic patch test of the quadratic elements, the totals of the
// body force and edge tractions, agreement of Quad4 with the Q1 kernels, and the errors for
// inverted elements, bad connectivity and bad edges.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "plasticity_ElementTestMeshes.hpp"
#include "plasticity_Elements.hpp"
#include "plasticity_Q1Assembly.hpp"
#include "plasticity_TestUtils.hpp"
#include "tfeti_CsrMatrix.hpp"
#include "tfeti_DenseUtils.hpp"

namespace {
// The shared measures: dot, norm2, maxAbs, asymmetry, multiply, eigenvalues.
using namespace plasticity_test;  // NOLINT(build/namespaces)

using plasticity::ElasticLaw;
using plasticity::ElementMesh;
using plasticity::ElementType;
using plasticity::LinearElasticMaterial;
using plasticity_test::LatticeMesh;
using plasticity_test::latticeMesh;
using plasticity_test::randomVertices;

const ElementType kAllTypes[] = {ElementType::Tri3, ElementType::Quad4, ElementType::Tri6,
                                 ElementType::Quad9};

// Displacement u = t + A x + Q(x), Q quadratic: Q_c = q[c][0] x^2 + q[c][1] x y + q[c][2] y^2.
// Its strain is linear: eps(x, y) = e0 + ex x + ey y.
struct PolynomialField {
  double t[2] = {0, 0};
  double A[4] = {0, 0, 0, 0};  // row-major: u_c += A[2c] x + A[2c+1] y
  double q[2][3] = {{0, 0, 0}, {0, 0, 0}};

  void displacement(double x, double y, double u[2]) const {
    for (int c = 0; c < 2; ++c)
      u[c] = t[c] + A[2 * c] * x + A[2 * c + 1] * y + q[c][0] * x * x + q[c][1] * x * y +
             q[c][2] * y * y;
  }
  // (eps_xx, eps_yy, gamma_xy) at (x, y).
  void strain(double x, double y, double e[3]) const {
    const double uxx = A[0] + 2 * q[0][0] * x + q[0][1] * y,
                 uxy = A[1] + q[0][1] * x + 2 * q[0][2] * y;
    const double uyx = A[2] + 2 * q[1][0] * x + q[1][1] * y,
                 uyy = A[3] + q[1][1] * x + 2 * q[1][2] * y;
    e[0] = uxx, e[1] = uyy, e[2] = uxy + uyx;
  }
  std::vector<double> nodal(const ElementMesh& m) const {
    std::vector<double> u(2 * m.numNodes());
    for (int n = 0; n < m.numNodes(); ++n)
      displacement(m.coords[2 * n], m.coords[2 * n + 1], &u[2 * n]);
    return u;
  }
};

// Exact stress (StressField's components: Voigt, then von Mises) of the field at (x, y).
void exactStress(const LinearElasticMaterial& law, const PolynomialField& f, double x, double y,
                 double s[plasticity::kNumStressComponents]) {
  double e[3];
  f.strain(x, y, e);
  const double e6[plasticity::kNumVoigt] = {e[0], e[1], 0, 0, 0, e[2]};
  plasticity::MaterialResponse r;
  law.evaluate({}, e6, r);
  for (int c = 0; c < plasticity::kNumVoigt; ++c) s[c] = r.stress[c];
  s[plasticity::kVonMises] = plasticity::vonMises(r.stress);
}

struct StressErrors {
  double gauss = 0.0, nodal = 0.0;  // max error over all components, relative to max |sigma|
};

StressErrors stressErrors(const ElementMesh& m, const LinearElasticMaterial& law,
                          const PolynomialField& f) {
  const plasticity::StressField sf = plasticity::recoverStresses(m, law, f.nodal(m));
  double scale = 0.0, eg = 0.0, en = 0.0;
  const int ngp = sf.gaussPointsPerElement;
  for (int e = 0; e < m.numElements(); ++e)
    for (int q = 0; q < ngp; ++q) {
      const double* xg = &sf.gaussCoords[(e * ngp + q) * 2];
      double s[plasticity::kNumStressComponents];
      exactStress(law, f, xg[0], xg[1], s);
      for (int c = 0; c < plasticity::kNumStressComponents; ++c) {
        scale = std::max(scale, std::abs(s[c]));
        eg = std::max(eg, std::abs(sf.atGaussPoint(e, q, c) - s[c]));
      }
    }
  for (int n = 0; n < m.numNodes(); ++n) {
    double s[plasticity::kNumStressComponents];
    exactStress(law, f, m.coords[2 * n], m.coords[2 * n + 1], s);
    for (int c = 0; c < plasticity::kNumStressComponents; ++c)
      en = std::max(en, std::abs(sf.atNode(n, c) - s[c]));
  }
  return {eg / scale, en / scale};
}

// The distorted 3x3-cell patch: random vertices, and curved interior edges for quadratic
// elements.
LatticeMesh distortedPatch(ElementType type) {
  return latticeMesh(type, 3, randomVertices(0.25), 0.2);
}

std::string thrownMessage(const ElementMesh& m) {
  try {
    plasticity::assembleStiffness(m, ElasticLaw(1.0, 0.3));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// ------------------------------------------------------------------ (a) linear patch test

TEUCHOS_UNIT_TEST(Elements, LinearPatchTestOnDistortedMesh) {
  const LinearElasticMaterial law(210.0, 0.3);
  PolynomialField f;
  f.t[0] = 0.2, f.t[1] = -0.1;
  f.A[0] = 0.3, f.A[1] = -0.7, f.A[2] = 0.4, f.A[3] = -0.2;
  for (ElementType type : kAllTypes) {
    const LatticeMesh L = distortedPatch(type);
    const ElementMesh& m = L.mesh;
    const StressErrors err = stressErrors(m, law, f);
    out << plasticity::elementTypeName(type) << ": stress error at Gauss points " << err.gauss
        << ", at nodes " << err.nodal << "\n";
    TEST_COMPARE(err.gauss, <, 1e-12);
    TEST_COMPARE(err.nodal, <, 1e-12);

    // K u against the consistent tractions sigma n of the constant stress on the four sides.
    const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, law);
    const std::vector<double> fu = multiply(K, f.nodal(m));
    double s[plasticity::kNumStressComponents];
    exactStress(law, f, 0, 0, s);
    const double normals[4][2] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
    std::vector<double> ft(fu.size(), 0.0);
    const double sxx = s[plasticity::kSxx], syy = s[plasticity::kSyy], sxy = s[plasticity::kSxy];
    for (int k = 0; k < 4; ++k) {
      const double t[2] = {sxx * normals[k][0] + sxy * normals[k][1],
                           sxy * normals[k][0] + syy * normals[k][1]};
      const std::vector<double> fk = plasticity::assembleEdgeTraction(m, L.sideEdges(k), t);
      for (std::size_t i = 0; i < ft.size(); ++i) ft[i] += fk[i];
    }
    double diff = 0.0, interior = 0.0;
    for (std::size_t i = 0; i < fu.size(); ++i) {
      diff = std::max(diff, std::abs(fu[i] - ft[i]));
      if (!L.onBoundary(static_cast<int>(i / 2))) interior = std::max(interior, std::abs(fu[i]));
    }
    out << plasticity::elementTypeName(type) << ": |K u - f_traction| / |f| " << diff / maxAbs(fu)
        << ", interior |K u| / |f| " << interior / maxAbs(fu) << "\n";
    TEST_COMPARE(diff / maxAbs(fu), <, 1e-12);
    TEST_COMPARE(interior / maxAbs(fu), <, 1e-12);
  }
}

// ------------------------------------------- (b) rigid body modes, symmetry, element rank

TEUCHOS_UNIT_TEST(Elements, RigidBodyModesInKernelAndSymmetric) {
  for (ElementType type : kAllTypes) {
    const ElementMesh m = distortedPatch(type).mesh;
    const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, ElasticLaw(210.0, 0.3));
    TEST_EQUALITY(K.rows, 2 * m.numNodes());
    double worst = 0.0;
    for (const auto& r : rigidModes(m.coords))
      worst = std::max(worst, norm2(multiply(K, r)) / (K.frobeniusNorm() * norm2(r)));
    out << plasticity::elementTypeName(type) << ": |K r| / (|K| |r|) " << worst << ", asymmetry "
        << asymmetry(K) << "\n";
    TEST_COMPARE(worst, <, 1e-14);
    TEST_COMPARE(asymmetry(K), <=, 1e-15);
  }
}

TEUCHOS_UNIT_TEST(Elements, SingleDistortedElementHasExactlyThreeZeroEigenvalues) {
  for (ElementType type : kAllTypes) {
    // One cell of a distorted patch, renumbered into a mesh of its own.
    const ElementMesh patch = distortedPatch(type).mesh;
    const int npe = plasticity::nodesPerElement(type);
    ElementMesh m;
    m.type = type;
    const int e = type == ElementType::Quad4 || type == ElementType::Quad9 ? 4 : 9;
    for (int a = 0; a < npe; ++a) {
      const int n = patch.connectivity[e * npe + a];
      m.coords.insert(m.coords.end(), {patch.coords[2 * n], patch.coords[2 * n + 1]});
      m.connectivity.push_back(a);
    }
    const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, ElasticLaw(1.0, 0.3));
    TEST_EQUALITY(K.rows, 2 * npe);
    TEST_EQUALITY(static_cast<int>(K.nnz()), 4 * npe * npe);
    const std::vector<double> w = eigenvalues(K);
    const double top = w.back();
    out << plasticity::elementTypeName(type) << ": |lambda_0..2| / lambda_max "
        << std::abs(w[0]) / top << " " << std::abs(w[1]) / top << " " << std::abs(w[2]) / top
        << ", lambda_3 / lambda_max " << w[3] / top << "\n";
    for (int i = 0; i < 3; ++i) TEST_COMPARE(std::abs(w[i]), <, 1e-13 * top);
    TEST_COMPARE(w[3], >, 1e-3 * top);
  }
}

// ------------------------------------------------------------ (c) quadratic patch test

TEUCHOS_UNIT_TEST(Elements, QuadraticPatchTestOfQuadraticElements) {
  // Quad9 with straight edges (bilinear, non-parallelogram geometry) and straight-sided Tri6
  // contain every quadratic displacement, so their stresses (linear) are exact at the Gauss
  // points and, extrapolated, at the nodes; the interior forces K u equal the consistent load
  // of the body force b = -div sigma that equilibrates the field. The linear elements cannot
  // reproduce it (the check must be able to tell).
  const LinearElasticMaterial law(210.0, 0.3);
  PolynomialField f;
  f.t[0] = 0.1, f.A[0] = 0.3, f.A[1] = -0.7, f.A[2] = 0.4, f.A[3] = -0.2;
  f.q[0][0] = 0.5, f.q[0][1] = -0.8, f.q[0][2] = 0.3;
  f.q[1][0] = -0.6, f.q[1][1] = 0.9, f.q[1][2] = 0.45;
  // div sigma: constant, from the constant strain gradients.
  double D[9];
  law.parameters().planeStrainMatrix(D);
  double e0[3], ex[3], ey[3];
  f.strain(0, 0, e0), f.strain(1, 0, ex), f.strain(0, 1, ey);
  double dsx[3] = {0, 0, 0}, dsy[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      dsx[i] += D[3 * i + j] * (ex[j] - e0[j]), dsy[i] += D[3 * i + j] * (ey[j] - e0[j]);
  const double b[2] = {-(dsx[0] + dsy[2]), -(dsx[2] + dsy[1])};

  for (ElementType type : kAllTypes) {
    const LatticeMesh L = latticeMesh(type, 3, randomVertices(0.25));
    const ElementMesh& m = L.mesh;
    const StressErrors err = stressErrors(m, law, f);
    const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, law);
    const std::vector<double> fu = multiply(K, f.nodal(m));
    const std::vector<double> fb = plasticity::assembleBodyForce(m, b);
    double interior = 0.0;
    for (std::size_t i = 0; i < fu.size(); ++i)
      if (!L.onBoundary(static_cast<int>(i / 2)))
        interior = std::max(interior, std::abs(fu[i] - fb[i]));
    interior /= maxAbs(fb);
    out << plasticity::elementTypeName(type) << ": stress error at Gauss points " << err.gauss
        << ", at nodes " << err.nodal << ", interior |K u - f_body| / |f_body| " << interior
        << "\n";
    if (plasticity::isQuadratic(type)) {
      TEST_COMPARE(err.gauss, <, 1e-12);
      TEST_COMPARE(err.nodal, <, 1e-12);
      TEST_COMPARE(interior, <, 1e-12);
    } else {
      TEST_COMPARE(err.gauss, >, 1e-3);
      TEST_COMPARE(interior, >, 1e-3);
    }
  }
}

// -------------------------------------------------------------- (d) load totals

TEUCHOS_UNIT_TEST(Elements, BodyForceIntegratesToTotalForceAndMoment) {
  const double b[2] = {0.7, -1.3};
  for (ElementType type : kAllTypes) {
    // Totals: b times the area (1). First moments: b times the integral of x (resp. y), 1/2;
    // checked with straight edges only, since on a curved Tri6 x det J is of degree 4, beyond
    // the 3-point rule (the totals need only det J, of degree 2).
    for (double curve : {0.2, 0.0}) {
      const ElementMesh m = latticeMesh(type, 3, randomVertices(0.25), curve).mesh;
      const std::vector<double> f = plasticity::assembleBodyForce(m, b);
      TEST_EQUALITY(static_cast<int>(f.size()), 2 * m.numNodes());
      double F[2] = {0, 0}, Mx = 0, My = 0;
      for (int n = 0; n < m.numNodes(); ++n) {
        F[0] += f[2 * n], F[1] += f[2 * n + 1];
        Mx += f[2 * n] * m.coords[2 * n];
        My += f[2 * n + 1] * m.coords[2 * n + 1];
      }
      out << plasticity::elementTypeName(type) << " (curve " << curve << "): total error "
          << std::abs(F[0] - b[0]) << " " << std::abs(F[1] - b[1]) << ", moment error "
          << std::abs(Mx - 0.5 * b[0]) << " " << std::abs(My - 0.5 * b[1]) << "\n";
      TEST_FLOATING_EQUALITY(F[0], b[0], 1e-14);
      TEST_FLOATING_EQUALITY(F[1], b[1], 1e-14);
      if (curve == 0.0) {
        TEST_FLOATING_EQUALITY(Mx, 0.5 * b[0], 1e-14);
        TEST_FLOATING_EQUALITY(My, 0.5 * b[1], 1e-14);
      }
    }
  }
}

TEUCHOS_UNIT_TEST(Elements, EdgeTractionIntegratesToTotalForceAndMoment) {
  const double t[2] = {2.5, -0.4};
  for (ElementType type : kAllTypes) {
    const LatticeMesh L = distortedPatch(type);
    const ElementMesh& m = L.mesh;
    // Each side has length 1: total t; the moment of the x-force about the y axis along the
    // bottom side is t_x times the integral of x ds (1/2), even with off-centre mid-nodes.
    for (int k = 0; k < 4; ++k) {
      const std::vector<double> f = plasticity::assembleEdgeTraction(m, L.sideEdges(k), t);
      double F[2] = {0, 0}, M = 0;
      for (int n = 0; n < m.numNodes(); ++n) {
        F[0] += f[2 * n], F[1] += f[2 * n + 1];
        M += f[2 * n] * (k % 2 == 0 ? m.coords[2 * n] : m.coords[2 * n + 1]);
      }
      TEST_FLOATING_EQUALITY(F[0], t[0], 1e-14);
      TEST_FLOATING_EQUALITY(F[1], t[1], 1e-14);
      TEST_FLOATING_EQUALITY(M, 0.5 * t[0], 1e-14);
    }
    // A slanted edge: the force is t times its length.
    // An interior element whose edge 1-2 is interior and slanted.
    const int npe = plasticity::nodesPerElement(type), nc = plasticity::cornersPerElement(type);
    const int* en = &m.connectivity[(nc == 4 ? 4 : 9) * npe];
    std::vector<int> edge = {en[1], en[2]};
    if (plasticity::isQuadratic(type)) edge.push_back(en[nc + 1]);
    const double dx = m.coords[2 * en[2]] - m.coords[2 * en[1]];
    const double dy = m.coords[2 * en[2] + 1] - m.coords[2 * en[1] + 1];
    // Quadratic patches have curved interior edges; straighten this one for a closed form.
    ElementMesh straight = m;
    if (plasticity::isQuadratic(type))
      for (int c = 0; c < 2; ++c)
        straight.coords[2 * edge[2] + c] =
            0.5 * (m.coords[2 * en[1] + c] + m.coords[2 * en[2] + c]);
    const std::vector<double> f = plasticity::assembleEdgeTraction(straight, edge, t);
    double Fy = 0.0;
    for (int n = 0; n < m.numNodes(); ++n) Fy += f[2 * n + 1];
    TEST_FLOATING_EQUALITY(Fy, t[1] * std::hypot(dx, dy), 1e-14);
  }
}

TEUCHOS_UNIT_TEST(Elements, EdgeNotOfTheMeshThrowsNamingIt) {
  const LatticeMesh L = distortedPatch(ElementType::Tri6);
  std::vector<int> edges = L.sideEdges(0);
  const double t[2] = {1, 0};
  // The second edge's middle node swapped with an end: no element has that edge.
  std::swap(edges[3 + 1], edges[3 + 2]);
  try {
    plasticity::assembleEdgeTraction(L.mesh, edges, t);
    TEST_ASSERT(false);
  } catch (const std::invalid_argument& e) {
    out << e.what() << "\n";
    TEST_INEQUALITY(std::string(e.what()).find("edge 1 "), std::string::npos);
  }
  // Two nodes per edge for a quadratic mesh is the wrong count.
  TEST_THROW(plasticity::assembleEdgeTraction(L.mesh, {0, 2, 4, 6}, t), std::invalid_argument);
}

// ----------------------------------------------------------- Quad4 against the Q1 kernels

TEUCHOS_UNIT_TEST(Elements, Quad4AgreesWithQ1Assembly) {
  const ElementMesh m = latticeMesh(ElementType::Quad4, 4, randomVertices(0.3)).mesh;
  plasticity::Q1Mesh q;
  q.coords = m.coords;
  q.cells = m.connectivity;
  const ElasticLaw law(210.0, 0.3);
  const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, law);
  const tfeti::CsrMatrix Kq = plasticity::assembleStiffness(q, plasticity::Field::Elasticity, law);
  TEST_EQUALITY(K.rows, Kq.rows);
  TEST_ASSERT(K.rowPtr == Kq.rowPtr);
  TEST_ASSERT(K.colInd == Kq.colInd);
  double diff = 0.0;
  for (std::size_t k = 0; k < std::min(K.nnz(), Kq.nnz()); ++k)
    diff = std::max(diff, std::abs(K.values[k] - Kq.values[k]));
  out << "max |K - K_Q1| / max |K| " << diff / K.maxAbs() << "\n";
  TEST_COMPARE(diff / K.maxAbs(), <, 1e-14);
  const double b[2] = {0.7, -1.3};
  const std::vector<double> f = plasticity::assembleBodyForce(m, b);
  const std::vector<double> fq = plasticity::assembleBodyLoad(q, plasticity::Field::Elasticity, b);
  double fd = 0.0;
  for (std::size_t i = 0; i < f.size(); ++i) fd = std::max(fd, std::abs(f[i] - fq[i]));
  TEST_COMPARE(fd / maxAbs(f), <, 1e-14);
}

// ---------------------------------------------------------------- (f) bad elements

TEUCHOS_UNIT_TEST(Elements, InvertedElementThrowsNamingIt) {
  for (ElementType type : kAllTypes) {
    ElementMesh m = distortedPatch(type).mesh;
    TEST_NOTHROW(plasticity::assembleStiffness(m, ElasticLaw()));
    // Mirror element 2's node order (corners reversed, mid-nodes to match): clockwise.
    const int npe = plasticity::nodesPerElement(type), nc = plasticity::cornersPerElement(type);
    int* en = &m.connectivity[2 * npe];
    std::vector<int> old(en, en + npe);
    for (int k = 0; k < nc; ++k) en[k] = old[(nc - k) % nc];
    if (plasticity::isQuadratic(type))
      for (int k = 0; k < nc; ++k) en[nc + k] = old[nc + (2 * nc - 1 - k) % nc];
    const std::string msg = thrownMessage(m);
    out << msg << "\n";
    TEST_INEQUALITY(msg.find("element 2 "), std::string::npos);
    TEST_INEQUALITY(msg.find("inverted"), std::string::npos);
    // Every entry point checks.
    const double b[2] = {1, 0};
    TEST_THROW(plasticity::assembleBodyForce(m, b), std::invalid_argument);
    TEST_THROW(plasticity::recoverStresses(m, LinearElasticMaterial(1, 0.3),
                                           std::vector<double>(2 * m.numNodes(), 0.0)),
               std::invalid_argument);
  }
}

// The kernels skip the checks for a mesh they already found valid (ElementMesh::checkedDigest),
// and repeat them once its coordinates or connectivity change in place.
TEUCHOS_UNIT_TEST(Elements, ChecksRepeatOnceTheMeshChanges) {
  for (ElementType type : kAllTypes) {
    ElementMesh m = distortedPatch(type).mesh;
    const std::array<std::uint64_t, 2> never{};
    TEST_ASSERT(m.checkedDigest == never);
    const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, ElasticLaw());
    const std::array<std::uint64_t, 2> digest = m.checkedDigest;
    TEST_ASSERT(digest != never);
    // Checked again or not, the same matrix.
    const tfeti::CsrMatrix K2 = plasticity::assembleStiffness(m, ElasticLaw());
    TEST_ASSERT(m.checkedDigest == digest);
    TEST_COMPARE_ARRAYS(K.values, K2.values);
    // Node 0 of element 0 moved through the element to its opposite side: inverted.
    const int dim = m.dim(), n0 = m.connectivity[0];
    const int far = m.connectivity[plasticity::cornersPerElement(type) / 2];
    const std::vector<double> saved = m.coords;
    for (int i = 0; i < dim; ++i)
      m.coords[dim * n0 + i] =
          saved[dim * far + i] + 2.0 * (saved[dim * far + i] - saved[dim * n0 + i]);
    TEST_THROW(plasticity::assembleStiffness(m, ElasticLaw()), std::invalid_argument);
    TEST_ASSERT(m.checkedDigest == digest);  // a failed check records nothing
    m.coords = saved;
    TEST_NOTHROW(plasticity::assembleStiffness(m, ElasticLaw()));
    TEST_ASSERT(m.checkedDigest == digest);
  }
}

TEUCHOS_UNIT_TEST(Elements, MisplacedMidNodeThrowsThroughTheNodalJacobian) {
  // A Quad9 on the unit square whose edge 0-1 mid-node sits at x = 0.2, inside the quarter
  // point: det J turns negative at corner 0 but stays positive at every 3x3 Gauss point.
  ElementMesh m;
  m.type = ElementType::Quad9;
  m.coords = {0, 0, 1, 0, 1, 1, 0, 1, 0.2, 0, 1, 0.5, 0.5, 1, 0, 0.5, 0.5, 0.5};
  m.connectivity = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  const std::string msg = thrownMessage(m);
  out << msg << "\n";
  TEST_INEQUALITY(msg.find("element 0 "), std::string::npos);
  m.coords[8] = 0.3;  // beyond the quarter point: valid
  TEST_EQUALITY(thrownMessage(m), std::string(""));
}

TEUCHOS_UNIT_TEST(Elements, ConnectivityOutOfRangeThrowsNamingIt) {
  for (ElementType type : kAllTypes) {
    ElementMesh m = distortedPatch(type).mesh;
    const int npe = plasticity::nodesPerElement(type);
    m.connectivity[5 * npe + 1] = m.numNodes();
    std::string msg = thrownMessage(m);
    out << msg << "\n";
    TEST_INEQUALITY(msg.find("element 5 references node " + std::to_string(m.numNodes())),
                    std::string::npos);
    m.connectivity[5 * npe + 1] = -1;
    msg = thrownMessage(m);
    TEST_INEQUALITY(msg.find("element 5 references node -1"), std::string::npos);
    const double b[2] = {1, 0};
    TEST_THROW(plasticity::assembleBodyForce(m, b), std::invalid_argument);
    TEST_THROW(plasticity::assembleEdgeTraction(m, {}, b), std::invalid_argument);
    // A truncated element.
    m.connectivity.pop_back();
    TEST_THROW(plasticity::assembleStiffness(m, ElasticLaw()), std::invalid_argument);
  }
}

// The catalogue's tables agree with its counts: codes map back to their type, facet node lists
// have their facet type's node count and distinct nodes, the VTK order and the reversal are
// permutations (the reversal an involution that keeps corner 0).
TEUCHOS_UNIT_TEST(ElementCatalogue, TablesAreConsistent) {
  for (plasticity::ElementType t : plasticity::allElementTypes()) {
    const plasticity::ElementInfo info = plasticity::elementInfo(t);
    out << plasticity::elementTypeName(t) << " (" << plasticity::elementLongName(t) << ")\n";
    plasticity::ElementType back = plasticity::ElementType::Line2;
    TEST_ASSERT(plasticity::elementTypeOfGmsh(info.gmshType, back) && back == t);
    TEST_ASSERT(plasticity::elementTypeOfVtk(info.vtkType, back) && back == t);
    auto isPermutation = [&](std::vector<int> p) {
      std::sort(p.begin(), p.end());
      for (int k = 0; k < static_cast<int>(p.size()); ++k)
        if (p[k] != k) return false;
      return static_cast<int>(p.size()) == info.nodes;
    };
    TEST_ASSERT(isPermutation(plasticity::vtkNodeOrder(t)));
    if (info.dim == 2) {
      const std::vector<int>& r = plasticity::reversedNodes(t);
      TEST_ASSERT(isPermutation(r));
      TEST_EQUALITY(r[0], 0);
      for (int k = 0; k < info.nodes; ++k) TEST_EQUALITY(r[r[k]], k);
    }
    if (info.dim < 2) continue;
    for (int f = 0; f < plasticity::facesPerElement(t); ++f) {
      const std::vector<int>& nodes = plasticity::facetNodes(t, f);
      TEST_EQUALITY(static_cast<int>(nodes.size()), plasticity::nodesPerElement(info.face));
      TEST_EQUALITY(std::set<int>(nodes.begin(), nodes.end()).size(), nodes.size());
    }
    TEST_THROW(plasticity::facetNodes(t, plasticity::facesPerElement(t)), std::out_of_range);
  }
  TEST_THROW(plasticity::facetNodes(plasticity::ElementType::Line3, 0), std::invalid_argument);
}
