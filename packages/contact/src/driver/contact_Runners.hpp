#pragma once
// The one place that maps the driver's (Study, Problem) to the functions that run it and dry-run
// it: runDriver and checkDriver (contact_Driver.hpp) look the runner up here and call it. A new
// study or problem is a new entry of the table in contact_Runners.cpp.
//
//   Study        problem           run                          check (--check)
//   single       poisson           runStructured                checkStructured
//   single       elasticity        runStructured                checkStructured
//   single       two_membranes     runTwoMembranes              checkTwoMembranes
//   single       elastic_contact   runContactProblem            checkContactProblem
//   single       nonlinear_contact runContactProblem            checkContactProblem
//   scalability  poisson           runStructuredScalability     checkStructuredScalability
//   scalability  elasticity        runStructuredScalability     checkStructuredScalability
//   scalability  two_membranes     runTwoMembranesScalability   checkTwoMembranesScalability
//
// The problem of Study = scalability is the first of "Scalability"/"Problems" (two_membranes is
// a study of its own; poisson and elasticity share one table).
#include <Teuchos_ParameterList.hpp>

#include <ostream>
#include <string>

#include "tfeti_Types.hpp"

namespace contact {

struct Runner {
  const char* study;    // single | scalability
  const char* problem;  // Problem (Study = single) or the first of Scalability/Problems
  // The full run on the validated parameters, its files in dir. Returns the process exit code:
  // 0; 2 a solve did not converge; 3 a load step did not converge (all output written).
  int (*run)(const Teuchos::RCP<const tfeti::Comm>& comm, Teuchos::ParameterList& params,
             const std::string& dir);
  // The dry run: the run's set-up and checks up to its first solve; rank 0 reports to out.
  // dir: the output directory (the restart files a nonlinear Restart would read).
  void (*check)(const Teuchos::RCP<const tfeti::Comm>& comm, Teuchos::ParameterList& params,
                const std::string& dir, std::ostream& out);
};

// The runner of the validated params (throws std::logic_error for a pair no entry has, which
// validateDriverParameters does not let through).
const Runner& runnerFor(const Teuchos::ParameterList& params);

}  // namespace contact
