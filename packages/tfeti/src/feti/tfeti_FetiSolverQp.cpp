// FetiSolver::solveQp: the dual QP of the inequality rows (reference paper, "FETI domain
// decomposition method (III), (IV)"), lambda = lambda~ + mu,
//   min 1/2 mu^T P F P mu - mu^T P (d - F lambda~)  s.t.  Q mu = 0,  l - lambda~ <= mu <= u -
//   lambda~
// by SMALBE (MPRGP inner solves) or by MPRGP on the penalized Hessian P F P + rho Q.
#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_MprgpSolMgr_decl.hpp"
#include "tfeti_PhaseTimer.hpp"
#include "tfeti_ProjectedOperators.hpp"
#include "tfeti_SmalbeSolMgr_decl.hpp"

namespace tfeti {

namespace {
// A previous disc solution within this share of its radius from the circle was on it.
constexpr double kOnCircle = 1e-8;
}  // namespace

bool frictionBox(const InequalityRow& r) {
  return r.disc == 0 && std::isfinite(r.upperBound) && r.lowerBound == -r.upperBound;
}

// The dual QP in mu and the operators its solvers share.
struct FetiSolver::DualQp {
  BoundConstrainedQp<Scalar, MultiVector, Operator> qp;
  Teuchos::RCP<Vector> mu;                 // qp.x
  Teuchos::RCP<const Operator> PFP, Q, H;  // H = P F P + rho Q
  Teuchos::RCP<const Operator> prec;       // null: MPRGP unpreconditioned
  double norm = 0.0;                       // the estimate of ||P F P||
  double rho = 0.0;
  bool warm = false;  // from the previous solve's multipliers
};

DualResult FetiSolver::solveQp(const std::string& method) {
  DualResult result;
  result.method = method;
  PhaseTimer t(*comm_, timings_.solve, &memory_, "solve");
  const auto map = tearing_.multiplierMap;
  DualQp dual;
  dual.qp.b = dualQpLinearTerm();
  setDualQpBounds(dual.qp);
  const bool smalbe = method == "SMALBE";
  dual.warm = warmStartAgreed();
  dual.mu = initialIncrement(dual.warm, !smalbe);
  dual.qp.x = dual.mu;
  dual.PFP = Teuchos::rcp(new ProjectedDualOperator(F_, *coarse_));
  dual.Q = Teuchos::rcp(new ComplementProjector(map, *coarse_));
  const long long before = F_->numApplies();
  dual.norm = projectedNormEstimate(*dual.PFP, *dual.qp.b, smalbe, dual.warm);
  normEstimate_ = dual.norm;
  dual.rho = (smalbe ? params_.sublist("SMALBE").get<double>("Penalty")
                     : params_.sublist("Penalty").get<double>("Penalty")) *
             dual.norm;
  result.rho = dual.rho;
  setQpOperators(dual);
  const Belos::ReturnType ret =
      smalbe ? solveSmalbe(dual, result.qp) : solvePenalty(dual, result.qp);
  // Every application of the Hessian is one of F (the projections are coarse solves): count
  // them all, the norm estimate's included.
  result.qp.hessianMultiplications = F_->numApplies() - before;
  completeQpResult(ret, result);
  Tpetra::deep_copy(*lambda_, *lambda0_);
  lambda_->update(1.0, *dual.mu, 1.0);
  return result;
}

Teuchos::RCP<Vector> FetiSolver::dualQpLinearTerm() const {
  // b = P (d - F lambda~)
  auto b = Teuchos::rcp(new Vector(tearing_.multiplierMap));
  F_->apply(*lambda0_, *b);
  b->update(1.0, *d_, -1.0);
  coarse_->project(*b, *b);
  return b;
}

void FetiSolver::setDualQpBounds(BoundConstrainedQp<Scalar, MultiVector, Operator>& qp) const {
  // l_I - lambda~_I <= mu_I <= u_I - lambda~_I (l = 0, u = +inf for the non-penetration rows; a
  // box for friction rows).
  const auto map = tearing_.multiplierMap;
  // A disc pair (3D friction, InequalityRow::disc) has no interval bounds but the disc
  // |mu + lambda~| <= g: radius g, centre -lambda~ (MPGP; the tearing numbers its two rows
  // consecutively on one rank).
  auto lower = Teuchos::rcp(new Vector(map));
  auto upper = Teuchos::rcp(new Vector(map));
  auto discs = Teuchos::rcp(new Vector(map));
  auto centers = Teuchos::rcp(new Vector(map));
  int anyLocal[2] = {0, 0}, any[2] = {0, 0};  // upper bounds, discs
  {
    const double inf = std::numeric_limits<double>::infinity();
    auto lo = lower->getDataNonConst();
    auto up = upper->getDataNonConst();
    auto dv = discs->getDataNonConst();
    auto cv = centers->getDataNonConst();
    auto l0 = lambda0_->getData();
    const bool tied = inequalitiesTied(params_);
    for (std::size_t i = 0; i < map->getNodeNumElements(); ++i) {
      const GO row = map->getGlobalElement(static_cast<LO>(i));
      lo[i] = -inf;
      up[i] = inf;
      dv[i] = std::numeric_limits<double>::quiet_NaN();
      cv[i] = -l0[i];
      if (!tied && tearing_.isInequality(row)) {
        const InequalityRow& r = tearing_.inequalityRows[row - tearing_.firstInequalityRow];
        if (r.disc != 0) {
          dv[i] = r.disc == 1 ? r.upperBound : -1.0;
          anyLocal[1] = 1;
          continue;
        }
        lo[i] = r.lowerBound - l0[i];
        up[i] = r.upperBound - l0[i];
        if (r.upperBound < inf) anyLocal[0] = 1;
      }
    }
  }
  // Without friction rows the QP keeps its lower bounds only (the solvers' one-sided path).
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 2, anyLocal, any);
  qp.lower = lower;
  if (any[0] == 1) qp.upper = upper;
  if (any[1] == 1) {
    qp.discs = discs;
    qp.discCenters = centers;
  }
}

