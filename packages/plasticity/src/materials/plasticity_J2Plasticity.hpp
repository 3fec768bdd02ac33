#pragma once
// J2 (von Mises) plasticity with linear isotropic hardening, small strain, in full 3D (Voigt
// order of plasticity_MaterialLaw.hpp). Plane strain is the same law evaluated with
// eps_zz = gamma_yz = gamma_xz = 0: sigma_zz enters the von Mises norm and the plastic flow has
// a zz component there. For linear hardening the radial return is closed form, so evaluate()
// needs no local iteration.
//
// History lives per (element, Gauss point) in two copies, committed and trial, as
// plasticity_MaterialLaw.hpp lays out: evaluate() starts from the committed copy and overwrites
// the trial one, so the Newton iterations of a load step may evaluate any number of times
// without drift; commit() accepts the step, revert() abandons it (e.g. for a cut-back).
#include <Kokkos_Core.hpp>

#include <vector>

#include "plasticity_ElasticLaw.hpp"
#include "plasticity_MaterialLaw.hpp"

namespace plasticity {

class J2PlasticMaterial : public MaterialLaw {
 public:
  // youngs, poisson: as ElasticLaw; yieldStress > 0 is the initial uniaxial yield stress;
  // hardeningModulus >= 0 is H in sigma_y(alpha) = yieldStress + H alpha (0: perfect
  // plasticity). Throws std::invalid_argument naming the offending parameter.
  J2PlasticMaterial(double youngs, double poisson, double yieldStress, double hardeningModulus,
                    int numElements, int gaussPointsPerElement);

  // Stress and 6x6 consistent tangent at `where` for the total strain (Voigt, engineering shears),
  // starting from the committed history; writes the resulting trial history at `where`.
  // Throws std::out_of_range for a point outside numElements x gaussPointsPerElement.
  void evaluate(const MaterialPointId& where, const double strain[kNumVoigt],
                MaterialResponse& out) const override;

  // Trial -> committed at every point (a converged load step).
  void commit();
  // Committed -> trial at every point (a rejected load step).
  void revert();

  // The committed history as a flat array (for restart files) and back; the size must be
  // numElements x gaussPointsPerElement x historySize(), else std::invalid_argument.
  std::vector<double> committedHistory() const;
  void setCommittedHistory(const std::vector<double>& values);
  static constexpr int historySize() { return kNumHistory; }

  // Equivalent plastic strain alpha (the hardening variable), committed or trial.
  double equivalentPlasticStrain(const MaterialPointId& where) const;
  double trialEquivalentPlasticStrain(const MaterialPointId& where) const;
  // Plastic strain tensor components in Voigt order (xx, yy, zz, yz, xz, xy) -- the shears are
  // tensor components, half the engineering shears -- committed or trial.
  void plasticStrain(const MaterialPointId& where, double ep[kNumVoigt]) const;
  void trialPlasticStrain(const MaterialPointId& where, double ep[kNumVoigt]) const;

  const ElasticLaw& elastic() const { return elastic_; }
  double yieldStress() const { return yieldStress_; }
  double hardeningModulus() const { return hardening_; }
  int numElements() const { return numElements_; }
  int gaussPointsPerElement() const { return gaussPoints_; }

 private:
  // Layout of the last extent of the history views: the plastic strain tensor (Voigt order,
  // tensor shears), then alpha.
  enum : int { kEp = 0, kAlpha = kNumVoigt, kNumHistory = kNumVoigt + 1 };
  using History = Kokkos::View<double***, Kokkos::HostSpace>;

  void checkPoint(const MaterialPointId& where) const;

  ElasticLaw elastic_;
  double yieldStress_;
  double hardening_;
  int numElements_;
  int gaussPoints_;
  History committed_;
  History trial_;
};

}  // namespace plasticity
