// Unit tests of the plane-strain J2 law (plasticity_J2Plasticity): the elastic range against
// LinearElasticMaterial, closed-form radial return on plane-strain pure shear and on a general
// proportional path, the consistent tangent against central differences, elastic unloading,
// commit/revert of the history, and parameter checks.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "plasticity_Elements.hpp"
#include "plasticity_J2Plasticity.hpp"
#include "plasticity_MaterialLaw.hpp"

namespace {

using plasticity::evaluatePlaneStrain;
using plasticity::J2PlasticMaterial;
using plasticity::LinearElasticMaterial;
using plasticity::MaterialPointId;
using plasticity::PlaneStrainResponse;
using plasticity::vonMises;

// Steel-like, in MPa; H large enough that hardening shows clearly in the stresses.
constexpr double kE = 200000.0, kNu = 0.3, kSy = 250.0, kH = 10000.0;
const double kSqrt3 = std::sqrt(3.0);

double mu() {
  return kE / (2.0 * (1.0 + kNu));
}

double vm(const PlaneStrainResponse& r) {
  return vonMises(r.stress[0], r.stress[1], r.stress[2], r.stress[3]);
}

// Shear strain gamma_xy at first yield in simple shear: sqrt(3) mu gamma = sigma_y.
double shearYieldStrain() {
  return kSy / (kSqrt3 * mu());
}

// max |A - B| / max |B| over the 3x3 tangent.
double tangentError(const double A[9], const double B[9]) {
  double diff = 0.0, scale = 0.0;
  for (int k = 0; k < 9; ++k) {
    diff = std::max(diff, std::abs(A[k] - B[k]));
    scale = std::max(scale, std::abs(B[k]));
  }
  return diff / scale;
}

// Central differences of (sigma_xx, sigma_yy, sigma_xy) in the strain at `where`; evaluate()
// only reads committed history, so the probes do not disturb one another.
void finiteDifferenceTangent(const J2PlasticMaterial& law, const MaterialPointId& where,
                             const double strain[3], double h, double D[9]) {
  for (int j = 0; j < 3; ++j) {
    double ep[3] = {strain[0], strain[1], strain[2]}, em[3] = {strain[0], strain[1], strain[2]};
    ep[j] += h;
    em[j] -= h;
    PlaneStrainResponse rp, rm;
    evaluatePlaneStrain(law, where, ep, rp);
    evaluatePlaneStrain(law, where, em, rm);
    for (int i = 0; i < 3; ++i) D[3 * i + j] = (rp.stress[i] - rm.stress[i]) / (2 * h);
  }
}

TEUCHOS_UNIT_TEST(J2Plasticity, ElasticBelowYieldMatchesLinearElastic) {
  J2PlasticMaterial j2(kE, kNu, kSy, kH, 3, 4);
  LinearElasticMaterial lin(kE, kNu);
  const double directions[4][3] = {{1, 0, 0}, {0.3, -0.8, 0.5}, {-1, -1, 0}, {0, 0, 1}};
  for (const auto& d : directions) {
    // Scale to 90% of first yield. Even (-1, -1, 0) has a deviator in plane strain, because
    // sigma_zz = lambda tr(eps) differs from sigma_xx = sigma_yy.
    PlaneStrainResponse unit;
    evaluatePlaneStrain(lin, {}, d, unit);
    const double s = 0.9 * kSy / vm(unit);
    const double strain[3] = {s * d[0], s * d[1], s * d[2]};
    PlaneStrainResponse a, b;
    const MaterialPointId where{2, 3};
    evaluatePlaneStrain(j2, where, strain, a);
    evaluatePlaneStrain(lin, {}, strain, b);
    for (int c = 0; c < 4; ++c) TEST_EQUALITY(a.stress[c], b.stress[c]);
    for (int k = 0; k < 9; ++k) TEST_EQUALITY(a.tangent[k], b.tangent[k]);
    TEST_EQUALITY(j2.trialEquivalentPlasticStrain(where), 0.0);
  }
}

// Simple shear gamma_xy = gamma (eps_xx = eps_yy = 0). The trial stress is pure shear,
// sigma_xy = mu gamma, with a deviator that has no normal components, so the flow is pure
// shear too: eps_zz^p = 0 and sigma_zz stays 0. With q = sqrt(3) sigma_xy and plastic shear
// gamma^p = sqrt(3) alpha, consistency gives
//   alpha = (sqrt(3) mu gamma - sigma_y) / (3 mu + H),  sigma_xy = (sigma_y + H alpha) / sqrt(3),
// so von Mises = sigma_y + H alpha (= sigma_y for H = 0). The path is radial, so reaching gamma
// in many committed increments must give the same state as one increment.
TEUCHOS_UNIT_TEST(J2Plasticity, SimpleShearClosedForm) {
  for (const double H : {kH, 0.0}) {
    const double gamma = 3.0 * shearYieldStrain();
    const double alpha = (kSqrt3 * mu() * gamma - kSy) / (3 * mu() + H);
    const double sxy = (kSy + H * alpha) / kSqrt3;
    const MaterialPointId where{0, 0};

    J2PlasticMaterial once(kE, kNu, kSy, H, 1, 1);
    const double strain[3] = {0, 0, gamma};
    PlaneStrainResponse r;
    evaluatePlaneStrain(once, where, strain, r);
    once.commit();
    TEST_FLOATING_EQUALITY(r.stress[2], sxy, 1e-10);
    for (int c : {0, 1, 3}) TEST_COMPARE(std::abs(r.stress[c]), <=, 1e-12 * kSy);
    TEST_FLOATING_EQUALITY(once.equivalentPlasticStrain(where), alpha, 1e-10);
    TEST_FLOATING_EQUALITY(vm(r), kSy + H * alpha, 1e-10);
    double ep[plasticity::kNumVoigt];  // (xx, yy, zz, yz, xz, xy), tensor shears
    once.plasticStrain(where, ep);
    TEST_FLOATING_EQUALITY(2 * ep[plasticity::kXY], kSqrt3 * alpha, 1e-10);
    for (int c : {0, 1, 2, 3, 4}) TEST_COMPARE(std::abs(ep[c]), <=, 1e-14);
    // The hardening slope of this path: d sigma_xy / d gamma = mu H / (3 mu + H).
    // (Absolute against mu because the slope vanishes for H = 0.)
    TEST_COMPARE(std::abs(r.tangent[8] - mu() * H / (3 * mu() + H)), <=, 1e-10 * mu());

    J2PlasticMaterial steps(kE, kNu, kSy, H, 1, 1);
    const int n = 12;
    PlaneStrainResponse s;
    for (int k = 1; k <= n; ++k) {
      const double g[3] = {0, 0, gamma * k / n};
      evaluatePlaneStrain(steps, where, g, s);
      steps.commit();
      const double a = steps.equivalentPlasticStrain(where);
      // Every step past yield stays on the (hardening) yield surface.
      if (a > 0) TEST_FLOATING_EQUALITY(vm(s), kSy + H * a, 1e-10);
    }
    for (int c = 0; c < 4; ++c) TEST_COMPARE(std::abs(s.stress[c] - r.stress[c]), <=, 1e-10 * kSy);
    TEST_FLOATING_EQUALITY(steps.equivalentPlasticStrain(where), alpha, 1e-10);
  }
}

// Plane-strain pure shear the other way: eps_xx = -eps_yy = e. The trial stress is
// sigma_xx = -sigma_yy = 2 mu e, sigma_zz = lambda * 0 = 0, a deviator with zero zz component,
// so again eps_zz^p = 0 and sigma_zz = 0. Here q_trial = 2 sqrt(3) mu e and
//   alpha = (2 sqrt(3) mu e - sigma_y) / (3 mu + H),  sigma_xx = -sigma_yy = (sigma_y + H
//   alpha)/sqrt(3).
TEUCHOS_UNIT_TEST(J2Plasticity, NormalPureShearClosedForm) {
  const double e = 2.5 * kSy / (2 * kSqrt3 * mu());
  const double alpha = (2 * kSqrt3 * mu() * e - kSy) / (3 * mu() + kH);
  const double sxx = (kSy + kH * alpha) / kSqrt3;
  J2PlasticMaterial j2(kE, kNu, kSy, kH, 1, 1);
  const double strain[3] = {e, -e, 0};
  PlaneStrainResponse r;
  evaluatePlaneStrain(j2, {0, 0}, strain, r);
  TEST_FLOATING_EQUALITY(r.stress[0], sxx, 1e-10);
  TEST_FLOATING_EQUALITY(r.stress[1], -sxx, 1e-10);
  TEST_COMPARE(std::abs(r.stress[2]), <=, 1e-12 * kSy);
  TEST_COMPARE(std::abs(r.stress[3]), <=, 1e-12 * kSy);
  TEST_FLOATING_EQUALITY(j2.trialEquivalentPlasticStrain({0, 0}), alpha, 1e-10);
  TEST_FLOATING_EQUALITY(vm(r), kSy + kH * alpha, 1e-10);
}

// A general proportional strain path eps(t) = t d with volume change (so sigma_zz != 0). The
// deviatoric strain keeps its direction, hence so do the trial deviator and the plastic flow:
// radial return is exact along the path, alpha = (q_trial - sigma_y) / (3 mu + H) with q_trial
// the von Mises stress of the purely elastic response, and many increments equal one.
TEUCHOS_UNIT_TEST(J2Plasticity, ProportionalPathIncrementsMatchOneStep) {
  const double d[3] = {1.0, -0.4, 0.7};
  LinearElasticMaterial lin(kE, kNu);
  PlaneStrainResponse unit;
  evaluatePlaneStrain(lin, {}, d, unit);
  const double t = 4.0 * kSy / vm(unit);  // four times the strain at first yield
  const double strain[3] = {t * d[0], t * d[1], t * d[2]};
  PlaneStrainResponse elastic;
  evaluatePlaneStrain(lin, {}, strain, elastic);
  const double alpha = (vm(elastic) - kSy) / (3 * mu() + kH);

  const MaterialPointId where{1, 2};
  J2PlasticMaterial once(kE, kNu, kSy, kH, 2, 3);
  PlaneStrainResponse r;
  evaluatePlaneStrain(once, where, strain, r);
  TEST_FLOATING_EQUALITY(once.trialEquivalentPlasticStrain(where), alpha, 1e-10);
  TEST_FLOATING_EQUALITY(vm(r), kSy + kH * alpha, 1e-10);
  TEST_COMPARE(std::abs(r.stress[3]), >, 1.0);  // sigma_zz really takes part

  J2PlasticMaterial steps(kE, kNu, kSy, kH, 2, 3);
  const int n = 20;
  PlaneStrainResponse s;
  for (int k = 1; k <= n; ++k) {
    const double e[3] = {strain[0] * k / n, strain[1] * k / n, strain[2] * k / n};
    evaluatePlaneStrain(steps, where, e, s);
    steps.commit();
  }
  for (int c = 0; c < 4; ++c) TEST_COMPARE(std::abs(s.stress[c] - r.stress[c]), <=, 1e-10 * kSy);
  TEST_FLOATING_EQUALITY(steps.equivalentPlasticStrain(where), alpha, 1e-10);
  double epOnce[plasticity::kNumVoigt], epSteps[plasticity::kNumVoigt];
  once.trialPlasticStrain(where, epOnce);
  steps.plasticStrain(where, epSteps);
  for (int c = 0; c < plasticity::kNumVoigt; ++c)
    TEST_COMPARE(std::abs(epSteps[c] - epOnce[c]), <=, 1e-10 * alpha);
}

// The consistent tangent against central differences: elastic, first plastic step from the
// virgin state, a non-radial plastic step from committed plastic history, and perfect
// plasticity. Strains are O(1e-3), so h = 1e-8 keeps truncation and round-off far below 1e-6.
TEUCHOS_UNIT_TEST(J2Plasticity, ConsistentTangentMatchesFiniteDifferences) {
  const double h = 1e-8;
  const double gy = shearYieldStrain();
  for (const double H : {kH, 0.0}) {
    J2PlasticMaterial j2(kE, kNu, kSy, H, 2, 1);
    const MaterialPointId virgin{0, 0}, loaded{1, 0};

    const double elasticStrain[3] = {0.2 * gy, -0.1 * gy, 0.3 * gy};
    const double plasticStrain[3] = {1.5 * gy, -0.7 * gy, 2.0 * gy};
    for (const double* e : {elasticStrain, plasticStrain}) {
      PlaneStrainResponse r;
      evaluatePlaneStrain(j2, virgin, e, r);
      double D[9];
      finiteDifferenceTangent(j2, virgin, e, h, D);
      TEST_COMPARE(tangentError(r.tangent, D), <=, 1e-6);
    }

    // Commit plastic history at `loaded`, then load in another direction.
    const double first[3] = {0, 0, 3 * gy};
    PlaneStrainResponse r0;
    evaluatePlaneStrain(j2, loaded, first, r0);
    j2.commit();
    TEST_COMPARE(j2.equivalentPlasticStrain(loaded), >, 0.0);
    const double second[3] = {2.0 * gy, 0.5 * gy, 3 * gy};
    PlaneStrainResponse r;
    evaluatePlaneStrain(j2, loaded, second, r);
    TEST_COMPARE(j2.trialEquivalentPlasticStrain(loaded), >, j2.equivalentPlasticStrain(loaded));
    double D[9];
    finiteDifferenceTangent(j2, loaded, second, h, D);
    TEST_COMPARE(tangentError(r.tangent, D), <=, 1e-6);
    // Associative flow with linear hardening keeps the tangent symmetric.
    TEST_COMPARE(std::abs(r.tangent[1] - r.tangent[3]), <=, 1e-10 * std::abs(r.tangent[0]));
    TEST_COMPARE(std::abs(r.tangent[2] - r.tangent[6]), <=, 1e-10 * std::abs(r.tangent[0]));
    TEST_COMPARE(std::abs(r.tangent[5] - r.tangent[7]), <=, 1e-10 * std::abs(r.tangent[0]));
  }
}

// Unloading from a committed plastic state in simple shear is elastic: the stress drops by
// mu * (change of gamma), the tangent is the elastic one and the history is untouched. The
// elastic range after hardening spans 2 (sigma_y + H alpha) / (sqrt(3) mu) in gamma.
TEUCHOS_UNIT_TEST(J2Plasticity, UnloadingAfterYieldIsElastic) {
  const double gy = shearYieldStrain();
  J2PlasticMaterial j2(kE, kNu, kSy, kH, 1, 1);
  LinearElasticMaterial lin(kE, kNu);
  const MaterialPointId where{0, 0};
  const double loaded[3] = {0, 0, 3 * gy};
  PlaneStrainResponse r1;
  evaluatePlaneStrain(j2, where, loaded, r1);
  j2.commit();
  const double alpha = j2.equivalentPlasticStrain(where);
  double ep1[plasticity::kNumVoigt];
  j2.plasticStrain(where, ep1);
  TEST_COMPARE(alpha, >, 0.0);

  // Back by 1.5 gamma_y: still inside the (grown) elastic range, sigma_xy turns negative.
  for (const double back : {0.5 * gy, 1.5 * gy}) {
    const double unloaded[3] = {0, 0, 3 * gy - back};
    PlaneStrainResponse r2;
    evaluatePlaneStrain(j2, where, unloaded, r2);
    TEST_FLOATING_EQUALITY(r2.stress[2], r1.stress[2] - mu() * back, 1e-10);
    TEST_COMPARE(vm(r2), <, kSy + kH * alpha);
    PlaneStrainResponse el;
    evaluatePlaneStrain(lin, {}, unloaded, el);
    for (int k = 0; k < 9; ++k) TEST_EQUALITY(r2.tangent[k], el.tangent[k]);
    TEST_EQUALITY(j2.trialEquivalentPlasticStrain(where), alpha);
    double ep2[plasticity::kNumVoigt];
    j2.trialPlasticStrain(where, ep2);
    for (int c = 0; c < plasticity::kNumVoigt; ++c) TEST_EQUALITY(ep2[c], ep1[c]);
  }
  // Committing the unloaded state keeps the plastic strain.
  j2.commit();
  TEST_EQUALITY(j2.equivalentPlasticStrain(where), alpha);
}

// revert() throws away trial history at every point and leaves the committed state; evaluate()
// never touches other points.
TEUCHOS_UNIT_TEST(J2Plasticity, RevertRestoresCommittedState) {
  const double gy = shearYieldStrain();
  J2PlasticMaterial j2(kE, kNu, kSy, kH, 2, 2);
  const MaterialPointId a{0, 1}, b{1, 0}, untouched{1, 1};
  const double first[3] = {0, 0, 2 * gy};
  PlaneStrainResponse rFirst;
  evaluatePlaneStrain(j2, a, first, rFirst);
  j2.commit();
  const double alphaA = j2.equivalentPlasticStrain(a);
  TEST_COMPARE(alphaA, >, 0.0);

  // A rejected step: more plastic flow at a, first plastic flow at b.
  const double further[3] = {gy, 0, 4 * gy};
  PlaneStrainResponse r;
  evaluatePlaneStrain(j2, a, further, r);
  evaluatePlaneStrain(j2, b, further, r);
  TEST_COMPARE(j2.trialEquivalentPlasticStrain(a), >, alphaA);
  TEST_COMPARE(j2.trialEquivalentPlasticStrain(b), >, 0.0);
  TEST_EQUALITY(j2.equivalentPlasticStrain(b), 0.0);
  TEST_EQUALITY(j2.trialEquivalentPlasticStrain(untouched), 0.0);

  j2.revert();
  TEST_EQUALITY(j2.trialEquivalentPlasticStrain(a), alphaA);
  TEST_EQUALITY(j2.trialEquivalentPlasticStrain(b), 0.0);
  double epC[plasticity::kNumVoigt], epT[plasticity::kNumVoigt];
  j2.plasticStrain(a, epC);
  j2.trialPlasticStrain(a, epT);
  for (int c = 0; c < plasticity::kNumVoigt; ++c) TEST_EQUALITY(epT[c], epC[c]);
  // A commit right after revert changes nothing, and the committed state answers as before.
  j2.commit();
  TEST_EQUALITY(j2.equivalentPlasticStrain(a), alphaA);
  TEST_EQUALITY(j2.equivalentPlasticStrain(b), 0.0);
  PlaneStrainResponse again;
  evaluatePlaneStrain(j2, a, first, again);
  for (int c = 0; c < 4; ++c)
    TEST_COMPARE(std::abs(again.stress[c] - rFirst.stress[c]), <=, 1e-12 * kSy);
}

// std::invalid_argument whose message contains `name`.
template <class F>
bool throwsNaming(F&& f, const std::string& name) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return std::string(e.what()).find(name) != std::string::npos;
  }
  return false;
}