bool FetiSolver::warmStartAgreed() const {
  const auto map = tearing_.multiplierMap;
  bool warm = params_.get<bool>("Warm start") && !previousLambda_.is_null() &&
              previousLambda_->getGlobalLength() == map->getGlobalNumElements() &&
              previousLambda_->getLocalLength() == map->getNodeNumElements();
  int warmAll = 0, warmLocal = warm ? 1 : 0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MIN, 1, &warmLocal, &warmAll);
  return warmAll == 1;
}

Teuchos::RCP<Vector> FetiSolver::warmIncrement() const {
  // lambda_previous - lambda~ as it is: on the bounds where the previous solution was.
  const auto map = tearing_.multiplierMap;
  auto mu = Teuchos::rcp(new Vector(map));
  auto m = mu->getDataNonConst();
  auto p = previousLambda_->getData();
  auto l0 = lambda0_->getData();
  const std::size_t n = map->getNodeNumElements();
  for (std::size_t i = 0; i < n; ++i) m[i] = p[i] - l0[i];
  // A disc whose previous solution was on its circle (a slipping node) starts on its new circle
  // in the same direction, and a friction box (2D, or a direction held on both sides in 3D) at
  // its new bound: Coulomb's bound mu lambda_N moves between Newton iterations, and the node
  // keeps slipping. Without it every disc or box whose bound grew starts inside, off the face,
  // and the face solves add them back a few at a time (each a loose solve).
  if (previousDiscRadii_.is_null() || previousDiscRadii_->getLocalLength() != n) return mu;
  auto ro = previousDiscRadii_->getData();
  for (std::size_t i = 0; i < n; ++i) {
    const GO row = map->getGlobalElement(static_cast<LO>(i));
    if (!tearing_.isInequality(row) || !(ro[i] > 0.0)) continue;
    const InequalityRow& q = tearing_.inequalityRows[row - tearing_.firstInequalityRow];
    if (!(q.upperBound > 0.0)) continue;
    if (q.disc == 0 && frictionBox(q)) {
      if (std::abs(p[i]) >= ro[i] * (1.0 - kOnCircle))
        m[i] = std::copysign(q.upperBound, p[i]) - l0[i];
      continue;
    }
    if (q.disc != 1 || i + 1 >= n) continue;
    const double norm = std::hypot(p[i], p[i + 1]);
    if (norm < ro[i] * (1.0 - kOnCircle)) continue;
    const double s = q.upperBound / norm;
    m[i] = s * p[i] - l0[i];
    m[i + 1] = s * p[i + 1] - l0[i + 1];
  }
  return mu;
}

