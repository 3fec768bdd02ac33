#pragma once
// SmalbeSolMgr: SMALBE-M (Dostál, "Optimal Quadratic Programming Algorithms", 2009: the
// semi-monotonic augmented Lagrangian method for bound and equality constraints with a fixed
// penalty rho and an adaptive precision control M) for
//   min 1/2 x^T A x - b^T x  subject to  l <= x <= u  and  Q x = 0   (u optional),
// Q an orthogonal projector (Q = Q^T = Q^2) onto the range of the equality-constraint rows, so
// ||Q x|| is the equality residual. With the multiplier mu in range(Q), the augmented Lagrangian
//   L(x, mu, rho) = 1/2 x^T (A + rho Q) x - b^T x + mu^T x
// is minimized subject to l <= x <= u by MPRGP (Hessian H = A + rho Q applied as an OperatorSum),
// warm-started from the previous x, to the precision
//   ||g^P(x, mu_k)|| <= min(M_k ||Q x||, eta)
// (or until SMALBE's final test holds, see below); then mu_{k+1} = mu_k + rho Q x_k, and M is
// divided by beta when L did not increase enough (k > 0; each L at the multiplier of its own
// inner solve, as published; a shortfall below the rounding level of L does not count):
//   L(x_k, mu_k, rho) < L(x_{k-1}, mu_{k-1}, rho) + rho/2 ||Q x_k||^2   =>   M_{k+1} = M_k / beta.
// The next inner solve starts at x_k with the gradient g_k + rho Q x_k (no multiplication).
// SMALBE stops when ||g^P|| <= tol ||b|| and ||A|| ||Q x|| <= tolE ||b||; g = A x - b + mu with
// the final mu (getMultiplier), the gradient of the Lagrangian, so the KKT conditions read
// g^P = 0 and Q x = 0.
//
// Parameters (getValidParameters(); unknown names throw). ||A|| is the given "Norm of A" or the
// power-iteration estimate, which makes every parameter below invariant to scaling A, b or x:
//  "Relative tolerance"        1e-6  ||g^P|| <= tol * ||b||
//  "Equality tolerance"        1e-6  ||A|| * ||Q x|| <= tolE * ||b|| (||A|| Q x has the units
//                                    of b)
//  "Maximum outer iterations"  100   limit on the multiplier updates
//  "Stall window"              50    stop (not converged) when ||Q x|| > the equality tolerance
//                                    has not halved over this many outer iterations, M
//                                    unchanged: an infeasible QP; 0: never
//  "Penalty"                   1.0   rho = Penalty * ||A||
//  "Initial M"                 1.0   M_0 = value * ||A||
//  "Beta"                      10.0  M is divided by Beta when the Lagrangian does not increase
//                                    enough (> 1)
//  "Lagrangian test"           "Dostal"  the test above; "shifted": L(x_k, mu_{k+1}) against
//                                    L(x_{k-1}, mu_k), the earlier implementation, which asks for
//                                    about rho ||Q x_{k-1}||^2 and fails almost always
//  "Reuse gradient"            true  start the inner solves from g_k + rho Q x_k; false: one
//                                    multiplication per outer iteration (the earlier behaviour)
//  "Eta"                       0.1   eta = value * ||b||
//  "Norm of A"                 0.0   ||A|| of the unaugmented Hessian; 0: power iterations
//  "Power iterations"          20    for the estimate of ||A||
//  "Verbosity"                 0     0 silent, 1 summary, 2 every outer iteration (rank 0)
//  "Face solve"                "none"  pcpg: once the active set (the components at a bound) is
//                                    the same after "Face settle iterations" + 1 consecutive
//                                    outer iterations, minimize on that face (active components
//                                    held at their bounds, Q x = 0) by projected preconditioned
//                                    CG with the face's projector (tfeti_FacePcpg.hpp); the
//                                    result is taken only when it passes the final test below
//                                    (then it ends the solve); otherwise a primal-dual active-set
//                                    step (rows that left the box join, active rows whose
//                                    multiplier has the wrong sign leave) and a new face solve,
//                                    and when the face does not change or "Maximum face solves"
//                                    (10) is reached SMALBE goes on from its own iterate.
//                                    "Face maximum iterations" (1000) limits one face solve;
//                                    it stops at ||P_F g|| <= "Face relative tolerance" (0.01)
//                                    * tol * ||b||, in (0, 1].
//  sublist "MPRGP"                   the inner solver's parameters (MprgpSolMgr); SMALBE replaces
//                                    its stopping test by the rule above and its "Norm of A" by
//                                    ||A|| + rho (an upper bound of ||A + rho Q||, no power
//                                    iterations); "Maximum iterations" limits each inner solve.
// When b = 0, ||b|| in the tolerances is replaced by ||A P(0)|| as in MPRGP.
// Belos's names are accepted as aliases (tfeti_SolverConventions.hpp): "Convergence Tolerance" =
// "Relative tolerance", "Maximum Iterations" = "Maximum outer iterations" (and in the "MPRGP"
// sublist as there). "Verbosity" also takes a Belos::MsgType mask: FinalSummary (the summary),
// IterationDetails (a line per outer iteration), Warnings (a line when not converged),
// TimingDetails, StatusTestDetails (the final test's values). Timers (Teuchos::TimeMonitor):
// "tfeti: SMALBE solve", and the inner solves' "tfeti: MPRGP solve" and "tfeti: Hessian apply"
// (the power iterations on A included).
// The equality constraints C x = d of a user's problem become the Q and the shift this solver
// takes through tfeti_EqualityConstraints.hpp.
#include <BelosTypes.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>

