// Unit tests of the J2 law in full 3D (6-component Voigt strain, 6x6 tangent): closed-form
// shear in each of the three planes and isochoric extension, the uniaxial-stress response
// (driven by Newton iterations on the lateral strains with the consistent tangent) against
// sigma = sigma_y + E H / (E + H) (eps - sigma_y / E), the 6x6 tangent against central
// differences, elastic unloading, and plane strain as the same law: 2D plane-strain kernels
// against the 3D kernels on a one-element-thick slab with u_z = 0.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "plasticity_ElementTestMeshes.hpp"
#include "plasticity_Elements.hpp"
#include "plasticity_J2Plasticity.hpp"
#include "plasticity_MaterialLaw.hpp"
#include "plasticity_TestUtils.hpp"
#include "plasticity_TotalLagrangian.hpp"
#include "tfeti_DenseUtils.hpp"

namespace {

using plasticity::ElementMesh;
using plasticity::ElementType;
using plasticity::J2PlasticMaterial;
using plasticity::kNumVoigt;
using plasticity::MaterialPointId;
using plasticity::MaterialResponse;

constexpr double kE = 200000.0, kNu = 0.3, kSy = 250.0, kH = 10000.0;
const double kSqrt3 = std::sqrt(3.0);
double mu() {
  return kE / (2.0 * (1.0 + kNu));
}
double bulk() {
  return kE / (3.0 * (1.0 - 2.0 * kNu));
}

}  // namespace

// Simple shear gamma in each plane: sigma = (sigma_y + H alpha) / sqrt(3) with
// alpha = (sqrt(3) mu gamma - sigma_y) / (3 mu + H), the other components zero, the plastic
// shear sqrt(3) alpha.
TEUCHOS_UNIT_TEST(J2Plasticity3D, ShearInEachPlaneClosedForm) {
  const double gamma = 3.0 * kSy / (kSqrt3 * mu());
  const double alpha = (kSqrt3 * mu() * gamma - kSy) / (3 * mu() + kH);
  const double tau = (kSy + kH * alpha) / kSqrt3;
  for (int c : {plasticity::kYZ, plasticity::kXZ, plasticity::kXY}) {
    J2PlasticMaterial j2(kE, kNu, kSy, kH, 1, 1);
    double strain[kNumVoigt] = {0, 0, 0, 0, 0, 0};
    strain[c] = gamma;
    MaterialResponse r;
    j2.evaluate({0, 0}, strain, r);
    TEST_FLOATING_EQUALITY(r.stress[c], tau, 1e-12);
    for (int k = 0; k < kNumVoigt; ++k)
      if (k != c) TEST_COMPARE(std::abs(r.stress[k]), <=, 1e-12 * kSy);
    TEST_FLOATING_EQUALITY(j2.trialEquivalentPlasticStrain({0, 0}), alpha, 1e-12);
    double ep[kNumVoigt];
    j2.trialPlasticStrain({0, 0}, ep);
    TEST_FLOATING_EQUALITY(2 * ep[c], kSqrt3 * alpha, 1e-12);
    // d tau / d gamma on the hardening branch: mu H / (3 mu + H).
    TEST_FLOATING_EQUALITY(r.tangent[kNumVoigt * c + c], mu() * kH / (3 * mu() + kH), 1e-10);
    TEST_FLOATING_EQUALITY(plasticity::vonMises(r.stress), kSy + kH * alpha, 1e-12);
  }
}

// eps = e diag(1, -1/2, -1/2) + v I: the deviator is radial with q_trial = 3 mu e, so
// alpha = (3 mu e - sigma_y) / (3 mu + H), sigma_xx - sigma_yy = sigma_y + H alpha, and the
// mean stress is 3 K v (plastic flow is isochoric).
TEUCHOS_UNIT_TEST(J2Plasticity3D, IsochoricExtensionClosedForm) {
  const double e = 4.0 * kSy / (3 * mu()), v = 2e-4;
  const double alpha = (3 * mu() * e - kSy) / (3 * mu() + kH), q = kSy + kH * alpha;
  J2PlasticMaterial j2(kE, kNu, kSy, kH, 1, 1);
  const double strain[kNumVoigt] = {e + v, -0.5 * e + v, -0.5 * e + v, 0, 0, 0};
  MaterialResponse r;
  j2.evaluate({0, 0}, strain, r);
  const double p = 3 * bulk() * v;
  TEST_FLOATING_EQUALITY(r.stress[0], p + 2.0 / 3.0 * q, 1e-12);
  TEST_FLOATING_EQUALITY(r.stress[1], p - 1.0 / 3.0 * q, 1e-12);
  TEST_FLOATING_EQUALITY(r.stress[2], p - 1.0 / 3.0 * q, 1e-12);
  for (int k = 3; k < kNumVoigt; ++k) TEST_COMPARE(std::abs(r.stress[k]), <=, 1e-12 * kSy);
  TEST_FLOATING_EQUALITY(j2.trialEquivalentPlasticStrain({0, 0}), alpha, 1e-12);
}

