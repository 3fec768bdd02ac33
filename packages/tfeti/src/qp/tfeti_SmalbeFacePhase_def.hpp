#pragma once
// SmalbeSolMgr's face phase ("Face solve" = pcpg): PCPG on a face of the box, SMALBE's final
// test on its result and the primal-dual active-set steps between faces; and "Initial face" =
// levels, the bisection over the level sets for the first face. Included by
// tfeti_SmalbeSolMgr_def.hpp.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <memory>
#include <vector>

#include "tfeti_BoundTraits.hpp"
#include "tfeti_FaceGramian.hpp"
#include "tfeti_FacePcpg.hpp"
#include "tfeti_FaceProjector.hpp"
#include "tfeti_OperatorSum.hpp"
#include "tfeti_SeparableSet.hpp"
#include "tfeti_SmalbeSolMgr_decl.hpp"
#include "tfeti_TimedOperator.hpp"

namespace tfeti {

namespace face_phase_detail {

// Whether a component of `now` (at a bound after the step) is neither on the face (sorted) nor
// one of its circles' two components: a row joins the face.
template <class S>
bool rowJoins(const std::vector<long long>& now, const std::vector<long long>& face,
              const std::vector<FaceCircle<S>>& circles) {
  std::vector<long long> onCircles;
  for (const auto& c : circles) onCircles.push_back(c.index), onCircles.push_back(c.index + 1);
  std::sort(onCircles.begin(), onCircles.end());
  return std::any_of(now.begin(), now.end(), [&](long long i) {
    return !std::binary_search(face.begin(), face.end(), i) &&
           !std::binary_search(onCircles.begin(), onCircles.end(), i);
  });
}

}  // namespace face_phase_detail

// What the faces of one face phase share: the operators, the work vectors and the tolerances.
template <class S, class MV, class OP>
struct SmalbeSolMgr<S, MV, OP>::FaceRun {
  bool root = false;
  Teuchos::RCP<const OP> A, M;  // the timed Hessian; the preconditioner (null: none)
  // Their in-face counterparts for the CG (setInFaceOperators; A and M where none is given).
  Teuchos::RCP<const OP> cgA, cgM;
  // Discs: the circles of the current face (tfeti_SeparableSet.hpp), the curvature nu / r on
  // their components (null without circles) and the face's Hessian A + diag(curvature).
  std::vector<typename SeparableSet<S, MV>::Circle> circles;
  Teuchos::RCP<MV> curvature;
  Teuchos::RCP<const OP> faceA;
  FaceStiffCircles<S, MV> stiff;  // the circles whose curvature outweighs A (tfeti_FacePcpg.hpp)
  std::map<long long, Teuchos::RCP<MV>> mColumns;  // M e_j for the stiff circles' components
  Teuchos::RCP<MV> x, g;                           // the face iterate and its gradient A x - b
  Teuchos::RCP<MV> t, mu, phi, chopped;
  magnitude_type gTol = 0, eTol = 0, scale = 0;
  S tightTol = 0, looseTol = 0;
  S circleTol = 0;  // a face with circles is linearized once more at this tolerance
  int maxIterations = 0;
  // Faces whose loose verdict already moved the active set: a verdict that leads back to one of
  // them (rows near a bound judged by a loose solution) is settled by the tight solve instead.
  std::vector<std::vector<long long>> visited;
  // Faces with circles whose loose solve was already repeated from its retracted result, once
  // per repeat.
  std::vector<std::vector<long long>> relinearized;
};

// SMALBE's final test on a face solve's result.
template <class S, class MV, class OP>
struct SmalbeSolMgr<S, MV, OP>::FaceOutcome {
  magnitude_type gp = 0, qx = 0;  // ||g^P|| of the Lagrangian's gradient, ||Q x||
  std::vector<S> sigma;           // the active rows' multipliers
};

template <class S, class MV, class OP>
bool SmalbeSolMgr<S, MV, OP>::faceSolve(std::vector<long long> active, magnitude_type gTol,
                                        magnitude_type eTol, magnitude_type scale,
                                        magnitude_type& gp, magnitude_type& qxNorm,
                                        const MV* start) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  FaceRun run = startFaceRun(gTol, eTol, scale, start);
  while (face_.solves - face_.circleSteps < params_.get<int>("Maximum face solves")) {
    ++face_.solves;
    const auto facePtr = faceOf(active, *run.x, run);
    const FaceProjector<S, MV, OP>& face = *facePtr;
    qApplies_ += face.projectorApplications();
    if (!face.valid()) {
      if (out_.wants(Belos::IterationDetails) && run.root)
        out_.write(
            "SMALBE face: the active rows are dependent on the equality rows; no face "
            "solve\n");
      break;
    }
    const std::vector<S> r = enterFace(face, run);
    // First to a loose tolerance (kFaceVerdictFactor): enough to tell whether the face holds (no
    // free row leaves the box, no active row pulls). Only a face that holds is solved to the
    // tight tolerance, from there; the active-set corrections before it cost loose solves only.
    int steps = 0;
    if (run.looseTol > run.tightTol && looseVerdictMoves(face, r, run, steps, active)) continue;
    // "Face maximum iterations" limits the face's loose and tight steps together.
    const FacePcpgResult<S> res = faceCg(face, run.tightTol, run.maxIterations - steps, run);
    steps += res.iterations;
    const FaceOutcome out = finalTestOnFace(face, active, r, run);
    const bool passed = out.gp <= gTol && out.qx <= eTol;
    std::vector<long long> next;
    if (!passed) next = activeSetStep(*run.x, face, out.sigma);
    reportFaceSolve(run, active.size(), steps, res.converged, out, passed, next.size());
    if (passed) {
      MVT::Assign(*run.x, *qp_.x);
      MVT::Assign(*run.mu, *mu_);
      gp = out.gp;
      qxNorm = out.qx;
      counters_.history.push_back(gp / scale);
      face_.accepted = true;
      return true;
    }
    // The same face again would give the same result; not with circles, whose normals and
    // curvature the next face takes from the retracted iterate (a Newton step on the circles).
    if (next == active && face.circles().empty()) break;
    if (next == active) {
      if (++face_.circleSteps > kMaxCircleSteps) break;
      continue;
    }
    run.visited.push_back(active);
    ++face_.activeSetChanges;
    active = std::move(next);
  }
  return false;  // SMALBE goes on from its own iterate (qp_.x and mu_ untouched)
}

