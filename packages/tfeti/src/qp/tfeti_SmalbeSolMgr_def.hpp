#pragma once
#include <Teuchos_Assert.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "tfeti_BoundTraits.hpp"
#include "tfeti_FacePcpg.hpp"
#include "tfeti_MprgpSolMgr_def.hpp"
#include "tfeti_OperatorSum.hpp"
#include "tfeti_QpChecks.hpp"
#include "tfeti_QpStatusTests.hpp"
#include "tfeti_SeparableSet.hpp"
#include "tfeti_SmalbeSolMgr_decl.hpp"
#include "tfeti_StrictParameters.hpp"
#include "tfeti_TimedOperator.hpp"

namespace tfeti {

template <class S, class MV, class OP>
Teuchos::RCP<const Teuchos::ParameterList> SmalbeSolMgr<S, MV, OP>::getValidParameters() {
  static Teuchos::RCP<Teuchos::ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::rcp(new Teuchos::ParameterList("SMALBE"));
    pl->set("Relative tolerance", 1e-6, "stop when ||g^P|| <= tolerance * ||b|| ...",
            strict::positive());
    pl->set("Equality tolerance", 1e-6, "... and ||A|| ||Q x|| <= tolerance * ||b||",
            strict::positive());
    pl->set("Maximum outer iterations", 100, "limit on multiplier updates", strict::count());
    pl->set("Stall window", 50,
            "stop, not converged, after this many outer iterations in which ||Q x|| (above the "
            "equality tolerance) did not fall below half its smallest value before them, M "
            "unchanged: the bounds leave no point with Q x = 0 (an infeasible QP, e.g. a load "
            "beyond what friction holds); 0: never. A feasible QP halves ||Q x|| at about "
            "every outer iteration",
            strict::count(0));
    pl->set("Penalty", 1.0, "rho = Penalty * ||A||", strict::positive());
    pl->set("Initial M", 1.0, "M_0 = value * ||A||", strict::positive());
    pl->set("Beta", 10.0, "M is divided by Beta when the Lagrangian does not increase enough",
            strict::between(1.0, std::numeric_limits<double>::infinity(), true, true));
    pl->set("Lagrangian test", "Dostal",
            "Dostal: L(x_k, mu_k) < L(x_{k-1}, mu_{k-1}) + rho/2 ||Q x_k||^2 divides M by Beta "
            "(SMALBE-M as published); shifted: the same with L(x_k, mu_{k+1}) and "
            "L(x_{k-1}, mu_k), the multipliers after the update (the earlier implementation, "
            "which demands an increase of about rho ||Q x_{k-1}||^2 and fails almost always)",
            Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
                Teuchos::tuple<std::string>("Dostal", "shifted"), "Lagrangian test")));
    pl->set("Eta", 0.1, "eta = value * ||b||: inner precision bound", strict::positive());
    pl->set("Reuse gradient", true,
            "start each inner solve from the last inner gradient plus rho Q x (the multiplier "
            "change) instead of a multiplication; false: recompute it (the earlier behaviour)");
    pl->set("Norm of A", 0.0, "||A||; 0: estimate by power iterations", strict::nonNegative());
    pl->set("Power iterations", 20, "power iterations for estimating ||A||", strict::count());
    pl->set("Verbosity", 0,
            "0 silent, 1 summary, 2 every outer iteration (rank 0), or a sum of Belos::MsgType "
            "values (Warnings 1, IterationDetails 2, FinalSummary 8, TimingDetails 16, "
            "StatusTestDetails 32)",
            strict::intBetween(0, kAllMsgTypes));
    pl->set("Face solve", "none",
            "none: SMALBE-M alone; pcpg: once the active set is unchanged over \"Face settle "
            "iterations\" outer iterations, solve on that face (active rows held at their bounds, "
            "Q x = 0 by a projector) by projected preconditioned CG and accept the result only "
            "if it passes SMALBE's final test; otherwise a primal-dual active-set step and a new "
            "face, and after \"Maximum face solves\" back to SMALBE's own iterate",
            Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
                Teuchos::tuple<std::string>("none", "pcpg"), "Face solve")));
    pl->set("Face settle iterations", 1,
            "a face solve follows an outer iteration whose active set equals that of this many "
            "outer iterations before it (0: after every outer iteration)",
            strict::count(0));
    pl->set("Initial face", "none",
            "with Face solve = pcpg: none: the first face is the settled active set of the outer "
            "iterations; levels: before the first outer iteration, a bisection over the level "
            "sets {i : level_i > tau} of the levels the caller gives (FETI: the contact rows' "
            "gaps, open rows held at their bounds) for the face whose loose solve neither leaves "
            "the box nor has multipliers of the wrong sign, then a face solve from it; start: "
            "before the first outer iteration, a face solve on the active set of the initial "
            "iterate (a warm start's, or 3D friction's, whose discs have no levels)",
            Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
                Teuchos::tuple<std::string>("none", "levels", "start"), "Initial face")));
    pl->set("Level search start", "half lowest",
            "with Initial face = levels: middle: the bisection starts at the middle of the "
            "distinct levels; half lowest: when the lowest level is negative (a prescribed "
            "indentation), the first trial frees the levels at or below half of it, Hertz's "
            "contact zone of a smooth body pressed that deep, and the next trials move by the "
            "verdict's own count (rows of the wrong sign freed, rows out of the box held), "
            "falling back to bisection when two such steps land on one side (middle otherwise)",
            Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
                Teuchos::tuple<std::string>("middle", "half lowest"), "Level search start")));
    pl->set(
        "Circle releases", "held while rows join",
        "with discs (3D friction) and Face solve = pcpg: held while rows join: a face phase "
        "that starts from circles (a warm start whose discs slide, the Newton loop's previous "
        "QP) or from another load's solution releases no circle in a loose verdict that also "
        "joins rows to the face; the circles whose multiplier pulls inward are released once "
        "the face stops growing; at once: every verdict releases them",
        Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
            Teuchos::tuple<std::string>("held while rows join", "at once"), "Circle releases")));
    pl->set("Maximum face solves", 10,
            "limit on face solves (active-set corrections included) in one SMALBE solve",
            strict::count());
    pl->set("Face maximum iterations", 1000, "limit on the CG steps of one face solve",
            strict::count());
    pl->set("Face relative tolerance", kFaceRelativeTolerance,
            "the face CG stops at ||P_F g|| <= value * \"Relative tolerance\" * ||b||; ||P_F g|| "
            "is the residual of the rows that hold with equality (for FETI ||B u - c|| over the "
            "gluing and contact rows), which SMALBE alone ends well below its tolerance",
            strict::between(0.0, 1.0, true, false));
    pl->sublist("MPRGP", false, "inner solver (MPRGP) parameters")
        .setParameters(*MprgpSolMgr<S, MV, OP>::getValidParameters());
  }
  return pl;
}

