#pragma once
#include <BelosStatusTestCombo.hpp>
#include <BelosStatusTestMaxIters.hpp>
#include <Teuchos_Assert.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <chrono>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "tfeti_BoundTraits.hpp"
#include "tfeti_MprgpIteration_def.hpp"
#include "tfeti_MprgpSolMgr_decl.hpp"
#include "tfeti_QpChecks.hpp"
#include "tfeti_QpStatusTests.hpp"
#include "tfeti_SeparableSet.hpp"
#include "tfeti_StrictParameters.hpp"
#include "tfeti_TimedOperator.hpp"

namespace tfeti {

template <class S, class MV, class OP>
Teuchos::RCP<const Teuchos::ParameterList> MprgpSolMgr<S, MV, OP>::getValidParameters() {
  static Teuchos::RCP<Teuchos::ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::rcp(new Teuchos::ParameterList("MPRGP"));
    pl->set("Relative tolerance", 1e-6, "stop when ||g^P|| <= tolerance * ||b||",
            strict::positive());
    pl->set("Maximum iterations", 10000, "limit on MPRGP steps; reaching it is Unconverged",
            strict::count());
    pl->set("Gamma", 1.0, "proportioning: proportional when ||beta||^2 <= Gamma^2 phi~^T phi",
            strict::positive());
    pl->set("Step length factor", 1.9, "alphaBar = factor / ||A||, in (0, 2]",
            strict::between(0.0, 2.0, true, false));
    pl->set(
        "Expansion step", "fixed",
        "fixed: x = P(x - alphaBar phi) (Dostál-Schöberl); optimal: the step minimizing f "
        "along -phi before the projection, alphaBar when that does not decrease f (one more "
        "multiplication; for Hessians whose norm the bounds do not see, e.g. P F P + rho Q); "
        "projected CG: x = P(x - alphaCg p), the conjugate gradient step projected onto the "
        "bounds, accepted when f is not above f at the feasible half step, else the fixed "
        "step from the half step (one more multiplication)",
        Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
            Teuchos::tuple<std::string>("fixed", "optimal", "projected CG"), "Expansion step")));
    pl->set("Norm of A", 0.0, "||A||; 0: estimate by power iterations", strict::nonNegative());
    pl->set("Power iterations", 20, "power iterations for estimating ||A||", strict::count());
    pl->set("Preconditioning in face", false,
            "CG directions from the preconditioner restricted to the free set");
    pl->set("Verbosity", 0,
            "0 silent, 1 summary, 2 every step (rank 0), or a sum of Belos::MsgType values "
            "(Warnings 1, IterationDetails 2, FinalSummary 8, TimingDetails 16, "
            "StatusTestDetails 32)",
            strict::intBetween(0, kAllMsgTypes));
  }
  return pl;
}

template <class S, class MV, class OP>
void MprgpSolMgr<S, MV, OP>::checkParameters(Teuchos::ParameterList& params) {
  applyParameterAliases(params, "MPRGP", belosAliases("Maximum iterations"));
  params.validateParametersAndSetDefaults(*getValidParameters());
  auto fail = [](bool bad, const std::string& what) {
    TEUCHOS_TEST_FOR_EXCEPTION(bad, std::invalid_argument, "MPRGP: parameter " << what);
  };
  const double tol = params.get<double>("Relative tolerance");
  const double factor = params.get<double>("Step length factor");
  fail(!(tol >= 0.0), "\"Relative tolerance\" must be >= 0");
  fail(params.get<int>("Maximum iterations") < 1, "\"Maximum iterations\" must be >= 1");
  fail(!(params.get<double>("Gamma") > 0.0), "\"Gamma\" must be > 0");
  fail(!(factor > 0.0 && factor <= 2.0), "\"Step length factor\" must be in (0, 2]");
  fail(!(params.get<double>("Norm of A") >= 0.0), "\"Norm of A\" must be >= 0 (0: estimate)");
  fail(params.get<int>("Power iterations") < 1, "\"Power iterations\" must be >= 1");
  verbosityMask(params.get<int>("Verbosity"), "MPRGP");
}

template <class S, class MV, class OP>
MprgpSolMgr<S, MV, OP>::MprgpSolMgr(const BoundConstrainedQp<S, MV, OP>& qp,
                                    const Teuchos::ParameterList& params,
                                    Teuchos::RCP<const OP> preconditioner)
    : M_(std::move(preconditioner)) {
  setParameters(params);
  setProblem(qp);
  checkReady();
}

