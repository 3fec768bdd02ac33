#pragma once
// Isotropic linear elasticity in plane strain: the constitutive law behind which J2
// plasticity will later sit. Stress and strain in Voigt order (xx, yy, xy) with engineering
// shear strain.
#include <stdexcept>
#include <string>

namespace plasticity {

struct ElasticLaw {
  double E = 1.0;
  double nu = 0.3;

  ElasticLaw() = default;
  ElasticLaw(double youngs, double poisson) : E(youngs), nu(poisson) {
    if (!(E > 0.0))
      throw std::invalid_argument("Young's modulus must be positive, got " + std::to_string(E));
    if (!(nu > -1.0 && nu < 0.5))
      throw std::invalid_argument("Poisson's ratio must lie in (-1, 0.5), got " +
                                  std::to_string(nu));
  }

  double lambda() const { return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)); }
  double mu() const { return E / (2.0 * (1.0 + nu)); }

  // D (3x3, row-major) with sigma = D * strain in plane strain.
  void planeStrainMatrix(double D[9]) const {
    const double l = lambda(), m = mu();
    D[0] = l + 2 * m;
    D[1] = l;
    D[2] = 0;
    D[3] = l;
    D[4] = l + 2 * m;
    D[5] = 0;
    D[6] = 0;
    D[7] = 0;
    D[8] = m;
  }
};

}  // namespace plasticity
