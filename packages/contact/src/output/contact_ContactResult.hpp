#pragma once
// What a contact run (contact::ContactSolver::solve, Problem = elastic_contact or
// nonlinear_contact) produced: every figure summary.json reports, as values, and the JSON writer
// that turns them into summary.json. summary.json is written from this object and nothing else,
// so a run through the tfeti_contact executable and one through ContactSolver report the same.
//
// Extending it (a new figure of the run, e.g. a friction force or stick/slip counts): add the
// value to the struct it belongs to (ContactMeasures for the "contact" object, StepRecord in
// contact_NonlinearHistory.hpp for a per-step value, ContactResult for a top-level key), fill it
// in one of ContactSolver::solve's named steps (contact_ContactSolver.cpp: measureContact for
// ContactMeasures, measureFinalState for the final state's fields and reactions, fillResult for
// the rest), or where only one problem has it in its run policy (contact_ElasticContactPolicy.cpp,
// contact_NonlinearContactPolicy.cpp: addContactMeasures); a per-step value where the policy
// evaluates the step (evaluateStep: NonlinearStepOutput::evaluate and fill for nonlinear_contact),
// and write its key in contactJson / summaryJson (contact_ContactResult.cpp), where each key of
// the file is written.
#include <optional>
#include <string>
#include <vector>

#include "contact_ContactOutput.hpp"
#include "contact_Friction.hpp"
#include "contact_Json.hpp"
#include "contact_NonlinearHistory.hpp"
#include "tfeti_FetiSolver.hpp"

namespace contact {

// A 3D line contact (a plane-strain slab, "Contact zone" = line): the half-width per node plane.
struct SlabContact {
  double lineLength = 0.0, forcePerUnitLength = 0.0;
  int nodePlanes = 0;
  double halfWidthMin = 0.0, halfWidthMax = 0.0;
};

// The "contact" object of summary.json: the contact zone of the final state.
struct ContactMeasures {
  tfeti::ConstraintReport constraints;  // of the (last) QP solve: rows B_I u <= c_I
  double pMax = 0.0;
  double pMaxRecovered = 0.0;  // the largest recovered pressure (contact_RecoveredFields.hpp)
  // The contact zone's extent: a half-width along x (metres), a half-angle (degrees) or a
  // contact radius (metres), as extentKey says.
  double extent = 0.0;
  std::string extentKey = "half_width";  // half_width | angle | contact_radius
  double force = 0.0;                    // the resultant contact force (along the load)
  double appliedForce = 0.0;
  double forceRelativeError = 0.0;  // |force - applied| / applied
  std::optional<SlabContact> slab;
  std::optional<HertzReference> hertz;
  // nonlinear_contact: the fixed boundaries' reaction along the load and its relative
  // difference from the contact force; max |du| of the last increment.
  double supportForce = 0.0, supportRelativeError = 0.0, lastMaxAbsIncrement = 0.0;
};

// The FETI solver's dimensions and counters.
struct FetiDimensions {
  std::string formulation, preconditioner, localSolver;
  long long primal = 0, dual = 0, gluingRows = 0, dirichletRows = 0, contactRows = 0, coarse = 0;
  long long largestScalingGroup = 0;
  long long dualOperatorApplies = 0;
  unsigned long long factorBytes = 0;
  // The subdomain factors' bytes against the nodes' memory before the last factorizations of
  // new subdomains (tfeti::FetiSolver::factorMemoryCheck).
  tfeti::NodeMemory factorMemory;
  // The same for the Dirichlet preconditioner (its blocks and interior factors), at the last
  // set-up that made some (tfeti::FetiSolver::preconditionerMemoryCheck).
  tfeti::NodeMemory preconditionerMemory;
  // FETI "Dual operator" and, when explicit, the bytes of the dense local F_s (all ranks, and
  // the largest rank's).
  std::string dualOperator = "implicit";
  unsigned long long explicitDualBytes = 0, explicitDualBytesMaxRank = 0;
  // FETI "Explicit device" and, with gpu, the device's work (tfeti::FetiSolver).
  tfeti::FetiSolver::ExplicitDeviceWork explicitDevice;
  // When explicit: the F_s assemblies of the run (tfeti::FetiSolver::explicitAssembly).
  tfeti::FetiSolver::ExplicitAssembly explicitAssembly;
  // How the dual operator was chosen ("Dual operator" = auto: why).
  tfeti::FetiSolver::DualOperatorChoice dualChoice;
};

// nonlinear_contact: how the load steps went ("nonlinear" object; the steps are in history).
struct NonlinearOutcome {
  bool geometricallyNonlinear = true;
  std::string stiffness;
  double eta1 = 0.0, eta2 = 0.0;
  bool stopped = false, restarted = false;
};

// A converged load step's Coulomb fixed point: its iterations and the last relative change of the
// slip bounds.
struct FixedPointStep {
  int step = 0, iterations = 0;
  double change = 0.0;
};

struct ContactResult {
  std::string problem;  // elastic_contact | nonlinear_contact
  int ranks = 0, subdomains = 0, dimension = 0;
  long long nodes = 0;
  // Every QP converged (elastic) / the run reached load factor 1 (nonlinear; false when stopped
  // by "Stop after step" or a step failed after the allowed cut-backs).
  bool converged = false;
  // The process exit code a run with this result gives: 0; 2 a QP did not converge (elastic);
  // 3 a load step did not converge after the allowed cut-backs (nonlinear).
  int exitCode = 0;
  std::string message;  // why not converged (empty when converged)