template <class S, class MV, class OP>
MprgpSolMgr<S, MV, OP>::MprgpSolMgr() {
  setParameters(Teuchos::ParameterList("MPRGP"));
}

template <class S, class MV, class OP>
void MprgpSolMgr<S, MV, OP>::setParameters(const Teuchos::ParameterList& params) {
  // Aliases are resolved within the list given, so that a Belos name there replaces the
  // package's name set earlier instead of conflicting with it.
  Teuchos::ParameterList given = params;
  applyParameterAliases(given, "MPRGP", belosAliases("Maximum iterations"));
  Teuchos::ParameterList merged = params_.numParams() == 0 ? given : params_;
  if (params_.numParams() != 0) merged.setParameters(given);
  checkParameters(merged);
  params_ = merged;
  out_.setMask(verbosityMask(params_.get<int>("Verbosity"), "MPRGP"));
  if (params_.get<double>("Norm of A") > 0.0) {
    normA_ = params_.get<double>("Norm of A");
    normGiven_ = true;
  }
}

template <class S, class MV, class OP>
void MprgpSolMgr<S, MV, OP>::setProblem(const BoundConstrainedQp<S, MV, OP>& qp) {
  TEUCHOS_TEST_FOR_EXCEPTION(
      qp.A.is_null() || qp.b.is_null() || qp.lower.is_null() || qp.x.is_null(),
      std::invalid_argument, "MPRGP: A, b, lower and x of the problem must all be set");
  qp_ = qp;
}

template <class S, class MV, class OP>
void MprgpSolMgr<S, MV, OP>::setPreconditioner(Teuchos::RCP<const OP> preconditioner) {
  M_ = std::move(preconditioner);
}

template <class S, class MV, class OP>
void MprgpSolMgr<S, MV, OP>::checkReady() const {
  TEUCHOS_TEST_FOR_EXCEPTION(qp_.A.is_null(), std::invalid_argument,
                             "MPRGP: no problem to solve (setProblem was not called)");
  TEUCHOS_TEST_FOR_EXCEPTION(
      params_.get<bool>("Preconditioning in face") && M_.is_null(), std::invalid_argument,
      "MPRGP: parameter \"Preconditioning in face\" = true needs a preconditioner");
}

template <class S, class MV, class OP>
void MprgpSolMgr<S, MV, OP>::reset(Belos::ResetType type) {
  counters_ = QpCounters{};
  g_ = Teuchos::null;
  g0_ = Teuchos::null;
  numIters_ = 0;
  achievedTol_ = 0;
  if ((type & Belos::Problem) != 0 && !normGiven_) normA_ = 0;
}

template <class S, class MV, class OP>
void MprgpSolMgr<S, MV, OP>::setConvergenceTest(Teuchos::RCP<Belos::StatusTest<S, MV, OP>> test,
                                                bool replaceDefault) {
  userTest_ = std::move(test);
  replaceDefault_ = replaceDefault && !userTest_.is_null();
}

template <class S, class MV, class OP>
void MprgpSolMgr<S, MV, OP>::setNormOfA(magnitude_type normA) {
  TEUCHOS_TEST_FOR_EXCEPTION(!(normA > 0) || !std::isfinite(normA), std::invalid_argument,
                             "MPRGP: ||A|| must be positive and finite, got " << normA);
  normA_ = normA;
  normGiven_ = true;
}

