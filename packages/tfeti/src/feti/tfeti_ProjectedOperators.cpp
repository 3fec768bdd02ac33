#include "tfeti_ProjectedOperators.hpp"

#include <Teuchos_LAPACK.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tfeti {
namespace {
void ensureColumns(Teuchos::RCP<MultiVector>& v, const Teuchos::RCP<const Map>& map,
                   std::size_t cols) {
  if (v.is_null() || v->getNumVectors() != cols) v = Teuchos::rcp(new MultiVector(map, cols));
}
}  // namespace
}  // namespace tfeti

namespace tfeti {

ProjectedDualOperator::ProjectedDualOperator(Teuchos::RCP<const Operator> F,
                                             const CoarseSpace& coarse)
    : F_(std::move(F)), coarse_(coarse) {}

void ProjectedDualOperator::apply(const MultiVector& X, MultiVector& Y,
                                  Teuchos::ETransp /*mode: symmetric*/, Scalar alpha,
                                  Scalar beta) const {
  ensureColumns(px_, X.getMap(), 1);
  ensureColumns(fpx_, X.getMap(), 1);
  for (std::size_t j = 0; j < X.getNumVectors(); ++j) {
    auto px = px_->getVectorNonConst(0);
    auto fpx = fpx_->getVectorNonConst(0);
    coarse_.project(*X.getVector(j), *px);
    F_->apply(*px, *fpx);
    coarse_.project(*fpx, *fpx);
    Y.getVectorNonConst(j)->update(alpha, *fpx, beta);
  }
}

void ComplementProjector::apply(const MultiVector& X, MultiVector& Y,
                                Teuchos::ETransp /*mode: symmetric*/, Scalar alpha,
                                Scalar beta) const {
  ensureColumns(px_, X.getMap(), 1);
  for (std::size_t j = 0; j < X.getNumVectors(); ++j) {
    auto px = px_->getVectorNonConst(0);
    coarse_.project(*X.getVector(j), *px);
    // Q x = x - P x
    Y.getVectorNonConst(j)->update(alpha, *X.getVector(j), -alpha, *px, beta);
  }
}

void ProjectedPlusComplement::apply(const MultiVector& X, MultiVector& Y,
                                    Teuchos::ETransp /*mode: symmetric*/, Scalar alpha,
                                    Scalar beta) const {
  // A applies to every column at once (the Dirichlet preconditioner solves a subdomain's
  // columns together: the stiff circles' columns of M, tfeti_SmalbeFacePhase_def.hpp).
  const std::size_t nv = X.getNumVectors();
  ensureColumns(px_, X.getMap(), nv);
  ensureColumns(apx_, X.getMap(), nv);
  for (std::size_t j = 0; j < nv; ++j) coarse_.project(*X.getVector(j), *px_->getVectorNonConst(j));
  A_->apply(*px_, *apx_);
  for (std::size_t j = 0; j < nv; ++j) {
    auto px = px_->getVector(j);
    auto apx = apx_->getVectorNonConst(j);
    coarse_.project(*apx, *apx);
    // y = alpha (P A P x + c (x - P x)) + beta y
    auto y = Y.getVectorNonConst(j);
    y->update(alpha, *apx, alpha * c_, *X.getVector(j), beta);
    y->update(-alpha * c_, *px, 1.0);
  }
}

void CoarseComplementColumns::setCandidates(const std::vector<long long>& candidates) {
  c_ = candidates;
  g_ = coarse_.columnsOfG(c_);
}

void CoarseComplementColumns::columns(const std::vector<long long>& J,
                                      std::vector<Scalar>& out) const {
  const std::size_t n = static_cast<std::size_t>(coarse_.dimension()), m = c_.size(), k = J.size();
  out.assign(m * k, 0.0);
  if (n == 0 || k == 0) return;
  // W = (G G^T)^{-1} G E_J^T, then E_C Q E_J^T = (G E_C^T)^T W.
  std::vector<double> rhs(n * k, 0.0), w(n * k);
  for (std::size_t c = 0; c < k; ++c) {
    const auto it = std::lower_bound(c_.begin(), c_.end(), J[c]);
    if (it == c_.end() || *it != J[c])
      throw std::logic_error("CoarseComplementColumns: " + std::to_string(J[c]) +
                             " is not a candidate");
    for (const auto& [r, v] : g_[static_cast<std::size_t>(it - c_.begin())])
      rhs[c * n + static_cast<std::size_t>(r)] = v;
  }
  coarse_.coarseSolveLocal(rhs.data(), w.data(), static_cast<int>(k));
  for (std::size_t c = 0; c < k; ++c)
    for (std::size_t i = 0; i < m; ++i) {
      double sum = 0.0;
      for (const auto& [r, v] : g_[i]) sum += v * w[c * n + static_cast<std::size_t>(r)];
      out[c * m + i] = sum;
    }
}

void CoarseComplementFactors::coefficients(const MultiVector& x, std::vector<Scalar>& a) const {
  a.assign(static_cast<std::size_t>(coarse_.dimension()), 0.0);
  coarse_.coefficientsEverywhere(*x.getVector(0), a.data());
}

void CoarseComplementFactors::applyG(const MultiVector& x, std::vector<Scalar>& c) const {
  c.assign(static_cast<std::size_t>(coarse_.dimension()), 0.0);
  coarse_.applyGEverywhere(*x.getVector(0), c.data());
}

const std::vector<Scalar>& CoarseComplementFactors::gramianFactor() const {
  if (!gramianFactor_.empty()) return gramianFactor_;
  const int n = static_cast<int>(coarse_.dimension());
  gramianFactor_ = coarse_.denseGramian();
  int info = 0;
  Teuchos::LAPACK<int, Scalar>().POTRF('L', n, gramianFactor_.data(), n, &info);
  // The sparse factorization of the same matrix succeeded when the coarse space was built.
  if (info != 0)
    throw std::logic_error(
        "CoarseComplementFactors: the dense Cholesky factorization of G G^T "
        "failed at column " +
        std::to_string(info));
  return gramianFactor_;
}

void CoarseComplementFactors::addTranspose(const std::vector<Scalar>& a, Scalar alpha,
                                           MultiVector& y) const {
  coarse_.addTransposeEverywhere(a.data(), alpha, *y.getVectorNonConst(0));
}

void CoarseComplementFactors::solve(std::vector<Scalar>& b) const {
  if (b.empty()) return;
  x_.resize(b.size());
  coarse_.coarseSolveLocal(b.data(), x_.data(), 1);
  b.swap(x_);
}

std::vector<std::vector<std::pair<int, Scalar>>> CoarseComplementFactors::columns(
    const std::vector<long long>& ids) const {
  const auto g = coarse_.columnsOfG(ids);
  std::vector<std::vector<std::pair<int, Scalar>>> out(g.size());
  for (std::size_t i = 0; i < g.size(); ++i)
    for (const auto& e : g[i]) out[i].emplace_back(static_cast<int>(e.first), e.second);
  return out;
}

}  // namespace tfeti