template <class S, class MV, class OP>
typename SmalbeSolMgr<S, MV, OP>::FaceRun SmalbeSolMgr<S, MV, OP>::startFaceRun(
    magnitude_type gTol, magnitude_type eTol, magnitude_type scale, const MV* start) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  using BT = BoundTraits<S, MV>;
  FaceRun run;
  run.root = BT::commRank(*qp_.x) == 0;
  run.A = TimedOperator<S, MV, OP>::wrap(qp_.A, solverTimer("tfeti: Hessian apply"));
  run.M = params_.sublist("MPRGP").get<bool>("Preconditioning in face") ? P_ : Teuchos::null;
  run.cgA = inFaceA_.is_null()
                ? run.A
                : TimedOperator<S, MV, OP>::wrap(inFaceA_, solverTimer("tfeti: Hessian apply"));
  run.cgM = run.M.is_null() || inFaceM_.is_null() ? run.M : inFaceM_;
  run.x = MVT::CloneCopy(start != nullptr ? *start : *qp_.x);
  run.g = MVT::Clone(*qp_.x, 1), run.t = MVT::Clone(*qp_.x, 1), run.mu = MVT::Clone(*qp_.x, 1);
  run.phi = MVT::Clone(*qp_.x, 1), run.chopped = MVT::Clone(*qp_.x, 1);
  run.gTol = gTol;
  run.eTol = eTol;
  run.scale = scale;
  run.tightTol = S(params_.get<double>("Face relative tolerance")) * gTol;
  run.looseTol =
      std::max(run.tightTol, std::min(S(kFaceVerdictFactor) * gTol, S(kLevelTolerance) * scale));
  run.circleTol = std::max(run.tightTol, std::min(run.looseTol, S(kCircleRelinearization) * gTol));
  run.maxIterations = params_.get<int>("Face maximum iterations");
  return run;
}

template <class S, class MV, class OP>
std::unique_ptr<FaceProjector<S, MV, OP>> SmalbeSolMgr<S, MV, OP>::faceOf(
    const std::vector<long long>& active, const MV& x, FaceRun& run) const {
  // A disc on its circle is a circle row (its normal held, its tangent free); the components of
  // a disc of radius 0 (a point) stay unit rows, held where they are.
  run.circles.clear();
  if (qp_.discs.is_null())
    return std::make_unique<FaceProjector<S, MV, OP>>(
        Q_, active, x, gramian_.get(), std::vector<FaceCircle<S>>(), complementFactors_.get());
  run.circles = feasibleSet(qp_).circles(x, active);
  std::vector<long long> unit;
  std::vector<FaceCircle<S>> rows;
  std::size_t k = 0;
  for (const long long i : active) {
    while (k < run.circles.size() && run.circles[k].index + 1 < i) ++k;
    const bool onCircle =
        k < run.circles.size() && (run.circles[k].index == i || run.circles[k].index + 1 == i);
    if (!onCircle) unit.push_back(i);
  }
  for (const auto& c : run.circles) rows.push_back({c.index, c.n0, c.n1});
  return std::make_unique<FaceProjector<S, MV, OP>>(Q_, std::move(unit), x, gramian_.get(),
                                                    std::move(rows), complementFactors_.get());
}

