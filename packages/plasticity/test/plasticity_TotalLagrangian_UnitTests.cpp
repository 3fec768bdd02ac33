// Unit tests of the total Lagrangian kernels (plasticity_TotalLagrangian) on distorted meshes of
// the unit square (curved edges for the quadratic elements), for every element type, with the
// linear elastic law acting as St. Venant-Kirchhoff: rigid rotations are stress-free, the
// tangent at u = 0 is the small-strain stiffness, the tangent is the derivative of the internal
// force (also for the J2 law while elastic), a homogeneous deformation is reproduced exactly,
// and an inverted deformation is an error naming the element.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "plasticity_ElementTestMeshes.hpp"
#include "plasticity_Elements.hpp"
#include "plasticity_J2Plasticity.hpp"
#include "plasticity_TestUtils.hpp"
#include "plasticity_TotalLagrangian.hpp"
#include "tfeti_CsrMatrix.hpp"

namespace {
using namespace plasticity_test;  // NOLINT(build/namespaces)

using plasticity::ElementMesh;
using plasticity::ElementType;
using plasticity::InvertedDeformationError;
using plasticity::LinearElasticMaterial;
using plasticity::StressField;

const ElementType kAllTypes[] = {ElementType::Tri3, ElementType::Quad4, ElementType::Tri6,
                                 ElementType::Quad9};
const double kE = 200.0, kNu = 0.3;

// Distorted mesh of the unit square; quadratic elements get curved interior edges as well, so
// that nothing below relies on affine element maps.
LatticeMesh distortedMesh(ElementType type, int n) {
  return latticeMesh(type, n, randomVertices(0.3), 0.3);
}

// u = (F - I) X + t at every node: the homogeneous deformation x = F X + t.
std::vector<double> homogeneous(const ElementMesh& m, const double F[2][2],
                                const double t[2] = nullptr) {
  std::vector<double> u(2 * m.numNodes());
  for (int n = 0; n < m.numNodes(); ++n) {
    const double X = m.coords[2 * n], Y = m.coords[2 * n + 1];
    u[2 * n] = (F[0][0] - 1) * X + F[0][1] * Y + (t ? t[0] : 0.0);
    u[2 * n + 1] = F[1][0] * X + (F[1][1] - 1) * Y + (t ? t[1] : 0.0);
  }
  return u;
}

// Largest |value| of the in-plane and zz stress components over all Gauss points.
double maxGaussStress(const StressField& s) {
  double m = 0.0;
  for (std::size_t k = 0; k < s.gauss.size(); ++k)
    if (static_cast<int>(k % plasticity::kNumStressComponents) < plasticity::kVonMises)
      m = std::max(m, std::abs(s.gauss[k]));
  return m;
}

// ---------------------------------------------------------------- (a) rigid rotation

TEUCHOS_UNIT_TEST(TotalLagrangian, RigidRotationIsStressFree) {
  const LinearElasticMaterial law(kE, kNu);
  const double pi = 3.14159265358979323846, t[2] = {0.3, -0.7};
  for (ElementType type : kAllTypes)
    for (double degrees : {90.0, 30.0}) {
      const ElementMesh m = distortedMesh(type, 3).mesh;
      const double c = std::cos(degrees * pi / 180), s = std::sin(degrees * pi / 180);
      const double R[2][2] = {{c, -s}, {s, c}};
      const std::vector<double> u = homogeneous(m, R, t);
      // The scales the errors are relative to: the small-strain kernels, which see a strain of
      // order 1 - cos and are far from stress-free.
      const double smallStrainForce = maxAbs(multiply(plasticity::assembleStiffness(m, law), u));
      const double smallStrainStress = maxGaussStress(plasticity::recoverStresses(m, law, u));
      TEST_COMPARE(smallStrainStress, >, 0.1 * kE);
      const double f = maxAbs(plasticity::internalForce(m, law, u));
      const StressField sigma = plasticity::cauchyStress(m, law, u);
      const double sig = maxGaussStress(sigma);
      out << plasticity::elementTypeName(type) << " " << degrees << " deg: |f_int| "
          << f / smallStrainForce << ", |sigma| " << sig / smallStrainStress << " (relative)\n";
      TEST_COMPARE(f / smallStrainForce, <, 1e-12);
      TEST_COMPARE(sig / smallStrainStress, <, 1e-12);
      // The Cauchy stress is reported where it acts: at the rotated Gauss points.
      const StressField ref = plasticity::recoverStresses(m, law, std::vector<double>(u.size()));
      double posErr = 0.0;
      for (std::size_t k = 0; k < ref.gaussCoords.size(); k += 2) {
        const double X = ref.gaussCoords[k], Y = ref.gaussCoords[k + 1];
        posErr = std::max({posErr, std::abs(sigma.gaussCoords[k] - (c * X - s * Y + t[0])),
                           std::abs(sigma.gaussCoords[k + 1] - (s * X + c * Y + t[1]))});
      }
      TEST_COMPARE(posErr, <, 1e-14);
    }
}

// ---------------------------------------------------------------- (b) tangent at u = 0

TEUCHOS_UNIT_TEST(TotalLagrangian, TangentAtZeroIsSmallStrainStiffness) {
  const LinearElasticMaterial law(kE, kNu);
  for (ElementType type : kAllTypes) {
    const ElementMesh m = distortedMesh(type, 3).mesh;
    const tfeti::CsrMatrix K0 = plasticity::assembleStiffness(m, law);
    const tfeti::CsrMatrix Kt =
        plasticity::tangentStiffness(m, law, std::vector<double>(2 * m.numNodes(), 0.0));
    TEST_EQUALITY(Kt.rowPtr == K0.rowPtr && Kt.colInd == K0.colInd, true);
    double d = 0.0;
    for (std::size_t k = 0; k < K0.values.size() && k < Kt.values.size(); ++k)
      d = std::max(d, std::abs(Kt.values[k] - K0.values[k]));
    out << plasticity::elementTypeName(type) << ": max |Kt - K| / max |K| = " << d / K0.maxAbs()
        << "\n";
    TEST_COMPARE(d / K0.maxAbs(), <, 1e-14);
  }
}

// ---------------------------------------------------------------- (c) finite differences

// A smooth, markedly nonlinear displacement: stretch, shear and rotation of order 0.2 plus a
// quadratic part, so that F varies over each element and the geometric stiffness matters.
std::vector<double> deformedState(const ElementMesh& m, double scale) {
  std::vector<double> u(2 * m.numNodes());
  for (int n = 0; n < m.numNodes(); ++n) {
    const double X = m.coords[2 * n], Y = m.coords[2 * n + 1];
    u[2 * n] = scale * (0.15 * X - 0.2 * Y + 0.1 * X * Y);
    u[2 * n + 1] = scale * (0.25 * X + 0.05 * Y - 0.1 * X * X + 0.05 * Y * Y);
  }
  return u;
}

// max |K - dF/du| / max |K| with dF/du by central differences, column by column.
double tangentError(const ElementMesh& m, const plasticity::MaterialLaw& law,
                    const std::vector<double>& u) {
  const tfeti::CsrMatrix K = plasticity::tangentStiffness(m, law, u);
  const double h = 1e-6;
  const int nd = static_cast<int>(u.size());
  double worst = 0.0;
  std::vector<double> up = u, um = u;
  for (int j = 0; j < nd; ++j) {
    up[j] = u[j] + h, um[j] = u[j] - h;
    const std::vector<double> fp = plasticity::internalForce(m, law, up);
    const std::vector<double> fm = plasticity::internalForce(m, law, um);
    up[j] = um[j] = u[j];
    for (int i = 0; i < nd; ++i) {
      const long k = K.find(i, j);
      const double kij = k < 0 ? 0.0 : K.values[k];
      worst = std::max(worst, std::abs(kij - (fp[i] - fm[i]) / (2 * h)));
    }
  }
  return worst / K.maxAbs();
}

TEUCHOS_UNIT_TEST(TotalLagrangian, TangentIsDerivativeOfInternalForce) {
  const LinearElasticMaterial law(kE, kNu);
  for (ElementType type : kAllTypes) {
    const ElementMesh m = distortedMesh(type, 2).mesh;
    const std::vector<double> u = deformedState(m, 1.0);
    // The geometric part must matter here, or this would not test it.
    const tfeti::CsrMatrix K0 = plasticity::assembleStiffness(m, law);
    const tfeti::CsrMatrix Kt = plasticity::tangentStiffness(m, law, u);
    double d = 0.0;
    for (std::size_t k = 0; k < K0.values.size(); ++k)
      d = std::max(d, std::abs(Kt.values[k] - K0.values[k]));
    TEST_COMPARE(d / K0.maxAbs(), >, 0.05);
    const double err = tangentError(m, law, u);
    out << plasticity::elementTypeName(type) << ": FD error " << err << "\n";
    TEST_COMPARE(err, <, 1e-6);
  }
}

TEUCHOS_UNIT_TEST(TotalLagrangian, TangentIsDerivativeOfInternalForceForElasticJ2) {
  for (ElementType type : kAllTypes) {
    const ElementMesh m = distortedMesh(type, 2).mesh;
    // Yield stress well above the stresses of the state: the law stays elastic throughout.
    const plasticity::J2PlasticMaterial j2(kE, kNu, 1e3, 10.0, m.numElements(),
                                           plasticity::numGaussPoints(type));
    const std::vector<double> u = deformedState(m, 1.0);
    const double vm = plasticity::cauchyStress(m, j2, u).atGaussPoint(0, 0, plasticity::kVonMises);
    TEST_COMPARE(vm, <, 1e3);
    TEST_COMPARE(vm, >, 1.0);
    double alpha = 0.0;
    for (int e = 0; e < m.numElements(); ++e)
      for (int q = 0; q < plasticity::numGaussPoints(type); ++q)
        alpha = std::max(alpha, j2.trialEquivalentPlasticStrain({e, q}));
    TEST_EQUALITY(alpha, 0.0);
    const double err = tangentError(m, j2, u);
    out << plasticity::elementTypeName(type) << ": FD error (J2, elastic) " << err << "\n";
    TEST_COMPARE(err, <, 1e-6);
  }
}

// ---------------------------------------------------------------- (d) homogeneous patch test

TEUCHOS_UNIT_TEST(TotalLagrangian, HomogeneousDeformationPatchTest) {
  const LinearElasticMaterial law(kE, kNu);
  const double F[2][2] = {{1.2, 0.15}, {-0.1, 0.9}};
  const double J = F[0][0] * F[1][1] - F[0][1] * F[1][0];
  // Exact E, S, P = F S and sigma = F S F^T / J.
  const double Ev[3] = {0.5 * (F[0][0] * F[0][0] + F[1][0] * F[1][0] - 1),
                        0.5 * (F[0][1] * F[0][1] + F[1][1] * F[1][1] - 1),
                        F[0][0] * F[0][1] + F[1][0] * F[1][1]};
  plasticity::PlaneStrainResponse r;  // stress (xx, yy, xy, zz)
  plasticity::evaluatePlaneStrain(law, {}, Ev, r);
  const double S[2][2] = {{r.stress[0], r.stress[2]}, {r.stress[2], r.stress[1]}};
  double P[2][2] = {{0, 0}, {0, 0}}, sigma[2][2] = {{0, 0}, {0, 0}};
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k) {
        P[i][j] += F[i][k] * S[k][j];
        for (int l = 0; l < 2; ++l) sigma[i][j] += F[i][k] * S[k][l] * F[j][l] / J;
      }
  const double exact[4] = {sigma[0][0], sigma[1][1], sigma[0][1], r.stress[3] / J};
  const double scale = std::max({std::abs(exact[0]), std::abs(exact[1]), std::abs(exact[2])});
  for (ElementType type : kAllTypes) {
    const LatticeMesh L = distortedMesh(type, 3);
    const ElementMesh& m = L.mesh;
    const std::vector<double> u = homogeneous(m, F);
    const StressField s = plasticity::cauchyStress(m, law, u);
    double err = 0.0;
    for (int e = 0; e < m.numElements(); ++e)
      for (int q = 0; q < s.gaussPointsPerElement; ++q)
        for (int c = 0; c < 4; ++c) {
          const int component[4] = {plasticity::kSxx, plasticity::kSyy, plasticity::kSxy,
                                    plasticity::kSzz};
          err = std::max(err, std::abs(s.atGaussPoint(e, q, component[c]) - exact[c]));
        }
    // The internal forces are the loads of the nominal traction P N on the reference sides
    // (outward normals of sides 0..3: -y, +x, +y, -x), and zero at interior nodes.
    const std::vector<double> f = plasticity::internalForce(m, law, u);
    std::vector<double> load(f.size(), 0.0);
    const double normals[4][2] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
    for (int k = 0; k < 4; ++k) {
      const double t[2] = {P[0][0] * normals[k][0] + P[0][1] * normals[k][1],
                           P[1][0] * normals[k][0] + P[1][1] * normals[k][1]};
      const std::vector<double> fk = plasticity::assembleEdgeTraction(m, L.sideEdges(k), t);
      for (std::size_t i = 0; i < f.size(); ++i) load[i] += fk[i];
    }
    double loadErr = 0.0, interior = 0.0;
    for (int n = 0; n < m.numNodes(); ++n)
      for (int c = 0; c < 2; ++c) {
        loadErr = std::max(loadErr, std::abs(f[2 * n + c] - load[2 * n + c]));
        if (!L.onBoundary(n)) interior = std::max(interior, std::abs(f[2 * n + c]));
      }
    out << plasticity::elementTypeName(type) << ": sigma error " << err / scale
        << ", |f - traction loads| " << loadErr / maxAbs(f) << ", interior |f| "
        << interior / maxAbs(f) << "\n";
    TEST_COMPARE(err / scale, <, 1e-12);
    TEST_COMPARE(loadErr / maxAbs(f), <, 1e-12);
    TEST_COMPARE(interior / maxAbs(f), <, 1e-12);
  }
}

