// Unit tests of the 3D elements (Tet4, Tet10, Hex8, Hex27) through the same kernels as the 2D
// ones: Gmsh node positions, the shape functions' interpolation properties, the linear patch test
// on distorted meshes (stresses exact, K u equal to the consistent face loads), exactly six zero
// eigenvalues per element stiffness (the rigid modes, no spurious ones), body and surface load
// totals, face validation, and total Lagrangian rigid rotations and tangents.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "plasticity_ElementTestMeshes3D.hpp"
#include "plasticity_Elements.hpp"
#include "plasticity_J2Plasticity.hpp"
#include "plasticity_TestUtils.hpp"
#include "plasticity_TotalLagrangian.hpp"

namespace {

using plasticity::ElementMesh;
using plasticity::ElementType;
using plasticity::LinearElasticMaterial;
using plasticity::StressField;
using plasticity_test::CubeMesh;
using plasticity_test::maxAbs;
using plasticity_test::multiply;

const ElementType kSolids3D[] = {ElementType::Tet4, ElementType::Tet10, ElementType::Hex8,
                                 ElementType::Hex27};
constexpr double kE = 200.0, kNu = 0.3;

// Cells per side giving a few hundred nodes for each type.
int cells(ElementType t) {
  return plasticity::isQuadratic(t) ? 2 : 3;
}

// u = A x + c at every node.
std::vector<double> affineField(const ElementMesh& m, const double A[3][3], const double c[3]) {
  std::vector<double> u(m.coords.size());
  for (int n = 0; n < m.numNodes(); ++n)
    for (int i = 0; i < 3; ++i) {
      u[3 * n + i] = c[i];
      for (int j = 0; j < 3; ++j) u[3 * n + i] += A[i][j] * m.coords[3 * n + j];
    }
  return u;
}

// Rigid modes: three translations and the rotations about x, y, z.
std::vector<std::vector<double>> rigidModes3D(const std::vector<double>& x) {
  const std::size_t nn = x.size() / 3;
  std::vector<std::vector<double>> R(6, std::vector<double>(x.size(), 0.0));
  for (std::size_t n = 0; n < nn; ++n) {
    for (int i = 0; i < 3; ++i) R[i][3 * n + i] = 1.0;
    for (int a = 0; a < 3; ++a) {  // rotation about axis a: e_a x x
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      R[3 + a][3 * n + b] = -x[3 * n + c];
      R[3 + a][3 * n + c] = x[3 * n + b];
    }
  }
  return R;
}

}  // namespace

// Gmsh's reference node positions (gmsh::model::mesh::getElementProperties, Gmsh 4.11) for the
// two quadratic solids; the linear ones are their first 4 and 8 rows.
TEUCHOS_UNIT_TEST(Elements3D, ReferenceNodesAreGmshs) {
  const double tet10[10][3] = {{0, 0, 0},   {1, 0, 0},  {0, 1, 0},  {0, 0, 1},   {.5, 0, 0},
                               {.5, .5, 0}, {0, .5, 0}, {0, 0, .5}, {0, .5, .5}, {.5, 0, .5}};
  const double hex27[27][3] = {
      {-1, -1, -1}, {1, -1, -1}, {1, 1, -1},  {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1},
      {-1, 1, 1},   {0, -1, -1}, {-1, 0, -1}, {-1, -1, 0}, {1, 0, -1},  {1, -1, 0}, {0, 1, -1},
      {1, 1, 0},    {-1, 1, 0},  {0, -1, 1},  {-1, 0, 1},  {1, 0, 1},   {0, 1, 1},  {0, 0, -1},
      {0, -1, 0},   {-1, 0, 0},  {1, 0, 0},   {0, 1, 0},   {0, 0, 1},   {0, 0, 0}};
  struct Case {
    ElementType t;
    const double (*ref)[3];
  };
  for (const Case& c : {Case{ElementType::Tet4, tet10}, Case{ElementType::Tet10, tet10},
                        Case{ElementType::Hex8, hex27}, Case{ElementType::Hex27, hex27}}) {
    for (int a = 0; a < plasticity::nodesPerElement(c.t); ++a) {
      double xi[3];
      plasticity::referenceNode(c.t, a, xi);
      for (int j = 0; j < 3; ++j) TEST_EQUALITY(xi[j], c.ref[a][j]);
    }
  }
}

