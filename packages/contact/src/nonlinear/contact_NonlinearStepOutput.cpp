#include "contact_NonlinearStepOutput.hpp"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>
#include <utility>

#include "contact_RecoveredFields.hpp"

namespace contact {

std::string stepBaseName(int step) {
  std::ostringstream base;
  base << "step_" << std::setw(4) << std::setfill('0') << step;
  return base.str();
}

NonlinearStepOutput::NonlinearStepOutput(const Teuchos::RCP<const tfeti::Comm>& comm,
                                         const NonlinearModel& model,
                                         const tfeti::FetiSolver& solver,
                                         const NonlinearOptions& options, std::string dir)
    : comm_(comm), model_(model), solver_(solver), options_(options), dir_(std::move(dir)) {}

void NonlinearStepOutput::evaluate(const Field& u) {
  const ElasticContactProblem& problem = model_.problem;
  stresses_.clear();
  plasticNodal_.assign(u.size(), {});
  double vm = 0.0, ep = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    const auto& em = problem.localElements[i];
    stresses_.push_back(plasticity::cauchyStress(em, *model_.laws[i], u[i], options_.kinematics));
    const auto& st = stresses_.back();
    for (int e = 0; e < em.numElements(); ++e)
      for (int q = 0; q < st.gaussPointsPerElement; ++q)
        vm = std::max(vm, st.atGaussPoint(e, q, plasticity::kVonMises));
    ep = std::max(ep, plasticStrain(model_.plastic[i], em, plasticNodal_[i]));
  }
  maxVonMises_ = globalMax(*comm_, vm);
  maxVonMisesNodal_ = maxNodalVonMises(*comm_, problem, stresses_);
  maxPlasticStrain_ = globalMax(*comm_, ep);
  // The gaps each row keeps after the last increment du (the solver's solution).
  Field du;
  for (std::size_t i = 0; i < u.size(); ++i) du.push_back(solver_.solution(i));
  const std::vector<double> current = model_.surfaceDisplacement(*comm_, u);
  nodes_ = contactNodes(problem, solver_, options_.rule, current,
                        model_.surfaceDisplacement(*comm_, du));
  recoverContactPressures(nodes_, problem);
  if (friction.active()) {
    addFrictionResults(nodes_, problem, solver_, friction,
                       model_.surfaceDisplacement(*comm_, model_.u), current);
    addAccumulatedSlip(nodes_, accumulatedSlip);
  }
}

std::string NonlinearStepOutput::writeVtu(const std::string& base, const Field& u) const {
  std::vector<SubdomainFields> fields;
  std::vector<std::string> names{"plastic_strain"};
  if (friction.active())
    names.insert(names.end(), kFrictionPointFields.begin(), kFrictionPointFields.end());
  if (model_.problem.namedPairs) names.push_back("contact_pair");
  for (std::size_t i = 0; i < u.size(); ++i) {
    fields.push_back({&model_.problem.localElements[i],
                      model_.problem.local[i].mesh.id,
                      &u[i],
                      &stresses_[i],
                      {plasticNodal_[i]}});
    if (friction.active())
      for (auto& f : frictionPointFields(nodes_, model_.problem.local[i].mesh.globalNode))
        fields.back().extra.push_back(std::move(f));
    if (model_.problem.namedPairs)
      fields.back().extra.push_back(
          contactPairField(nodes_, model_.problem.local[i].mesh.globalNode));
  }
  return contact::writeVtu(*comm_, dir_, base, stressPiece(fields, names));
}

const std::vector<std::string> kFrictionPointFields{"contact_pressure", "tangential_traction",
                                                    "slip_increment",   "accumulated_slip",
                                                    "net_slip",         "friction_state"};

std::vector<std::vector<double>> frictionPointFields(const std::vector<ContactNode>& nodes,
                                                     const std::vector<tfeti::GO>& globalNode) {
  std::map<tfeti::GO, const ContactNode*> bySlave;
  for (const auto& n : nodes) bySlave[n.slaveNode] = &n;
  const std::size_t count = globalNode.size();
  std::vector<std::vector<double>> f(kFrictionPointFields.size(), std::vector<double>(count, 0.0));
  for (std::size_t k = 0; k < count; ++k) {
    const auto it = bySlave.find(globalNode[k]);
    if (it == bySlave.end()) {
      f[5][k] = -1.0;
      continue;
    }
    const ContactNode& n = *it->second;
    const double values[] = {n.pressure, n.tangentialTraction,   n.slip, n.accumulatedSlip,
                             n.netSlip,  double(n.frictionState)};
    for (std::size_t c = 0; c < f.size(); ++c) f[c][k] = values[c];
  }
  return f;
}

void NonlinearStepOutput::writeContactCsv(const std::string& path) const {
  contact::writeContactCsv(*comm_, path, nodes_, model_.dim());
}

void NonlinearStepOutput::fill(StepRecord& rec, const double direction[]) const {
  const int dim = model_.dim();
  rec.pMax = maxPressure(nodes_);
  rec.contactExtent = contactExtent(nodes_, options_.rule, dim);
  rec.maxVonMises = maxVonMises_;
  rec.maxPlasticStrain = maxPlasticStrain_;
  rec.contactForce = resultantForce(nodes_, direction, dim);
}

std::vector<PvdEntry> stepCollection(const NonlinearHistory& history) {
  std::vector<PvdEntry> entries;
  for (const auto& s : history.steps)
    entries.push_back({s.loadFactor, stepBaseName(s.step) + ".pvtu"});
  return entries;
}

void saveRestart(const tfeti::Comm& comm, const std::string& restartDir,
                 const NonlinearHistory& history, const NonlinearModel& model,
                 const FrictionHistory* friction) {
  const bool root = comm.getRank() == 0;
  const std::string stepDir = restartStepDirectory(restartDir, history.step);
  if (root) std::filesystem::create_directories(stepDir);
  comm.barrier();
  for (std::size_t i = 0; i < model.u.size(); ++i) {
    SubdomainRestart s;
    s.id = model.problem.local[i].mesh.id;
    s.displacement = model.u[i];
    if (model.plastic[i]) s.history = model.plastic[i]->committedHistory();
    writeSubdomainRestart(stepDir, s);
  }
  comm.barrier();
  if (root) {
    // Every rank holds the whole friction state (the contact nodes are global).
    if (friction) writeFrictionRestart(stepDir, *friction);
    writeRestartState(restartDir, history);
    // Older steps are no longer named by state.txt.
    for (const auto& entry : std::filesystem::directory_iterator(restartDir))
      if (entry.is_directory() && entry.path().string() != stepDir)
        std::filesystem::remove_all(entry.path());
  }
  comm.barrier();
}

}  // namespace contact