Teuchos::RCP<Vector> FetiSolver::initialIncrement(bool warm, bool penalty) const {
  // From 0, or (warm start) from P (lambda_previous - lambda~): in the kernel of G, projected
  // onto the bounds by MPRGP. The rows of a nonlinear iteration keep their canonical order as
  // long as each slave node keeps its segment; any start is valid, a close one is cheap.
  if (!warm) return Teuchos::rcp(new Vector(tearing_.multiplierMap));
  auto mu = warmIncrement();
  coarse_->project(*mu, *mu);
  // The penalty's minimizer is not in the kernel of G: the last one's Q mu (about ||P F P|| / rho,
  // from the rows at their bounds) is added back. From P mu alone every QP of a converging Newton
  // loop went 60-100 multiplications back to it and ended a tolerance's width elsewhere, so that
  // Coulomb's slip bounds did not settle (nl_cattaneo_alone_mu03.xml: exit code 3 after 25,375
  // multiplications; 960 now). docs/qp_solvers.md, "The penalty's warm start".
  if (penalty && !previousPenaltyOffset_.is_null() &&
      previousPenaltyOffset_->getMap()->isSameAs(*mu->getMap()))
    mu->update(1.0, *previousPenaltyOffset_, 1.0);
  return mu;
}

double FetiSolver::projectedNormEstimate(const Operator& PFP, const MultiVector& b, bool smalbe,
                                         bool warm) {
  // ||P F P|| sets the scale of rho (both methods) and of MPRGP's step length; estimated once.
  const Teuchos::ParameterList& sp = params_.sublist("SMALBE");
  const Teuchos::ParameterList& pen = params_.sublist("Penalty");
  double norm = smalbe ? sp.get<double>("Norm of A") : 0.0;
  // A warm start after update() keeps K, so ||P F P|| moves only with the contact rows: the
  // previous estimate (already enlarged by 5 %) is kept instead of new power iterations.
  if (norm <= 0.0 && warm && previousNorm_ > 0.0) norm = previousNorm_;
  if (norm <= 0.0) {
    const int its = smalbe ? sp.get<int>("Power iterations") : pen.get<int>("Power iterations");
    // A new tangent moves the dominant eigenvector little: a few power iterations from the
    // last one estimate its norm.
    const int warmIts = params_.get<int>("Warm power iterations");
    const auto map = tearing_.multiplierMap;
    int sameLocal = !normVector_.is_null() &&
                            normVector_->getGlobalLength() == map->getGlobalNumElements() &&
                            normVector_->getLocalLength() == map->getNodeNumElements()
                        ? 1
                        : 0,
        same = 0;
    Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MIN, 1, &sameLocal, &same);
    const bool fromLast = warmIts > 0 && same == 1;
    if (!fromLast) normVector_ = Teuchos::rcp(new Vector(map));  // zero: the fixed start
    auto start = Teuchos::rcp(new Vector(map));
    Tpetra::deep_copy(*start, *normVector_);
    norm = MprgpSolMgr<Scalar, MultiVector, Operator>::estimateNorm(
        PFP, b, fromLast ? warmIts : its, nullptr, start.get());
    normVector_ = start;
  }
  return norm;
}

void FetiSolver::setQpOperators(DualQp& dual) const {
  // Preconditioning in face: P M P acts on range(P), where the Hessian is P F P; on range(Q) the
  // Hessian is rho I, so the preconditioner is P M P + Q / rho (singular without the Q part).
  if (params_.get<bool>(kPreconditioningInFace) && !M_.is_null())
    dual.prec = Teuchos::rcp(new ProjectedPlusComplement(M_, *coarse_, 1.0 / dual.rho));
  // P F P + rho Q sharing P x between its two terms: two coarse projections, not three.
  dual.H = Teuchos::rcp(new ProjectedPlusComplement(F_, *coarse_, dual.rho));
}