template <class S, class MV, class OP>
std::vector<S> SmalbeSolMgr<S, MV, OP>::enterFace(const FaceProjector<S, MV, OP>& face,
                                                  FaceRun& run) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;
  using BT = BoundTraits<S, MV>;
  const MV* upper = qp_.upper.get();
  const std::vector<long long>& active = face.active();
  // The active rows' bound values: the upper bound where x reached it, else the lower one
  // (rows that an active-set step added from outside the box go to the bound they crossed). A
  // component without bounds (a disc of radius 0) stays where it is (its centre).
  const std::vector<S> xa = BT::gatherAt(*run.x, active), la = BT::gatherAt(*qp_.lower, active);
  std::vector<S> ua(active.size(), std::numeric_limits<S>::infinity());
  if (upper != nullptr) ua = BT::gatherAt(*upper, active);
  std::vector<S> r(active.size());
  for (std::size_t i = 0; i < active.size(); ++i)
    r[i] = xa[i] >= ua[i] ? ua[i] : std::isfinite(la[i]) ? la[i] : xa[i];
  // A circle row holds n . x = r + n . c.
  for (const auto& c : run.circles) r.push_back(c.radius + c.n0 * c.c0 + c.n1 * c.c1);
  face.projectAffine(r, *run.x);
  OPT::Apply(*run.A, *run.x, *run.g);
  MVT::MvAddMv(S(1), *run.g, S(-1), *qp_.b, *run.g);
  ++counters_.hessianMultiplications;
  setCircleCurvature(face, run);
  return r;
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::setCircleCurvature(const FaceProjector<S, MV, OP>& face,
                                                 FaceRun& run) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  using BT = BoundTraits<S, MV>;
  run.faceA = run.cgA;
  run.curvature = Teuchos::null;
  run.stiff = FaceStiffCircles<S, MV>();
  if (run.circles.empty()) return;
  // The face's Hessian gains the circles' curvature nu / r (nu = -sigma, the multiplier that
  // holds x on the circle, from the gradient at the entry point): the Hessian of the Lagrangian
  // f + sum nu / (2 r) (|x_k - c_k|^2 - r^2), whose gradient g + (nu / r) (x - c) is g's
  // tangential part on the circles. Its minimizer on the face, retracted onto the circles, is a
  // Newton step for the problem with the circles themselves.
  const std::vector<S> sigma = face.activeMultipliers(*run.g);
  std::vector<long long> idx;
  std::vector<S> d, stiffCurvature;
  for (std::size_t k = 0; k < run.circles.size(); ++k) {
    const auto& c = run.circles[k];
    const S nu = std::max(-sigma[face.active().size() + k], S(0));
    idx.push_back(c.index), idx.push_back(c.index + 1);
    d.push_back(nu / c.radius), d.push_back(nu / c.radius);
    if (nu / c.radius > S(kStiffCurvature) * normA_) {
      run.stiff.components.push_back(c.index), run.stiff.components.push_back(c.index + 1);
      run.stiff.t0.push_back(-c.n1), run.stiff.t1.push_back(c.n0);
      stiffCurvature.push_back(nu / c.radius);
    }
  }
  setStiffCircles(run, stiffCurvature);
  run.curvature = MVT::Clone(*run.x, 1);
  MVT::MvInit(*run.curvature, S(0));
  BT::setAt(idx, d, *run.curvature);
  run.faceA = OperatorSum<S, MV, OP>::shift(run.cgA, run.curvature);
  addCurvatureGradient(run, *run.x, S(1), *run.g);
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::setStiffCircles(FaceRun& run, const std::vector<S>& curvature) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;
  using BT = BoundTraits<S, MV>;
  FaceStiffCircles<S, MV>& st = run.stiff;
  const int s = st.count();
  if (s == 0) return;
  // C = K^{-1} + E^T M E (tfeti_FacePcpg.hpp). Without M the identity stands for (A / ||A||)^{-1},
  // so K is scaled by 1 / ||A|| and E^T E = I; with M, its columns at the circles' components
  // (computed once a face phase) combine into M E.
  std::vector<S> C(static_cast<std::size_t>(s) * s, S(0));
  if (run.M.is_null()) {
    for (int k = 0; k < s; ++k) C[k * s + k] = S(normA_) / curvature[k] + S(1);
  } else {
    st.ME = MVT::Clone(*run.x, s);
    // The columns not computed yet in this face phase, kStiffColumnBlock at a time: M applies to
    // them together (one interior solve per subdomain with that many right-hand sides instead
    // of one each).
    std::vector<long long> missing;
    for (long long j : st.components)
      if (run.mColumns.find(j) == run.mColumns.end()) missing.push_back(j);
    std::sort(missing.begin(), missing.end());
    missing.erase(std::unique(missing.begin(), missing.end()), missing.end());
    for (std::size_t first = 0; first < missing.size(); first += kStiffColumnBlock) {
      const std::size_t n = std::min(missing.size() - first, kStiffColumnBlock);
      auto E = MVT::Clone(*run.x, static_cast<int>(n));
      auto ME = MVT::Clone(*run.x, static_cast<int>(n));
      MVT::MvInit(*E, S(0));
      std::vector<int> col(1);
      for (std::size_t c = 0; c < n; ++c) {
        col[0] = static_cast<int>(c);
        BT::setAt({missing[first + c]}, {S(1)}, *MVT::CloneViewNonConst(*E, col));
      }
      OPT::Apply(*run.M, *E, *ME);
      face_.stiffPreconditionerApplications += static_cast<int>(n);
      for (std::size_t c = 0; c < n; ++c) {
        col[0] = static_cast<int>(c);
        run.mColumns.emplace(missing[first + c], MVT::CloneCopy(*ME, col));
      }
    }
    std::vector<int> col(1);
    for (int k = 0; k < s; ++k) {
      col[0] = k;
      auto mk = MVT::CloneViewNonConst(*st.ME, col);
      MVT::MvInit(*mk, S(0));
      for (int c = 0; c < 2; ++c) {
        const auto& mj = run.mColumns.at(st.components[2 * k + c]);
        MVT::MvAddMv(S(1), *mk, c == 0 ? st.t0[k] : st.t1[k], *mj, *mk);
      }
      const std::vector<S> at = BT::gatherAt(*mk, st.components);
      for (int l = 0; l < s; ++l) C[k * s + l] = st.t0[l] * at[2 * l] + st.t1[l] * at[2 * l + 1];
    }
    for (int k = 0; k < s; ++k) {
      for (int l = k + 1; l < s; ++l)
        C[k * s + l] = C[l * s + k] = S(0.5) * (C[k * s + l] + C[l * s + k]);
      C[k * s + k] += S(1) / curvature[k];
    }
  }
  int info = 0;
  Teuchos::LAPACK<int, S>().POTRF('L', s, C.data(), s, &info);
  if (info != 0) {
    st = FaceStiffCircles<S, MV>();  // M not positive definite on E: plain M
    return;
  }
  st.factor = std::move(C);
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::addCurvatureGradient(const FaceRun& run, const MV& x, S alpha,
                                                   MV& g) const {
  using BT = BoundTraits<S, MV>;
  // g += alpha (nu / r) (x - c) on the circles' components.
  std::vector<long long> idx;
  for (const auto& c : run.circles) idx.push_back(c.index), idx.push_back(c.index + 1);
  const std::vector<S> xc = BT::gatherAt(x, idx), d = BT::gatherAt(*run.curvature, idx);
  std::vector<S> v(idx.size());
  for (std::size_t k = 0; k < run.circles.size(); ++k) {
    v[2 * k] = d[2 * k] * (xc[2 * k] - run.circles[k].c0);
    v[2 * k + 1] = d[2 * k + 1] * (xc[2 * k + 1] - run.circles[k].c1);
  }
  BT::addAt(idx, v, alpha, g);
}