template <class S, class MV, class OP>
SmalbeSolMgr<S, MV, OP>::SmalbeSolMgr(const BoundConstrainedQp<S, MV, OP>& qp,
                                      Teuchos::RCP<const OP> Q,
                                      const Teuchos::ParameterList& params,
                                      Teuchos::RCP<const OP> preconditioner)
    : P_(std::move(preconditioner)) {
  setParameters(params);
  setProblem(qp, std::move(Q));
  // Validates the inner solver's use of the preconditioner now rather than at the first solve.
  MprgpSolMgr<S, MV, OP> check(qp_, params_.sublist("MPRGP"), P_);
}

template <class S, class MV, class OP>
SmalbeSolMgr<S, MV, OP>::SmalbeSolMgr() {
  setParameters(Teuchos::ParameterList("SMALBE"));
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::setProblem(const BoundConstrainedQp<S, MV, OP>& qp,
                                         Teuchos::RCP<const OP> Q) {
  TEUCHOS_TEST_FOR_EXCEPTION(
      qp.A.is_null() || qp.b.is_null() || qp.lower.is_null() || qp.x.is_null() || Q.is_null(),
      std::invalid_argument, "SMALBE: A, b, lower, x and Q must all be set");
  qp_ = qp;
  Q_ = std::move(Q);
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::reset(Belos::ResetType) {
  counters_ = QpCounters{};
  face_ = FaceCounters{};
  mu_ = Teuchos::null;
  qApplies_ = 0;
  achievedTol_ = achievedEqualityTol_ = 0;
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::setParameters(const Teuchos::ParameterList& params) {
  // Aliases resolved within the list given (see MprgpSolMgr::setParameters), also in the inner
  // solver's sublist.
  Teuchos::ParameterList given = params;
  applyParameterAliases(given, "SMALBE", belosAliases("Maximum outer iterations"));
  if (given.isSublist("MPRGP"))
    applyParameterAliases(given.sublist("MPRGP"), "SMALBE/MPRGP",
                          belosAliases("Maximum iterations"));
  Teuchos::ParameterList merged = params_.numParams() == 0 ? given : params_;
  if (params_.numParams() != 0) merged.setParameters(given);
  merged.validateParametersAndSetDefaults(*getValidParameters());
  auto fail = [](bool bad, const std::string& what) {
    TEUCHOS_TEST_FOR_EXCEPTION(bad, std::invalid_argument, "SMALBE: parameter " << what);
  };
  fail(!(merged.get<double>("Relative tolerance") >= 0.0), "\"Relative tolerance\" must be >= 0");
  fail(!(merged.get<double>("Equality tolerance") >= 0.0), "\"Equality tolerance\" must be >= 0");
  fail(merged.get<int>("Maximum outer iterations") < 1,
       "\"Maximum outer iterations\" must be >= 1");
  fail(!(merged.get<double>("Penalty") > 0.0), "\"Penalty\" must be > 0");
  fail(!(merged.get<double>("Initial M") > 0.0), "\"Initial M\" must be > 0");
  fail(!(merged.get<double>("Beta") > 1.0), "\"Beta\" must be > 1");
  fail(!(merged.get<double>("Eta") > 0.0), "\"Eta\" must be > 0");
  fail(!(merged.get<double>("Norm of A") >= 0.0), "\"Norm of A\" must be >= 0 (0: estimate)");
  fail(merged.get<int>("Power iterations") < 1, "\"Power iterations\" must be >= 1");
  const int mask = verbosityMask(merged.get<int>("Verbosity"), "SMALBE");
  MprgpSolMgr<S, MV, OP>::checkParameters(merged.sublist("MPRGP"));
  params_ = merged;
  out_.setMask(mask);
}

template <class S, class MV, class OP>
Belos::ReturnType SmalbeSolMgr<S, MV, OP>::solve() {
  Teuchos::TimeMonitor monitor(*solverTimer("tfeti: SMALBE solve"));
  const bool root = qp_.x.is_null() || BoundTraits<S, MV>::commRank(*qp_.x) == 0;
  return out_.reportingErrors("SMALBE", root, [&] { return solveTimed(); });
}

// The state of one solve, shared by its steps.
template <class S, class MV, class OP>
struct SmalbeSolMgr<S, MV, OP>::SolveState {
  bool root = false;
  std::chrono::steady_clock::time_point start;
  // ||b|| (or its substitute) and the tolerances scaled by it.
  magnitude_type scale = 0, gTol = 0, eTol = 0, eta = 0;
  magnitude_type beta = 0;
  bool shiftedTest = false, reuseGradient = false, faceMode = false;
  int maxOuter = 0, settleRequired = 0;
  // The inner problem: min L(x, mu, rho) on the bounds, its linear term bInner = b - mu.
  BoundConstrainedQp<S, MV, OP> inner;
  Teuchos::RCP<MV> bInner, Qx, gNext;
  Teuchos::ParameterList innerParams;
  Teuchos::RCP<StatusTestSmalbeInner<S, MV, OP>> innerTest;
  // Progress.
  int k = 0;
  bool converged = false, innerFailed = false;
  magnitude_type gp = 0, qxNorm = 0;
  S lagrangianPrev = 0;
  magnitude_type noisePrev = 0;
  std::vector<long long> activePrev;
  int settled = 0;
  // The stall test: the smallest ||Q x|| so far, the outer iteration that halved it last (or
  // reduced M), and whether the window since then has run out.
  magnitude_type stallBest = std::numeric_limits<magnitude_type>::infinity();
  int stallSince = 0, stallWindow = 0;
  bool stalled = false;
};

template <class S, class MV, class OP>
Belos::ReturnType SmalbeSolMgr<S, MV, OP>::solveTimed() {
  using BT = BoundTraits<S, MV>;
  TEUCHOS_TEST_FOR_EXCEPTION(qp_.A.is_null(), std::invalid_argument,
                             "SMALBE: no problem to solve (setProblem was not called)");
  counters_ = QpCounters{};
  face_ = FaceCounters{};
  qApplies_ = 0;
  startOnCircles_ = false;
  checkQpMaps(qp_, "SMALBE", Q_.get());
  MprgpIteration<S, MV, OP>::checkProblemData(qp_);
  SolveState s;
  s.root = BT::commRank(*qp_.x) == 0;
  s.start = std::chrono::steady_clock::now();
  setNormAndPenalty();
  setTolerances(s);
  setUpOuterIterations(s);
  setUpFaceGramian(s);
  const std::string initialFace = params_.get<std::string>("Initial face");
  if (s.faceMode && initialFace == "levels" && !levels_.is_null()) startFromLevelFace(s);
  if (s.faceMode && initialFace == "start") startFromInitialFace(s);
  for (; s.k < s.maxOuter && !s.converged && !s.stalled; ++s.k) outerIteration(s);
  finishSolve(s);
  return s.converged ? Belos::Converged : Belos::Unconverged;
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::setNormAndPenalty() {
  normA_ = params_.get<double>("Norm of A");
  if (!(normA_ > 0))
    normA_ = MprgpSolMgr<S, MV, OP>::estimateNorm(
        *TimedOperator<S, MV, OP>::wrap(qp_.A, solverTimer("tfeti: Hessian apply")), *qp_.x,
        params_.get<int>("Power iterations"), &counters_.hessianMultiplications);
  rho_ = params_.get<double>("Penalty") * normA_;
  M_ = params_.get<double>("Initial M") * normA_;
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::setTolerances(SolveState& s) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;
  std::vector<magnitude_type> n(1);
  MVT::MvNorm(*qp_.b, n);
  counters_.rhsNorm = n[0];
  s.scale = n[0];
  if (s.scale == magnitude_type(0)) {
    auto y = MVT::Clone(*qp_.x, 1);
    auto Ay = MVT::Clone(*qp_.x, 1);
    MVT::MvInit(*y, S(0));
    feasibleSet(qp_).project(*y);
    OPT::Apply(*TimedOperator<S, MV, OP>::wrap(qp_.A, solverTimer("tfeti: Hessian apply")), *y,
               *Ay);
    ++counters_.hessianMultiplications;
    MVT::MvNorm(*Ay, n);
    s.scale = n[0] > magnitude_type(0) ? n[0] : magnitude_type(1);
  }
  s.gTol = params_.get<double>("Relative tolerance") * s.scale;
  s.eTol = params_.get<double>("Equality tolerance") * s.scale / normA_;
  s.eta = params_.get<double>("Eta") * s.scale;
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::setUpOuterIterations(SolveState& s) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  s.beta = params_.get<double>("Beta");
  s.shiftedTest = params_.get<std::string>("Lagrangian test") == "shifted";
  s.reuseGradient = params_.get<bool>("Reuse gradient");
  s.maxOuter = params_.get<int>("Maximum outer iterations");
  s.stallWindow = params_.get<int>("Stall window");
  s.gNext = MVT::Clone(*qp_.x, 1);
  mu_ = MVT::Clone(*qp_.x, 1);
  if (mu0_.is_null())
    MVT::MvInit(*mu_, S(0));
  else
    MVT::Assign(*mu0_, *mu_);
  s.bInner = MVT::Clone(*qp_.x, 1);
  s.Qx = MVT::Clone(*qp_.x, 1);
  const Teuchos::RCP<const OP> H =
      augmented_.is_null() ? OperatorSum<S, MV, OP>::build(qp_.A, S(1), Q_, S(rho_)) : augmented_;
  // With disc constraints the inner solver is MPGP (the same iteration on discs).
  s.inner = BoundConstrainedQp<S, MV, OP>{H,         s.bInner,  qp_.lower,      qp_.x,
                                          qp_.upper, qp_.discs, qp_.discCenters};
  s.innerParams = params_.sublist("MPRGP");
  s.innerTest = Teuchos::rcp(new StatusTestSmalbeInner<S, MV, OP>(Q_, M_, s.eta, s.gTol, s.eTol));
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::setUpFaceGramian(SolveState& s) {
  using BT = BoundTraits<S, MV>;
  s.faceMode = params_.get<std::string>("Face solve") == "pcpg";
  // The faces' columns of Q, shared by all faces of this solve (every bound component a
  // candidate, both components of every disc included: a circle row combines their columns).
  gramian_ = Teuchos::null;
  if (s.faceMode) {
    std::vector<long long> bounded = BT::finiteIndices(*qp_.lower);
    for (const MV* v : {qp_.upper.get(), qp_.discs.get()}) {
      if (v == nullptr) continue;
      const std::vector<long long> more = BT::finiteIndices(*v);
      std::vector<long long> both;
      std::set_union(bounded.begin(), bounded.end(), more.begin(), more.end(),
                     std::back_inserter(both));
      bounded = std::move(both);
    }
    gramian_ = Teuchos::rcp(
        new FaceGramian<S, MV, OP>(Q_, std::move(bounded), *qp_.x, complementColumns_));
  }
  s.settleRequired = params_.get<int>("Face settle iterations");
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::startFromLevelFace(SolveState& s) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  // The active set from the levels (for contact: the gap, whose sublevel sets are the contact
  // zones of smooth convex bodies) instead of from MPRGP's expansion steps, which on fine
  // meshes open a few rows at a time.
  feasibleSet(qp_).project(*qp_.x);
  // An initial iterate that already passes the final test (no load: x = 0 with the gap
  // multiplier, FetiSolver) is the answer, as SMALBE's first inner solve would return it; the
  // loose face solves of the search would only replace it by rounding.
  testInitialIterate(s);
  if (!s.converged) {
    auto x = MVT::CloneCopy(*qp_.x);
    bool found = false;
    std::vector<long long> active = levelFace(kLevelTolerance * s.scale, *x, found);
    if (found)
      s.converged = faceSolve(std::move(active), s.gTol, s.eTol, s.scale, s.gp, s.qxNorm, x.get());
  }
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::startFromInitialFace(SolveState& s) {
  // The active set of the initial iterate as the first face: for a warm start (the Newton
  // loop's previous QP) it is close to the answer, and with discs (3D friction) the inner MPGP
  // solves would otherwise find it through CG steps along the circles, each followed by a
  // projection and a fresh gradient (docs/qp_solvers.md, "The face solve with discs").
  using MVT = Belos::MultiVecTraits<S, MV>;
  const SeparableSet<S, MV> set = feasibleSet(qp_);
  set.project(*qp_.x);
  // A given face start (the Newton loop's previous solution, for a new tangent and right-hand
  // side) is practically never the answer already, and the face solve tests its entry point
  // anyway (a converged one takes no CG step): the test of the initial iterate would cost a
  // multiplication per QP for nothing (step-42 at 64^3: 7 of the plastic run's 188).
  if (faceStart_.is_null()) {
    testInitialIterate(s);
    if (s.converged) return;
  }
  auto y = MVT::CloneCopy(faceStart_.is_null() ? *qp_.x : *faceStart_);
  set.project(*y);
  // A start with circles (discs at their bound: the previous QP's slip set) holds the releases of
  // its loose verdicts while rows join (holdsCircleReleases).
  const std::vector<long long> active = set.activeIndices(*y);
  startOnCircles_ = !qp_.discs.is_null() && !set.circles(*y, active).empty();
  s.converged = faceSolve(active, s.gTol, s.eTol, s.scale, s.gp, s.qxNorm, y.get());
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::testInitialIterate(SolveState& s) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;
  std::vector<magnitude_type> n(1);
  auto g = MVT::Clone(*qp_.x, 1), phi = MVT::Clone(*qp_.x, 1), chopped = MVT::Clone(*qp_.x, 1);
  OPT::Apply(*s.inner.A, *qp_.x, *g);
  ++counters_.hessianMultiplications;
  MVT::MvAddMv(S(1), *g, S(-1), *qp_.b, *g);
  MVT::MvAddMv(S(1), *g, S(1), *mu_, *g);
  const SeparableSet<S, MV> set = feasibleSet(qp_);
  set.freeGradient(*qp_.x, *g, *phi);
  set.choppedGradient(*qp_.x, *g, *chopped);
  MVT::MvAddMv(S(1), *phi, S(1), *chopped, *phi);
  MVT::MvNorm(*phi, n);
  s.gp = n[0];
  OPT::Apply(*Q_, *qp_.x, *s.Qx);
  ++qApplies_;
  MVT::MvNorm(*s.Qx, n);
  s.qxNorm = n[0];
  s.converged = s.gp <= s.gTol && s.qxNorm <= s.eTol;
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::outerIteration(SolveState& s) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;
  MVT::MvAddMv(S(1), *qp_.b, S(-1), *mu_, *s.bInner);  // L's linear term: b - mu
  s.innerTest->setM(M_);
  MprgpSolMgr<S, MV, OP> mprgp(s.inner, s.innerParams, P_);
  mprgp.setOutputStream(out_.getStream());
  mprgp.setNormOfA(normA_ + rho_);
  if (s.reuseGradient && s.k > 0) mprgp.setInitialGradient(s.gNext);
  mprgp.setConvergenceTest(s.innerTest, true);
  const Belos::ReturnType innerResult = mprgp.solve();
  const QpCounters& ic = mprgp.counters();
  counters_.hessianMultiplications += ic.hessianMultiplications;
  counters_.cgSteps += ic.cgSteps;
  counters_.expansionSteps += ic.expansionSteps;
  counters_.proportioningSteps += ic.proportioningSteps;
  if (innerResult != Belos::Converged) s.innerFailed = true;

  std::vector<magnitude_type> n(1);
  OPT::Apply(*Q_, *qp_.x, *s.Qx);
  ++qApplies_;
  MVT::MvNorm(*s.Qx, n);
  s.qxNorm = n[0];
  s.gp = ic.projectedGradientNorm;
  counters_.history.push_back(s.gp / s.scale);
  s.converged = s.gp <= s.gTol && s.qxNorm <= s.eTol;

  magnitude_type noise = 0;
  const S lagrangianK = lagrangianAt(*mprgp.getGradient(), noise);
  // mu_{k+1} = mu_k + rho Q x_k: even after convergence, so that A x - b + mu is the
  // gradient the inner solver drove to zero.
  MVT::MvAddMv(S(1), *mu_, S(rho_), *s.Qx, *mu_);
  // SMALBE-M compares L(x_k, mu_k) with L(x_{k-1}, mu_{k-1}), each at the multiplier of its
  // own inner solve; "shifted" compares L(x_k, mu_{k+1}) = L(x_k, mu_k) + rho ||Q x_k||^2
  // with L(x_{k-1}, mu_k), which asks for an increase of about rho ||Q x_{k-1}||^2.
  const S lagrangian = s.shiftedTest ? lagrangianK + S(rho_) * s.qxNorm * s.qxNorm : lagrangianK;
  const S required = S(0.5) * S(rho_) * s.qxNorm * s.qxNorm;
  // M is reduced only when the shortfall exceeds the rounding level of L (otherwise the
  // decision, and with it the iteration, would depend on the order of the reductions).
  const bool reduceM = !s.converged && s.k > 0 &&
                       lagrangian + std::max(noise, s.noisePrev) < s.lagrangianPrev + required;
  reportOuterIteration(s, mprgp.getNumIters(), lagrangian, required, reduceM);
  if (s.converged) return;
  if (faceAfterOuterIteration(s)) {
    s.converged = true;
    return;
  }
  if (reduceM) M_ /= s.beta;
  // Stalled: ||Q x|| has not halved for a window of outer iterations with M unchanged. Feasible
  // QPs halve it at about every one (docs/qp_solvers.md, "When the equality constraints stall").
  if (s.qxNorm < magnitude_type(0.5) * s.stallBest || reduceM) {
    s.stallBest = std::min(s.stallBest, s.qxNorm);
    s.stallSince = s.k;
  }
  s.stalled = s.stallWindow > 0 && s.qxNorm > s.eTol && s.k - s.stallSince >= s.stallWindow;
  if (s.reuseGradient) {
    // The next inner gradient at the same x: H x - b + mu_{k+1} = g + rho Q x.
    MVT::MvAddMv(S(1), *mprgp.getGradient(), S(rho_), *s.Qx, *s.gNext);
  }
  s.lagrangianPrev = lagrangian;
  s.noisePrev = noise;
}

template <class S, class MV, class OP>
S SmalbeSolMgr<S, MV, OP>::lagrangianAt(const MV& innerGradient, magnitude_type& noise) const {
  using MVT = Belos::MultiVecTraits<S, MV>;
  // L(x_k, mu_k) = 1/2 x^T (g - b + mu) with g = H x - b + mu_k the inner gradient.
  std::vector<S> d(1);
  auto w = MVT::CloneCopy(innerGradient);
  MVT::MvAddMv(S(1), *w, S(-1), *qp_.b, *w);
  MVT::MvAddMv(S(1), *w, S(1), *mu_, *w);
  MVT::MvDot(*qp_.x, *w, d);
  // The rounding level of that dot product: Lagrangian changes below it carry no information.
  std::vector<magnitude_type> nx(1), nw(1);
  MVT::MvNorm(*qp_.x, nx);
  MVT::MvNorm(*w, nw);
  noise = magnitude_type(1e3) * std::numeric_limits<magnitude_type>::epsilon() * nx[0] * nw[0];
  return S(0.5) * d[0];
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::reportOuterIteration(const SolveState& s, int innerSteps,
                                                   S lagrangian, S required, bool reduceM) {
  if (!out_.wants(Belos::IterationDetails) || !s.root) return;
  auto line = SolverOutput::line();
  line << "SMALBE " << std::setw(4) << s.k + 1 << "  ||g^P||/||b|| = " << std::scientific
       << std::setprecision(3) << s.gp / s.scale
       << "  ||A|| ||Qx||/||b|| = " << normA_ * s.qxNorm / s.scale << "  M/||A|| = " << M_ / normA_
       << "  MPRGP steps " << innerSteps << "  L increase "
       << (s.k > 0 ? lagrangian - s.lagrangianPrev : S(0)) << " (needed " << required
       << (reduceM ? ", M reduced)" : ")") << std::fixed << std::setprecision(2) << "  [QP "
       << std::chrono::duration<double>(std::chrono::steady_clock::now() - s.start).count()
       << " s]\n";
  out_.write(line);
}

template <class S, class MV, class OP>
bool SmalbeSolMgr<S, MV, OP>::faceAfterOuterIteration(SolveState& s) {
  // The face phase: once the active set has settled, solve on that face like the tied
  // problem; accepted only when the result passes the final test above.
  std::vector<long long> active = feasibleSet(qp_).activeIndices(*qp_.x);
  if (s.k > 0 && active != s.activePrev) ++face_.activeSetChanges;
  s.settled = s.k > 0 && active == s.activePrev ? s.settled + 1 : 0;
  s.activePrev = active;
  if (s.faceMode && s.settled >= s.settleRequired &&
      face_.solves < params_.get<int>("Maximum face solves")) {
    if (faceSolve(std::move(active), s.gTol, s.eTol, s.scale, s.gp, s.qxNorm)) return true;
    s.settled = 0;
  }
  return false;
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::finishSolve(const SolveState& s) {
  qApplies_ += s.innerTest->projectorApplications();
  if (!gramian_.is_null()) qApplies_ += gramian_->projectorApplications();
  gramian_ = Teuchos::null;  // its columns belong to this solve's Q
  counters_.outerIterations = s.k;
  counters_.projectedGradientNorm = s.gp;
  counters_.equalityResidualNorm = s.qxNorm;
  counters_.converged = s.converged;
  counters_.message = summaryMessage(s);
  achievedTol_ = s.gp / s.scale;
  achievedEqualityTol_ = normA_ * s.qxNorm / s.scale;
  reportSolve(s);
}

template <class S, class MV, class OP>
std::string SmalbeSolMgr<S, MV, OP>::summaryMessage(const SolveState& s) const {
  std::ostringstream msg;
  msg << std::scientific << std::setprecision(3);
  if (s.converged)
    msg << "converged after " << s.k << " outer iterations"
        << (face_.accepted ? " (the last a face solve)" : "")
        << ": ||g^P||/||b|| = " << s.gp / s.scale
        << ", ||A|| ||Qx||/||b|| = " << normA_ * s.qxNorm / s.scale;
  else if (s.stalled)
    msg << "not converged: the equality constraints stalled: ||A|| ||Qx||/||b|| = "
        << normA_ * s.qxNorm / s.scale << " (tolerance "
        << params_.get<double>("Equality tolerance") << ") did not halve in the last "
        << s.stallWindow << " outer iterations (\"Stall window\"), after " << s.k
        << ": the bounds may leave no multipliers that meet them (a load beyond what friction "
           "or contact can hold); ||g^P||/||b|| = "
        << s.gp / s.scale;
  else
    msg << "not converged: the limit of " << s.maxOuter
        << " outer iterations was reached with ||g^P||/||b|| = " << s.gp / s.scale << " (tolerance "
        << params_.get<double>("Relative tolerance")
        << "), ||A|| ||Qx||/||b|| = " << normA_ * s.qxNorm / s.scale << " (tolerance "
        << params_.get<double>("Equality tolerance") << ")";
  if (s.faceMode)
    msg << "; face solve: " << face_.solves << " face solves, " << face_.iterations
        << " face CG steps, " << face_.activeSetChanges << " active-set changes";
  if (face_.levelSolves > 0)
    msg << ", " << face_.levelSolves << " level-search face solves (their CG steps included)";
  if (face_.circleSteps > 0)
    msg << ", " << face_.circleSteps << " of them Newton steps on the circles";
  if (face_.stiffPreconditionerApplications > 0)
    msg << ", " << face_.stiffPreconditionerApplications
        << " preconditioner applications for stiff circles";
  if (s.innerFailed)
    msg << "; some inner MPRGP solves hit their \"Maximum iterations\" before reaching the "
           "inner precision";
  return msg.str();
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::reportSolve(const SolveState& s) {
  const bool root = s.root;
  if (out_.wants(Belos::FinalSummary) && root) {
    auto line = SolverOutput::line();
    line << "SMALBE: " << counters_.message << "; " << counters_.cgSteps << " CG, "
         << counters_.expansionSteps << " expansion, " << counters_.proportioningSteps
         << " proportioning steps, " << counters_.hessianMultiplications
         << " Hessian multiplications, rho = " << rho_ << ", final M = " << M_ << "\n";
    out_.write(line);
  } else if (!s.converged && out_.wants(Belos::Warnings) && root) {
    out_.write("SMALBE: warning: " + counters_.message + "\n");
  }
  if (out_.wants(Belos::TimingDetails) && root) {
    auto line = SolverOutput::line();
    line << "SMALBE: solve " << std::scientific << std::setprecision(3)
         << std::chrono::duration<double>(std::chrono::steady_clock::now() - s.start).count()
         << " s\n";
    out_.write(line);
  }
  if (out_.wants(Belos::StatusTestDetails) && root) {
    auto line = SolverOutput::line();
    line << "SMALBE: final test: ||g^P|| = " << std::scientific << std::setprecision(3) << s.gp
         << (s.gp <= s.gTol ? " <= " : " > ") << s.gTol << " and ||Q x|| = " << s.qxNorm
         << (s.qxNorm <= s.eTol ? " <= " : " > ") << s.eTol
         << (s.converged ? ": Passed" : ": Failed") << "\n";
    out_.write(line);
  }
}

}  // namespace tfeti

#include "tfeti_SmalbeFacePhase_def.hpp"
