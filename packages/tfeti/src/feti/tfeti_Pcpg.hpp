#pragma once
// Projected preconditioned conjugate gradients (Farhat & Roux) for the equality-constrained
// dual problem  min 1/2 l^T F l - l^T d  subject to  G l = e:  CG on P F P from the particular
// solution l0 with G l0 = e, preconditioned by P M^{-1} P.
//
// Stopping rule: ||P (F l - d)|| <= tolerance * ||P d||, the projected gradient relative to the
// projected right-hand side (independent of the initial guess).
// Belos conventions (tfeti_SolverConventions.hpp): "Convergence Tolerance" and "Maximum
// Iterations" are aliases of "Relative tolerance" and "Maximum iterations"; "Verbosity" takes a
// Belos::MsgType mask too (IterationDetails: every iteration, FinalSummary: the summary,
// Warnings: a line when not converged, TimingDetails: the solve's time); timers "tfeti: PCPG
// solve" and "tfeti: Hessian apply" (every application of F).
#include <Teuchos_ParameterList.hpp>

#include <functional>
#include <vector>

#include "tfeti_CoarseSpace.hpp"
#include "tfeti_SolverOutput.hpp"

namespace tfeti {

struct PcpgResult {
  bool converged = false;
  int iterations = 0;
  double projectedGradientNorm = 0.0;  // final ||P g||
  double relativeResidual = 0.0;       // ||P g|| / ||P d||
  std::vector<double> history;         // relative residual per iteration
};

class Pcpg {
 public:
  // Valid parameters with their defaults: "Relative tolerance" (1e-6), "Maximum iterations"
  // (1000), "Verbosity" (0: silent, 1: summary, 2: every iteration).
  static Teuchos::RCP<const Teuchos::ParameterList> validParameters();
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters() {
    return validParameters();
  }
  // The parameters in use, defaults filled in, under the package's names.
  const Teuchos::ParameterList& getCurrentParameters() const { return params_; }

  Pcpg(Teuchos::RCP<const Operator> F, const CoarseSpace& coarse,
       Teuchos::RCP<const Operator> preconditioner, const Teuchos::ParameterList& params);

  // Solves from lambda (on entry the particular solution, G lambda = e; on exit the solution);
  // g returns F lambda - d.
  PcpgResult solve(const Vector& d, Vector& lambda, Vector& g);
  // Of the last solve: iterations, and ||P g|| / ||P d|| (the quantity the tolerance bounds).
  int getNumIters() const { return last_.iterations; }
  double achievedTol() const { return last_.relativeResidual; }
  // Progress lines (Verbosity >= 1, rank 0) go here; null: std::cout (never reformatted).
  void setOutputStream(Teuchos::RCP<std::ostream> os) { out_.setStream(std::move(os)); }

 private:
  Teuchos::RCP<const Operator> F_;
  const CoarseSpace& coarse_;
  Teuchos::RCP<const Operator> M_;
  Teuchos::ParameterList params_;
  double tol_;
  int maxIter_;
  SolverOutput out_;
  PcpgResult last_;
};

}  // namespace tfeti