#include <memory>
#include <vector>

#include "tfeti_ComplementColumns.hpp"
#include "tfeti_ComplementFactors.hpp"
#include "tfeti_QpProblem.hpp"
#include "tfeti_SolverConventions.hpp"
#include "tfeti_SolverOutput.hpp"

namespace tfeti {
template <class S, class MV, class OP>
class FaceGramian;
template <class S, class MV, class OP>
class FaceProjector;
template <class S>
struct FacePcpgResult;
template <class S, class MV>
struct FaceStiffCircles;
}  // namespace tfeti

namespace tfeti {

// What the face phase ("Face solve" = pcpg) did in the last solve.
struct FaceCounters {
  long long solves = 0;            // face solves started (active-set corrections included)
  long long iterations = 0;        // their CG steps (one multiplication each)
  bool accepted = false;           // the result is a face solve's
  long long activeSetChanges = 0;  // outer iterations and face corrections whose active set
                                   // differs from the one before
  long long levelSolves = 0;       // the loose face solves of "Initial face" = levels
  long long circleSteps = 0;       // face solves that repeated a face with circles from its
                                   // retracted result (Newton steps on the circles; not counted
                                   // against "Maximum face solves")
  long long stiffPreconditionerApplications = 0;  // M applied to stiff circles' components
};

template <class S, class MV, class OP>
class SmalbeSolMgr {
 public:
  using magnitude_type = typename Teuchos::ScalarTraits<S>::magnitudeType;

  // qp.A is the unaugmented Hessian; qp.x holds the initial guess and receives the solution.
  // The preconditioner goes to MPRGP (used with "Preconditioning in face" in the sublist).
  SmalbeSolMgr(const BoundConstrainedQp<S, MV, OP>& qp, Teuchos::RCP<const OP> Q,
               const Teuchos::ParameterList& params,
               Teuchos::RCP<const OP> preconditioner = Teuchos::null);

  // Belos's way: construct, then setProblem and setParameters (defaults until then).
  SmalbeSolMgr();

  // The problem (A, b, lower, x and Q must be set); the next solve() starts from qp.x.
  void setProblem(const BoundConstrainedQp<S, MV, OP>& qp, Teuchos::RCP<const OP> Q);
  const BoundConstrainedQp<S, MV, OP>& getProblem() const { return qp_; }
  void setPreconditioner(Teuchos::RCP<const OP> preconditioner) { P_ = std::move(preconditioner); }
  // Changes the parameters given (Belos aliases resolved) and keeps the others as they are.
  void setParameters(const Teuchos::ParameterList& params);
  void setParameters(const Teuchos::RCP<Teuchos::ParameterList>& params) { setParameters(*params); }
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
  // The parameters in use, defaults filled in, under the package's names.
  const Teuchos::ParameterList& getCurrentParameters() const { return params_; }
  // Forgets the results of the last solve (counters, multiplier); the initial multiplier, the
  // augmented Hessian and the settings stay.
  void reset(Belos::ResetType type = Belos::Problem);

