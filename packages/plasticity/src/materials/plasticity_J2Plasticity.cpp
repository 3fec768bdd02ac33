#include "plasticity_J2Plasticity.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace plasticity {

J2PlasticMaterial::J2PlasticMaterial(double youngs, double poisson, double yieldStress,
                                     double hardeningModulus, int numElements,
                                     int gaussPointsPerElement)
    : elastic_(youngs, poisson),
      yieldStress_(yieldStress),
      hardening_(hardeningModulus),
      numElements_(numElements),
      gaussPoints_(gaussPointsPerElement) {
  // Negated comparisons so that NaN is rejected too.
  if (!(yieldStress > 0.0) || !std::isfinite(yieldStress))
    throw std::invalid_argument("yield stress must be positive and finite, got " +
                                std::to_string(yieldStress));
  if (!(hardeningModulus >= 0.0) || !std::isfinite(hardeningModulus))
    throw std::invalid_argument("hardening modulus must be non-negative and finite, got " +
                                std::to_string(hardeningModulus));
  if (numElements < 1)
    throw std::invalid_argument("number of elements must be positive, got " +
                                std::to_string(numElements));
  if (gaussPointsPerElement < 1)
    throw std::invalid_argument("Gauss points per element must be positive, got " +
                                std::to_string(gaussPointsPerElement));
  // Views are zero-initialised: the virgin state has no plastic strain.
  committed_ = History("J2 committed history", numElements, gaussPointsPerElement, kNumHistory);
  trial_ = History("J2 trial history", numElements, gaussPointsPerElement, kNumHistory);
}

void J2PlasticMaterial::checkPoint(const MaterialPointId& where) const {
  if (where.element < 0 || where.element >= numElements_ || where.gaussPoint < 0 ||
      where.gaussPoint >= gaussPoints_)
    throw std::out_of_range("J2 material point (element " + std::to_string(where.element) +
                            ", Gauss point " + std::to_string(where.gaussPoint) + ") outside " +
                            std::to_string(numElements_) + " x " + std::to_string(gaussPoints_));
}

void J2PlasticMaterial::evaluate(const MaterialPointId& where, const double strain[kNumVoigt],
                                 MaterialResponse& out) const {
  checkPoint(where);
  const int e = where.element, g = where.gaussPoint;
  const double l = elastic_.lambda(), m = elastic_.mu();
  double ep[kNumVoigt];
  for (int c = 0; c < kNumVoigt; ++c) ep[c] = committed_(e, g, kEp + c);
  const double alpha = committed_(e, g, kAlpha);

  // Elastic strain (engineering shears, while the history holds tensor shears); the stress is
  // written as LinearElasticMaterial writes it so that, with no plastic strain, the elastic
  // response is bit-for-bit the linear elastic one.
  double ee[kNumVoigt];
  for (int c = 0; c < 3; ++c) ee[c] = strain[c] - ep[c];
  for (int c = 3; c < kNumVoigt; ++c) ee[c] = strain[c] - 2 * ep[c];
  const double trace = ee[kXX] + ee[kYY] + ee[kZZ];
  double s[kNumVoigt];
  for (int c = 0; c < 3; ++c) s[c] = l * trace + 2 * m * ee[c];
  for (int c = 3; c < kNumVoigt; ++c) s[c] = m * ee[c];

  const double p = (s[kXX] + s[kYY] + s[kZZ]) / 3.0;
  double dev[kNumVoigt];  // the deviator, tensor shears (= the shear stresses)
  for (int c = 0; c < kNumVoigt; ++c) dev[c] = c < 3 ? s[c] - p : s[c];
  // |dev|^2 with each shear counted twice (dev_ij = dev_ji). The xy shear is added first so
  // that plane strain (zero yz, xz) sums exactly as the plane-strain law always did.
  const double devNorm2 = dev[kXX] * dev[kXX] + dev[kYY] * dev[kYY] + dev[kZZ] * dev[kZZ] +
                          2 * dev[kXY] * dev[kXY] + 2 * dev[kYZ] * dev[kYZ] +
                          2 * dev[kXZ] * dev[kXZ];
  const double qTrial = std::sqrt(1.5 * devNorm2);
  const double f = qTrial - (yieldStress_ + hardening_ * alpha);

  if (f <= 0.0) {
    for (int c = 0; c < kNumVoigt; ++c) out.stress[c] = s[c];
    elastic_.voigtMatrix(out.tangent);
    for (int c = 0; c < kNumVoigt; ++c) trial_(e, g, kEp + c) = ep[c];
    trial_(e, g, kAlpha) = alpha;
    return;
  }

  // Radial return. With sigma_y linear in alpha the consistency condition
  // qTrial - 3 mu dGamma = yieldStress + H (alpha + dGamma) is linear in dGamma.
  const double dGamma = f / (3 * m + hardening_);
  const double shrink = 3 * m * dGamma / qTrial;  // f > 0 implies qTrial > 0
  for (int c = 0; c < kNumVoigt; ++c) out.stress[c] = s[c] - shrink * dev[c];

  // Flow direction df/dsigma = 3/2 dev / q, the same for trial and returned stress.
  const double flow = 1.5 * dGamma / qTrial;
  for (int c = 0; c < kNumVoigt; ++c) trial_(e, g, kEp + c) = ep[c] + flow * dev[c];
  trial_(e, g, kAlpha) = alpha + dGamma;

  // Consistent tangent (Simo & Hughes, Box 3.2):
  //   C = K 1(x)1 + 2 mu theta I_dev - 2 mu thetaBar n(x)n,  n = dev / |dev|,
  //   theta = 1 - 3 mu dGamma / qTrial,  thetaBar = 3 mu / (3 mu + H) - (1 - theta).
  // Against engineering shear strains a shear column of n(x)n carries the tensor component
  // n_ij once (eps_ij and eps_ji both move) and I_dev's shear diagonal is 1/2.
  const double K = l + 2.0 * m / 3.0;
  const double theta = 1.0 - shrink;
  const double thetaBar = 3 * m / (3 * m + hardening_) - shrink;
  const double invNorm = 1.0 / std::sqrt(devNorm2);
  double n[kNumVoigt];
  for (int c = 0; c < kNumVoigt; ++c) n[c] = dev[c] * invNorm;
  for (int i = 0; i < kNumVoigt; ++i)
    for (int j = 0; j < kNumVoigt; ++j) {
      const bool normal = i < 3 && j < 3;
      const double bulk = normal ? 1.0 : 0.0;
      const double Idev = normal ? (i == j ? 2.0 / 3 : -1.0 / 3) : (i == j ? 0.5 : 0.0);
      out.tangent[kNumVoigt * i + j] =
          K * bulk + 2 * m * theta * Idev - 2 * m * thetaBar * n[i] * n[j];
    }
}

