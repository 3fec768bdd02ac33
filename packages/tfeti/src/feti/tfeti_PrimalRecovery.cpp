// FetiSolver's primal recovery after the dual solve: u = K+ (f - B^T lambda) + R alpha, alpha
// fitted on the rows that hold with equality, alpha = (G_A G_A^T)^{-1} G_A (F lambda - d).
#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_PhaseTimer.hpp"

namespace tfeti {

std::string FetiSolver::recoverPrimal() {
  PhaseTimer t(*comm_, timings_.recovery, &memory_, "recovery");
  MultiVector rhs(tearing_.primalMap, 1);
  u_vec_ = Teuchos::rcp(new MultiVector(tearing_.primalMap, 1));
  MultiVector& u = *u_vec_;
  Tpetra::deep_copy(rhs, *f_);
  tearing_.B->apply(*lambda_, rhs, Teuchos::TRANS, -1.0, 1.0);
  Kplus_->apply(rhs, u);
  // Nothing acts (no load, no multiplier, no prescribed value): u = 0 exactly. The fit would be
  // singular when a body is held by contact alone and, unloaded, touches nothing; of the rigid
  // motions it leaves free, zero is the smallest.
  const bool unloaded = nothingActs();
  std::string fitFailure;
  if (coarse_->dimension() > 0 && !unloaded) fitFailure = addKernelComponent(u);
  keepSubdomainSolutions(u);
  return fitFailure;
}

bool FetiSolver::nothingActs() const {
  Teuchos::Array<double> fNorm(1);
  f_->normInf(fNorm());
  double acting[3] = {fNorm[0], lambda_->normInf(), 0.0}, anyActing[3];
  {
    auto c = tearing_.rhs->getData();
    const auto& map = *tearing_.multiplierMap;
    for (std::size_t i = 0; i < map.getNodeNumElements(); ++i)
      if (!tearing_.isInequality(map.getGlobalElement(static_cast<LO>(i))))
        acting[2] = std::max(acting[2], std::abs(c[i]));
  }
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 3, acting, anyActing);
  return anyActing[0] == 0.0 && anyActing[1] == 0.0 && anyActing[2] == 0.0;
}

std::string FetiSolver::addKernelComponent(MultiVector& u) const {
  Vector g(tearing_.multiplierMap);
  F_->apply(*lambda_, g);
  g.update(-1.0, *d_, 1.0);
  Vector alpha(coarse_->coarseMap());
  std::string fitFailure;
  if (tearing_.numInequalityRows == 0 || inequalitiesTied(params_)) {
    coarse_->leastSquaresCoefficients(g, alpha);
  } else {
    // Inactive inequality rows (lambda_i = 0) have a gap: they must not enter the fit.
    Vector mask(tearing_.multiplierMap);
    rowsHoldingWithEquality(mask);
    try {
      coarse_->leastSquaresOnRows(g, mask, alpha, params_.get<std::string>("Coarse solver"));
    } catch (const std::runtime_error& e) {
      // Too few rows hold with equality to fix the rigid motions: a dual solve that did not
      // converge (every friction row at its bound, where the bounds cannot balance the load),
      // or a body held along the surface by friction rows that all slide. The fit on all rows
      // (G G^T is regular) gives the last state; solve() reports the failure.
      fitFailure = e.what();
      coarse_->leastSquaresCoefficients(g, alpha);
    }
  }
  coarse_->addKernelCombination(alpha, u);
  return fitFailure;
}

void FetiSolver::rowsHoldingWithEquality(Vector& mask) const {
  // After the penalty's equality projection, MPRGP's rows (the projection moves a multiplier at
  // its bound a hair off it).
  if (!holdingRows_.is_null())
    Tpetra::deep_copy(mask, *holdingRows_);
  else
    markRowsHoldingWithEquality(*lambda_, mask);
}

void FetiSolver::markRowsHoldingWithEquality(const Vector& lambda, Vector& mask) const {
  auto m = mask.getDataNonConst();
  auto l = lambda.getData();
  const auto& map = *tearing_.multiplierMap;
  // Likewise a friction row whose multiplier is at a bound (slip): only the rows with the
  // multiplier strictly inside its bounds hold with equality.
  for (std::size_t i = 0; i < map.getNodeNumElements(); ++i) {
    const GO row = map.getGlobalElement(static_cast<LO>(i));
    bool holds = true;
    if (tearing_.isInequality(row)) {
      const InequalityRow& r = tearing_.inequalityRows[row - tearing_.firstInequalityRow];
      if (r.disc == 1) {
        // A disc pair (3D friction; both rows here, consecutive): it sticks, and both rows
        // hold, only strictly inside |lambda_T| <= g. On the circle the node slides: each
        // multiplier is inside [-g, g], so the test per row would count both as holding, and
        // the fit, pulled towards a zero slip there, would leave the gluing and Dirichlet rows
        // violated (the next Newton iteration's dual then has b outside the range of F where
        // those rows are redundant, and no minimizer).
        const double g = r.upperBound, t = std::hypot(l[i], l[i + 1]);
        holds = t < g && !(std::abs(t - g) <= 1e-10 * g);
        m[i] = m[i + 1] = holds ? 1.0 : 0.0;
        ++i;
        continue;
      }
      holds = r.boundActive(l[i]) == 0;
    }
    m[i] = holds ? 1.0 : 0.0;
  }
}

void FetiSolver::keepSubdomainSolutions(const MultiVector& u) {
  auto uv = u.getData(0);
  u_.assign(subdomains_.size(), {});
  std::size_t offset = 0;
  for (std::size_t i = 0; i < subdomains_.size(); ++i) {
    const int n = subdomains_[i]->numDofs();
    u_[i].assign(uv.getRawPtr() + offset, uv.getRawPtr() + offset + n);
    offset += n;
  }
}

}  // namespace tfeti
