#pragma once
// The tfeti_contact driver: reads a validated ParameterList, runs the requested study and writes
// summary.json (and VTU) into the output directory.
//   Study = "single":      one problem (Problem, Mesh, Material, Load, FETI), with VTU output
//   Study = "scalability": the reference paper's table (dimensions and iteration counts of FETI
//                          and TFETI for every preconditioner over H and H/h), or for
//                          two_membranes the QP solvers' Hessian multiplications over H and H/h
//   Problem = poisson, elasticity: the structured model problems (contact_StructuredRun.hpp)
//   Problem = two_membranes: the contact benchmark (contact_TwoMembranesRun.hpp)
//   Problem = elastic_contact, nonlinear_contact: contact::ContactSolver
//   (contact_ContactSolver.hpp; dry run: contact_ContactCheck.hpp)
// Which function runs (and dry-runs) which (Study, Problem): the table of contact_Runners.hpp.
#include <Teuchos_ParameterList.hpp>

#include <ostream>
#include <string>

#include "tfeti_Types.hpp"

namespace contact {

// Every parameter the driver accepts, with defaults and documentation.
Teuchos::RCP<const Teuchos::ParameterList> validDriverParameters();

// Validates params (throws std::invalid_argument naming the source and the bad parameter with the
// valid ones) and fills in defaults.
void validateDriverParameters(Teuchos::ParameterList& params, const std::string& source);

// Output/Verbosity 2 shows every SMALBE outer iteration (SMALBE/Verbosity 2 unless set).
void applyOutputVerbosity(Teuchos::ParameterList& params);

// Runs the study. Returns the process exit code: 0 on success, 2 when a solve did not converge
// (all output is still written).
int runDriver(const Teuchos::RCP<const tfeti::Comm>& comm, Teuchos::ParameterList& params,
              const std::string& outputDirectory);

// The dry run (--check): the study's set-up (meshing, partitioning, distribution, contact
// search) through the full run's own checks, without factorizing or solving; rank 0 reports
// the bodies, boundaries, subdomains per rank, unknowns, contact rows and estimated memory to
// `out`. Throws what the full run would throw before its first solve (with the restart files a
// nonlinear Restart would read from outputDirectory); returns 0.
int checkDriver(const Teuchos::RCP<const tfeti::Comm>& comm, Teuchos::ParameterList& params,
                const std::string& outputDirectory, std::ostream& out);

}  // namespace contact