// N_a(x_b) = delta_ab, partition of unity, and derivatives against central differences.
TEUCHOS_UNIT_TEST(Elements3D, ShapeFunctionsInterpolateAndDifferentiate) {
  for (ElementType t : kSolids3D) {
    const int npe = plasticity::nodesPerElement(t);
    double N[plasticity::kMaxElementNodes], dN[plasticity::kMaxElementNodes][plasticity::kMaxDim];
    double worst = 0.0;
    for (int b = 0; b < npe; ++b) {
      double xi[3];
      plasticity::referenceNode(t, b, xi);
      plasticity::shapeFunctions(t, xi, N, dN);
      for (int a = 0; a < npe; ++a) worst = std::max(worst, std::abs(N[a] - (a == b ? 1 : 0)));
    }
    const double p[3] = {0.21, 0.17, 0.33}, h = 1e-6;
    plasticity::shapeFunctions(t, p, N, dN);
    double sum = 0.0, fd = 0.0;
    for (int a = 0; a < npe; ++a) sum += N[a];
    for (int j = 0; j < 3; ++j) {
      double pp[3] = {p[0], p[1], p[2]}, pm[3] = {p[0], p[1], p[2]};
      pp[j] += h, pm[j] -= h;
      double Np[plasticity::kMaxElementNodes], Nm[plasticity::kMaxElementNodes],
          d[plasticity::kMaxElementNodes][plasticity::kMaxDim];
      plasticity::shapeFunctions(t, pp, Np, d);
      plasticity::shapeFunctions(t, pm, Nm, d);
      for (int a = 0; a < npe; ++a)
        fd = std::max(fd, std::abs((Np[a] - Nm[a]) / (2 * h) - dN[a][j]));
    }
    out << plasticity::elementTypeName(t) << ": |N_a(x_b) - delta| " << worst << ", |sum N - 1| "
        << std::abs(sum - 1) << ", FD derivative error " << fd << "\n";
    TEST_COMPARE(worst, <, 1e-15);
    TEST_COMPARE(std::abs(sum - 1), <, 1e-14);
    TEST_COMPARE(fd, <, 1e-8);
  }
}

