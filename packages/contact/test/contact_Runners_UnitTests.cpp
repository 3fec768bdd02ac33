// The driver's dispatcher (contact_Runners.hpp): every (Study, problem) the driver accepts maps to
// its runner and dry run; and the typed results of the structured and two-membrane studies
// write summary.json's keys in the order readers expect (a table row's unconverged solve: null).
#include <Teuchos_UnitTestHarness.hpp>

#include <string>
#include <vector>

#include "contact_ContactCheck.hpp"
#include "contact_ContactSolver.hpp"
#include "contact_Runners.hpp"
#include "contact_StructuredResult.hpp"
#include "contact_StructuredRun.hpp"
#include "contact_TwoMembranesResult.hpp"
#include "contact_TwoMembranesRun.hpp"

namespace {

using Teuchos::ParameterList;

ParameterList input(const std::string& study, const std::string& problem) {
  ParameterList p("tfeti_contact");
  p.set("Study", study);
  if (study == "scalability")
    p.sublist("Scalability")
        .set("Problems", Teuchos::Array<std::string>(std::vector<std::string>{problem}));
  else
    p.set("Problem", problem);
  return p;
}

// The top-level keys of a summary, in the order written.
std::vector<std::string> keys(const contact::Json& j) {
  std::vector<std::string> k;
  const std::string text = j.dump();
  // Top-level keys sit at an indentation of two spaces.
  for (std::size_t at = text.find("\n  \""); at != std::string::npos;
       at = text.find("\n  \"", at + 1)) {
    const std::size_t begin = at + 4, end = text.find('"', begin);
    k.push_back(text.substr(begin, end - begin));
  }
  return k;
}

TEUCHOS_UNIT_TEST(Runners, EveryStudyAndProblemHasItsRunner) {
  using namespace contact;
  struct Case {
    const char* study;
    const char* problem;
    decltype(Runner::run) run;
  };
  const Case cases[] = {
      {"single", "poisson", runStructured},
      {"single", "elasticity", runStructured},
      {"single", "two_membranes", runTwoMembranes},
      {"single", "elastic_contact", runContactProblem},
      {"single", "nonlinear_contact", runContactProblem},
      {"scalability", "poisson", runStructuredScalability},
      {"scalability", "elasticity", runStructuredScalability},
      {"scalability", "two_membranes", runTwoMembranesScalability},
  };
  for (const Case& c : cases) {
    const Runner& r = runnerFor(input(c.study, c.problem));
    TEST_EQUALITY(std::string(r.study), std::string(c.study));
    TEST_EQUALITY(std::string(r.problem), std::string(c.problem));
    TEST_ASSERT(r.run == c.run);
    TEST_ASSERT(r.check != nullptr);
  }
  TEST_ASSERT(runnerFor(input("single", "elastic_contact")).check == checkContactProblem);
  // Study = scalability dispatches on the table's first problem, not on Problem.
  ParameterList p = input("scalability", "elasticity");
  p.set("Problem", "two_membranes");
  TEST_ASSERT(runnerFor(p).run == runStructuredScalability);
  TEST_THROW(runnerFor(input("scalability", "elastic_contact")), std::logic_error);
}

TEUCHOS_UNIT_TEST(Runners, StructuredSummaryKeys) {
  contact::StructuredRunResult r;
  r.problem = "poisson";
  const std::vector<std::string> expected = {"study",
                                             "problem",
                                             "ranks",
                                             "dimension",
                                             "subdomains",
                                             "elements",
                                             "formulation",
                                             "preconditioner",
                                             "local_solver",
                                             "dual_solver",
                                             "primal_dim",
                                             "dual_dim",
                                             "gluing_rows",
                                             "dirichlet_rows",
                                             "contact_rows",
                                             "coarse_dim",
                                             "largest_scaling_group",
                                             "converged",
                                             "iterations",
                                             "relative_residual",
                                             "residual_history",
                                             "dual_operator_applies",
                                             "factor_bytes",
                                             "factor_memory_check",
                                             "preconditioner_memory_check",
                                             "dual_operator",
                                             "explicit_dual_bytes",
                                             "explicit_dual_bytes_max_rank",
                                             "explicit_device",
                                             "memory",
                                             "stopping_rule",
                                             "tolerance",
                                             "preconditioner_factor_bytes",
                                             "timings",
                                             "peak_rss_mb",
                                             "solution_norm2",
                                             "max_abs_u"};
  TEST_ASSERT(keys(contact::summaryJson(r)) == expected);

  contact::StructuredScalabilityResult t;
  contact::StructuredTableRow row;
  row.problem = "poisson";
  row.hInverse = 2;
  row.hOverh = 4;
  row.feti = {{"none", 7}, {"lumped", std::nullopt}};
  t.table.push_back(row);
  const std::string text = contact::summaryJson(t).dump();
  TEST_ASSERT(text.find("\"none\": 7") != std::string::npos);
  TEST_ASSERT(text.find("\"lumped\": null") != std::string::npos);
  TEST_ASSERT(text.find("\"h_inverse\": 8") != std::string::npos);
}

TEUCHOS_UNIT_TEST(Runners, TwoMembranesSummaryKeys) {
  contact::TwoMembranesResult r;
  r.contactCsv = "out/contact.csv";
  const std::vector<std::string> expected = {"study",
                                             "problem",
                                             "ranks",
                                             "subdomains",
                                             "elements",
                                             "H",
                                             "h",
                                             "formulation",
                                             "preconditioner",
                                             "local_solver",
                                             "dual_solver",
                                             "primal_dim",
                                             "dual_dim",
                                             "gluing_rows",
                                             "dirichlet_rows",
                                             "contact_rows",
                                             "coarse_dim",
                                             "largest_scaling_group",
                                             "converged",
                                             "iterations",
                                             "relative_residual",
                                             "residual_history",
                                             "dual_operator_applies",
                                             "factor_bytes",
                                             "factor_memory_check",
                                             "preconditioner_memory_check",
                                             "dual_operator",
                                             "explicit_dual_bytes",
                                             "explicit_dual_bytes_max_rank",
                                             "explicit_device",
                                             "memory",
                                             "qp",
                                             "contact",
                                             "timings",
                                             "peak_rss_mb",
                                             "solution_norm2",
                                             "max_abs_u",
                                             "min_u",
                                             "contact_csv"};
  TEST_ASSERT(keys(contact::summaryJson(r)) == expected);
  const std::vector<std::string> table = {"study", "problem", "ranks", "all_converged", "table"};
  TEST_ASSERT(keys(contact::summaryJson(contact::TwoMembranesScalabilityResult{})) == table);
}

}  // namespace