template <class S, class MV, class OP>
FacePcpgResult<S> SmalbeSolMgr<S, MV, OP>::faceCg(const FaceProjector<S, MV, OP>& face, S tol,
                                                  int maxIterations, FaceRun& run) {
  // The stiff circles' update is M's (P M P + Q / rho for FETI), whose image of a face vector
  // the in-face M gives only up to range(Q): with stiff circles the CG keeps M.
  const Teuchos::RCP<const OP> M = run.stiff.empty() ? run.cgM : run.M;
  FacePcpg<S, MV, OP> pcpg(run.faceA, M, face, tol, maxIterations, S(0), run.stiff);
  const FacePcpgResult<S> res = pcpg.solve(*run.x, *run.g);
  counters_.hessianMultiplications += res.iterations;
  face_.iterations += res.iterations;
  return res;
}

template <class S, class MV, class OP>
bool SmalbeSolMgr<S, MV, OP>::looseVerdictMoves(const FaceProjector<S, MV, OP>& face,
                                                const std::vector<S>& r, FaceRun& run, int& steps,
                                                std::vector<long long>& active) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  using BT = BoundTraits<S, MV>;
  // A face with circles solved again from its retracted result goes to circleTol: the tight
  // solve's linearization point.
  const auto repeats = std::count(run.relinearized.begin(), run.relinearized.end(), active);
  const S tol = repeats > 0 ? run.circleTol : run.looseTol;
  const FacePcpgResult<S> lr = faceCg(face, tol, run.maxIterations, run);
  steps += lr.iterations;
  auto xp = MVT::CloneCopy(*run.x);
  BT::setAt(face.active(), r, *xp);
  feasibleSet(qp_).project(*xp);  // the boxes, and the circles retracted
  // The verdict on the rows by the problem's own gradient (without the circles' curvature).
  auto g = MVT::CloneCopy(*run.g);
  if (!run.circles.empty()) addCurvatureGradient(run, *run.x, S(-1), *g);
  std::vector<long long> next =
      activeSetStep(*xp, face, face.activeMultipliers(*g), holdsCircleReleases());
  const bool seen = std::find(run.visited.begin(), run.visited.end(), next) != run.visited.end();
  // An unconverged loose solve gives no verdict; the tight one judges the face. Nor does one that
  // took no step (its entry point already met the loose tolerance, as in an inexact Newton QP
  // whose tolerance is loose) and would move the face: that verdict judges the warm start, not
  // the face, and such verdicts wandered between faces (the elasto-plastic Hertz sphere at 0.54M:
  // ten faces of 1954-1986 rows without a CG step, then SMALBE's outer iterations).
  if (!lr.converged || (lr.iterations == 0 && next != active)) return false;
  if (next == active || seen) {
    // A face with circles that holds, or whose verdict leads back to a face already left (the
    // tight solve settles it), is solved once more from its retracted result, loosely, then
    // again to circleTol: the tight solve that follows is then the last Newton step on the
    // circles instead of the one before it (their linearization's error is quadratic in the
    // distance to the answer: from the loose tolerance it left the tight solve's result just
    // above SMALBE's tolerance, and a second tight solve followed).
    const bool again =
        !face.circles().empty() && (repeats == 0 || (repeats == 1 && run.circleTol < run.looseTol));
    if (!again) return false;
    run.relinearized.push_back(active);
    ++face_.circleSteps;
    MVT::Assign(*xp, *run.x);
    return true;
  }
  if (out_.wants(Belos::IterationDetails) && run.root) {
    auto line = SolverOutput::line();
    line << "SMALBE face " << face_.solves << ": " << active.size() << " active rows, "
         << lr.iterations << " CG steps to the loose tolerance, next face " << next.size()
         << " active rows\n";
    out_.write(line);
  }
  run.visited.push_back(active);
  ++face_.activeSetChanges;
  active = std::move(next);
  MVT::Assign(*xp, *run.x);
  return true;
}