// Linear patch test: for u = A x + c the recovered stresses are the constant exact ones at every
// Gauss point and node, and K u equals the consistent loads of the traction sigma n on the six
// cube faces (zero at interior nodes).
TEUCHOS_UNIT_TEST(Elements3D, LinearPatchTestOnDistortedMeshes) {
  const LinearElasticMaterial law(kE, kNu);
  const double A[3][3] = {{1e-3, 2e-4, -3e-4}, {-1e-4, -5e-4, 4e-4}, {2.5e-4, 1e-4, 7e-4}};
  const double c[3] = {0.1, -0.2, 0.3};
  double strain[plasticity::kNumVoigt] = {A[0][0],           A[1][1],           A[2][2],
                                          A[1][2] + A[2][1], A[0][2] + A[2][0], A[0][1] + A[1][0]};
  plasticity::MaterialResponse exact;
  law.evaluate({}, strain, exact);
  const double* s = exact.stress;
  const double sigma[3][3] = {{s[0], s[5], s[4]}, {s[5], s[1], s[3]}, {s[4], s[3], s[2]}};
  const double scale = maxAbs(std::vector<double>(s, s + 6));
  for (ElementType t : kSolids3D) {
    const CubeMesh C =
        plasticity_test::cubeMesh(t, cells(t), plasticity_test::randomVertices3(0.25));
    const ElementMesh& m = C.mesh;
    const std::vector<double> u = affineField(m, A, c);
    const StressField sf = plasticity::recoverStresses(m, law, u);
    double eg = 0.0, en = 0.0;
    for (int e = 0; e < m.numElements(); ++e)
      for (int q = 0; q < sf.gaussPointsPerElement; ++q)
        for (int k = 0; k < plasticity::kNumVoigt; ++k)
          eg = std::max(eg, std::abs(sf.atGaussPoint(e, q, k) - s[k]));
    for (int n = 0; n < m.numNodes(); ++n)
      for (int k = 0; k < plasticity::kNumVoigt; ++k)
        en = std::max(en, std::abs(sf.atNode(n, k) - s[k]));
    const double vmErr = std::abs(sf.atNode(0, plasticity::kVonMises) - plasticity::vonMises(s));

    const std::vector<double> fu = multiply(plasticity::assembleStiffness(m, law), u);
    std::vector<double> ft(fu.size(), 0.0);
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        double t3[3];
        for (int i = 0; i < 3; ++i) t3[i] = sigma[i][axis] * (side ? 1.0 : -1.0);
        const std::vector<double> fk =
            plasticity::assembleSurfaceTraction(m, C.sideFaces(axis, side), t3);
        for (std::size_t i = 0; i < ft.size(); ++i) ft[i] += fk[i];
      }
    double diff = 0.0, interior = 0.0;
    for (std::size_t i = 0; i < fu.size(); ++i) {
      diff = std::max(diff, std::abs(fu[i] - ft[i]));
      if (!C.onBoundary(static_cast<int>(i / 3))) interior = std::max(interior, std::abs(fu[i]));
    }
    out << plasticity::elementTypeName(t) << " (" << m.numElements() << " elements): stress error "
        << eg / scale << " (Gauss), " << en / scale << " (nodes); |K u - f_traction| "
        << diff / maxAbs(fu) << ", interior |K u| " << interior / maxAbs(fu) << "\n";
    // Round-off level (the sums run over up to 27 Gauss points and 81 dofs per element).
    TEST_COMPARE(eg / scale, <, 1e-11);
    TEST_COMPARE(en / scale, <, 1e-11);
    TEST_COMPARE(vmErr / scale, <, 1e-11);
    TEST_COMPARE(diff / maxAbs(fu), <, 1e-11);
    TEST_COMPARE(interior / maxAbs(fu), <, 1e-11);
  }
}

// One distorted element per type: its stiffness has exactly six zero eigenvalues, the rigid
// modes are its kernel, and it is symmetric.
TEUCHOS_UNIT_TEST(Elements3D, ElementStiffnessHasExactlySixRigidModes) {
  const LinearElasticMaterial law(kE, kNu);
  for (ElementType t : kSolids3D) {
    const CubeMesh C = plasticity_test::cubeMesh(t, 1, plasticity_test::randomVertices3(0.0));
    ElementMesh m = C.mesh;
    // Keep one element (the first Kuhn tetrahedron for Tet), with its own nodes, distorted.
    const int npe = plasticity::nodesPerElement(t);
    ElementMesh one{t, {}, {}};
    for (int a = 0; a < npe; ++a) {
      const int n = m.connectivity[a];
      for (int i = 0; i < 3; ++i)
        one.coords.push_back(m.coords[3 * n + i] * (1.0 + 0.2 * i) +
                             0.07 * plasticity_test::jitter(a, i, 5));
      one.connectivity.push_back(a);
    }
    // The jitter moves the mid nodes off their edges too: a curved element.
    const tfeti::CsrMatrix K = plasticity::assembleStiffness(one, law);
    const std::vector<double> w = plasticity_test::eigenvalues(K);
    const double top = w.back();
    int zeros = 0;
    for (double v : w) zeros += std::abs(v) < 1e-10 * top;
    double kr = 0.0;
    for (const auto& r : rigidModes3D(one.coords))
      kr = std::max(kr, maxAbs(multiply(K, r)) / maxAbs(r));
    out << plasticity::elementTypeName(t) << ": eigenvalues/max " << w[5] / top << " (6th), "
        << w[6] / top << " (7th); ||K R|| / ||K|| " << kr / K.maxAbs() << ", asymmetry "
        << plasticity_test::asymmetry(K) << "\n";
    TEST_EQUALITY(zeros, 6);
    TEST_COMPARE(w[6] / top, >, 1e-4);
    TEST_COMPARE(w.front(), >, -1e-12 * top);
    TEST_COMPARE(kr / K.maxAbs(), <, 1e-12);
    TEST_COMPARE(plasticity_test::asymmetry(K), <, 1e-14);
  }
}

