#pragma once
// The driver's studies of the reference paper's linear model problems (Problem = poisson |
// elasticity on a structured mesh of a rectangle or a box, contact_StructuredProblem.hpp): one
// solve with summary.json (and VTU in 2D), and the scalability table (dimensions and iteration
// counts of FETI and TFETI for every preconditioner over H and H/h). What they report:
// contact_StructuredResult.hpp.
#include <Teuchos_ParameterList.hpp>

#include <ostream>
#include <string>

#include "tfeti_Types.hpp"

namespace contact {

// Study = single: returns 0, or 2 when PCPG did not converge (all output still written).
int runStructured(const Teuchos::RCP<const tfeti::Comm>& comm, Teuchos::ParameterList& params,
                  const std::string& dir);
// Study = scalability: returns 0, or 2 when a solve of the table did not converge.
int runStructuredScalability(const Teuchos::RCP<const tfeti::Comm>& comm,
                             Teuchos::ParameterList& params, const std::string& dir);

// The dry runs (--check) of both: the problem's checks, meshing and distribution (of the
// largest row of the table); rank 0 reports to `out`.
void checkStructured(const Teuchos::RCP<const tfeti::Comm>& comm, Teuchos::ParameterList& params,
                     std::ostream& out);
void checkStructuredScalability(const Teuchos::RCP<const tfeti::Comm>& comm,
                                Teuchos::ParameterList& params, std::ostream& out);

}  // namespace contact
