#pragma once
// The material-point interface between the element kernels and a constitutive law, in full 3D.
//
// Voigt order: strain and stress have 6 components in the order (xx, yy, zz, yz, xz, xy), with
// engineering shear strains gamma_ij = 2 eps_ij; the tangent is the 6x6 d(stress)/d(strain) in
// the same order (row-major). Plane strain is the special case of the same law, not a second
// copy: the 2D kernels pass eps_zz = gamma_yz = gamma_xz = 0 and use the in-plane block (rows and
// columns xx, yy, xy), while sigma_zz, which plane strain does not make vanish, is still there
// for von Mises (hence for J2 yield).
//
// How a history law (J2) plugs in: the kernels call evaluate() once per Gauss point with the
// point's identity (element, Gauss point) and its total strain. The law keeps its history
// variables in Kokkos::Views of extent numElements x numGaussPoints that it owns, reads the
// committed state at `where` and writes the trial state there (a const method may write through
// a View handle), and exposes commit() for the nonlinear solver after a converged load step.
// Total Lagrangian kinematics pass the Green-Lagrange strain and receive the second
// Piola-Kirchhoff stress through the same call; the geometric stiffness is the kernel's
// business, not the law's.
//
// The interface is virtual: the kernels run on the Serial (host) backend, where a virtual call
// per Gauss point costs nothing next to the B^T D B product. A device backend would need the
// law as a template parameter of the kernels instead; the value types below already fit that.
#include "plasticity_ElasticLaw.hpp"

namespace plasticity {

// Voigt indices of the components.
enum VoigtComponent { kXX = 0, kYY, kZZ, kYZ, kXZ, kXY, kNumVoigt };

// Which integration point is being evaluated: the key of per-point history variables.
struct MaterialPointId {
  int element = 0;
  int gaussPoint = 0;
};

// What a law returns at one material point.
struct MaterialResponse {
  double stress[kNumVoigt] = {0, 0, 0, 0, 0, 0};
  // d stress / d strain, 6x6 row-major: the consistent tangent the stiffness is assembled from.
  double tangent[kNumVoigt * kNumVoigt] = {};
};

class MaterialLaw {
 public:
  virtual ~MaterialLaw() = default;
  // Stress and tangent for the total strain (Voigt, engineering shears) at the point `where`.
  virtual void evaluate(const MaterialPointId& where, const double strain[kNumVoigt],
                        MaterialResponse& out) const = 0;
};

// The plane-strain view of a law: strain (eps_xx, eps_yy, gamma_xy), stress (xx, yy, xy, zz)
// and the 3x3 in-plane tangent -- a convenience for 2D callers and tests, evaluated through the
// 3D law with eps_zz = gamma_yz = gamma_xz = 0.
struct PlaneStrainResponse {
  double stress[4] = {0, 0, 0, 0};  // sigma_xx, sigma_yy, sigma_xy, sigma_zz
  double tangent[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
};
inline void evaluatePlaneStrain(const MaterialLaw& law, const MaterialPointId& where,
                                const double strain[3], PlaneStrainResponse& out) {
  const double e[kNumVoigt] = {strain[0], strain[1], 0, 0, 0, strain[2]};
  MaterialResponse r;
  law.evaluate(where, e, r);
  const int in[3] = {kXX, kYY, kXY};
  for (int i = 0; i < 3; ++i) {
    out.stress[i] = r.stress[in[i]];
    for (int j = 0; j < 3; ++j) out.tangent[3 * i + j] = r.tangent[kNumVoigt * in[i] + in[j]];
  }
  out.stress[3] = r.stress[kZZ];
}

// Isotropic linear elasticity in closed form; history-free, so `where` is ignored.
class LinearElasticMaterial : public MaterialLaw {
 public:
  explicit LinearElasticMaterial(const ElasticLaw& law) : law_(law) {}
  LinearElasticMaterial(double youngs, double poisson) : law_(youngs, poisson) {}

  const ElasticLaw& parameters() const { return law_; }

  void evaluate(const MaterialPointId&, const double strain[kNumVoigt],
                MaterialResponse& out) const override {
    const double l = law_.lambda(), m = law_.mu();
    const double trace = strain[kXX] + strain[kYY] + strain[kZZ];
    for (int c = 0; c < 3; ++c) out.stress[c] = l * trace + 2 * m * strain[c];
    for (int c = 3; c < kNumVoigt; ++c) out.stress[c] = m * strain[c];
    law_.voigtMatrix(out.tangent);
  }

 private:
  ElasticLaw law_;
};

}  // namespace plasticity
