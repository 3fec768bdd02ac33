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

void J2PlasticMaterial::evaluate(const MaterialPointId& where, const double strain[3],
                                 MaterialResponse& out) const {
  checkPoint(where);
  const int e = where.element, g = where.gaussPoint;
  const double l = elastic_.lambda(), m = elastic_.mu();
  const double epXX = committed_(e, g, kEpXX), epYY = committed_(e, g, kEpYY),
               epXY = committed_(e, g, kEpXY), epZZ = committed_(e, g, kEpZZ),
               alpha = committed_(e, g, kAlpha);

  // Elastic strain with eps_zz = 0; written as LinearElasticMaterial does so that, with no
  // plastic strain, the elastic response is bit-for-bit the linear elastic one.
  const double exx = strain[0] - epXX, eyy = strain[1] - epYY, gxy = strain[2] - 2 * epXY,
               ezz = -epZZ;
  const double trace = exx + eyy + ezz;
  double s[4] = {l * trace + 2 * m * exx, l * trace + 2 * m * eyy, m * gxy,
                 l * trace + 2 * m * ezz};

  const double p = (s[0] + s[1] + s[3]) / 3.0;
  const double dev[4] = {s[0] - p, s[1] - p, s[2], s[3] - p};  // (xx, yy, xy, zz)
  const double devNorm2 = dev[0] * dev[0] + dev[1] * dev[1] + dev[3] * dev[3] + 2 * dev[2] * dev[2];
  const double qTrial = std::sqrt(1.5 * devNorm2);
  const double f = qTrial - (yieldStress_ + hardening_ * alpha);

  if (f <= 0.0) {
    for (int c = 0; c < 4; ++c) out.stress[c] = s[c];
    elastic_.planeStrainMatrix(out.tangent);
    trial_(e, g, kEpXX) = epXX;
    trial_(e, g, kEpYY) = epYY;
    trial_(e, g, kEpXY) = epXY;
    trial_(e, g, kEpZZ) = epZZ;
    trial_(e, g, kAlpha) = alpha;
    return;
  }

  // Radial return. With sigma_y linear in alpha the consistency condition
  // qTrial - 3 mu dGamma = yieldStress + H (alpha + dGamma) is linear in dGamma.
  const double dGamma = f / (3 * m + hardening_);
  const double shrink = 3 * m * dGamma / qTrial;  // f > 0 implies qTrial > 0
  for (int c = 0; c < 4; ++c) out.stress[c] = s[c] - shrink * dev[c];

  // Flow direction df/dsigma = 3/2 dev / q, the same for trial and returned stress.
  const double flow = 1.5 * dGamma / qTrial;
  trial_(e, g, kEpXX) = epXX + flow * dev[0];
  trial_(e, g, kEpYY) = epYY + flow * dev[1];
  trial_(e, g, kEpXY) = epXY + flow * dev[2];
  trial_(e, g, kEpZZ) = epZZ + flow * dev[3];
  trial_(e, g, kAlpha) = alpha + dGamma;

  // Consistent tangent (Simo & Hughes, Box 3.2):
  //   C = K 1(x)1 + 2 mu theta I_dev - 2 mu thetaBar n(x)n,  n = dev / |dev|,
  //   theta = 1 - 3 mu dGamma / qTrial,  thetaBar = 3 mu / (3 mu + H) - (1 - theta).
  // Only the (xx, yy, xy) rows and columns are needed because eps_zz is prescribed; against
  // engineering shear the xy column of n(x)n carries n_xy once and I_dev's shear entry is 1/2.
  const double K = l + 2.0 * m / 3.0;
  const double theta = 1.0 - shrink;
  const double thetaBar = 3 * m / (3 * m + hardening_) - shrink;
  const double invNorm = 1.0 / std::sqrt(devNorm2);
  const double n[3] = {dev[0] * invNorm, dev[1] * invNorm, dev[2] * invNorm};
  const double Idev[9] = {2.0 / 3, -1.0 / 3, 0, -1.0 / 3, 2.0 / 3, 0, 0, 0, 0.5};
  const double bulk[9] = {1, 1, 0, 1, 1, 0, 0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      out.tangent[3 * i + j] =
          K * bulk[3 * i + j] + 2 * m * theta * Idev[3 * i + j] - 2 * m * thetaBar * n[i] * n[j];
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

void J2PlasticMaterial::plasticStrain(const MaterialPointId& where, double ep[4]) const {
  checkPoint(where);
  for (int c = 0; c < 4; ++c) ep[c] = committed_(where.element, where.gaussPoint, kEpXX + c);
}

void J2PlasticMaterial::trialPlasticStrain(const MaterialPointId& where, double ep[4]) const {
  checkPoint(where);
  for (int c = 0; c < 4; ++c) ep[c] = trial_(where.element, where.gaussPoint, kEpXX + c);
}

}  // namespace plasticity