// A uniform body force sums to b times the volume, and a uniform traction on a cube face to t
// times its area (both 1 on the unit cube, whose faces the distortion keeps).
TEUCHOS_UNIT_TEST(Elements3D, BodyAndSurfaceLoadTotals) {
  const double b[3] = {1.5, -2.0, 0.25}, t[3] = {-0.5, 3.0, 1.25};
  for (ElementType type : kSolids3D) {
    const CubeMesh C =
        plasticity_test::cubeMesh(type, cells(type), plasticity_test::randomVertices3(0.25));
    const std::vector<double> fb = plasticity::assembleBodyForce(C.mesh, b);
    double worst = 0.0;
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        const std::vector<double> fs =
            plasticity::assembleSurfaceTraction(C.mesh, C.sideFaces(axis, side), t);
        for (int i = 0; i < 3; ++i) {
          double total = 0.0;
          for (std::size_t k = i; k < fs.size(); k += 3) total += fs[k];
          worst = std::max(worst, std::abs(total - t[i]) / std::abs(t[i]));
        }
      }
    double bodyErr = 0.0;
    for (int i = 0; i < 3; ++i) {
      double total = 0.0;
      for (std::size_t k = i; k < fb.size(); k += 3) total += fb[k];
      bodyErr = std::max(bodyErr, std::abs(total - b[i]) / std::abs(b[i]));
    }
    out << plasticity::elementTypeName(type) << ": body total error " << bodyErr
        << ", face total error " << worst << "\n";
    TEST_COMPARE(bodyErr, <, 1e-13);
    TEST_COMPARE(worst, <, 1e-13);
  }
}

// Faces that are not element faces, or whose mid nodes are misplaced, are errors naming them.
TEUCHOS_UNIT_TEST(Elements3D, BadFacesAreErrorsNamingThem) {
  const double t[3] = {0, 0, 1};
  for (ElementType type : kSolids3D) {
    const CubeMesh C = plasticity_test::cubeMesh(type, 2, plasticity_test::randomVertices3(0.0));
    std::vector<int> faces = C.sideFaces(2, 1);
    const int npf = plasticity::nodesPerFace(type);
    TEST_NOTHROW(plasticity::assembleSurfaceTraction(C.mesh, faces, t));
    // The reversed orientation of a linear face (corners 0, n-1, ..., 1) is the same face.
    if (!plasticity::isQuadratic(type)) {
      std::vector<int> reversed = faces;
      for (std::size_t f = 0; f < faces.size(); f += npf)
        std::reverse(reversed.begin() + f + 1, reversed.begin() + f + npf);
      TEST_NOTHROW(plasticity::assembleSurfaceTraction(C.mesh, reversed, t));
    }
    // The second face with two nodes exchanged (a mid node with a corner for quadratic faces,
    // two corners' order broken for Quad4; a Tri3 has no invalid order of its own nodes).
    std::vector<int> bad = faces;
    if (type == ElementType::Tet4) {
      bad[npf + 2] = C.id(0, 0, 0);  // not on the face at all
    } else if (type == ElementType::Hex8) {
      std::swap(bad[npf + 1], bad[npf + 2]);  // corners out of cyclic order
    } else {
      std::swap(bad[npf + 0], bad[npf + npf - 1]);  // a corner and a mid node
    }
    try {
      plasticity::assembleSurfaceTraction(C.mesh, bad, t);
      out << "no error for " << plasticity::elementTypeName(type) << "\n";
      success = false;
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      out << what << "\n";
      TEST_ASSERT(what.find("face 1 ") != std::string::npos);
      TEST_ASSERT(what.find(plasticity::elementTypeName(type)) != std::string::npos);
    }
  }
}