template <class S, class MV, class OP>
typename MprgpSolMgr<S, MV, OP>::magnitude_type MprgpSolMgr<S, MV, OP>::estimateNorm(
    const OP& A, const MV& like, int iterations, long long* multiplications, MV* start) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  auto v = MVT::Clone(like, 1);
  auto w = MVT::Clone(like, 1);
  std::vector<magnitude_type> n(1);
  if (start != nullptr) MVT::MvNorm(*start, n);
  if (start != nullptr && n[0] > magnitude_type(0) && std::isfinite(n[0]))
    MVT::MvAddMv(S(1), *start, S(0), *start, *v);
  else
    BoundTraits<S, MV>::fillDeterministic(*v);
  MVT::MvNorm(*v, n);
  MVT::MvScale(*v, S(1) / n[0]);
  magnitude_type est = 0;
  for (int k = 0; k < iterations; ++k) {
    Belos::OperatorTraits<S, MV, OP>::Apply(A, *v, *w);
    if (multiplications != nullptr) ++*multiplications;
    MVT::MvNorm(*w, n);
    est = n[0];
    if (!std::isfinite(est))
      throw std::runtime_error("MPRGP: A produced NaN or Inf while estimating ||A||");
    if (est == magnitude_type(0)) break;
    MVT::MvAddMv(S(1) / est, *w, S(0), *w, *v);
  }
  if (!(est > magnitude_type(0)))
    throw std::runtime_error("MPRGP: the estimate of ||A|| is zero (A = 0 on the start vector)");
  if (start != nullptr) MVT::MvAddMv(S(1), *v, S(0), *v, *start);
  return magnitude_type(1.05) * est;
}

template <class S, class MV, class OP>
Belos::ReturnType MprgpSolMgr<S, MV, OP>::solve() {
  Teuchos::TimeMonitor monitor(*solverTimer("tfeti: MPRGP solve"));
  const bool root = qp_.x.is_null() || BoundTraits<S, MV>::commRank(*qp_.x) == 0;
  return out_.reportingErrors("MPRGP", root, [&] { return solveTimed(); });
}