Belos::ReturnType FetiSolver::solveSmalbe(DualQp& dual, QpCounters& counters) {
  dual.qp.A = dual.PFP;
  Teuchos::ParameterList sp = params_.sublist("SMALBE");
  sp.set("Norm of A", dual.norm);
  for (const char* tol : {"Relative tolerance", "Equality tolerance"})
    sp.set(tol, toleranceFactor_ * sp.get<double>(tol));
  sp.sublist("MPRGP").set(kPreconditioningInFace, !dual.prec.is_null());
  // An inexact QP may stop its face CG nearer its own tolerance than an exact one (step-42 at
  // 32^3 plastic, Inexact QP factor 1e6, 0.3: 364 -> 286 multiplications, the same force).
  if (toleranceFactor_ > 1.0)
    sp.set("Face relative tolerance",
           std::max(sp.get<double>("Face relative tolerance"),
                    params_.get<double>("Inexact face relative tolerance")));
  // A warm start (the Newton loop's previous QP on the same rows) gives the first face: the
  // active set of the previous solution. The gaps' levels serve only a cold start; with discs
  // (3D friction) the inner MPGP solves are slow where discs slide, and for frictionless rows
  // the face is found in one or two face solves instead of SMALBE's first outer iteration
  // (docs/qp_solvers.md, "The face solve with discs"). With friction the slipping rows start on
  // their new bounds (warmIncrement): before, 2D friction's boxes whose bound grew started
  // inside, and the Coulomb bounds updated in the Newton loop cycled (nl_cattaneo_alone_mu03.xml:
  // step 2 did not settle in 50 iterations).
  const bool warmFace = dual.warm && sp.get<std::string>("Initial face") != "none";
  if (warmFace) sp.set("Initial face", "start");
  SmalbeSolMgr<Scalar, MultiVector, Operator> solver(dual.qp, dual.Q, sp, dual.prec);
  solver.setOutputStream(out_);
  solver.setAugmentedHessian(dual.H);
  solver.setWarmStartFromOtherLoad(dual.warm && loadStepStart_);
  // The face solves' columns of Q from G's entries: step-42 at 64^3 elastic asked for about 800
  // per QP at 7 ms each as applications of Q; the solve fell from 75-78 s to 55-57 s.
  solver.setComplementColumns(Teuchos::rcp(new CoarseComplementColumns(*coarse_)));
  // Every face CG direction p lies in ker G, where P F P p = P F p and (P M P + Q / rho) p =
  // P M p, and the face's projector removes the outer P: F and M alone, without the four coarse
  // projections of each CG step.
  solver.setInFaceOperators(F_, dual.prec.is_null() ? Teuchos::null : M_);
  solver.setComplementFactors(Teuchos::rcp(new CoarseComplementFactors(*coarse_)));
  if (warmFace) solver.setFaceStart(warmIncrement());
  const auto nu0 = smalbeInitialMultiplier(dual.warm, *dual.Q);
  if (!nu0.is_null()) solver.setInitialMultiplier(nu0);
  // The gaps as the levels of SMALBE's "Initial face" = levels (frictionless contact only:
  // the tangential rows' boxes have no level), not for warm starts, which have their face.
  // With discs (3D friction) the normal rows have their gaps as levels and the friction rows
  // none (their discs, and boxes on symmetry planes, start free); 2D friction's boxes keep
  // SMALBE's own first face.
  if (!dual.warm && tearing_.numInequalityRows > 0 && !inequalitiesTied(params_) &&
      (dual.qp.upper.is_null() || !dual.qp.discs.is_null()))
    solver.setFaceLevels(contactGapLevels(dual.qp.discs.get()));
  const Belos::ReturnType ret = solver.solve();
  counters = solver.counters();
  equalityMultiplier_ = Teuchos::rcp(new Vector(tearing_.multiplierMap));
  Tpetra::deep_copy(*equalityMultiplier_, *solver.getMultiplier()->getVector(0));
  return ret;
}

Teuchos::RCP<Vector> FetiSolver::smalbeInitialMultiplier(bool warm, const Operator& Q) const {
  // SMALBE's equality multiplier of the previous solve, moved into the new range(Q).
  // Otherwise, from the geometry: with lambda = lambda~ + mu, the KKT conditions read
  // P F P mu - b + nu = c - B u (zero on the equality rows and the active inequality rows, the
  // open gap elsewhere) with nu = Q (c - B u); u = 0 gives nu_0 = Q c_I. Without a load
  // (lambda~ = 0, b = P c) mu = 0 then meets them at once, so the result is the exact zero.
  const auto map = tearing_.multiplierMap;
  Vector from(map);
  if (warm && !previousEqualityMultiplier_.is_null()) {
    auto dst = from.getDataNonConst();
    auto src = previousEqualityMultiplier_->getData();
    for (std::size_t i = 0; i < map->getNodeNumElements(); ++i) dst[i] = src[i];
  } else if (!warm && tearing_.numInequalityRows > 0 && !inequalitiesTied(params_) &&
             params_.get<std::string>("Initial equality multiplier") == "gap") {
    auto dst = from.getDataNonConst();
    auto c = tearing_.rhs->getData();
    for (std::size_t i = 0; i < map->getNodeNumElements(); ++i)
      dst[i] = tearing_.isInequality(map->getGlobalElement(static_cast<LO>(i))) ? c[i] : 0.0;
  } else {
    return Teuchos::null;
  }
  auto nu0 = Teuchos::rcp(new Vector(map));
  Q.apply(from, *nu0);
  return nu0;
}

