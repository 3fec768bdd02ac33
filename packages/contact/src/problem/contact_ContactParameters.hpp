#pragma once
// The "Contact problem" parameters of Problem = elastic_contact and nonlinear_contact (bodies on
// a Gmsh mesh in contact, contact_ElasticContactProblem.hpp): their valid list, the problem
// description read from them and the FETI list of a run. The run is contact::ContactSolver's
// (contact_ContactSolver.hpp), its dry run checkContactProblem (contact_ContactCheck.hpp).
#include <Teuchos_ParameterList.hpp>

#include <string>

#include "contact_ElasticContactProblem.hpp"
#include "tfeti_Types.hpp"

namespace contact {

// Adds the "Contact problem" sublist to the driver's valid parameters.
void addElasticContactParameters(Teuchos::ParameterList& valid);

// The problem description from the "Contact problem" and "Material" (or per body "Materials")
// sublists (validated).
ElasticContactSpec elasticContactSpec(const Teuchos::ParameterList& params);

// The FETI list of a run: "Inequality rows" = equalities when the pair is tied (an error when
// set there for a frictionless pair).
Teuchos::ParameterList fetiParameters(const Teuchos::ParameterList& params,
                                      const ElasticContactSpec& spec);

}  // namespace contact
