#pragma once
// The state of a ContactSolver run, shared by the driver's named steps
// (contact_ContactSolver.cpp) and its run policy (contact_RunPolicy.hpp): what setup() builds,
// and what solve()'s load steps carry.
#include <Teuchos_ParameterList.hpp>

#include <chrono>
#include <iomanip>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "contact_ContactOutput.hpp"
#include "contact_ContactResult.hpp"
#include "contact_ElasticContactProblem.hpp"
#include "contact_FrictionHistory.hpp"
#include "contact_LoadStepControl.hpp"
#include "contact_NonlinearIteration.hpp"
#include "contact_NonlinearModel.hpp"
#include "contact_NonlinearOptions.hpp"
#include "contact_NonlinearStepOutput.hpp"
#include "contact_RunPolicy.hpp"

namespace contact {

// A set-up run.
struct ContactRun {
  Teuchos::RCP<const tfeti::Comm> comm;
  std::unique_ptr<const RunPolicy> policy;  // the problem's case of the load-step loop
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  bool solved = false;
  int verbosity = 1;
  bool vtu = false;  // Output/VTU: the final state as VTU
  ElasticContactSpec spec;
  Teuchos::ParameterList feti;
  NonlinearOptions options;
  std::unique_ptr<NonlinearModel> model;
  std::unique_ptr<tfeti::FetiSolver> solver;
  double loadNorm = 0.0, appliedForce = 0.0;
  double loadDirection[3] = {0.0, 0.0, 0.0};
  NonlinearHistory history;
  ModelFriction friction;
  FrictionHistory frictionHistory;  // read by a restart, kept up to date by the load steps
  // Coulomb friction alone holds a body along the surface: every load step starts sticking
  // (stickingBounds), as the previous step's bounds may not hold the new load.
  bool frictionSticks = false;
  // The load factor beyond which the contact and friction rows cannot hold the load
  // (InitialFriction): with Tresca rows, where it is finite.
  std::optional<FrictionLoadLimit> frictionLimit;
  // The final state, once the policy has evaluated it: its stresses and contact nodes.
  bool evaluated = false;
  std::vector<plasticity::StressField> stresses;
  // The stresses are not computed yet: ContactSolver::stresses() asks the policy for them (the
  // nonlinear runs' own output uses its step's stresses, not these).
  bool stressesPending = false;
  std::vector<ContactNode> nodes;
  // The largest von Mises stress of the nodal averages over all subdomains (maxNodalVonMises).
  double maxVonMisesNodal = 0.0;

  std::string elapsed() const {
    std::ostringstream s;
    s << std::fixed << std::setprecision(1)
      << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s";
    return s.str();
  }
};

// solve()'s load steps: the iteration that solves a step, the output of the converged ones, the
// step control, and how the loop ended.
struct LoadSteps {
  LoadSteps(ContactRun& r, const std::string& dir)
      : iteration(r.comm, *r.model, *r.solver, r.options, r.loadNorm),
        output(r.comm, *r.model, *r.solver, r.options, dir),
        control(r.history, r.options.steps, r.options.maxCutbacks, r.options.stopAfter) {}

  LoadStepIteration iteration;
  NonlinearStepOutput output;
  LoadStepControl control;
  std::vector<FixedPointStep> fixedPointSteps;  // Coulomb, per converged step
  tfeti::DualResult lastQp;
  // failed: no cut-back left; stopped: Stop after step; qpFailed: a kept step's QP did not
  // converge.
  bool failed = false, stopped = false, qpFailed = false;
  std::string failure;
};

}  // namespace contact
