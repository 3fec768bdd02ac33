#pragma once
// Total Lagrangian (geometrically nonlinear) kernels on the elements of plasticity_Elements, in
// 2D (plane strain: F_zz = 1) and 3D through one code path: everything is integrated over the
// reference mesh, the law sees the Green-Lagrange strain E = (F^T F - I) / 2 of F = I + du/dX
// (Voigt, engineering shears) and returns the second Piola-Kirchhoff stress S and dS/dE. A
// small-strain law thus becomes its large-rotation counterpart (linear elasticity: St.
// Venant-Kirchhoff), exact under rigid rotations, which the small-strain kernels are not.
//
// Every entry point validates the mesh as plasticity_Elements does, and throws
// InvertedDeformationError (an std::invalid_argument) naming the first element in which
// det F <= 0 at some Gauss point: a Newton solver can catch exactly that to cut the step back.
#include <stdexcept>
#include <string>
#include <vector>

#include "plasticity_Elements.hpp"
#include "plasticity_MaterialLaw.hpp"
#include "tfeti_CsrMatrix.hpp"

namespace plasticity {

// SmallStrain: the same kernels with the linearized strain (F = I in B, no initial stress
// term, Cauchy = the law's stress), so that one code path serves both kinematics.
enum class Kinematics { SmallStrain, TotalLagrangian };

class InvertedDeformationError : public std::invalid_argument {
 public:
  explicit InvertedDeformationError(const std::string& what) : std::invalid_argument(what) {}
};

// Internal nodal forces f = sum_e int B_NL(u)^T S(E(u)) dV0, dim dofs per node (in 2D per unit
// thickness). Evaluates the law once per Gauss point (writing a history law's trial state).
std::vector<double> internalForce(const ElementMesh& mesh, const MaterialLaw& law,
                                  const std::vector<double>& u,
                                  Kinematics kinematics = Kinematics::TotalLagrangian);

// d internalForce / du: the material part B_NL^T (dS/dE) B_NL plus the initial-stress part
// grad N_a . S . grad N_b (times the identity in the components). Same pattern as
// assembleStiffness, which it equals at u = 0 for a law stress-free at zero strain.
// initialStress = false leaves the initial-stress part out: the material tangent alone is
// positive semidefinite with the rigid motions of the current configuration as its kernel
// (what a FETI subdomain needs), while the full tangent of a stressed body is not singular.
tfeti::CsrMatrix tangentStiffness(const ElementMesh& mesh, const MaterialLaw& law,
                                  const std::vector<double>& u,
                                  Kinematics kinematics = Kinematics::TotalLagrangian,
                                  bool initialStress = true);

// Cauchy stress sigma = F S F^T / det F (in 2D sigma_zz = S_zz / det F, as F_zz = 1) at each
// Gauss point, its von Mises value, and the usual nodal extrapolation. gaussCoords are the deformed
// positions x = X + u, where the Cauchy stress acts.
StressField cauchyStress(const ElementMesh& mesh, const MaterialLaw& law,
                         const std::vector<double>& u,
                         Kinematics kinematics = Kinematics::TotalLagrangian);

namespace detail {
// Gauss-point stresses (Cauchy; the law's stress for SmallStrain) with their positions, deformed
// or reference, as a StressField: cauchyStress and recoverStresses.
StressField gaussPointStresses(const ElementMesh& mesh, const MaterialLaw& law,
                               const std::vector<double>& u, Kinematics kinematics,
                               bool deformedPositions);
}  // namespace detail

}  // namespace plasticity