template <class S, class MV, class OP>
Belos::ReturnType MprgpSolMgr<S, MV, OP>::solveTimed() {
  using MVT = Belos::MultiVecTraits<S, MV>;
  using BT = BoundTraits<S, MV>;
  checkReady();
  counters_ = QpCounters{};
  checkQpMaps(qp_, "MPRGP");
  MprgpIteration<S, MV, OP>::checkProblemData(qp_);
  const bool root = BT::commRank(*qp_.x) == 0;
  const auto start = std::chrono::steady_clock::now();
  // The same problem with A under the "tfeti: Hessian apply" timer.
  const auto hessianTimer = solverTimer("tfeti: Hessian apply");
  const double hessianTime0 = hessianTimer->totalElapsedTime();
  BoundConstrainedQp<S, MV, OP> timed = qp_;
  timed.A = TimedOperator<S, MV, OP>::wrap(qp_.A, hessianTimer);

  if (!normGiven_)
    normA_ = estimateNorm(*timed.A, *qp_.x, params_.get<int>("Power iterations"),
                          &counters_.hessianMultiplications);
  std::vector<magnitude_type> n(1);
  MVT::MvNorm(*qp_.b, n);
  counters_.rhsNorm = n[0];
  magnitude_type scale = n[0];
  if (scale == magnitude_type(0) && !replaceDefault_) {
    // b = 0: ||b|| gives no scale, the gradient at P(0) does (non-zero unless P(0) solves it).
    auto y = MVT::Clone(*qp_.x, 1);
    auto Ay = MVT::Clone(*qp_.x, 1);
    MVT::MvInit(*y, S(0));
    feasibleSet(qp_).project(*y);
    Belos::OperatorTraits<S, MV, OP>::Apply(*timed.A, *y, *Ay);
    ++counters_.hessianMultiplications;
    MVT::MvNorm(*Ay, n);
    scale = n[0];
  }
  if (scale == magnitude_type(0)) scale = 1;

  auto maxIters = Teuchos::rcp(
      new Belos::StatusTestMaxIters<S, MV, OP>(params_.get<int>("Maximum iterations")));
  auto gradTest = Teuchos::rcp(new StatusTestProjectedGradient<S, MV, OP>());
  gradTest->setRelativeTolerance(params_.get<double>("Relative tolerance"), scale);
  Teuchos::RCP<Belos::StatusTest<S, MV, OP>> convTest;
  if (userTest_.is_null())
    convTest = gradTest;
  else if (replaceDefault_)
    convTest = userTest_;
  else
    convTest = Teuchos::rcp(new Belos::StatusTestCombo<S, MV, OP>(
        Belos::StatusTestCombo<S, MV, OP>::OR, gradTest, userTest_));
  convTest->reset();
  auto combo = Teuchos::rcp(new Belos::StatusTestCombo<S, MV, OP>(
      Belos::StatusTestCombo<S, MV, OP>::OR, maxIters, convTest));

  typename MprgpIteration<S, MV, OP>::Options opts;
  opts.gamma = params_.get<double>("Gamma");
  opts.alphaBar = params_.get<double>("Step length factor") / normA_;
  opts.optimalExpansion = params_.get<std::string>("Expansion step") == "optimal";
  opts.projectedCgExpansion = params_.get<std::string>("Expansion step") == "projected CG";
  opts.printScale = scale;
  opts.verbosity = out_.wants(Belos::IterationDetails) ? 2 : 0;
  opts.out = &out_.stream();
  const Teuchos::RCP<const OP> M =
      params_.get<bool>("Preconditioning in face") ? M_ : Teuchos::RCP<const OP>();
  MprgpIteration<S, MV, OP> iteration(timed, M, combo, opts);
  const SeparableSet<S, MV> set = feasibleSet(qp_);
  if (!g0_.is_null() && set.isFeasible(*qp_.x)) iteration.setInitialGradient(g0_);
  iteration.initialize();
  iteration.iterate();

  const QpCounters& ic = iteration.counters();
  counters_.hessianMultiplications += ic.hessianMultiplications;
  counters_.cgSteps = ic.cgSteps;
  counters_.expansionSteps = ic.expansionSteps;
  counters_.proportioningSteps = ic.proportioningSteps;
  counters_.history = ic.history;
  for (double& h : counters_.history) h /= scale;
  counters_.projectedGradientNorm = iteration.projectedGradientNorm();
  numIters_ = iteration.getNumIters();
  g_ = iteration.getGradient();
  // Every step ends with a projection onto the box or only moves into it: this cannot fail.
  TEUCHOS_TEST_FOR_EXCEPTION(!set.isFeasible(*qp_.x), std::logic_error,
                             "MPRGP: internal error, the solution violates the bounds");

  const bool converged =
      iteration.reachedStationaryPoint() || convTest->getStatus() == Belos::Passed;
  counters_.converged = converged;
  std::ostringstream msg;
  msg << std::scientific << std::setprecision(3);
  if (iteration.reachedStationaryPoint())
    msg << "converged: the projected gradient is exactly zero after " << numIters_ << " steps";
  else if (!converged && iteration.stalledAtRounding())
    msg << "not converged: stopped after " << numIters_
        << " steps, the search direction's curvature is at rounding level, with ||g^P|| = "
        << counters_.projectedGradientNorm << " (" << counters_.projectedGradientNorm / scale
        << " relative, tolerance " << params_.get<double>("Relative tolerance") << ")";
  else if (converged)
    msg << "converged after " << numIters_
        << " steps: ||g^P|| = " << counters_.projectedGradientNorm << " ("
        << counters_.projectedGradientNorm / scale << " relative)";
  else
    msg << "not converged: the limit of " << params_.get<int>("Maximum iterations")
        << " steps was reached with ||g^P|| = " << counters_.projectedGradientNorm << " ("
        << counters_.projectedGradientNorm / scale << " relative, tolerance "
        << params_.get<double>("Relative tolerance") << ")";
  counters_.message = msg.str();
  achievedTol_ = counters_.projectedGradientNorm / scale;
  if (out_.wants(Belos::FinalSummary) && root) {
    auto line = SolverOutput::line();
    line << "MPRGP: " << counters_.message << "; " << counters_.cgSteps << " CG, "
         << counters_.expansionSteps << " expansion, " << counters_.proportioningSteps
         << " proportioning steps, " << counters_.hessianMultiplications
         << " multiplications by A, ||A|| = " << normA_ << "\n";
    out_.write(line);
  } else if (!converged && out_.wants(Belos::Warnings) && root) {
    out_.write("MPRGP: warning: " + counters_.message + "\n");
  }
  if (out_.wants(Belos::TimingDetails) && root) {
    auto line = SolverOutput::line();
    line << "MPRGP: solve " << std::scientific << std::setprecision(3)
         << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
         << " s, of which " << hessianTimer->totalElapsedTime() - hessianTime0 << " s in "
         << counters_.hessianMultiplications << " multiplications by A\n";
    out_.write(line);
  }
  if (out_.wants(Belos::StatusTestDetails) && root) {
    std::ostringstream tests;
    combo->print(tests);
    out_.write("MPRGP: status tests at the end:\n" + tests.str());
  }
  return converged ? Belos::Converged : Belos::Unconverged;
}

}  // namespace tfeti
