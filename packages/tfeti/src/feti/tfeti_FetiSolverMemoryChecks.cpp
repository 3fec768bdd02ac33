// FetiSolver's memory checks: before the subdomain factorizations, the Dirichlet
// preconditioner's interior factorizations and the explicit dual operator's assembly, what each
// will allocate against what the nodes have available (tfeti_NodeMemory.hpp). A problem too
// large for its nodes stops with a message naming the phase before it allocates anything; the
// forecast for a dry run (FetiSolver::forecastSetupMemory) counts the same.
#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_NodeMemory.hpp"

namespace tfeti {

NodeMemory FetiSolver::nodesHold(double need, bool cannotTell, double held) const {
  int mine = cannotTell ? 1 : 0, any = 0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, mine, Teuchos::outArg(any));
  if (any) return NodeMemory{};  // Amesos2's solvers: nothing known to check
  return nodeMemory(*comm_, need, held);
}

void FetiSolver::checkFactorMemory() {
  factorMemory_ = NodeMemory{};
  if (!params_.get<bool>("Memory check")) return;
  // The predictions make the symbolic analyses (kept for the factorizations): their memory is
  // then in use, and what is available is read after them. The factorizations go one by one:
  // the need is the factors made so far plus the next one's transient, at its peak.
  RunningPeak need;
  bool cannotTell = false;
  collectively(*comm_, [&] {
    for (auto& s : subdomains_) {
      const MemoryPrediction p = s->predictFactorMemory();
      cannotTell = cannotTell || !p.known();
      if (p.known()) need.make(static_cast<double>(p.held), static_cast<double>(p.transient));
    }
  });
  factorMemory_ = nodesHold(need.peak, cannotTell, need.running);
  if (factorMemory_.fits) return;
  throw std::invalid_argument(
      "the subdomain factors (\"Local solver\" = " + params_.get<std::string>("Local solver") +
      ") do not fit: " + describe(factorMemory_) +
      " before the factorizations; run on more nodes (or fewer ranks per node), or set FETI "
      "\"Memory check\" = false to go on regardless (swap); --check estimates the factors' "
      "bytes before anything is factorized");
}

void FetiSolver::checkPreconditionerMemory(const std::vector<std::vector<int>>& dofs,
                                           const std::vector<char>& rebuild,
                                           PreconditionerType type, bool releaseStiffness) {
  preconditionerMemory_ = NodeMemory{};
  int makes = 0, anyMakes = 0;
  if (type == PreconditionerType::Dirichlet)
    for (char r : rebuild) makes |= r;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, makes, Teuchos::outArg(anyMakes));
  if (!anyMakes || !params_.get<bool>("Memory check")) return;
  // The set-up goes subdomain by subdomain: a preconditioner (its blocks and interior factor,
  // with the factorization's transient while it is made) replaces the last one, then K goes
  // (releaseStiffness). The need is the peak of that running sum.
  const std::string solver = params_.get<std::string>("Local solver");
  RunningPeak need;
  bool cannotTell = false;
  collectively(*comm_, [&] {
    for (std::size_t i = 0; i < subdomains_.size(); ++i) {
      Subdomain& s = *subdomains_[i];
      if (rebuild[i]) {
        const MemoryPrediction p = s.predictPreconditionerMemory(dofs[i], type, solver);
        cannotTell = cannotTell || !p.known();
        if (p.known())
          need.make(static_cast<double>(p.held), static_cast<double>(p.transient),
                    static_cast<double>(s.preconditionerMemory()));
      }
      if (releaseStiffness) need.release(static_cast<double>(s.stiffness().bytes()));
    }
  });
  preconditionerMemory_ = nodesHold(need.peak, cannotTell);
  if (preconditionerMemory_.fits) return;
  throw std::invalid_argument(
      "the Dirichlet preconditioner's interior factors (\"Local solver\" = " + solver +
      ") do not fit: " + describe(preconditionerMemory_) +
      " after the subdomain factorizations; use FETI \"Preconditioner\" = lumped, run on more "
      "nodes (or fewer ranks per node), or set FETI \"Memory check\" = false to go on "
      "regardless (swap)");
}