template <class S, class MV, class OP>
typename SmalbeSolMgr<S, MV, OP>::FaceOutcome SmalbeSolMgr<S, MV, OP>::finalTestOnFace(
    const FaceProjector<S, MV, OP>& face, const std::vector<long long>& active,
    const std::vector<S>& r, FaceRun& run) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;
  using BT = BoundTraits<S, MV>;
  MV& x = *run.x;
  MV& g = *run.g;
  MV& t = *run.t;
  MV& mu = *run.mu;
  FaceOutcome out;
  std::vector<magnitude_type> n(1);
  // The active components exactly at their bounds (P_F leaves rounding errors there, which
  // would make them free, with their multiplier counted as a free gradient).
  BT::setAt(face.active(), r, x);
  // The result as SMALBE's: feasible (projected onto the box, the circles retracted), the
  // gradient recomputed, the equality multiplier mu = -Q (g - E_A^T sigma) that leaves g + mu =
  // P_F g + E_A^T sigma (zero on the free rows up to the tolerance, sigma on the active ones),
  // then the final test.
  const SeparableSet<S, MV> set = feasibleSet(qp_);
  set.project(x);
  OPT::Apply(*run.A, x, g);
  MVT::MvAddMv(S(1), g, S(-1), *qp_.b, g);
  ++counters_.hessianMultiplications;
  OPT::Apply(*Q_, x, t);
  ++qApplies_;
  MVT::MvNorm(t, n);
  out.qx = n[0];
  // With circles, the rows at the retracted x (their normals moved with it).
  std::unique_ptr<FaceProjector<S, MV, OP>> retracted;
  if (!run.circles.empty()) {
    retracted = faceOf(active, x, run);
    qApplies_ += retracted->projectorApplications();
  }
  const FaceProjector<S, MV, OP>& rows =
      retracted != nullptr && retracted->valid() ? *retracted : face;
  out.sigma = rows.activeMultipliers(g);
  MVT::Assign(g, t);
  rows.addRows(out.sigma, S(-1), t);
  OPT::Apply(*Q_, t, mu);
  ++qApplies_;
  MVT::MvScale(mu, S(-1));
  MVT::MvAddMv(S(1), g, S(1), mu, t);  // the Lagrangian's gradient
  set.freeGradient(x, t, *run.phi);
  set.choppedGradient(x, t, *run.chopped);
  MVT::MvAddMv(S(1), *run.phi, S(1), *run.chopped, *run.phi);
  MVT::MvNorm(*run.phi, n);
  out.gp = n[0];
  return out;
}