// Uniaxial stress, strain-driven in eps_xx with the other five strains found by Newton on
// sigma_k = 0 (k != xx) with the consistent tangent; each increment committed. Closed form:
// sigma_xx = sigma_y + E_t (eps_xx - sigma_y / E), E_t = E H / (E + H); lateral plastic strains
// -alpha / 2; and Newton converges in a few iterations (quadratically) because the tangent is
// consistent.
TEUCHOS_UNIT_TEST(J2Plasticity3D, UniaxialStressResponse) {
  J2PlasticMaterial j2(kE, kNu, kSy, kH, 1, 1);
  const double eMax = 5.0 * kSy / kE;
  const int steps = 10;
  double strain[kNumVoigt] = {0, 0, 0, 0, 0, 0};
  int maxIterations = 0;
  MaterialResponse r;
  for (int s = 1; s <= steps; ++s) {
    strain[0] = eMax * s / steps;
    int it = 0;
    for (; it < 20; ++it) {
      j2.evaluate({0, 0}, strain, r);
      double res = 0.0;
      for (int k = 1; k < kNumVoigt; ++k) res = std::max(res, std::abs(r.stress[k]));
      if (res < 1e-10 * kSy) break;
      // Solve C_ll d = -sigma_l for the five lateral strains (C_ll is SPD for H > 0).
      std::vector<double> A(25);
      for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) A[5 * i + j] = r.tangent[kNumVoigt * (i + 1) + (j + 1)];
      const std::vector<double> Ainv = tfeti::dense::pseudoInverseSpd(5, A);
      for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) strain[i + 1] -= Ainv[5 * i + j] * r.stress[j + 1];
    }
    maxIterations = std::max(maxIterations, it);
    j2.commit();
  }
  const double Et = kE * kH / (kE + kH);
  const double expected = kSy + Et * (eMax - kSy / kE);
  const double alpha = j2.equivalentPlasticStrain({0, 0});
  double ep[kNumVoigt];
  j2.plasticStrain({0, 0}, ep);
  out << "sigma_xx " << r.stress[0] << " (closed form " << expected << "), alpha " << alpha
      << ", Newton iterations per step <= " << maxIterations << "\n";
  TEST_FLOATING_EQUALITY(r.stress[0], expected, 1e-9);
  TEST_FLOATING_EQUALITY(alpha, (expected - kSy) / kH, 1e-9);
  TEST_FLOATING_EQUALITY(ep[0], alpha, 1e-9);
  TEST_FLOATING_EQUALITY(ep[1], -0.5 * alpha, 1e-9);
  TEST_FLOATING_EQUALITY(ep[2], -0.5 * alpha, 1e-9);
  TEST_COMPARE(maxIterations, <=, 4);
}