  // The augmented Hessian A + rho Q applied by the caller's own operator (e.g. one that shares
  // work between A and Q) instead of the OperatorSum of the two; its rho must be the one the
  // solve uses, getPenalty(): the "Penalty" parameter times ||A||, so give "Norm of A" (the
  // power-iteration estimate is not known beforehand).
  void setAugmentedHessian(Teuchos::RCP<const OP> H) { augmented_ = std::move(H); }
  // The warm start comes from another load (a nonlinear method's first QP of a load step): its
  // circles (discs at their bound) slid under that load. The loose face verdicts then release no
  // circle while rows join the face: the slip zone grows first, and a circle whose multiplier
  // is still of the wrong sign is released once the face stops growing (docs/friction.md,
  // "Releases after a new load"). A start from the same load holds them only if it has circles
  // ("Circle releases"; a start without circles, false, releases at once).
  void setWarmStartFromOtherLoad(bool other) { otherLoad_ = other; }
  // Starting multiplier (in range(Q); default zero).
  void setInitialMultiplier(Teuchos::RCP<const MV> mu0) { mu0_ = std::move(mu0); }
  // Levels of the lower-bounded components for "Initial face" = levels (FETI: the contact rows'
  // gaps); a non-finite level: not a candidate. The initial face is one of the nested sets
  // {i : level_i > tau}.
  void setFaceLevels(Teuchos::RCP<const MV> levels) { levels_ = std::move(levels); }
  // "Initial face" = start: the point whose active set (after the projection onto the feasible
  // set) is the first face, and where its face solve starts; null: the initial iterate x. For
  // FETI a warm start before its projection onto ker G, which moves it off the bounds it held.
  void setFaceStart(Teuchos::RCP<const MV> start) { faceStart_ = std::move(start); }
  // The columns of Q the face solves need, from Q's structure (FETI: G's columns and coarse
  // solves with many right-hand sides); null: one application of Q per column. Either way the
  // same columns, to rounding.
  void setComplementColumns(Teuchos::RCP<ComplementColumns<S>> columns) {
    complementColumns_ = std::move(columns);
  }
  // Q's factors (FETI: G and the coarse factor), with which each application of a face's
  // projector costs one of Q instead of two (tfeti_FaceProjector.hpp); null: Q applied as is.
  void setComplementFactors(Teuchos::RCP<const ComplementFactors<S, MV>> factors) {
    complementFactors_ = std::move(factors);
  }
  // Operators the face solves may apply in place of A and of the preconditioner on vectors of
  // ker Q, where every face CG direction lies: A_f v - A v and M_f v - M v in range(Q) whenever
  // Q v = 0 (FETI: F for P F P, and M for P M P + Q / rho; neither needs a coarse projection).
  // The face CG's recursive gradient then differs from A x - b by a part in range(Q), which
  // every use of it removes (P_F, and the multipliers S^{-1} E_A P g); the face's entry and final
  // gradients stay A x - b. Null: A and the preconditioner themselves.
  void setInFaceOperators(Teuchos::RCP<const OP> A, Teuchos::RCP<const OP> M) {
    inFaceA_ = std::move(A);
    inFaceM_ = std::move(M);
  }
  // Progress lines of SMALBE and its inner MPRGP (Verbosity >= 1, rank 0) go here, e.g. a
  // Teuchos::FancyOStream; null: std::cout. Its format state is never changed.
  void setOutputStream(Teuchos::RCP<std::ostream> os) { out_.setStream(std::move(os)); }

  // Converged, or Unconverged with counters().message saying why. Throws like MPRGP.
  Belos::ReturnType solve();

