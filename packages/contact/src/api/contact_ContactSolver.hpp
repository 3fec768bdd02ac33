#pragma once
// contact::ContactSolver: bodies on a Gmsh mesh in contact (Problem = elastic_contact or
// nonlinear_contact of tfeti_contact), solved from C++ without the executable:
//
//   contact::ContactSolver solver(comm);
//   solver.setParameters(params);          // the tfeti_contact list; validated, defaults filled in
//   solver.setOutputDirectory("out/run");  // optional: CSV, VTU, restart files, summary.json
//   solver.setup();                        // mesh, partition, contact search, factorization
//   const contact::ContactResult r = solver.solve();
//   if (!r.converged) ...                  // r.message says why; r.exitCode as tfeti_contact's
//
// One driver serves both problems: the load-step loop of the reference paper's nonlinear
// algorithm (contact_NonlinearIteration.hpp). The elastic problem is its one-step case: a single
// increment from u = 0 at load factor 1 on the reference geometry, which solves the linear
// problem exactly (no second iteration, no refactorization, the contact rows of the set-up).
// Where the two differ, the driver asks its run policy (contact_RunPolicy.hpp).
// tfeti_contact runs through this object; its summary.json is summaryJson(result).
//
// Every collective call (setup, solve) must be made on every rank of the communicator.
#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <string>
#include <vector>

#include "contact_ContactResult.hpp"
#include "contact_ElasticContactProblem.hpp"
#include "plasticity_Elements.hpp"
#include "tfeti_Types.hpp"

namespace contact {

struct StepOutcome;       // contact_NonlinearIteration.hpp
struct FixedPointRecord;  // contact_FrictionStep.hpp
struct ContactRun;        // contact_ContactRun.hpp: the state of a set-up run
struct LoadSteps;         // contact_ContactRun.hpp: the state of solve()'s load-step loop

class ContactSolver {
 public:
  explicit ContactSolver(Teuchos::RCP<const tfeti::Comm> comm);
  ~ContactSolver();
  ContactSolver(const ContactSolver&) = delete;
  ContactSolver& operator=(const ContactSolver&) = delete;

  // Every parameter tfeti_contact accepts (--print-parameters).
  static Teuchos::RCP<const Teuchos::ParameterList> validParameters();

  // A copy of `params`, validated as tfeti_contact validates its input (an unknown, mistyped or
  // out-of-range parameter throws std::invalid_argument naming `source` and the parameter) with
  // defaults filled in. "Problem" must be elastic_contact or nonlinear_contact. A relative
  // "Mesh file" is looked up next to `source` when that is a file, then in the working directory.
  void setParameters(const Teuchos::ParameterList& params,
                     const std::string& source = "ContactSolver parameters");
  // The validated list (what summary.json echoes under "parameters").
  const Teuchos::ParameterList& parameters() const;

  // Where the run writes its files (created on rank 0): contact_pressure.csv, solution.pvtu
  // (Output/VTU), summary.json, and for nonlinear_contact the per-step files, iterations.csv,
  // steps.csv, steps.pvd and the restart files (also read by Nonlinear/Restart). Empty (the
  // default): nothing is written; a nonlinear Restart then needs a directory.
  void setOutputDirectory(const std::string& dir);

  // The problem's set-up: meshing, partitioning, distribution, contact search, the FETI solver
  // (factorization); the checks the run makes before solving (throw std::invalid_argument
  // naming the parameter, or std::runtime_error). Collective.
  void setup();

  // Solves (setup() first when not yet done) and returns the result; non-convergence is
  // reported in it (converged, exitCode, message), not thrown. Collective; once per setup().
  ContactResult solve();

  // After solve(): the problem (mesh, this rank's subdomains and their element meshes), the
  // final displacement and the Cauchy stresses (nodal and per Gauss point) per local subdomain.
  const ElasticContactProblem& problem() const;
  const std::vector<std::vector<double>>& displacement() const;
  const std::vector<plasticity::StressField>& stresses() const;

 private:
  // solve(), as its named steps (contact_ContactSolver.cpp); where the two problems differ, the
  // run's policy decides (contact_RunPolicy.hpp).
  void prepareLoadSteps(LoadSteps& s);
  void runLoadSteps(LoadSteps& s);
  bool rejectStep(LoadSteps& s, int step, double t, const std::string& reason);
  void acceptStep(LoadSteps& s, int step, double t, StepOutcome& out,
                  const FixedPointRecord& fixedPoint);
  void saveStep(LoadSteps& s, const StepRecord& rec);
  ContactResult fillResult(const LoadSteps& s) const;
  void measureContact(ContactResult& res) const;
  void measureFinalState(ContactResult& res);
  void writeResultFiles(ContactResult& res, const LoadSteps& s);
  void writeTables() const;

  Teuchos::RCP<const tfeti::Comm> comm_;
  Teuchos::ParameterList params_;
  std::string source_, dir_;
  bool haveParameters_ = false;
  std::unique_ptr<ContactRun> run_;
};

// tfeti_contact's Problem = elastic_contact and nonlinear_contact: the solver on the validated
// `params`, its files in `dir`. Returns the result's exit code (0; 2: a QP did not converge; 3: a
// load step did not converge after the allowed cut-backs), all files written either way.
int runContactProblem(const Teuchos::RCP<const tfeti::Comm>& comm, Teuchos::ParameterList& params,
                      const std::string& dir);

}  // namespace contact