// ---------------------------------------------------------------- (e) inverted deformation

TEUCHOS_UNIT_TEST(TotalLagrangian, InvertedDeformationThrowsNamingTheElement) {
  const LinearElasticMaterial law(kE, kNu);
  for (ElementType type : kAllTypes) {
    const LatticeMesh L = distortedMesh(type, 3);
    const ElementMesh& m = L.mesh;
    // Push one interior vertex across its neighbours: only the elements around it fold over.
    const int s = plasticity::isQuadratic(type) ? 2 : 1;
    const int node = (2 * s) * L.side + 2 * s;  // vertex (2, 2) of the 3 x 3 cells
    std::vector<double> u(2 * m.numNodes(), 0.0);
    u[2 * node] = 0.8, u[2 * node + 1] = 0.8;
    const int npe = plasticity::nodesPerElement(type);
    auto check = [&](auto call) {
      try {
        call();
        return std::string("no exception");
      } catch (const InvertedDeformationError& e) {
        const std::string msg = e.what();
        const std::size_t p = msg.find(" element ");
        if (p == std::string::npos || msg.find("inverted") == std::string::npos) return msg;
        const int el = std::stoi(msg.substr(p + 9));
        const int* en = &m.connectivity[static_cast<std::size_t>(el) * npe];
        if (std::find(en, en + npe, node) == en + npe)
          return "names element not at the node: " + msg;
        return std::string("ok");
      }
    };
    const std::string a = check([&] { plasticity::internalForce(m, law, u); });
    const std::string b = check([&] { plasticity::tangentStiffness(m, law, u); });
    const std::string c = check([&] { plasticity::cauchyStress(m, law, u); });
    out << plasticity::elementTypeName(type) << ": " << a << " / " << b << " / " << c << "\n";
    TEST_EQUALITY(a, "ok");
    TEST_EQUALITY(b, "ok");
    TEST_EQUALITY(c, "ok");
    // A reflection inverts every element; element 0 is named first.
    const double mirror[2][2] = {{-1, 0}, {0, 1}};
    try {
      plasticity::internalForce(m, law, homogeneous(m, mirror));
      TEST_ASSERT(false);
    } catch (const InvertedDeformationError& e) {
      TEST_INEQUALITY(std::string(e.what()).find("element 0 "), std::string::npos);
    }
    // The undeformed mesh itself is valid.
    TEST_NOTHROW(plasticity::internalForce(m, law, std::vector<double>(u.size(), 0.0)));
  }
}

}  // namespace

