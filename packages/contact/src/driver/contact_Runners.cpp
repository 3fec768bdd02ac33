#include "contact_Runners.hpp"

#include <stdexcept>
#include <string>

#include "contact_ContactCheck.hpp"
#include "contact_ContactSolver.hpp"
#include "contact_StructuredRun.hpp"
#include "contact_TwoMembranesRun.hpp"

namespace contact {

namespace {

using Teuchos::ParameterList;
using CommPtr = Teuchos::RCP<const tfeti::Comm>;

// The checks that need no output directory.
void structured(const CommPtr& comm, ParameterList& params, const std::string&, std::ostream& out) {
  checkStructured(comm, params, out);
}
void structuredTable(const CommPtr& comm, ParameterList& params, const std::string&,
                     std::ostream& out) {
  checkStructuredScalability(comm, params, out);
}
void membranes(const CommPtr& comm, ParameterList& params, const std::string&, std::ostream& out) {
  checkTwoMembranes(comm, params, out);
}
void membranesTable(const CommPtr& comm, ParameterList& params, const std::string&,
                    std::ostream& out) {
  checkTwoMembranesScalability(comm, params, out);
}

const Runner kRunners[] = {
    {"single", "poisson", runStructured, structured},
    {"single", "elasticity", runStructured, structured},
    {"single", "two_membranes", runTwoMembranes, membranes},
    {"single", "elastic_contact", runContactProblem, checkContactProblem},
    {"single", "nonlinear_contact", runContactProblem, checkContactProblem},
    {"scalability", "poisson", runStructuredScalability, structuredTable},
    {"scalability", "elasticity", runStructuredScalability, structuredTable},
    {"scalability", "two_membranes", runTwoMembranesScalability, membranesTable},
};

}  // namespace

const Runner& runnerFor(const ParameterList& params) {
  const std::string study = params.get<std::string>("Study");
  const std::string problem =
      study == "scalability"
          ? params.sublist("Scalability").get<Teuchos::Array<std::string>>("Problems")[0]
          : params.get<std::string>("Problem");
  for (const Runner& r : kRunners)
    if (study == r.study && problem == r.problem) return r;
  throw std::logic_error("tfeti_contact: no runner for Study = " + study + ", problem " + problem);
}

}  // namespace contact