template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::reportFaceSolve(const FaceRun& run, std::size_t activeRows, int steps,
                                              bool cgConverged, const FaceOutcome& out, bool passed,
                                              std::size_t nextRows) {
  if (!out_.wants(Belos::IterationDetails) || !run.root) return;
  auto line = SolverOutput::line();
  line << "SMALBE face " << face_.solves << ": " << activeRows << " active rows, " << steps
       << " CG steps" << (cgConverged ? "" : " (not converged)") << std::scientific
       << std::setprecision(3) << ", ||g^P||/||b|| = " << out.gp / run.scale
       << "  ||A|| ||Qx||/||b|| = " << normA_ * out.qx / run.scale
       << (passed ? ": accepted" : ": rejected");
  if (!passed) line << ", next face " << nextRows << " active rows";
  line << "\n";
  out_.write(line);
}

// The primal-dual active-set step: the rows at a bound of the projected iterate xp, less the
// face's own rows whose multiplier sigma has the wrong sign (a lower bound is held by sigma
// >= 0, an upper one by sigma <= 0). A row that has just left the box joins whatever its
// gradient at the projected point (which is not a multiplier: judging it would undo most of
// the step, a few rows joining per face).
template <class S, class MV, class OP>
std::vector<long long> SmalbeSolMgr<S, MV, OP>::activeSetStep(const MV& xp,
                                                              const FaceProjector<S, MV, OP>& rows,
                                                              const std::vector<S>& sigma,
                                                              bool holdCircles) const {
  using BT = BoundTraits<S, MV>;
  const MV* upper = qp_.upper.get();
  const std::vector<long long>& face = rows.active();
  const std::vector<long long> now = feasibleSet(qp_).activeIndices(xp);
  const std::vector<S> xn = BT::gatherAt(xp, now), ln = BT::gatherAt(*qp_.lower, now);
  std::vector<S> un(now.size(), std::numeric_limits<S>::infinity());
  if (upper != nullptr) un = BT::gatherAt(*upper, now);
  // A circle whose multiplier sigma = n . g is positive pulls x into its disc: released (both
  // components), unless holdCircles and a row joins (a component at a bound that is neither
  // the face's nor one of its circles'). The components of a disc of radius 0 are never
  // released.
  std::vector<long long> released;
  const auto& circles = rows.circles();
  const bool hold = holdCircles && face_phase_detail::rowJoins(now, face, circles);
  for (std::size_t k = 0; k < circles.size() && !hold; ++k)
    if (sigma[face.size() + k] > S(0))
      released.push_back(circles[k].index), released.push_back(circles[k].index + 1);
  std::vector<long long> next;
  for (std::size_t i = 0; i < now.size(); ++i) {
    if (std::binary_search(released.begin(), released.end(), now[i])) continue;
    const auto it = std::lower_bound(face.begin(), face.end(), now[i]);
    bool release = false;
    const bool bounded = std::isfinite(ln[i]) || std::isfinite(un[i]);
    if (bounded && it != face.end() && *it == now[i] && ln[i] < un[i]) {
      const S si = sigma[static_cast<std::size_t>(it - face.begin())];
      release = xn[i] <= ln[i] ? si < S(0) : si > S(0);
    }
    if (!release) next.push_back(now[i]);
  }
  return next;
}