// ---------------------------------------------------------------- total Lagrangian in 3D

// A rigid rotation (about a general axis) plus translation: no internal force, no Cauchy
// stress; and rotating a homogeneous deformation F to Q F rotates the Cauchy stress to
// Q sigma Q^T (objectivity), at positions moved by Q.
TEUCHOS_UNIT_TEST(TotalLagrangian3D, RigidRotationAndObjectivity) {
  const LinearElasticMaterial law(kE, kNu);
  // Rotation by 50 degrees about (1, 2, 2)/3 (Rodrigues).
  const double pi = 3.14159265358979323846, th = 50 * pi / 180, k[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3};
  double Q[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double K = i == j ? 0.0 : (((j - i + 3) % 3 == 1) ? -k[3 - i - j] : k[3 - i - j]);
      Q[i][j] = (i == j ? std::cos(th) : 0.0) + std::sin(th) * K + (1 - std::cos(th)) * k[i] * k[j];
    }
  const double F[3][3] = {{1.05, 0.02, -0.03}, {0.01, 0.97, 0.04}, {-0.02, 0.03, 1.02}};
  double QF[3][3] = {}, QmI[3][3], FmI[3][3], QFmI[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      for (int l = 0; l < 3; ++l) QF[i][j] += Q[i][l] * F[l][j];
    }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      QmI[i][j] = Q[i][j] - (i == j);
      FmI[i][j] = F[i][j] - (i == j);
      QFmI[i][j] = QF[i][j] - (i == j);
    }
  const double c[3] = {0.3, -0.1, 0.2}, zero[3] = {0, 0, 0};
  for (ElementType t : kSolids3D) {
    const ElementMesh m =
        plasticity_test::cubeMesh(t, 2, plasticity_test::randomVertices3(0.25)).mesh;
    const std::vector<double> uR = affineField(m, QmI, c);
    const double smallForce = maxAbs(multiply(plasticity::assembleStiffness(m, law), uR));
    const double fR = maxAbs(plasticity::internalForce(m, law, uR)) / smallForce;
    const StressField sR = plasticity::cauchyStress(m, law, uR);
    double sig = 0.0;
    for (std::size_t i = 0; i < sR.gauss.size(); ++i) sig = std::max(sig, std::abs(sR.gauss[i]));
    const StressField a = plasticity::cauchyStress(m, law, affineField(m, FmI, zero));
    const StressField b = plasticity::cauchyStress(m, law, affineField(m, QFmI, zero));
    double rotErr = 0.0, scale = 0.0, posErr = 0.0;
    for (int e = 0; e < m.numElements(); ++e)
      for (int q = 0; q < a.gaussPointsPerElement; ++q) {
        auto tensor = [&](const StressField& f, double S[3][3]) {
          const int v[3][3] = {{0, 5, 4}, {5, 1, 3}, {4, 3, 2}};
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) S[i][j] = f.atGaussPoint(e, q, v[i][j]);
        };
        double Sa[3][3], Sb[3][3];
        tensor(a, Sa), tensor(b, Sb);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            double r = 0.0;
            for (int p = 0; p < 3; ++p)
              for (int s = 0; s < 3; ++s) r += Q[i][p] * Sa[p][s] * Q[j][s];
            rotErr = std::max(rotErr, std::abs(Sb[i][j] - r));
            scale = std::max(scale, std::abs(Sa[i][j]));
          }
        const std::size_t g = (static_cast<std::size_t>(e) * a.gaussPointsPerElement + q) * 3;
        for (int i = 0; i < 3; ++i) {
          double r = 0.0;
          for (int j = 0; j < 3; ++j) r += Q[i][j] * a.gaussCoords[g + j];
          posErr = std::max(posErr, std::abs(b.gaussCoords[g + i] - r));
        }
      }
    out << plasticity::elementTypeName(t) << ": rigid |f_int| " << fR << " (relative), |sigma| "
        << sig << "; objectivity error " << rotErr / scale << ", position error " << posErr << "\n";
    TEST_COMPARE(fR, <, 1e-12);
    TEST_COMPARE(sig, <, 1e-10 * kE);
    TEST_COMPARE(rotErr / scale, <, 1e-12);
    TEST_COMPARE(posErr, <, 1e-14);
  }
}