// The 6x6 consistent tangent against central differences: elastic, first yield from the
// virgin state, a non-radial step from committed plastic history, perfect plasticity.
TEUCHOS_UNIT_TEST(J2Plasticity3D, ConsistentTangentMatchesFiniteDifferences) {
  const double g = kSy / kE;
  const double elastic[kNumVoigt] = {0.2 * g, -0.1 * g, 0.05 * g, 0.1 * g, -0.05 * g, 0.15 * g};
  const double plastic[kNumVoigt] = {1.5 * g, -0.7 * g, 0.4 * g, 1.1 * g, -0.9 * g, 2.0 * g};
  const double other[kNumVoigt] = {-0.5 * g, 2.1 * g, -0.3 * g, -1.4 * g, 0.6 * g, 0.2 * g};
  for (const double H : {kH, 0.0})
    for (int history = 0; history < 2; ++history)
      for (const double* e : {elastic, plastic, other}) {
        // Re-evaluating the committed strain itself sits exactly on the yield surface, where
        // the response has a kink (elastic one way, plastic the other): no derivative there.
        if (history && e == plastic) continue;
        J2PlasticMaterial j2(kE, kNu, kSy, H, 1, 1);
        if (history) {
          MaterialResponse pre;
          j2.evaluate({0, 0}, plastic, pre);
          j2.commit();
        }
        MaterialResponse r;
        j2.evaluate({0, 0}, e, r);
        const double h = 1e-9;
        double err = 0.0, scale = 0.0, asym = 0.0;
        for (int j = 0; j < kNumVoigt; ++j) {
          double ep[kNumVoigt], em[kNumVoigt];
          std::copy(e, e + kNumVoigt, ep), std::copy(e, e + kNumVoigt, em);
          ep[j] += h, em[j] -= h;
          MaterialResponse rp, rm;
          j2.evaluate({0, 0}, ep, rp);
          j2.evaluate({0, 0}, em, rm);
          for (int i = 0; i < kNumVoigt; ++i) {
            const double fd = (rp.stress[i] - rm.stress[i]) / (2 * h);
            err = std::max(err, std::abs(fd - r.tangent[kNumVoigt * i + j]));
            scale = std::max(scale, std::abs(r.tangent[kNumVoigt * i + j]));
            asym = std::max(asym,
                            std::abs(r.tangent[kNumVoigt * i + j] - r.tangent[kNumVoigt * j + i]));
          }
        }
        out << "H " << H << ", history " << history << ": alpha "
            << j2.trialEquivalentPlasticStrain({0, 0}) << ", FD tangent error " << err / scale
            << "\n";
        TEST_COMPARE(err / scale, <, 1e-6);
        TEST_COMPARE(asym / scale, <, 1e-12);
      }
}

// After plastic loading (committed), a strain decrement back inside the yield surface is
// elastic: the stress changes by C_el d eps, the history does not, the tangent is elastic.
TEUCHOS_UNIT_TEST(J2Plasticity3D, UnloadingIsElastic) {
  const double g = kSy / kE;
  const double load[kNumVoigt] = {2.0 * g, -1.0 * g, 0.5 * g, 1.5 * g, -0.5 * g, 1.0 * g};
  J2PlasticMaterial j2(kE, kNu, kSy, kH, 1, 1);
  MaterialResponse r1, r2;
  j2.evaluate({0, 0}, load, r1);
  j2.commit();
  const double alpha = j2.equivalentPlasticStrain({0, 0});
  TEST_COMPARE(alpha, >, 0.0);
  double back[kNumVoigt], de[kNumVoigt];
  for (int k = 0; k < kNumVoigt; ++k) de[k] = -0.3 * load[k], back[k] = load[k] + de[k];
  j2.evaluate({0, 0}, back, r2);
  double C[kNumVoigt * kNumVoigt];
  j2.elastic().voigtMatrix(C);
  for (int i = 0; i < kNumVoigt; ++i) {
    double ds = 0.0;
    for (int j = 0; j < kNumVoigt; ++j) ds += C[kNumVoigt * i + j] * de[j];
    TEST_COMPARE(std::abs(r2.stress[i] - (r1.stress[i] + ds)), <=, 1e-10 * kSy);
  }
  for (int k = 0; k < kNumVoigt * kNumVoigt; ++k) TEST_EQUALITY(r2.tangent[k], C[k]);
  TEST_EQUALITY(j2.trialEquivalentPlasticStrain({0, 0}), alpha);
}