template <class S, class MV, class OP>
typename SmalbeSolMgr<S, MV, OP>::FaceVerdict SmalbeSolMgr<S, MV, OP>::trialFace(
    const std::vector<long long>& active, const std::vector<long long>& judged, magnitude_type tol,
    MV& x) {
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;
  using BT = BoundTraits<S, MV>;
  FaceVerdict v;
  ++face_.levelSolves;
  FaceProjector<S, MV, OP> face(Q_, active, x, gramian_.get(), {}, complementFactors_.get());
  qApplies_ += face.projectorApplications();
  if (!face.valid()) return v;
  v.valid = true;
  // The rows at their lower bounds; the components of a disc of radius 0 (no bounds) at the
  // centre, where the projection has put them.
  std::vector<S> values = BT::gatherAt(*qp_.lower, active);
  const std::vector<S> xa = BT::gatherAt(x, active);
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i])) values[i] = xa[i];
  face.projectAffine(values, x);
  const auto A = TimedOperator<S, MV, OP>::wrap(qp_.A, solverTimer("tfeti: Hessian apply"));
  auto g = MVT::Clone(x, 1);
  OPT::Apply(*A, x, *g);
  MVT::MvAddMv(S(1), *g, S(-1), *qp_.b, *g);
  ++counters_.hessianMultiplications;
  const bool precondition = params_.sublist("MPRGP").get<bool>("Preconditioning in face");
  const Teuchos::RCP<const OP> M = !precondition        ? Teuchos::null
                                   : inFaceM_.is_null() ? P_
                                                        : inFaceM_;
  const auto faceA = inFaceA_.is_null() ? A
                                        : TimedOperator<S, MV, OP>::wrap(
                                              inFaceA_, solverTimer("tfeti: Hessian apply"));
  // Solved loosely, to kLevelReduction of its own start's projected gradient (or to tol if that
  // is looser; tfeti_SmalbeSolMgr_decl.hpp), then, if the verdict says nothing, to tol.
  const int maxIterations = params_.get<int>("Face maximum iterations");
  const auto solveTo = [&](S reduction) {
    const FacePcpgResult<S> res =
        FacePcpg<S, MV, OP>(faceA, M, face, S(tol), maxIterations, reduction).solve(x, *g);
    BT::setAt(active, values, x);
    judgeTrialFace(face, judged, x, *g, v);
    return res;
  };
  const FacePcpgResult<S> loose = solveTo(S(kLevelReduction));
  int steps = loose.iterations;
  // The bisection goes on from a verdict of one kind only. A loose solve that judges nothing
  // (near its start the signs have not shown yet: every row seems where it belongs) or both (rows
  // out of the box and wrong signs at once, still moving) is taken on to tol.
  if ((v.leftBox == 0) == (v.wrongSign == 0) && !(loose.projectedGradientNorm <= S(tol)))
    steps += solveTo(S(0)).iterations;
  counters_.hessianMultiplications += steps;
  face_.iterations += steps;
  if (out_.wants(Belos::IterationDetails) && BT::commRank(x) == 0) {
    auto line = SolverOutput::line();
    line << "SMALBE level face: " << active.size() << " active rows, " << steps << " CG steps, "
         << v.leftBox << " free rows outside the box, " << v.wrongSign
         << " active rows with a multiplier of the wrong sign\n";
    out_.write(line);
  }
  return v;
}

// The level rows outside their (lower) bounds (friction rows are not judged), and the active level
// rows whose multiplier has the wrong sign: a lower bound is held by a multiplier pushing x up,
// sigma >= 0 (g = sigma on the row; not the points of discs of radius 0).
template <class S, class MV, class OP>
void SmalbeSolMgr<S, MV, OP>::judgeTrialFace(const FaceProjector<S, MV, OP>& face,
                                             const std::vector<long long>& judged, const MV& x,
                                             const MV& g, FaceVerdict& v) const {
  using BT = BoundTraits<S, MV>;
  v.leftBox = v.wrongSign = 0;
  const std::vector<S> xj = BT::gatherAt(x, judged), lj = BT::gatherAt(*qp_.lower, judged);
  for (std::size_t i = 0; i < judged.size(); ++i)
    if (xj[i] < lj[i]) ++v.leftBox;
  const std::vector<long long>& active = face.active();
  const std::vector<S> sigma = face.activeMultipliers(g);
  for (std::size_t i = 0; i < active.size(); ++i)
    if (sigma[i] < S(0) && std::binary_search(judged.begin(), judged.end(), active[i]))
      ++v.wrongSign;
}

