#pragma once
// The dry run (--check, contact_DryRun.hpp) of Problem = elastic_contact and nonlinear_contact,
// whose run is contact::ContactSolver's (contact_ContactSolver.hpp): the runs' checks, meshing,
// partitioning and first contact search, and a nonlinear Restart's files.
#include <Teuchos_ParameterList.hpp>

#include <ostream>
#include <string>

#include "tfeti_Types.hpp"

namespace contact {

// The checks and set-up of the run up to its first solve (with the restart files a nonlinear
// Restart would read from outputDirectory/restart); rank 0 reports to `out`.
void checkContactProblem(const Teuchos::RCP<const tfeti::Comm>& comm,
                         Teuchos::ParameterList& params, const std::string& outputDirectory,
                         std::ostream& out);

}  // namespace contact
