#pragma once
// The driver's studies of Dostál's two-membrane benchmark (Problem = two_membranes,
// contact_TwoMembranes.hpp): one solve with VTU, contact CSV and summary.json, and the
// scalability table (Hessian multiplications over H and H/h for each dual QP solver). What they
// report: contact_TwoMembranesResult.hpp.
#include <Teuchos_ParameterList.hpp>

#include <ostream>
#include <string>

#include "tfeti_Types.hpp"

namespace contact {

// Study = single: returns 0, or 2 when the QP solve did not converge (all output still written).
int runTwoMembranes(const Teuchos::RCP<const tfeti::Comm>& comm, Teuchos::ParameterList& params,
                    const std::string& dir);
// Study = scalability: returns 0, or 2 when a solve of the table did not converge.
int runTwoMembranesScalability(const Teuchos::RCP<const tfeti::Comm>& comm,
                               Teuchos::ParameterList& params, const std::string& dir);

// The dry runs (--check) of both: the problem's checks and set-up (of the largest row of the
// table); rank 0 reports to `out`.
void checkTwoMembranes(const Teuchos::RCP<const tfeti::Comm>& comm, Teuchos::ParameterList& params,
                       std::ostream& out);
void checkTwoMembranesScalability(const Teuchos::RCP<const tfeti::Comm>& comm,
                                  Teuchos::ParameterList& params, std::ostream& out);

}  // namespace contact
