#pragma once
// Problem = elastic_contact of the tfeti_contact driver (see contact_ElasticContactProblem.hpp):
// its parameters and dry run; the run itself is contact::ContactSolver's
// (contact_ContactSolver.hpp).
#include <Teuchos_ParameterList.hpp>

#include <ostream>
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

// The dry run (--check, contact_DryRun.hpp) of Problem = elastic_contact and nonlinear_contact:
// the runs' checks, meshing, partitioning and first contact search, and a nonlinear Restart's
// files in outputDirectory/restart; rank 0 reports to `out`.
void checkContactProblem(const Teuchos::RCP<const tfeti::Comm>& comm,
                         Teuchos::ParameterList& params, const std::string& outputDirectory,
                         std::ostream& out);

}  // namespace contact