Teuchos::RCP<Vector> FetiSolver::contactGapLevels(const MultiVector* discs) const {
  const auto map = tearing_.multiplierMap;
  auto levels = Teuchos::rcp(new Vector(map));
  auto dst = levels->getDataNonConst();
  auto c = tearing_.rhs->getData();
  Teuchos::ArrayRCP<const double> dv;
  if (discs != nullptr) dv = discs->getData(0);
  for (std::size_t i = 0; i < map->getNodeNumElements(); ++i) {
    const GO row = map->getGlobalElement(static_cast<LO>(i));
    // Friction rows (discs, or boxes with an upper bound) have no level.
    const bool friction = (!dv.is_null() && !std::isnan(dv[i])) ||
                          (tearing_.isInequality(row) &&
                           tearing_.inequalityRows[row - tearing_.firstInequalityRow].upperBound <
                               std::numeric_limits<double>::infinity());
    dst[i] =
        !friction && tearing_.isInequality(row) ? c[i] : std::numeric_limits<double>::quiet_NaN();
  }
  return levels;
}

Belos::ReturnType FetiSolver::solvePenalty(DualQp& dual, QpCounters& counters) {
  dual.qp.A = dual.H;
  Teuchos::ParameterList mp = params_.sublist("MPRGP");
  mp.set("Relative tolerance", toleranceFactor_ * mp.get<double>("Relative tolerance"));
  // ||P F P + rho Q|| = max(||P F P||, rho): P and Q are complementary orthogonal projectors.
  if (mp.get<double>("Norm of A") == 0.0) mp.set("Norm of A", std::max(dual.norm, dual.rho));
  mp.set(kPreconditioningInFace, !dual.prec.is_null());
  MprgpSolMgr<Scalar, MultiVector, Operator> solver(dual.qp, mp, dual.prec);
  solver.setOutputStream(out_);
  const Belos::ReturnType ret = solver.solve();
  counters = solver.counters();
  // Q mu, kept for the next warm start (initialIncrement) and removed by the projection.
  penaltyOffset_ = Teuchos::rcp(new Vector(tearing_.multiplierMap));
  dual.Q->apply(*dual.mu, *penaltyOffset_);
  counters.equalityResidualNorm = penaltyOffset_->norm2();
  if (params_.sublist("Penalty").get<bool>("Equality projection"))
    projectPenaltySolution(dual, counters);
  return ret;
}

void FetiSolver::projectPenaltySolution(DualQp& dual, QpCounters& counters) {
  // The penalty meets G lambda = e only to about ||P F P|| / rho: each subdomain's rigid-mode
  // balance is off by that much, a residual R (e - G lambda) that no Newton iteration removes,
  // since every QP solves for the whole lambda again (nl_hertz_sphere_elastic.xml stalled at
  // ||res|| / ||f|| = 1e-5 against Eta 2 = 1e-6, at any Penalty). mu <- P mu removes Q mu, which
  // lies in range(G^T) where P F P and b do not see it; the bounds are then off by at most
  // ||Q mu||. (Moving only the rows off their bounds instead, so that the rows at a bound stay
  // there, changes P mu too, and the Newton iterations drifted: the Hertz sphere did not
  // converge.)
  counters.equalityProjectionNorm = counters.equalityResidualNorm;
  // The primal fit takes the rows holding with equality from MPRGP's solution: the projection
  // moves a row at its bound a hair off it, and counted after it, inactive rows with an open
  // gap entered the fit (the pin in its hole with 1 % clearance then converged 5 % per Newton
  // iteration, the Cattaneo cylinders not at all).
  Vector lambda(tearing_.multiplierMap);
  Tpetra::deep_copy(lambda, *lambda0_);
  lambda.update(1.0, *dual.mu, 1.0);
  holdingRows_ = Teuchos::rcp(new Vector(tearing_.multiplierMap));
  markRowsHoldingWithEquality(lambda, *holdingRows_);
  dual.mu->update(-1.0, *penaltyOffset_, 1.0);  // P mu = mu - Q mu
  Vector left(tearing_.multiplierMap);
  dual.Q->apply(*dual.mu, left);
  counters.equalityResidualNorm = left.norm2();
}

void FetiSolver::completeQpResult(Belos::ReturnType ret, DualResult& result) const {
  result.converged = ret == Belos::Converged && result.qp.converged;
  result.iterations =
      static_cast<int>(result.qp.cgSteps + result.qp.expansionSteps + result.qp.proportioningSteps);
  result.projectedGradientNorm = result.qp.projectedGradientNorm;
  result.relativeResidual =
      result.qp.rhsNorm > 0.0 ? result.qp.projectedGradientNorm / result.qp.rhsNorm : 0.0;
  result.history = result.qp.history;
}

}  // namespace tfeti
