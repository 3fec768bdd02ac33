// contact::ContactSolver from C++: the two cylinders configured by a ParameterList built here
// (the same problem as tests/inputs/two_cylinders_coarse.xml), checked against Hertz, against
// the KKT conditions its per-node result must meet, and against the summary.json of the
// tfeti_contact run of that input on the same rank count (CONTACT_EXE_SUMMARY_DIR: every figure
// equal but timings, memory and file paths); a nonlinear run through the object (per-step
// history); non-convergence and bad parameters reported as the executable reports them.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "contact_ContactSolver.hpp"
#include "contact_RunSummary.hpp"

namespace {

using Teuchos::Array;
using Teuchos::ParameterList;

Teuchos::RCP<const tfeti::Comm> comm() {
  return Teuchos::DefaultComm<int>::getComm();
}

template <class T>
Array<T> arr(std::initializer_list<T> v) {
  return Array<T>(v.begin(), v.end());
}

// tests/inputs/two_cylinders_coarse.xml as a ParameterList: a steel cylinder (R = 1 m) on a
// block, line load 4e7 N/m (half model: traction 2e7), coarse mesh, 4 + 4 subdomains, SMALBE.
ParameterList twoCylinders() {
  ParameterList p("tfeti_contact");
  p.set("Problem", "elastic_contact");
  p.sublist("Material").set("Young's modulus", 2.0e11).set("Poisson's ratio", 0.3);
  auto& cp = p.sublist("Contact problem");
  cp.set("Mesh file", std::string(CONTACT_TEST_EXAMPLES_DIR) + "/two_cylinders.geo");
  cp.set("Element order", 1);
  cp.set("Mesh size factor", 2.0);
  cp.set("Bodies", arr<std::string>({"cylinder", "block"}));
  cp.set("Subdomains per body", arr<int>({4, 4}));
  cp.set("Fixed boundaries", arr<std::string>({"fixed"}));
  cp.set("Symmetry boundaries", arr<std::string>({"cylinder_symmetry", "block_symmetry"}));
  cp.set("Symmetry components", arr<int>({0, 0}));
  cp.set("Traction boundaries", arr<std::string>({"load"}));
  cp.set("Tractions", arr<double>({0.0, -2.0e7}));
  cp.set("Slave", "cylinder_contact");
  cp.set("Master", "block_contact");
  cp.set("Search radius", 0.1);
  cp.sublist("Hertz").set("Compare", true).set("Radius 1", 1.0).set("Line load", 4.0e7);
  auto& feti = p.sublist("FETI");
  feti.set("Dual solver", "SMALBE");
  feti.sublist("SMALBE").set("Relative tolerance", 1e-7).set("Equality tolerance", 1e-9);
  return p;
}

std::string outputDirectory(const std::string& name) {
  return "contact_solver_out/" + name + "_np" + std::to_string(comm()->getSize());
}

// summary.json as its lines, without those that differ between two runs of one input: times,
// memory (the nodes' available memory too), the files' paths and the mesh file's path (resolved
// from where each input was).
std::vector<std::string> comparableLines(const std::string& path) {
  static const std::set<std::string> volatileKeys = {"factorization_s",
                                                     "tearing_s",
                                                     "coarse_s",
                                                     "preconditioner_s",
                                                     "dual_rhs_s",
                                                     "setup_s",
                                                     "solve_s",
                                                     "recovery_s",
                                                     "per_iteration_s",
                                                     "peak_rss_mb",
                                                     "wall_time",
                                                     "contact_csv",
                                                     "vtu",
                                                     "iterations_csv",
                                                     "steps_csv",
                                                     "Mesh file",
                                                     "node_available_bytes"};
  std::ifstream in(path);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    const auto q = line.find('"');
    if (q != std::string::npos) {
      const auto e = line.find('"', q + 1);
      if (e != std::string::npos && volatileKeys.count(line.substr(q + 1, e - q - 1))) continue;
    }
    // A removed last member leaves the one before it with a comma: compare without them.
    if (!line.empty() && line.back() == ',') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

TEUCHOS_UNIT_TEST(ContactSolver, TwoCylindersAgainstHertzAndExecutable) {
  contact::ContactSolver solver(comm());
  solver.setParameters(twoCylinders());
  const std::string dir = outputDirectory("two_cylinders");
  solver.setOutputDirectory(dir);
  const contact::ContactResult r = solver.solve();
  TEST_ASSERT(r.converged);
  TEST_EQUALITY(r.exitCode, 0);
  TEST_EQUALITY_CONST(r.problem, "elastic_contact");
  TEST_EQUALITY(r.dimension, 2);
  TEST_EQUALITY(r.ranks, comm()->getSize());

  // Hertz: the coarse mesh (4 mm elements, a/5) meets the integration test's tolerances.
  const contact::ContactMeasures& c = r.contact;
  TEST_ASSERT(c.hertz.has_value());
  TEST_EQUALITY_CONST(c.extentKey, "half_width");
  const double l = 4.0e7, E = 2.0e11, nu = 0.3, R = 1.0;
  const double Estar = E / (2.0 * (1.0 - nu * nu));
  const double a = std::sqrt(4.0 * l * R / (M_PI * Estar)), p0 = 2.0 * l / (M_PI * a);
  TEST_FLOATING_EQUALITY(c.hertz->pMax, p0, 1e-12);
  TEST_FLOATING_EQUALITY(c.hertz->extent, a, 1e-12);
  TEST_ASSERT(std::abs(c.pMax - p0) / p0 < 0.03);
  TEST_ASSERT(std::abs(c.extent - a) / a < 0.05);
  TEST_FLOATING_EQUALITY(c.hertz->pMaxError, std::abs(c.pMax - p0) / p0, 1e-12);
  // The contact force balances the half model's load l / 2.
  TEST_FLOATING_EQUALITY(c.appliedForce, l / 2.0, 1e-12);
  TEST_ASSERT(std::abs(c.force - l / 2.0) / (l / 2.0) < 1e-6);

  // The per-node result: the KKT conditions of the contact rows, node by node (multiplier >= 0,
  // gap >= 0, complementarity), to the QP's accuracy relative to the displacement's scale; the
  // multipliers sum to the force, p_max is the largest pressure, the nodes are sorted by x.
  TEST_EQUALITY(static_cast<long long>(r.contactNodes.size()), r.feti.contactRows);
  double sum = 0.0, pMax = 0.0;
  const double gapScale = 1e-6 * r.maxAbsU;
  int inContact = 0;
  for (std::size_t k = 0; k < r.contactNodes.size(); ++k) {
    const contact::ContactNode& n = r.contactNodes[k];
    TEST_ASSERT(n.lambda >= 0.0);
    TEST_ASSERT(n.gap >= -gapScale);
    TEST_ASSERT(n.lambda * std::abs(n.gap) <= gapScale * c.force);
    if (k > 0) TEST_ASSERT(r.contactNodes[k - 1].x <= n.x);
    sum += n.lambda;
    pMax = std::max(pMax, n.pressure);
    if (n.lambda > 0.0) ++inContact;
  }
  TEST_FLOATING_EQUALITY(sum, c.force, 1e-12);
  TEST_EQUALITY(pMax, c.pMax);
  TEST_EQUALITY(static_cast<long long>(inContact), c.constraints.activeRows);
  TEST_ASSERT(c.constraints.maxPenetration <= gapScale);

  // QP counters and the one-step history of the elastic run.
  TEST_EQUALITY_CONST(r.qp.method, "SMALBE");
  TEST_ASSERT(r.qp.qp.hessianMultiplications > 0);
  // The face found from the gaps may end the solve before any outer iteration (FETI's defaults
  // "Face solve" = pcpg, "Initial face" = levels).
  TEST_ASSERT(r.qp.converged);
  TEST_EQUALITY(static_cast<int>(r.history.steps.size()), 1);
  TEST_EQUALITY(r.history.steps[0].loadFactor, 1.0);
  TEST_EQUALITY(r.history.steps[0].outerIterations, 1);
  TEST_EQUALITY(r.history.steps[0].hessianMultiplications, r.qp.qp.hessianMultiplications);
  TEST_EQUALITY(r.history.steps[0].pMax, c.pMax);
  // The single increment solves the linear problem: f - B^T lambda - K u vanishes to the QP's
  // accuracy.
  out << "relative residual of the one step: " << r.history.steps[0].residuals.at(0) << "\n";
  TEST_ASSERT(r.history.steps[0].residuals.at(0) < 1e-5);

  // Stresses and displacements of every local subdomain.
  TEST_EQUALITY(solver.displacement().size(), solver.problem().local.size());
  TEST_EQUALITY(solver.stresses().size(), solver.problem().local.size());
  double maxU = 0.0;
  for (const auto& u : solver.displacement())
    for (double v : u) maxU = std::max(maxU, std::abs(v));
  TEST_ASSERT(maxU <= r.maxAbsU);

  // summary.json is the result's: the file written equals summaryJson(result) and the
  // executable's run of tests/inputs/two_cylinders_coarse.xml on as many ranks.
  // Rank 0 writes the files: it compares them.
  if (comm()->getRank() != 0) return;
  {
    contact::Json expected = contact::summaryJson(r);
    expected["parameters"] = contact::parametersJson(solver.parameters());
    std::ifstream file(dir + "/summary.json");
    std::stringstream text;
    text << file.rdbuf();
    TEST_ASSERT(text.str() == expected.dump());
  }
  const std::vector<std::string> mine = comparableLines(dir + "/summary.json");
  TEST_ASSERT(mine.size() > 50);
  const char* exeDir = std::getenv("CONTACT_EXE_SUMMARY_DIR");
  TEST_ASSERT(exeDir != nullptr);
  if (exeDir) {
    const std::vector<std::string> exe = comparableLines(std::string(exeDir) + "/summary.json");
    if (exe.empty()) out << "no summary.json in " << exeDir << "\n";
    TEST_EQUALITY(exe.size(), mine.size());
    for (std::size_t k = 0; k < std::min(exe.size(), mine.size()); ++k)
      if (exe[k] != mine[k]) {
        out << "summary.json line " << k << ": executable " << exe[k] << "\n  object " << mine[k]
            << "\n";
        success = false;
        break;
      }
  }
}

// A nonlinear run through the object: two load steps, small strain, elastic. The per-step
// history holds both steps with their iterations; the last step meets the stopping test and
// balances the load, and agrees with the one-step elastic run of the same problem (the rows
// follow the deformed geometry: a small difference).
TEUCHOS_UNIT_TEST(ContactSolver, NonlinearStepsThroughTheObject) {
  ParameterList p = twoCylinders();
  p.set("Problem", "nonlinear_contact");
  p.sublist("Nonlinear").set("Load steps", 2).set("Geometrically nonlinear", false);
  contact::ContactSolver solver(comm());
  solver.setParameters(p);
  const contact::ContactResult r = solver.solve();
  TEST_ASSERT(r.converged);
  TEST_EQUALITY(r.exitCode, 0);
  TEST_EQUALITY_CONST(r.problem, "nonlinear_contact");
  TEST_EQUALITY(r.history.step, 2);
  TEST_EQUALITY(r.history.loadFactor, 1.0);
  TEST_EQUALITY(static_cast<int>(r.history.steps.size()), 2);
  std::size_t iterations = 0;
  for (std::size_t k = 0; k < r.history.steps.size(); ++k) {
    const contact::StepRecord& s = r.history.steps[k];
    TEST_EQUALITY(s.step, static_cast<int>(k) + 1);
    TEST_FLOATING_EQUALITY(s.loadFactor, 0.5 * static_cast<double>(k + 1), 1e-14);
    TEST_EQUALITY(static_cast<std::size_t>(s.outerIterations), s.residuals.size());
    TEST_ASSERT(s.outerIterations >= 2);  // the increment, then the check that it is converged
    TEST_ASSERT(s.residuals.back() < 1e-6 && s.increments.back() < 1e-6);
    TEST_ASSERT(s.hessianMultiplications > 0 && s.pMax > 0.0);
    iterations += s.residuals.size();
  }
  TEST_EQUALITY(r.history.iterations.size(), iterations);  // none rejected
  const contact::ContactMeasures& c = r.contact;
  TEST_ASSERT(r.haveContact);
  TEST_EQUALITY(c.pMax, r.history.steps.back().pMax);
  TEST_ASSERT(c.forceRelativeError < 1e-6);
  TEST_ASSERT(c.supportRelativeError < 1e-6);
  TEST_ASSERT(c.hertz.has_value());
  // The final state's stresses, computed when asked for: the last step's largest von Mises
  // stress, which its output took from the trial state.
  TEST_EQUALITY(solver.stresses().size(), solver.problem().local.size());
  double vm = 0.0;
  for (const auto& st : solver.stresses())
    for (std::size_t k = plasticity::kVonMises; k < st.gauss.size();
         k += plasticity::kNumStressComponents)
      vm = std::max(vm, st.gauss[k]);
  Teuchos::reduceAll(*comm(), Teuchos::REDUCE_MAX, vm, Teuchos::outArg(vm));
  out << "max von Mises of the final stresses " << vm << ", of the last step "
      << r.history.steps.back().maxVonMises << "\n";
  TEST_FLOATING_EQUALITY(vm, r.history.steps.back().maxVonMises, 1e-10);

  // The one-step elastic run of the same problem. The nonlinear loop searches the contact on the
  // current geometry and reports the nodes at their current positions (the elastic run: the
  // reference ones), so the half-width, measured between nodes, moves with them: measured 2.5e-5
  // for p_max and 2.2e-3 for the half-width on 1, 2 and 3 ranks.
  contact::ContactSolver elastic(comm());
  elastic.setParameters(twoCylinders());
  const contact::ContactResult e = elastic.solve();
  TEST_ASSERT(e.converged);
  out << std::setprecision(10) << "p_max nonlinear " << c.pMax << ", elastic " << e.contact.pMax
      << " (" << std::abs(c.pMax - e.contact.pMax) / e.contact.pMax << "); half-width " << c.extent
      << ", " << e.contact.extent << " ("
      << std::abs(c.extent - e.contact.extent) / e.contact.extent << ")\n";
  TEST_ASSERT(std::abs(c.pMax - e.contact.pMax) / e.contact.pMax < 1e-4);
  TEST_ASSERT(std::abs(c.extent - e.contact.extent) / e.contact.extent < 5e-3);
}

// A QP that cannot converge in one SMALBE outer iteration, its face solves limited to one CG
// step: reported by the result (and the exit code the executable returns), its last state kept.
TEUCHOS_UNIT_TEST(ContactSolver, NonConvergenceIsReported) {
  ParameterList p = twoCylinders();
  p.sublist("FETI").sublist("SMALBE").set("Maximum outer iterations", 1);
  p.sublist("FETI").sublist("SMALBE").set("Face maximum iterations", 1);
  contact::ContactSolver solver(comm());
  solver.setParameters(p);
  const contact::ContactResult r = solver.solve();
  TEST_ASSERT(!r.converged);
  TEST_EQUALITY(r.exitCode, 2);
  TEST_ASSERT(!r.message.empty());
  TEST_ASSERT(!r.qp.converged && !r.qp.qp.message.empty());
  TEST_EQUALITY(static_cast<int>(r.history.steps.size()), 1);
  TEST_ASSERT(r.maxAbsU > 0.0);
}

// Parameters are validated as tfeti_contact validates its input.
TEUCHOS_UNIT_TEST(ContactSolver, ParametersAreValidated) {
  contact::ContactSolver solver(comm());
  ParameterList misspelt = twoCylinders();
  misspelt.sublist("Contact problem").set("Slavee", "cylinder_contact");
  TEST_THROW(solver.setParameters(misspelt, "my list"), std::invalid_argument);
  try {
    solver.setParameters(misspelt, "my list");
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    TEST_ASSERT(what.find("my list") != std::string::npos);
    TEST_ASSERT(what.find("Slavee") != std::string::npos);
  }
  ParameterList poisson = twoCylinders();
  poisson.set("Problem", "poisson");
  TEST_THROW(solver.setParameters(poisson), std::invalid_argument);
  ParameterList negative = twoCylinders();
  negative.sublist("Material").set("Young's modulus", -1.0);
  TEST_THROW(solver.setParameters(negative), std::invalid_argument);
  TEST_THROW(solver.setup(), std::logic_error);  // no valid parameters were set
}

}  // namespace
