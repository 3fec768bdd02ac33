#pragma once
// The material of every body of a contact problem, read in one place for the elastic and the
// nonlinear runs (2D and 3D alike). Either one "Material" for all bodies (as the structured
// problems have), or "Materials" with one sublist per body of "Contact problem/Bodies":
//
//   <ParameterList name="Materials">
//     <ParameterList name="cylinder">
//       <Parameter name="Young's modulus" type="double" value="7e10"/>
//       <Parameter name="Poisson's ratio" type="double" value="0.3"/>
//     </ParameterList>
//     <ParameterList name="block"> ... </ParameterList>
//   </ParameterList>
//
// Giving both is an error (it would leave a body with two materials), as are a body without a
// sublist and a sublist naming no body.
#include <Teuchos_ParameterList.hpp>

#include <string>
#include <vector>

#include "contact_ElasticContactProblem.hpp"
#include "contact_Json.hpp"
#include "plasticity_ElasticLaw.hpp"

namespace contact {

struct BodyMaterial {
  plasticity::ElasticLaw elastic;
  double yieldStress = 0.0;  // J2 (nonlinear_contact); 0: elastic
  double hardening = 0.0;    // linear isotropic hardening modulus
};

// Adds "Material" (one material for every body) and the documentation of "Materials" to the
// driver's valid parameters.
void addMaterialParameters(Teuchos::ParameterList& valid);

// The valid parameters of one body's sublist of "Materials" (those of "Material").
Teuchos::RCP<const Teuchos::ParameterList> validBodyMaterialParameters();

// What the input says about materials before the Teuchos validation fills in defaults: the
// "Materials" sublist (taken out of the parameters: its sublists are named by the user's
// bodies, which a fixed list of valid parameters cannot know) and the names of the parameters
// the input gives in "Material".
struct GivenMaterials {
  Teuchos::ParameterList perBody{"Materials"};
  std::vector<std::string> global;
};
GivenMaterials takeBodyMaterials(Teuchos::ParameterList& params);

// After the Teuchos validation: checks the per-body materials against the problem's bodies and
// the global "Material", fills their defaults and puts them back; with per-body materials the
// global "Material" (then holding defaults only) is removed, so that the echoed parameters show
// each material once. Throws std::invalid_argument naming the parameter, the body and the
// valid choices.
void restoreBodyMaterials(Teuchos::ParameterList& params, const GivenMaterials& given);

// The material of every body of "Contact problem/Bodies", in that order (validated params).
std::vector<BodyMaterial> bodyMaterials(const Teuchos::ParameterList& params);

// Hertz's combined modulus of two bodies in contact: 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2;
// with one body (a rigid obstacle as the other) E* = E / (1 - nu^2).
double combinedModulus(const std::vector<plasticity::ElasticLaw>& bodies);

// The summary's record of the bodies' materials: s["materials"] = {body: {youngs_modulus,
// poissons_ratio[, yield_stress, hardening_modulus]}}, and, when all bodies share one material,
// s["material"] as well (the record of a run with one Material).
void addMaterialSummary(Json& s, const std::vector<ElasticContactSpec::Body>& bodies);

}  // namespace contact
