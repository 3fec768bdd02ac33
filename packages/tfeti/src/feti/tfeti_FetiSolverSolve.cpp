// FetiSolver::solve(): the dual problem by the chosen solver, then the primal solution. The
// equality-only case (PCPG) is here; the QP of the inequality rows is in tfeti_FetiSolverQp.cpp,
// the primal recovery in tfeti_PrimalRecovery.cpp.
#include "tfeti_FetiSolver.hpp"
#include "tfeti_PhaseTimer.hpp"

namespace tfeti {

DualResult FetiSolver::solve() {
  const std::string method = dualSolverFor(params_, tearing_.numInequalityRows);
  lambda_ = Teuchos::rcp(new Vector(tearing_.multiplierMap));
  holdingRows_ = Teuchos::null;
  penaltyOffset_ = Teuchos::null;
  DualResult result = method == "PCPG" ? solvePcpg() : solveQp(method);
  const std::string fitFailure = recoverPrimal();
  // A converged QP whose rows holding with equality leave a rigid motion free (a body held by
  // friction alone with every node at its slip bound) does not determine u: reported as not
  // converged, so that a load step is cut back and a single solve exits as unconverged, with
  // its last state written, instead of an error that loses the run.
  if (result.converged && !fitFailure.empty()) {
    result.converged = result.qp.converged = false;
    result.qp.message = "the dual solve converged, but " + fitFailure;
  }
  return result;
}

DualResult FetiSolver::solvePcpg() {
  DualResult result;
  Vector g(tearing_.multiplierMap);
  PhaseTimer t(*comm_, timings_.solve, &memory_, "solve");
  Tpetra::deep_copy(*lambda_, *lambda0_);
  Teuchos::ParameterList pp = params_.sublist("PCPG");
  pp.set("Relative tolerance", toleranceFactor_ * pp.get<double>("Relative tolerance"));
  Pcpg pcpg(F_, *coarse_, M_, pp);
  const long long before = F_->numApplies();
  pcpg.setOutputStream(out_);
  static_cast<PcpgResult&>(result) = pcpg.solve(*d_, *lambda_, g);
  result.method = "PCPG";
  // The same counters as the QP solvers, so that a tied and a contact solve compare directly.
  result.qp.hessianMultiplications = F_->numApplies() - before;
  result.qp.cgSteps = result.iterations;
  result.qp.converged = result.converged;
  result.qp.projectedGradientNorm = result.projectedGradientNorm;
  return result;
}

}  // namespace tfeti
