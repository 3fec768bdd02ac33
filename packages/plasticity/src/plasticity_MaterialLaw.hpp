#pragma once
// The material-point interface between the element kernels and a constitutive law in plane
// strain. Strain and stress are in Voigt order (xx, yy, xy) with engineering shear strain
// gamma_xy = 2 eps_xy; the out-of-plane stress sigma_zz is returned too because plane strain
// does not make it vanish and von Mises (hence J2 yield) depends on it.
//
// How J2 plasticity plugs in: the kernels call evaluate() once per Gauss point with the point's
// identity (element, Gauss point) and its total strain. A J2 law keeps its history variables
// (plastic strain, equivalent plastic strain, committed and trial copies) in Kokkos::Views of
// extent numElements x numGaussPoints that it owns, reads the committed state at `where` and
// writes the trial state there (a const method may write through a View handle), and exposes
// commit() for the nonlinear solver after a converged load step. The kernels' signatures stay
// as they are; the only addition is a tangent assembly taking the current displacement, which
// the kernel already supports internally (strain from u at each Gauss point). Total Lagrangian
// kinematics would pass the Green-Lagrange strain and receive the second Piola-Kirchhoff
// stress through the same call; the geometric stiffness is the kernel's business, not the law's.
//
// The interface is virtual: the kernels run on the Serial (host) backend, where a virtual call
// per Gauss point costs nothing next to the B^T D B product. A device backend would need the
// law as a template parameter of the kernels instead; the value types below already fit that.
#include "plasticity_ElasticLaw.hpp"

namespace plasticity {

// Which integration point is being evaluated: the key of per-point history variables.
struct MaterialPointId {
  int element = 0;
  int gaussPoint = 0;
};

// What a law returns at one material point.
struct MaterialResponse {
  double stress[4] = {0, 0, 0, 0};  // sigma_xx, sigma_yy, sigma_xy, sigma_zz
  // d(sigma_xx, sigma_yy, sigma_xy) / d(eps_xx, eps_yy, gamma_xy), 3x3 row-major: the
  // consistent tangent the stiffness is assembled from.
  double tangent[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
};

class MaterialLaw {
 public:
  virtual ~MaterialLaw() = default;
  // Stress and tangent for the total strain (eps_xx, eps_yy, gamma_xy) at the point `where`.
  virtual void evaluate(const MaterialPointId& where, const double strain[3],
                        MaterialResponse& out) const = 0;
};

// Isotropic linear elasticity in closed form; history-free, so `where` is ignored.
class LinearElasticMaterial : public MaterialLaw {
 public:
  explicit LinearElasticMaterial(const ElasticLaw& law) : law_(law) {}
  LinearElasticMaterial(double youngs, double poisson) : law_(youngs, poisson) {}

  const ElasticLaw& parameters() const { return law_; }

  void evaluate(const MaterialPointId&, const double strain[3],
                MaterialResponse& out) const override {
    const double l = law_.lambda(), m = law_.mu();
    const double trace = strain[0] + strain[1];
    out.stress[0] = l * trace + 2 * m * strain[0];
    out.stress[1] = l * trace + 2 * m * strain[1];
    out.stress[2] = m * strain[2];
    out.stress[3] = l * trace;  // eps_zz = 0
    law_.planeStrainMatrix(out.tangent);
  }

 private:
  ElasticLaw law_;
};

}  // namespace plasticity