  FetiDimensions feti;
  ElasticContactProblem::Distribution distribution;  // subdomains to ranks, and its balance
  tfeti::DualResult qp;  // the (last) QP solve: counters, residual history, method, rho
  std::string contactType = "frictionless";  // elastic_contact: frictionless | tied | bonded
  std::string contactDiscretization = "node_to_segment";  // or mortar, or mixed (pairs differ)
  // The bodies and their materials (summary.json: "materials" per body, and "material" when
  // every body has the same).
  std::vector<ElasticContactSpec::Body> materials;

  bool haveContact = false;  // the contact object is filled (nonlinear: a step converged)
  ContactMeasures contact;
  // The slave nodes with a contact row (every rank holds all): position, multiplier, pressure,
  // the master's normal and the gap the solve left (ContactNode::gap, c_I - B_I u >= 0; 0 in
  // contact), and with friction the tangential results.
  std::vector<ContactNode> contactNodes;
  // With Contact pairs: every pair's name and contact force (summary contact.pairs); the keys
  // of `contact` then hold the totals over all pairs.
  std::vector<PairForce> pairs;

  double maxVonMises = 0.0, maxPlasticStrain = 0.0, maxAbsU = 0.0;
  double maxVonMisesNodal = 0.0;  // of the nodal averages over all subdomains

  // Prescribed displacements: the rows and the record per entry (boundary, component, value,
  // reaction) as prescribedSummary writes it.
  long long prescribedRows = 0;
  std::optional<Json> prescribed;
  // Kinematic couplings: their rows and the record per coupling (boundary, component, nodes,
  // displacement, spread) as couplingSummary writes it.
  long long couplingRows = 0;
  std::optional<Json> couplings;

  // The per-step history: one step for elastic_contact (its single increment), the converged
  // load steps (and every iteration, rejected ones too) for nonlinear_contact.
  NonlinearHistory history;
  NonlinearOutcome nonlinear;
  // Friction on the contact pair (nonlinear_contact): the law, and Coulomb's fixed point per
  // converged step; the per-node friction results are in contactNodes.
  ModelFriction friction;
  std::vector<FixedPointStep> fixedPoint;
  // The load factor beyond which the contact and friction rows cannot hold the load
  // (friction_limit): with Tresca rows, where it is finite.
  std::optional<FrictionLoadLimit> frictionLimit;

  tfeti::FetiTimings timings;
  double wallTime = 0.0, peakRssMb = 0.0;
  // Files written (empty without an output directory).
  std::string contactCsv, iterationsCsv, stepsCsv, vtu;
};

// The "contact" object of summary.json.
Json contactJson(const ContactResult& result);
// summary.json of the run, without "parameters" (writeSummary adds them).
Json summaryJson(const ContactResult& result);

}  // namespace contact
