// Solves a small Poisson problem through the installed packages and checks the answer against a
// direct solve: the installed headers, libraries and CMake configs are complete. The contact
// solver object (contact::ContactSolver) is there too: its parameters validate as tfeti_contact's.
#include <Tpetra_Core.hpp>

#include <iostream>

#include "contact_ContactSolver.hpp"
#include "contact_StructuredProblem.hpp"
#include "tfeti_FetiSolver.hpp"

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  contact::StructuredProblem problem;
  problem.subdomains = {3, 3};
  problem.elements = {4, 4};
  Teuchos::ParameterList params;
  params.sublist("PCPG").set("Relative tolerance", 1e-9);
  tfeti::FetiSolver solver(comm, 9, contact::buildLocalSubdomains(problem, *comm), params);
  const auto result = solver.solve();
  const double err = contact::relativeErrorAgainstDirectSolve(problem, solver);
  std::cout << "consumer: " << result.iterations << " iterations, error " << err << "\n";
  contact::ContactSolver contactSolver(comm);
  Teuchos::ParameterList contactParams;
  contactParams.set("Problem", "elastic_contact");
  contactSolver.setParameters(contactParams);
  const bool defaults =
      contactSolver.parameters().sublist("FETI").get<std::string>("Dual solver") == "auto";
  std::cout << "consumer: ContactSolver parameters " << (defaults ? "validated" : "WRONG") << "\n";
  return result.converged && err < 1e-6 && defaults ? 0 : 1;
}