// Plane strain is the 3D law with eps_zz = 0: the plane-strain kernels on a 2D mesh and the 3D
// kernels on the same mesh extruded one unit thick (u_z = 0, the in-plane field on every node
// layer) give the same in-plane internal forces (summed over the layers), Cauchy stresses
// (all six components) and plastic strains, with J2 past yield and total Lagrangian
// kinematics. Quad4 against Hex8 and Quad9 against Hex27.
TEUCHOS_UNIT_TEST(J2Plasticity3D, PlaneStrainEqualsTheThreeDLawWithZeroEpsZZ) {
  const std::pair<ElementType, ElementType> pairs[] = {{ElementType::Quad4, ElementType::Hex8},
                                                       {ElementType::Quad9, ElementType::Hex27}};
  for (const auto& pr : pairs) {
    const ElementMesh m2 =
        plasticity_test::latticeMesh(pr.first, 2, plasticity_test::randomVertices(0.2)).mesh;
    const int nn = m2.numNodes(), layers = plasticity::isQuadratic(pr.first) ? 3 : 2;
    ElementMesh m3{pr.second, {}, {}};
    for (int l = 0; l < layers; ++l)
      for (int n = 0; n < nn; ++n)
        m3.coords.insert(m3.coords.end(),
                         {m2.coords[2 * n], m2.coords[2 * n + 1], double(l) / (layers - 1)});
    // Hex node a: the quad node with the same (xi, eta), on the layer of its zeta.
    const int n2 = plasticity::nodesPerElement(pr.first),
              n3 = plasticity::nodesPerElement(pr.second);
    for (int e = 0; e < m2.numElements(); ++e)
      for (int a = 0; a < n3; ++a) {
        double X[3];
        plasticity::referenceNode(pr.second, a, X);
        for (int b = 0; b < n2; ++b) {
          double x[2];
          plasticity::referenceNode(pr.first, b, x);
          if (x[0] == X[0] && x[1] == X[1]) {
            const int layer = static_cast<int>(std::lround((X[2] + 1) / 2 * (layers - 1)));
            m3.connectivity.push_back(layer * nn + m2.connectivity[e * n2 + b]);
          }
        }
      }
    std::vector<double> u2(2 * nn), u3(3 * nn * layers, 0.0);
    for (int n = 0; n < nn; ++n) {
      const double x = m2.coords[2 * n], y = m2.coords[2 * n + 1];
      u2[2 * n] = 0.02 * x + 0.01 * y * y - 0.005 * x * y;
      u2[2 * n + 1] = -0.015 * y + 0.012 * x * x;
      for (int l = 0; l < layers; ++l)
        for (int i = 0; i < 2; ++i) u3[3 * (l * nn + n) + i] = u2[2 * n + i];
    }
    const int g2 = plasticity::numGaussPoints(pr.first), g3 = plasticity::numGaussPoints(pr.second);
    J2PlasticMaterial j2a(kE, kNu, kSy, kH, m2.numElements(), g2);
    J2PlasticMaterial j2b(kE, kNu, kSy, kH, m2.numElements(), g3);
    const std::vector<double> f2 = plasticity::internalForce(m2, j2a, u2);
    const std::vector<double> f3 = plasticity::internalForce(m3, j2b, u3);
    double fErr = 0.0;
    for (int n = 0; n < nn; ++n)
      for (int i = 0; i < 2; ++i) {
        double sum = 0.0;
        for (int l = 0; l < layers; ++l) sum += f3[3 * (l * nn + n) + i];
        fErr = std::max(fErr, std::abs(sum - f2[2 * n + i]));
      }
    const plasticity::StressField s2 = plasticity::cauchyStress(m2, j2a, u2);
    const plasticity::StressField s3 = plasticity::cauchyStress(m3, j2b, u3);
    double sErr = 0.0, sScale = 0.0;
    for (int n = 0; n < nn; ++n)
      for (int l = 0; l < layers; ++l)
        for (int c = 0; c < plasticity::kNumStressComponents; ++c) {
          sErr = std::max(sErr, std::abs(s3.atNode(l * nn + n, c) - s2.atNode(n, c)));
          sScale = std::max(sScale, std::abs(s2.atNode(n, c)));
        }
    double aMax2 = 0.0, aMax3 = 0.0;
    for (int e = 0; e < m2.numElements(); ++e) {
      for (int q = 0; q < g2; ++q)
        aMax2 = std::max(aMax2, j2a.trialEquivalentPlasticStrain({e, q}));
      for (int q = 0; q < g3; ++q)
        aMax3 = std::max(aMax3, j2b.trialEquivalentPlasticStrain({e, q}));
    }
    out << plasticity::elementTypeName(pr.first) << " vs " << plasticity::elementTypeName(pr.second)
        << ": |f2 - sum f3| / |f2| " << fErr / plasticity_test::maxAbs(f2) << ", nodal stress "
        << sErr / sScale << ", max alpha " << aMax2 << " / " << aMax3 << "\n";
    TEST_COMPARE(aMax2, >, 0.0);
    TEST_COMPARE(fErr / plasticity_test::maxAbs(f2), <, 1e-12);
    TEST_COMPARE(sErr / sScale, <, 1e-12);
    TEST_FLOATING_EQUALITY(aMax3, aMax2, 1e-12);
  }
}