double FetiSolver::explicitBlockTransient(std::size_t i,
                                          const ExplicitDualOperator::PlannedBlock& p) {
  const std::size_t m = static_cast<std::size_t>(p.rows);
  const std::size_t old = static_cast<std::size_t>(std::max(p.oldRows, 0));
  Subdomain& s = *subdomains_[i];
  // As assemble() goes: a block solved for wholly comes from the Schur complement where the
  // subdomain can give it, one with rows kept by solves.
  if (m > 0 && p.solved == p.rows &&
      parseBlockAssembly(params_.get<std::string>("Explicit assembly")) == BlockAssembly::Schur) {
    const std::vector<int> dofs = subdomainDualDofs(tearing_, i);
    const std::ptrdiff_t peak = s.predictInverseBlockMemory(dofs);
    if (peak >= 0) return explicitSchurTransient(static_cast<double>(peak), dofs.size(), m, old);
  }
  return explicitSolvesTransient(s.numDofs(), m, p.solved, old);
}

double FetiSolver::explicitAssemblyNeed(
    DenseStorage storage, bool releaseStiffness,
    const std::vector<ExplicitDualOperator::PlannedBlock>& plan) {
  double blocks = 0.0, transient = 0.0, freed = 0.0, full = 0.0;
  for (std::size_t i = 0; i < subdomains_.size(); ++i) {
    const std::size_t m = static_cast<std::size_t>(plan[i].rows);
    full += static_cast<double>(sizeof(double) * m * m);
    if (!plan[i].takenOver) {
      blocks += static_cast<double>(explicitBlockBytes(storage, m));
      transient = std::max(transient, explicitBlockTransient(i, plan[i]));
      // What the solves leave with the factor (Tacho's workspace): as held as the blocks. The
      // Schur assembly makes no solve, but only CHOLMOD offers it, whose solves keep nothing.
      if (plan[i].solved > 0)
        blocks += static_cast<double>(subdomains_[i]->pseudoInverseSolveKeeps(
            explicitSolveWidth(static_cast<std::size_t>(plan[i].solved))));
    }
    if (releaseStiffness) freed += static_cast<double>(subdomains_[i]->stiffness().bytes());
  }
  // On a device, the blocks go up as one full copy of them all on the host.
  if (parseExplicitDevice(params_.get<std::string>("Explicit device")) == ExplicitDevice::Gpu)
    transient = std::max(transient, full);
  return blocks + transient - freed;
}

bool FetiSolver::explicitDoesNotFit(DenseStorage storage, const ExplicitDualOperator* previous,
                                    bool releaseStiffness) {
  if (!params_.get<bool>("Memory check")) {
    dualChoice_.fitsMemory = true;
    dualChoice_.nodeNeedBytes = 0.0;
    dualChoice_.nodeAvailableBytes = -1.0;
    return false;
  }
  // Every block the new operator assembles, wholly or in part, takes new memory while the
  // previous operator still holds the old values: all of them after a set-up from scratch, the
  // refactorized subdomains' and those whose rows moved after update(). Which ones is a rank's
  // own matter (a refactorized plastic subdomain here, elastic ones kept there); the check is
  // collective, so every rank takes part in it where any assembles.
  const std::vector<ExplicitDualOperator::PlannedBlock> plan =
      ExplicitDualOperator::plannedBlocks(tearing_, subdomains_, storage, previous);
  int assembles = 0, anyAssembles = 0;
  for (const auto& p : plan) assembles = p.takenOver ? assembles : 1;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, assembles, Teuchos::outArg(anyAssembles));
  if (!anyAssembles) return false;  // the last check stands
  const NodeMemory node = nodesHold(explicitAssemblyNeed(storage, releaseStiffness, plan), false);
  dualChoice_.fitsMemory = node.fits;
  dualChoice_.nodeNeedBytes = node.needBytes;
  dualChoice_.nodeAvailableBytes = node.known ? node.availableBytes : -1.0;
  if (node.fits) return false;
  if (!dualChoice_.automatic)
    throw std::invalid_argument(
        "FETI \"Dual operator\" = explicit: the dense local F_s (" +
        params_.get<std::string>("Explicit storage") + ") do not fit: " + describe(node) +
        " after the factorizations and the preconditioner; use \"Dual operator\" = implicit "
        "(or auto, which falls back to implicit), or more nodes (--check prints the F_s bytes "
        "before anything is factorized)");
  // auto: implicit after all; the K kept for the Schur assembly go now.
  dualChoice_.chosen = "implicit";
  if (releaseStiffness)
    for (auto& s : subdomains_) s->releaseStiffness();
  return true;
}

}  // namespace tfeti
