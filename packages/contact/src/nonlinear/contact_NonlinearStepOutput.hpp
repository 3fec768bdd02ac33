#pragma once
// What a converged load step of the nonlinear contact loop reports and writes: the Cauchy
// stresses, von Mises and equivalent plastic strain, the contact nodes (multipliers, pressure,
// extent), the step's VTU piece and CSV, its StepRecord and its restart files.
#include <map>
#include <string>
#include <vector>

#include "contact_ContactOutput.hpp"
#include "contact_Friction.hpp"
#include "contact_FrictionHistory.hpp"
#include "contact_NonlinearHistory.hpp"
#include "contact_NonlinearModel.hpp"
#include "contact_NonlinearOptions.hpp"

namespace contact {

// step_NNNN: the files of a converged load step.
std::string stepBaseName(int step);

class NonlinearStepOutput {
 public:
  NonlinearStepOutput(const Teuchos::RCP<const tfeti::Comm>& comm, const NonlinearModel& model,
                      const tfeti::FetiSolver& solver, const NonlinearOptions& options,
                      std::string dir);

  // Stresses, plastic strain and contact nodes of the trial state u (the laws' trial history
  // and the solver's last multipliers); collective.
  void evaluate(const Field& u);
  bool evaluated() const { return !nodes_.empty(); }
  const std::vector<ContactNode>& nodes() const { return nodes_; }
  double maxVonMises() const { return maxVonMises_; }
  // Of the nodal averages over all subdomains (maxNodalVonMises).
  double maxVonMisesNodal() const { return maxVonMisesNodal_; }
  double maxPlasticStrain() const { return maxPlasticStrain_; }

  // Friction on the contact pair: evaluate adds each contact node's friction results (the
  // step's slip from model.u, the step's start) and its slip accumulated over the steps
  // (`accumulatedSlip`, the converged steps' sums, plus this step's).
  ModelFriction friction;
  std::map<int, AccumulatedSlip> accumulatedSlip;
  // After a converged step's evaluate: its slip joins accumulatedSlip.
  void commitSlip() { commitAccumulatedSlip(accumulatedSlip, nodes_); }

  // DIR/base.pvtu of u with the evaluated fields; returns its path. With friction, point data
  // of the contact nodes (frictionPointFields) join them.
  std::string writeVtu(const std::string& base, const Field& u) const;
  void writeContactCsv(const std::string& path) const;

  // The results of the evaluated state: p_max, the contact extent, von Mises, plastic strain
  // and the resultant contact force along `direction` (dim entries).
  void fill(StepRecord& record, const double direction[]) const;

 private:
  Teuchos::RCP<const tfeti::Comm> comm_;
  const NonlinearModel& model_;
  const tfeti::FetiSolver& solver_;
  const NonlinearOptions& options_;
  std::string dir_;
  std::vector<plasticity::StressField> stresses_;
  std::vector<std::vector<double>> plasticNodal_;
  std::vector<ContactNode> nodes_;
  double maxVonMises_ = 0.0, maxPlasticStrain_ = 0.0, maxVonMisesNodal_ = 0.0;
};

// The ParaView collection of the converged steps' VTU files, the load factor as time (a
// restarted run's history holds the steps of the run it continues).
std::vector<PvdEntry> stepCollection(const NonlinearHistory& history);

// The friction results as point data of a subdomain's nodes (local numbering, globalNode its
// untorn ids): contact_pressure, tangential_traction, slip_increment, accumulated_slip,
// net_slip and friction_state (0 open, 1 stick, 2 slip; -1 at a node without a contact row,
// whose other fields are 0). Every copy of a slave node carries its values.
extern const std::vector<std::string> kFrictionPointFields;
std::vector<std::vector<double>> frictionPointFields(const std::vector<ContactNode>& nodes,
                                                     const std::vector<tfeti::GO>& globalNode);

// The restart files of the converged state (model.u and the committed history) for
// history.step in restartDir, with `friction` (when given) in friction.txt, then state.txt;
// older steps' files are removed. Collective.
void saveRestart(const tfeti::Comm& comm, const std::string& restartDir,
                 const NonlinearHistory& history, const NonlinearModel& model,
                 const FrictionHistory* friction = nullptr);

}  // namespace contact
