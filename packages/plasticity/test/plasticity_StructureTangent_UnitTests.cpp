// The tangent a Newton solver refactorizes, checked on whole structures rather than at one
// material point or element: the assembled tangentStiffness(u) times a direction v against
// central differences of the assembled internalForce, on meshes of many distorted elements in a
// deformation that leaves some Gauss points elastic, some yielding for the first time and some
// reloading a committed plastic history. Small strain and total Lagrangian, 2D (plane strain)
// and 3D, every assembled element type.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "plasticity_ElementTestMeshes.hpp"
#include "plasticity_ElementTestMeshes3D.hpp"
#include "plasticity_Elements.hpp"
#include "plasticity_J2Plasticity.hpp"
#include "plasticity_TestUtils.hpp"
#include "plasticity_TotalLagrangian.hpp"

namespace {

using plasticity::ElementMesh;
using plasticity::ElementType;
using plasticity::Kinematics;
using plasticity_test::jitter;
using plasticity_test::maxAbs;
using plasticity_test::multiply;

constexpr double kE = 200.0, kNu = 0.3, kYield = 0.6, kH = 15.0;

// A smooth, strongly non-uniform field: the strain grows from ~0 at one corner to several times
// the yield strain at the opposite one, so the structure holds elastic and plastic points.
std::vector<double> bendingField(const ElementMesh& m, double scale) {
  const int dim = m.dim();
  std::vector<double> u(m.coords.size());
  for (std::size_t a = 0; a < m.coords.size() / dim; ++a) {
    const double* x = &m.coords[dim * a];
    const double z = dim == 3 ? x[2] : 0.0;
    const double s = x[0] * x[0] + x[1] * x[1] + z * z;
    u[dim * a] = scale * (0.6 * s * x[1] + 0.2 * x[0] * x[0] * x[0]);
    u[dim * a + 1] = scale * (-0.5 * s * x[0] + 0.3 * x[1] * z);
    if (dim == 3) u[dim * a + 2] = scale * (0.4 * x[0] * x[1] * z - 0.3 * s * z);
  }
  return u;
}

struct PointCounts {
  int elastic = 0, plastic = 0, total = 0;
};

PointCounts countPlasticPoints(const ElementMesh& m, const plasticity::J2PlasticMaterial& j2) {
  PointCounts c;
  const int ng = plasticity::numGaussPoints(m.type);
  for (int e = 0; e < m.numElements(); ++e)
    for (int g = 0; g < ng; ++g) {
      const bool plastic =
          j2.trialEquivalentPlasticStrain({e, g}) > j2.equivalentPlasticStrain({e, g}) + 1e-14;
      ++(plastic ? c.plastic : c.elastic);
      ++c.total;
    }
  return c;
}

// max |(f(u + h v) - f(u - h v)) / 2h - K(u) v| / max |K(u) v| for the J2 law after a committed
// history, at u (its plastic points counted at u).
double fdTangentError(const ElementMesh& m, Kinematics kin, PointCounts& counts) {
  const int ng = plasticity::numGaussPoints(m.type);
  plasticity::J2PlasticMaterial j2(kE, kNu, kYield, kH, m.numElements(), ng);
  // A committed history from an earlier, different deformation: reloading as well as first
  // yield in the check below.
  plasticity::internalForce(m, j2, bendingField(m, -0.004), kin);
  j2.commit();
  const std::vector<double> u = bendingField(m, 0.007);
  std::vector<double> v(u.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = 1e-2 * jitter(static_cast<int>(i), 5, 11) + 0.2 * u[i];
  const tfeti::CsrMatrix K = plasticity::tangentStiffness(m, j2, u, kin);
  counts = countPlasticPoints(m, j2);  // the trial state at u (tangentStiffness evaluates it)
  const std::vector<double> Kv = multiply(K, v);
  const double h = 1e-7;
  std::vector<double> up = u, um = u;
  for (std::size_t i = 0; i < u.size(); ++i) up[i] += h * v[i], um[i] -= h * v[i];
  const std::vector<double> fp = plasticity::internalForce(m, j2, up, kin);
  const std::vector<double> fm = plasticity::internalForce(m, j2, um, kin);
  double err = 0.0;
  for (std::size_t i = 0; i < Kv.size(); ++i)
    err = std::max(err, std::abs((fp[i] - fm[i]) / (2 * h) - Kv[i]));
  return err / maxAbs(Kv);
}

const char* name(Kinematics k) {
  return k == Kinematics::SmallStrain ? "small strain" : "total Lagrangian";
}

TEUCHOS_UNIT_TEST(StructureTangent, ThreeDStructuresMatchFiniteDifferences) {
  for (ElementType t :
       {ElementType::Tet4, ElementType::Tet10, ElementType::Hex8, ElementType::Hex27})
    for (Kinematics kin : {Kinematics::SmallStrain, Kinematics::TotalLagrangian}) {
      const ElementMesh m =
          plasticity_test::cubeMesh(t, 3, plasticity_test::randomVertices3(0.2)).mesh;
      PointCounts c;
      const double err = fdTangentError(m, kin, c);
      out << plasticity::elementTypeName(t) << ", " << name(kin) << ": " << m.numElements()
          << " elements, " << c.plastic << " of " << c.total
          << " Gauss points loading plastically; FD tangent error " << err << "\n";
      TEST_COMPARE(err, <, 1e-6);
      // A structure in both states: the check covers the elastic and the plastic branch.
      TEST_COMPARE(c.plastic, >, c.total / 10);
      TEST_COMPARE(c.elastic, >, c.total / 10);
    }
}

TEUCHOS_UNIT_TEST(StructureTangent, PlaneStrainStructuresMatchFiniteDifferences) {
  for (ElementType t :
       {ElementType::Tri3, ElementType::Quad4, ElementType::Tri6, ElementType::Quad9})
    for (Kinematics kin : {Kinematics::SmallStrain, Kinematics::TotalLagrangian}) {
      const ElementMesh m =
          plasticity_test::latticeMesh(t, 6, plasticity_test::randomVertices(0.2)).mesh;
      PointCounts c;
      const double err = fdTangentError(m, kin, c);
      out << plasticity::elementTypeName(t) << ", " << name(kin) << ": " << m.numElements()
          << " elements, " << c.plastic << " of " << c.total
          << " Gauss points loading plastically; FD tangent error " << err << "\n";
      TEST_COMPARE(err, <, 1e-6);
      TEST_COMPARE(c.plastic, >, c.total / 10);
      TEST_COMPARE(c.elastic, >, c.total / 10);
    }
}

// The tangent is assembled in chunks of elements (kTangentChunk = 1024 in
// plasticity_TotalLagrangian.cpp) from the upper triangles of the element matrices: on a mesh of
// more elements than one chunk it is still the derivative of the internal force, with the
// initial-stress part, and exactly symmetric.
TEUCHOS_UNIT_TEST(StructureTangent, TangentOfMoreElementsThanOneChunk) {
  const ElementMesh m =
      plasticity_test::cubeMesh(ElementType::Hex8, 11, plasticity_test::randomVertices3(0.2)).mesh;
  TEST_COMPARE(m.numElements(), >, 1024);
  PointCounts c;
  const double err = fdTangentError(m, Kinematics::TotalLagrangian, c);
  out << m.numElements() << " elements, " << c.plastic << " of " << c.total
      << " Gauss points loading plastically; FD tangent error " << err << "\n";
  TEST_COMPARE(err, <, 1e-6);
  TEST_COMPARE(c.plastic, >, 0);
  plasticity::J2PlasticMaterial j2(kE, kNu, kYield, kH, m.numElements(),
                                   plasticity::numGaussPoints(m.type));
  const tfeti::CsrMatrix K =
      plasticity::tangentStiffness(m, j2, bendingField(m, 0.007), Kinematics::TotalLagrangian);
  double asymmetry = 0.0;
  for (int i = 0; i < K.rows; ++i)
    for (int k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k)
      asymmetry = std::max(asymmetry, std::abs(K.values[k] - K.values[K.find(K.colInd[k], i)]));
  TEST_EQUALITY_CONST(asymmetry, 0.0);
}

// The 3D rigid modes at positions x (3 per node): 3 translations, then 3 rotations.
std::vector<std::vector<double>> rigidModes3(const std::vector<double>& x) {
  const std::size_t n = x.size() / 3;
  std::vector<std::vector<double>> R(6, std::vector<double>(x.size(), 0.0));
  for (std::size_t a = 0; a < n; ++a) {
    for (int c = 0; c < 3; ++c) R[c][3 * a + c] = 1.0;
    for (int k = 0; k < 3; ++k) {  // rotation about axis k: e_k x x
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      R[3 + k][3 * a + j] = x[3 * a + i];
      R[3 + k][3 * a + i] = -x[3 * a + j];
    }
  }
  return R;
}

// Which rigid modes the tangent a TFETI subdomain is given has, stated as a test: in small
// strain all six of the reference positions X; in total Lagrangian the material tangent (what
// the driver refactorizes) all six of the current positions X + u, while the full tangent (with
// the initial-stress part) keeps only the translations: a stressed body's rotation changes the
// direction of its internal forces, so K R_rot = W f_int != 0.
TEUCHOS_UNIT_TEST(StructureTangent, RigidModesOfTheTangents) {
  const ElementMesh m =
      plasticity_test::cubeMesh(ElementType::Hex8, 3, plasticity_test::randomVertices3(0.2)).mesh;
  plasticity::J2PlasticMaterial j2(kE, kNu, kYield, kH, m.numElements(),
                                   plasticity::numGaussPoints(m.type));
  const std::vector<double> u = bendingField(m, 0.007);
  std::vector<double> x = m.coords;
  for (std::size_t i = 0; i < x.size(); ++i) x[i] += u[i];
  auto relativeDefect = [&](const tfeti::CsrMatrix& K, const std::vector<double>& r) {
    double kr = maxAbs(multiply(K, r)), kn = 0.0;
    for (double v : K.values) kn = std::max(kn, std::abs(v));
    return kr / (kn * maxAbs(r));
  };
  const tfeti::CsrMatrix Kss = plasticity::tangentStiffness(m, j2, u, Kinematics::SmallStrain);
  const tfeti::CsrMatrix Kmat =
      plasticity::tangentStiffness(m, j2, u, Kinematics::TotalLagrangian, false);
  const tfeti::CsrMatrix Kfull =
      plasticity::tangentStiffness(m, j2, u, Kinematics::TotalLagrangian);
  const auto RX = rigidModes3(m.coords), Rx = rigidModes3(x);
  for (int k = 0; k < 6; ++k) {
    const double ss = relativeDefect(Kss, RX[k]), mat = relativeDefect(Kmat, Rx[k]),
                 full = relativeDefect(Kfull, Rx[k]);
    out << "mode " << k << ": small strain " << ss << ", TL material " << mat << ", TL full "
        << full << "\n";
    TEST_COMPARE(ss, <, 1e-12);
    TEST_COMPARE(mat, <, 1e-12);
    if (k < 3) TEST_COMPARE(full, <, 1e-12);
    if (k >= 3) TEST_COMPARE(full, >, 1e-6);
  }
  // The small-strain tangent does not annihilate the rotations of the current positions (the
  // kernel defect the first refactorization reported).
  TEST_COMPARE(relativeDefect(Kss, Rx[3]), >, 1e-6);
}

}  // namespace