TEUCHOS_UNIT_TEST(J2Plasticity, InvalidParametersThrow) {
  const double nan = std::nan("");
  auto make = [](double E, double nu, double sy, double H, int ne, int ng) {
    return [=] {
      J2PlasticMaterial law(E, nu, sy, H, ne, ng);
      (void)law;
    };
  };
  TEST_ASSERT(throwsNaming(make(0.0, kNu, kSy, kH, 1, 1), "Young"));
  TEST_ASSERT(throwsNaming(make(-kE, kNu, kSy, kH, 1, 1), "Young"));
  TEST_ASSERT(throwsNaming(make(kE, 0.5, kSy, kH, 1, 1), "Poisson"));
  TEST_ASSERT(throwsNaming(make(kE, -1.0, kSy, kH, 1, 1), "Poisson"));
  TEST_ASSERT(throwsNaming(make(kE, kNu, 0.0, kH, 1, 1), "yield stress"));
  TEST_ASSERT(throwsNaming(make(kE, kNu, nan, kH, 1, 1), "yield stress"));
  TEST_ASSERT(throwsNaming(make(kE, kNu, kSy, -1.0, 1, 1), "hardening modulus"));
  TEST_ASSERT(throwsNaming(make(kE, kNu, kSy, nan, 1, 1), "hardening modulus"));
  TEST_ASSERT(throwsNaming(make(kE, kNu, kSy, kH, 0, 1), "number of elements"));
  TEST_ASSERT(throwsNaming(make(kE, kNu, kSy, kH, 1, 0), "Gauss points"));
  TEST_NOTHROW(J2PlasticMaterial(kE, kNu, kSy, 0.0, 1, 1));

  // Points outside the history arrays are refused rather than read out of bounds.
  J2PlasticMaterial j2(kE, kNu, kSy, kH, 2, 3);
  const double strain[3] = {0, 0, 0};
  PlaneStrainResponse r;
  TEST_THROW(evaluatePlaneStrain(j2, {2, 0}, strain, r), std::out_of_range);
  TEST_THROW(evaluatePlaneStrain(j2, {0, 3}, strain, r), std::out_of_range);
  TEST_THROW(evaluatePlaneStrain(j2, {-1, 0}, strain, r), std::out_of_range);
  TEST_THROW(j2.equivalentPlasticStrain({0, -1}), std::out_of_range);
}

}  // namespace