// ---------------------------------------------------------------- small strain, material tangent

namespace {

// The small-strain kinematics of the same kernels is linear elasticity: f_int = K u for the
// elastic law, the tangent is K at any u, and the Cauchy stress is the small-strain stress.
TEUCHOS_UNIT_TEST(TotalLagrangian, SmallStrainKinematicsIsLinearElasticity) {
  const LinearElasticMaterial law(kE, kNu);
  for (ElementType type : kAllTypes) {
    const ElementMesh m = distortedMesh(type, 3).mesh;
    const std::vector<double> u = deformedState(m, 1.0);
    const tfeti::CsrMatrix K = plasticity::assembleStiffness(m, law);
    std::vector<double> Ku(u.size(), 0.0);
    K.multiply(u.data(), Ku.data());
    const auto f = plasticity::internalForce(m, law, u, plasticity::Kinematics::SmallStrain);
    double d = 0.0, s = 0.0;
    for (std::size_t i = 0; i < f.size(); ++i) {
      d = std::max(d, std::abs(f[i] - Ku[i]));
      s = std::max(s, std::abs(Ku[i]));
    }
    const tfeti::CsrMatrix Kt =
        plasticity::tangentStiffness(m, law, u, plasticity::Kinematics::SmallStrain);
    double dk = 0.0;
    for (std::size_t k = 0; k < K.values.size(); ++k)
      dk = std::max(dk, std::abs(Kt.values[k] - K.values[k]));
    const StressField a = plasticity::cauchyStress(m, law, u, plasticity::Kinematics::SmallStrain);
    const StressField b = plasticity::recoverStresses(m, law, u);
    double ds = 0.0;
    for (std::size_t k = 0; k < a.gauss.size(); ++k)
      ds = std::max(ds, std::abs(a.gauss[k] - b.gauss[k]));
    out << plasticity::elementTypeName(type) << ": |f - K u| / |K u| = " << d / s
        << ", |Kt - K| / |K| = " << dk / K.maxAbs() << ", |sigma - sigma_lin| = " << ds << "\n";
    TEST_COMPARE(d / s, <, 1e-13);
    TEST_COMPARE(dk / K.maxAbs(), <, 1e-14);
    TEST_COMPARE(ds, <, 1e-12 * kE);
  }
}

// The material tangent without the initial-stress part is what a FETI subdomain is factorized
// with in a nonlinear run: its kernel must hold the rigid motions of the current configuration
// (translations, and the rotation about the deformed positions), while the full tangent of the
// stressed body does not annihilate that rotation.
TEUCHOS_UNIT_TEST(TotalLagrangian, MaterialTangentKernelIsCurrentRigidMotion) {
  const LinearElasticMaterial law(kE, kNu);
  for (ElementType type : kAllTypes) {
    const ElementMesh m = distortedMesh(type, 3).mesh;
    const std::vector<double> u = deformedState(m, 1.0);
    const tfeti::CsrMatrix Km =
        plasticity::tangentStiffness(m, law, u, plasticity::Kinematics::TotalLagrangian, false);
    const tfeti::CsrMatrix Kt = plasticity::tangentStiffness(m, law, u);
    const int n = m.numNodes();
    std::vector<std::vector<double>> modes(3, std::vector<double>(2 * n, 0.0));
    for (int a = 0; a < n; ++a) {
      const double x = m.coords[2 * a] + u[2 * a], y = m.coords[2 * a + 1] + u[2 * a + 1];
      modes[0][2 * a] = 1.0;
      modes[1][2 * a + 1] = 1.0;
      modes[2][2 * a] = -y;
      modes[2][2 * a + 1] = x;
    }
    std::vector<double> y(2 * n);
    for (int k = 0; k < 3; ++k) {
      double norm = 0.0;
      for (double v : modes[k]) norm += v * v;
      norm = std::sqrt(norm);
      Km.multiply(modes[k].data(), y.data());
      double r = 0.0;
      for (double v : y) r = std::max(r, std::abs(v));
      out << plasticity::elementTypeName(type) << " mode " << k
          << ": |K_mat r| / (|K| |r|) = " << r / (Km.maxAbs() * norm) << "\n";
      TEST_COMPARE(r / (Km.maxAbs() * norm), <, 1e-12);
    }
    Kt.multiply(modes[2].data(), y.data());
    double r = 0.0;
    for (double v : y) r = std::max(r, std::abs(v));
    TEST_COMPARE(r / Kt.maxAbs(), >, 1e-4);
  }
}

}  // namespace