// The tangent (material + initial stress) against central differences of the internal force,
// for St. Venant-Kirchhoff and for J2 past yield (with committed plastic history).
TEUCHOS_UNIT_TEST(TotalLagrangian3D, TangentMatchesFiniteDifferences) {
  for (ElementType t : kSolids3D) {
    const ElementMesh m =
        plasticity_test::cubeMesh(t, 1, plasticity_test::randomVertices3(0.0)).mesh;
    ElementMesh d = m;
    for (std::size_t i = 0; i < d.coords.size(); ++i)
      d.coords[i] += 0.04 * plasticity_test::jitter(static_cast<int>(i), 7, 9);
    const double F[3][3] = {{0.04, 0.01, -0.02}, {0.015, -0.03, 0.02}, {-0.01, 0.025, 0.05}};
    const double c[3] = {0, 0, 0};
    const std::vector<double> u = affineField(d, F, c);
    std::vector<double> v(u.size());
    for (std::size_t i = 0; i < v.size(); ++i)
      v[i] = 1e-2 * plasticity_test::jitter(static_cast<int>(i), 3, 4) + 0.3 * u[i];
    const LinearElasticMaterial svk(kE, kNu);
    plasticity::J2PlasticMaterial j2(kE, kNu, 0.5, 20.0, d.numElements(),
                                     plasticity::numGaussPoints(t));
    // Some committed plastic history first (a different deformation), then the check.
    plasticity::internalForce(d, j2, affineField(d, F, c));
    j2.commit();
    std::vector<double> u2 = u;
    for (std::size_t i = 0; i < u2.size(); ++i) u2[i] = 1.3 * u[i] + 0.2 * v[i];
    for (const plasticity::MaterialLaw* law : {static_cast<const plasticity::MaterialLaw*>(&svk),
                                               static_cast<const plasticity::MaterialLaw*>(&j2)}) {
      const tfeti::CsrMatrix K = plasticity::tangentStiffness(d, *law, u2);
      const std::vector<double> Kv = multiply(K, v);
      const double h = 1e-7;
      std::vector<double> up = u2, um = u2;
      for (std::size_t i = 0; i < u2.size(); ++i) up[i] += h * v[i], um[i] -= h * v[i];
      const std::vector<double> fp = plasticity::internalForce(d, *law, up);
      const std::vector<double> fm = plasticity::internalForce(d, *law, um);
      double err = 0.0;
      for (std::size_t i = 0; i < Kv.size(); ++i)
        err = std::max(err, std::abs((fp[i] - fm[i]) / (2 * h) - Kv[i]));
      const double alpha = law == &j2 ? j2.trialEquivalentPlasticStrain({0, 0}) : 0.0;
      out << plasticity::elementTypeName(t) << (law == &j2 ? " J2" : " SVK")
          << ": FD tangent error " << err / maxAbs(Kv) << " (alpha at a Gauss point " << alpha
          << ")\n";
      TEST_COMPARE(err / maxAbs(Kv), <, 1e-6);
      if (law == &j2) TEST_COMPARE(j2.trialEquivalentPlasticStrain({0, 0}), >, 0.0);
    }
  }
}