  // Counters summed over all inner solves; history: ||g^P|| / ||b|| per outer iteration.
  const QpCounters& counters() const { return counters_; }
  // The face phase's counters (its multiplications are in counters() too).
  const FaceCounters& faceCounters() const { return face_; }
  // The equality multiplier mu (in range(Q)): A x - b + mu is the Lagrangian's gradient.
  Teuchos::RCP<const MV> getMultiplier() const { return mu_; }
  long long projectorApplications() const { return qApplies_; }
  // Outer iterations of the last solve.
  int getNumIters() const { return counters_.outerIterations; }
  // ||g^P|| / ||b|| reached (the quantity "Relative tolerance" bounds) and ||A|| ||Q x|| / ||b||
  // (bounded by "Equality tolerance").
  magnitude_type achievedTol() const { return achievedTol_; }
  magnitude_type achievedEqualityTol() const { return achievedEqualityTol_; }
  magnitude_type getNormOfA() const { return normA_; }
  magnitude_type getPenalty() const { return rho_; }
  magnitude_type getM() const { return M_; }

 private:
  BoundConstrainedQp<S, MV, OP> qp_;
  Teuchos::RCP<const OP> Q_, P_, augmented_;
  bool otherLoad_ = false;
  bool startOnCircles_ = false;  // this solve's face phase started from circles
  Teuchos::ParameterList params_;
  Teuchos::RCP<const MV> mu0_;
  Teuchos::RCP<MV> mu_;
  QpCounters counters_;
  FaceCounters face_;
  long long qApplies_ = 0;
  magnitude_type normA_ = 0, rho_ = 0, M_ = 0;
  magnitude_type achievedTol_ = 0, achievedEqualityTol_ = 0;
  SolverOutput out_;
  // The steps of solve() (tfeti_SmalbeSolMgr_def.hpp), sharing the state of the solve.
  struct SolveState;
  Belos::ReturnType solveTimed();
  void setNormAndPenalty();                  // ||A||, rho and M_0
  void setTolerances(SolveState& s);         // ||b|| (or ||A P(0)|| when b = 0) and the tolerances
  void setUpOuterIterations(SolveState& s);  // the multiplier, the inner problem, the rules
  void setUpFaceGramian(SolveState& s);
  void startFromLevelFace(SolveState& s);  // "Initial face" = levels
  void testInitialIterate(SolveState& s);
  // "Initial face" = start: a face solve on the initial iterate's active set.
  void startFromInitialFace(SolveState& s);  // the final test at the starting point
  void outerIteration(SolveState& s);  // an inner solve, the multiplier update, the face phase
  // L(x, mu) from the inner gradient, and the rounding level of that value.
  S lagrangianAt(const MV& innerGradient, magnitude_type& noise) const;
  void reportOuterIteration(const SolveState& s, int innerSteps, S lagrangian, S required,
                            bool reduceM);
  // The face phase after an outer iteration once the active set has settled; true: accepted.
  bool faceAfterOuterIteration(SolveState& s);
  void finishSolve(const SolveState& s);  // the counters, the message, the final report
  std::string summaryMessage(const SolveState& s) const;
  void reportSolve(const SolveState& s);
  // The face phase ("Face solve" = pcpg): PCPG on the face of `active`, then SMALBE's final test
  // on the result; on failure primal-dual active-set steps within "Maximum face solves". True:
  // x, the multiplier, gp and qxNorm hold the accepted result; false: all untouched.
  // start: the first face solve's starting point instead of SMALBE's iterate.
  bool faceSolve(std::vector<long long> active, magnitude_type gTol, magnitude_type eTol,
                 magnitude_type scale, magnitude_type& gp, magnitude_type& qxNorm,
                 const MV* start = nullptr);
  // The steps of faceSolve (tfeti_SmalbeFacePhase_def.hpp).
  struct FaceRun;      // what the faces of one face phase share
  struct FaceOutcome;  // SMALBE's final test on a face solve's result
  FaceRun startFaceRun(magnitude_type gTol, magnitude_type eTol, magnitude_type scale,
                       const MV* start);
  // The face of the active components at x: a disc on its circle a circle row (run.circles).
  std::unique_ptr<FaceProjector<S, MV, OP>> faceOf(const std::vector<long long>& active,
                                                   const MV& x, FaceRun& run) const;
  // x onto the face (the active rows at their values, returned) and its gradient; with circles
  // the face's Hessian and gradient gain their curvature (run.faceA, run.curvature).
  std::vector<S> enterFace(const FaceProjector<S, MV, OP>& face, FaceRun& run);
  // The circles' curvature in the face's Hessian (run.faceA) and gradient.
  void setCircleCurvature(const FaceProjector<S, MV, OP>& face, FaceRun& run);
  // The preconditioner's update by the stiff circles' curvature (run.stiff, tfeti_FacePcpg.hpp).
  void setStiffCircles(FaceRun& run, const std::vector<S>& curvature);
  // g += alpha diag(run.curvature) (x - c) on the circles' components.
  void addCurvatureGradient(const FaceRun& run, const MV& x, S alpha, MV& g) const;
  FacePcpgResult<S> faceCg(const FaceProjector<S, MV, OP>& face, S tol, int maxIterations,
                           FaceRun& run);
  // The loose face solve; true when its verdict moved `active` (and x) to a new face.
  bool looseVerdictMoves(const FaceProjector<S, MV, OP>& face, const std::vector<S>& r,
                         FaceRun& run, int& steps, std::vector<long long>& active);
  FaceOutcome finalTestOnFace(const FaceProjector<S, MV, OP>& face,
                              const std::vector<long long>& active, const std::vector<S>& r,
                              FaceRun& run);
  void reportFaceSolve(const FaceRun& run, std::size_t activeRows, int steps, bool cgConverged,
                       const FaceOutcome& out, bool passed, std::size_t nextRows);
  // The primal-dual active-set step from the projected iterate xp on `face`.
  // holdCircles: while a row joins, no circle is released (holdsCircleReleases).
  std::vector<long long> activeSetStep(const MV& xp, const FaceProjector<S, MV, OP>& rows,
                                       const std::vector<S>& sigma, bool holdCircles = false) const;
  // Whether this solve's loose verdicts hold their circle releases while rows join ("Circle
  // releases"): after another load's solution, or from a start with circles. A start without
  // them (the normal step's first frictional QP, from a frictionless solution) releases at once:
  // the circles its own verdicts add are often wrong (the 0.1M Cattaneo sphere's step 1: 101 ->
  // 141 multiplications with them held).
  bool holdsCircleReleases() const {
    return params_.get<std::string>("Circle releases") == "held while rows join" &&
           (otherLoad_ || startOnCircles_);
  }
  // "Initial face" = levels: a search over the level sets (bisection, or with "Level search
  // start" = half lowest count steps from Hertz's zone) for the face on which neither a free
  // component leaves the box nor an active one has a multiplier of the wrong sign, each face
  // solved to the loose tolerance tol from x (updated). Returns the face found (or the last one
  // between too many and too few active components); found is false when the levels do not
  // discriminate (fewer than two distinct values): no initial face then.
  std::vector<long long> levelFace(magnitude_type tol, MV& x, bool& found);
  // "Level search start" = half lowest: the index of the largest of the sorted distinct levels
  // tau at or below half the lowest, where that is informative; kNoLevelGuess otherwise.
  std::size_t startLevel(const std::vector<S>& tau) const;
  static constexpr std::size_t kNoLevelGuess = static_cast<std::size_t>(-1);
  struct FaceVerdict {
    bool valid = false;       // the face's projector exists (active rows independent of Q's)
    long long leftBox = 0;    // free components outside the box after the face solve
    long long wrongSign = 0;  // active components whose multiplier has the wrong sign
  };
  // judged: the rows whose multiplier sign counts (the level rows).
  FaceVerdict trialFace(const std::vector<long long>& active, const std::vector<long long>& judged,
                        magnitude_type tol, MV& x);
  // The verdict of a trial face at x, g (its rows' multipliers): the judged rows outside their
  // lower bounds and the judged active rows whose multiplier has the wrong sign.
  void judgeTrialFace(const FaceProjector<S, MV, OP>& face, const std::vector<long long>& judged,
                      const MV& x, const MV& g, FaceVerdict& v) const;
  Teuchos::RCP<const MV> levels_;
  Teuchos::RCP<const MV> faceStart_;
  Teuchos::RCP<FaceGramian<S, MV, OP>> gramian_;  // during a solve with "Face solve" = pcpg
  Teuchos::RCP<ComplementColumns<S>> complementColumns_;
  Teuchos::RCP<const OP> inFaceA_, inFaceM_;  // setInFaceOperators
  Teuchos::RCP<const ComplementFactors<S, MV>> complementFactors_;
  // "Face relative tolerance"'s default (docs/qp_solvers.md, "Face solve"): the face CG's
  // ||P_F g|| is the residual of the rows that hold with equality (for FETI, B u - c over the
  // gluing rows and the contact rows in contact), which SMALBE alone ends one to two orders
  // below its tolerance; stopping at half the tolerance left 10-100 times its primal residual.
  static constexpr double kFaceRelativeTolerance = 0.01;
  // The level search's face solves only decide which way to go: each stops at kLevelReduction of
  // its own start's projected gradient, or at 1e-3 of ||b|| if that is looser. Measured
  // (multiplications of the whole solve, 2 ranks; docs/qp_solvers.md, "Where the first face
  // comes from"): 1e-3 of ||b|| alone / with 0.1 / with 0.3: step-42 32^3 elastic 218 / 171 /
  // 161, plastic 507 / 478 / 454, the Hertz sphere at 0.1M 370 / 366 / 371,
  // examples/two_cylinders_elastic.xml 73 / 61 / 59, examples/hertz_sphere_tet.xml 129 / 129 /
  // 93. A looser ||b|| share instead (1e-2, 3e-2) left the Hertz sphere's first trial at its
  // start, which judged nothing, and cost 567.
  static constexpr double kLevelTolerance = 1e-3;
  static constexpr double kLevelReduction = 0.3;
  // A face solve first stops at ||P_F g|| <= min(kFaceVerdictFactor * tol, kLevelTolerance) *
  // ||b|| and takes the active-set step from there when its verdict changes the face; only a face
  // that holds is solved to "Face relative tolerance" * tol. Looser verdicts misjudge the rows at
  // the edge of the contact zone, whose multipliers are small, and the faces then wander
  // (docs/qp_solvers.md, "Loose verdicts": two cylinders at 0.5M unknowns, 226 multiplications
  // with tight faces, 167 / 139 / 134 / 122 / 116 at 1, 10, 100, 300, 1000 tol, 1e-3: 478).
  static constexpr double kFaceVerdictFactor = 300;
  // Newton steps on the circles of one face phase (faces solved again with the same active
  // set): each gains one to two digits (measured on the Cattaneo sphere), so ten that do not
  // pass SMALBE's final test mean the face is wrong; SMALBE then goes on from its own iterate.
  static constexpr int kMaxCircleSteps = 10;
  // The tolerance (times SMALBE's) of a face with circles' last linearization before its tight
  // solve (docs/qp_solvers.md, "Newton steps on the circles").
  static constexpr double kCircleRelinearization = 10;
  // The stiff circles' columns M e_j are computed this many at a time: M's interior solves take
  // them as one block of right-hand sides; the block's work vectors (a primal and two dual
  // vectors per column) bound it.
  static constexpr std::size_t kStiffColumnBlock = 32;
  // A circle whose curvature nu / r in the face's Hessian exceeds this times ||A|| updates the
  // face's preconditioner (tfeti_FacePcpg.hpp; docs/qp_solvers.md, "Stiff circles"). Measured
  // with the first version (the stiff components scaled by 1 / (nu / r) alone) on the 0.1M
  // Cattaneo sphere (Coulomb, both steps): 1,459 multiplications without, 1,185 / 908 / 932 /
  // 933 at 1 / 0.1 / 0.01 / 0.001.
  static constexpr double kStiffCurvature = 0.1;
};

}  // namespace tfeti