template <class S, class MV, class OP>
std::vector<long long> SmalbeSolMgr<S, MV, OP>::levelFace(magnitude_type tol, MV& x, bool& found) {
  using BT = BoundTraits<S, MV>;
  // The candidates and their levels, the same on every rank and rank count.
  const std::vector<long long> rows = BT::finiteIndices(*levels_);
  const std::vector<S> level = BT::gatherAt(*levels_, rows);
  std::vector<S> tau = level;
  std::sort(tau.begin(), tau.end());
  tau.erase(std::unique(tau.begin(), tau.end()), tau.end());
  // Every face holds the points of discs of radius 0 (3D friction's open nodes) where they are.
  const std::vector<long long> points =
      qp_.discs.is_null() ? std::vector<long long>() : feasibleSet(qp_).pointComponents(x);
  const auto faceAbove = [&](std::size_t k) {
    std::vector<long long> a;
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (level[i] > tau[k]) a.push_back(rows[i]);
    if (points.empty()) return a;  // sorted: rows is
    std::vector<long long> both;
    std::merge(a.begin(), a.end(), points.begin(), points.end(), std::back_inserter(both));
    return both;
  };
  // One level (the two membranes: every gap zero) says nothing about the face.
  found = tau.size() > 1;
  if (!found) return {};
  // Level k holds the rows at or below tau[k] free: the larger k, the more free rows. Too many
  // free rows leave the box (tension on a closed contact row), too few leave active rows with
  // a multiplier of the wrong sign (penetration): bisect between the two.
  std::size_t lo = 0, hi = tau.size() - 1;
  // "half lowest": a smooth body pressed a depth d into another (a prescribed indentation) is in
  // contact, by Hertz, where its initial gap is below -d/2 (a^2 = R d; the gap at a is
  // a^2/2R - d). The first trial frees those rows. A finite body's zone differs from Hertz's by
  // tens of per cent in area (step-42's cube at 64^3: 89 rows against 69), so the next trials
  // step by the verdict's own count, as a primal-dual active-set step would: free as many more
  // rows as had the wrong sign, or hold as many as left the box. Two count steps to the same
  // side in a row are followed by a bisection (or, before the other side is known, the step
  // doubles), so a count that misleads costs no more than the bisection. Without a negative
  // lowest level (bodies that just touch, loaded by a force) there is no guess: plain bisection.
  const std::size_t guess = startLevel(tau);
  const bool walk = guess != kNoLevelGuess;
  // freeRows[k]: the rows at or below tau[k] (for the count steps).
  std::vector<long long> freeRows;
  if (walk) {
    std::vector<S> sorted = level;
    std::sort(sorted.begin(), sorted.end());
    for (const S t : tau)
      freeRows.push_back(std::upper_bound(sorted.begin(), sorted.end(), t) - sorted.begin());
  }
  bool belowKnown = false, aboveKnown = false;
  int lastSide = 0, sameSide = 0;  // +1: too few free rows, -1: too many
  long long lastStep = 0;
  std::size_t k = walk ? guess : lo + (hi - lo) / 2;
  while (lo < hi) {
    const FaceVerdict v = trialFace(faceAbove(k), rows, tol, x);
    // Too few free rows (or not enough to carry Q's rows), too many, or neither (the face) or
    // both (the primal-dual steps go on from it).
    const bool tooFew = !v.valid || (v.wrongSign > 0 && v.leftBox == 0);
    const bool tooMany = v.valid && v.leftBox > 0 && v.wrongSign == 0;
    if (!tooFew && !tooMany) return faceAbove(k);
    const int side = tooFew ? 1 : -1;
    sameSide = side == lastSide ? sameSide + 1 : 1;
    lastSide = side;
    if (tooFew) {
      lo = k + 1;
      belowKnown = true;
    } else {
      hi = k;
      aboveKnown = true;
    }
    if (lo >= hi) break;
    const bool bracketed = belowKnown && aboveKnown;
    if (!walk || (bracketed && sameSide > 2)) {
      k = lo + (hi - lo) / 2;
      sameSide = 0;
      continue;
    }
    // The count step; an invalid face (dependent on Q's rows) has no count: one row.
    long long step = std::max<long long>(1, tooFew ? v.wrongSign : v.leftBox);
    if (!bracketed && sameSide > 1) step = std::max(step, 2 * lastStep);
    lastStep = step;
    const long long want = freeRows[k] + side * step;
    if (tooFew) {
      for (k = lo; k < hi && freeRows[k] < want;) ++k;
    } else {
      for (k = hi - 1; k > lo && freeRows[k] > want;) --k;
    }
  }
  return faceAbove(lo);
}

template <class S, class MV, class OP>
std::size_t SmalbeSolMgr<S, MV, OP>::startLevel(const std::vector<S>& tau) const {
  if (params_.get<std::string>("Level search start") != "half lowest" || tau.empty() ||
      !(tau.front() < S(0)))
    return kNoLevelGuess;
  const S half = tau.front() / S(2);
  const std::size_t k =
      static_cast<std::size_t>(std::upper_bound(tau.begin(), tau.end(), half) - tau.begin()) - 1;
  // One free level alone is the deepest point: no zone to speak of (a touch by rounding).
  return k >= 1 && k + 1 < tau.size() ? k : kNoLevelGuess;
}

}  // namespace tfeti