void J2PlasticMaterial::commit() {
  Kokkos::deep_copy(committed_, trial_);
}

void J2PlasticMaterial::revert() {
  Kokkos::deep_copy(trial_, committed_);
}

std::vector<double> J2PlasticMaterial::committedHistory() const {
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(numElements_) * gaussPoints_ * kNumHistory);
  for (int e = 0; e < numElements_; ++e)
    for (int g = 0; g < gaussPoints_; ++g)
      for (int k = 0; k < kNumHistory; ++k) out.push_back(committed_(e, g, k));
  return out;
}

void J2PlasticMaterial::setCommittedHistory(const std::vector<double>& values) {
  const std::size_t n = static_cast<std::size_t>(numElements_) * gaussPoints_ * kNumHistory;
  if (values.size() != n)
    throw std::invalid_argument("J2 history: " + std::to_string(values.size()) +
                                " values, expected " + std::to_string(n));
  std::size_t i = 0;
  for (int e = 0; e < numElements_; ++e)
    for (int g = 0; g < gaussPoints_; ++g)
      for (int k = 0; k < kNumHistory; ++k) committed_(e, g, k) = values[i++];
  revert();
}

double J2PlasticMaterial::equivalentPlasticStrain(const MaterialPointId& where) const {
  checkPoint(where);
  return committed_(where.element, where.gaussPoint, kAlpha);
}

double J2PlasticMaterial::trialEquivalentPlasticStrain(const MaterialPointId& where) const {
  checkPoint(where);
  return trial_(where.element, where.gaussPoint, kAlpha);
}

void J2PlasticMaterial::plasticStrain(const MaterialPointId& where, double ep[kNumVoigt]) const {
  checkPoint(where);
  for (int c = 0; c < kNumVoigt; ++c) ep[c] = committed_(where.element, where.gaussPoint, kEp + c);
}

void J2PlasticMaterial::trialPlasticStrain(const MaterialPointId& where,
                                           double ep[kNumVoigt]) const {
  checkPoint(where);
  for (int c = 0; c < kNumVoigt; ++c) ep[c] = trial_(where.element, where.gaussPoint, kEp + c);
}

}  // namespace plasticity
