#pragma once
// What differs between the two problems ContactSolver runs through its one load-step loop. The
// elastic problem is the loop's one-step case (contact_ElasticContactPolicy.cpp), the nonlinear
// problem its load-stepped case (contact_NonlinearContactPolicy.cpp); the driver asks its policy
// at the named steps where they part, never which problem it runs.
#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact_ContactResult.hpp"
#include "contact_ElasticContactProblem.hpp"
#include "contact_NonlinearModel.hpp"
#include "contact_NonlinearOptions.hpp"

namespace contact {

struct ContactRun;  // contact_ContactRun.hpp
struct LoadSteps;   // contact_ContactRun.hpp

class RunPolicy {
 public:
  // "Problem": elastic_contact or nonlinear_contact (ContactSolver::setParameters checks it).
  static std::unique_ptr<const RunPolicy> forProblem(const std::string& problem);
  virtual ~RunPolicy() = default;

  // summary.json's "problem".
  virtual std::string name() const = 0;

  // --- setup()
  // The spec the parameters give and the options read from them, with the checks made before
  // meshing (throw std::invalid_argument naming the parameter).
  virtual ElasticContactSpec readParameters(const Teuchos::ParameterList& params,
                                            NonlinearOptions& options) const = 0;
  // What the options need of the mesh: its dimension and how many pairs have a rigid obstacle.
  virtual void fitOptions(const Teuchos::ParameterList& params, int dim, int rigidObstacles,
                          NonlinearOptions& options) const = 0;
  // The residual's scale.
  virtual double loadNorm(const tfeti::Comm& comm, const ElasticContactProblem& problem,
                          const NonlinearOptions& options) const = 0;
  // The equality rows the FETI solver is built with, the run starting from u at load factor t.
  virtual std::vector<tfeti::EqualityRow> initialEqualityRows(const ElasticContactProblem& problem,
                                                              double t, const Field& u) const = 0;
  // The contact rows (model.problem.inequalities) the FETI solver is built with, the run's first
  // increment going from model.u to load factor t (collective).
  virtual void initialContact(const tfeti::Comm& comm, NonlinearModel& model,
                              const NonlinearOptions& options, double t) const = 0;

  // --- the load steps
  // Whether each iteration gets a progress line (Verbosity 2).
  virtual bool printsIterations() const = 0;
  // Whether a step that did not converge is kept, its failure reported (exit code 2), rather
  // than reverted and cut back.
  virtual bool keepsUnconvergedStep() const = 0;
  // Whether each accepted step is saved: its files, the tables, the restart files, its line.
  virtual bool savesSteps() const = 0;
  // An accepted step's figures in `rec`, from its trial state u (before the model commits it).
  virtual void evaluateStep(ContactRun& r, LoadSteps& s, const Field& u, StepRecord& rec) const = 0;
  // The final state's stresses and contact nodes in r (r.evaluated when they are known).
  virtual void evaluateFinalState(ContactRun& r, LoadSteps& s) const = 0;
  // The final state's Cauchy stresses in r.stresses, for a policy whose evaluateFinalState
  // leaves them to be computed when the C++ API asks for them (r.stressesPending).
  virtual void finalStresses(ContactRun& /*r*/) const {}

  // --- the result
  // The applied load's resultant at the final load factor.
  virtual double appliedForce(const ContactRun& r) const = 0;
  // The contact figures only this case reports (`c` has the common ones).
  virtual void addContactMeasures(ContactMeasures& c, const ContactRun& r) const = 0;
  // The final state's contact CSV (res.contactCsv) and, with r.vtu, its VTU in `dir`.
  virtual void writeFinalState(ContactResult& res, const ContactRun& r, const LoadSteps& s,
                               const std::string& dir) const = 0;
  // The run's last line (rank 0, Verbosity > 0).
  virtual void report(const ContactResult& res, const ContactRun& r, const LoadSteps& s) const = 0;
};

// The two cases, each in its own file.
std::unique_ptr<const RunPolicy> elasticContactPolicy();
std::unique_ptr<const RunPolicy> nonlinearContactPolicy();

inline std::unique_ptr<const RunPolicy> RunPolicy::forProblem(const std::string& problem) {
  if (problem == "elastic_contact") return elasticContactPolicy();
  if (problem == "nonlinear_contact") return nonlinearContactPolicy();
  throw std::invalid_argument("RunPolicy: no run policy for \"Problem\" = " + problem);
}

}  // namespace contact
