#pragma once
// Isotropic linear elasticity: the constitutive law behind which J2 plasticity sits. Stress and
// strain in the package's Voigt order (xx, yy, zz, yz, xz, xy) with engineering shear strains
// (gamma_ij = 2 eps_ij), see plasticity_MaterialLaw.hpp.
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

  // C (6x6, row-major) with sigma = C * strain in Voigt order.
  void voigtMatrix(double C[36]) const {
    const double l = lambda(), m = mu();
    for (int k = 0; k < 36; ++k) C[k] = 0;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) C[6 * i + j] = l;
      C[7 * i] = l + 2 * m;
      C[7 * (i + 3)] = m;
    }
  }

  // The plane-strain D (3x3, row-major, strain (xx, yy, xy)): the in-plane block of voigtMatrix.
  void planeStrainMatrix(double D[9]) const {
    double C[36];
    voigtMatrix(C);
    const int in[3] = {0, 1, 5};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) D[3 * i + j] = C[6 * in[i] + in[j]];
  }
};

}  // namespace plasticity
