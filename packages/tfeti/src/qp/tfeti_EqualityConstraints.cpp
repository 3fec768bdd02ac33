#include "tfeti_EqualityConstraints.hpp"

#include <Teuchos_LAPACK.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace tfeti {

namespace {

// Q x = U (U^T x) with orthonormal columns U.
class RangeProjector : public Operator {
 public:
  explicit RangeProjector(Teuchos::RCP<const MultiVector> U)
      : U_(std::move(U)),
        coefMap_(Tpetra::createLocalMapWithNode<LO, GO, Node>(U_->getNumVectors(),
                                                              U_->getMap()->getComm())) {}
  Teuchos::RCP<const Map> getDomainMap() const override { return U_->getMap(); }
  Teuchos::RCP<const Map> getRangeMap() const override { return U_->getMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp = Teuchos::NO_TRANS,
             Scalar alpha = 1.0, Scalar beta = 0.0) const override {
    // Q is symmetric: the transposed application is the same.
    MultiVector coef(coefMap_, X.getNumVectors());
    coef.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, *U_, X, 0.0);  // U^T X, all-reduced
    if (beta == 0.0) Y.putScalar(0.0);  // Y may hold NaN: beta = 0 must ignore it
    Y.multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, alpha, *U_, coef, beta);
  }

 private:
  Teuchos::RCP<const MultiVector> U_;
  Teuchos::RCP<const Map> coefMap_;
};

}  // namespace

EqualityConstraints::EqualityConstraints(Teuchos::RCP<const MultiVector> rowsOfC,
                                         std::vector<double> d, double rankTolerance)
    : C_(std::move(rowsOfC)), d_(std::move(d)) {
  TEUCHOS_TEST_FOR_EXCEPTION(C_.is_null(), std::invalid_argument,
                             "EqualityConstraints: the rows of C are not given");
  const int m = static_cast<int>(C_->getNumVectors());
  if (static_cast<int>(d_.size()) != m) {
    std::ostringstream msg;
    msg << "EqualityConstraints: C has " << m << " rows, d has " << d_.size() << " entries";
    throw std::invalid_argument(msg.str());
  }
  for (int k = 0; k < m; ++k)
    if (!std::isfinite(d_[k]))
      throw std::invalid_argument("EqualityConstraints: d_" + std::to_string(k) + " is not finite");
  // The Gram matrix C C^T (replicated) and its eigendecomposition G = V diag(w) V^T.
  auto local = Tpetra::createLocalMapWithNode<LO, GO, Node>(m, C_->getMap()->getComm());
  MultiVector gram(local, m);
  gram.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, *C_, *C_, 0.0);
  std::vector<double> G(static_cast<std::size_t>(m) * m), w(m);
  {
    auto g = gram.get2dView();
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) G[i + j * m] = g[j][i];
  }
  for (double v : G)
    if (!std::isfinite(v)) throw std::invalid_argument("EqualityConstraints: C is not finite");
  Teuchos::LAPACK<int, double> lapack;
  int info = 0, lwork = std::max(1, 3 * m);
  std::vector<double> work(lwork);
  lapack.SYEV('V', 'U', m, G.data(), m, w.data(), work.data(), lwork, &info);
  TEUCHOS_TEST_FOR_EXCEPTION(info != 0, std::runtime_error,
                             "EqualityConstraints: the eigensolver failed (info " << info << ")");
  const double wMax = m > 0 ? w[m - 1] : 0.0;
  TEUCHOS_TEST_FOR_EXCEPTION(!(wMax > 0.0), std::invalid_argument,
                             "EqualityConstraints: C is zero (no constraint to impose)");
  // U = C^T V_k diag(w_k)^{-1/2}: an orthonormal basis of range(C^T); x0 = C^T G^+ d.
  std::vector<int> kept;
  for (int k = 0; k < m; ++k)
    if (w[k] > rankTolerance * wMax) kept.push_back(k);
  rank_ = static_cast<int>(kept.size());
  MultiVector W(local, rank_), z(local, 1);
  std::vector<double> Gd(m, 0.0), residual(d_);
  for (int c = 0; c < rank_; ++c) {
    const int k = kept[c];
    double vd = 0.0;
    for (int i = 0; i < m; ++i) vd += G[i + k * m] * d_[i];
    for (int i = 0; i < m; ++i) {
      W.replaceLocalValue(i, c, G[i + k * m] / std::sqrt(w[k]));
      Gd[i] += G[i + k * m] * vd / w[k];
      residual[i] -= G[i + k * m] * vd;  // d minus its part in range(C C^T) = range(C)
    }
  }
  double dNorm = 0.0, rNorm = 0.0;
  for (int i = 0; i < m; ++i)
    dNorm = std::max(dNorm, std::abs(d_[i])), rNorm = std::max(rNorm, std::abs(residual[i]));
  if (rNorm > 1e-10 * std::max(dNorm, 1e-300)) {
    std::ostringstream msg;
    msg << "EqualityConstraints: C x = d has no solution: C has rank " << rank_ << " of " << m
        << " rows and d is not in its range (the dependent rows disagree; residual " << rNorm
        << " against max|d| = " << dNorm << ")";
    throw std::invalid_argument(msg.str());
  }
  auto U = Teuchos::rcp(new MultiVector(C_->getMap(), rank_));
  U->multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, *C_, W, 0.0);
  Q_ = Teuchos::rcp(new RangeProjector(U));
  for (int i = 0; i < m; ++i) z.replaceLocalValue(i, 0, Gd[i]);
  x0_ = Teuchos::rcp(new Vector(C_->getMap()));
  x0_->multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, *C_, z, 0.0);
}

EqualityConstraints::Qp EqualityConstraints::shift(const Qp& qp) const {
  TEUCHOS_TEST_FOR_EXCEPTION(
      qp.A.is_null() || qp.b.is_null() || qp.lower.is_null() || qp.x.is_null(),
      std::invalid_argument, "EqualityConstraints::shift: A, b, lower and x must all be set");
  TEUCHOS_TEST_FOR_EXCEPTION(!qp.x->getMap()->isSameAs(*x0_->getMap()), std::invalid_argument,
                             "EqualityConstraints::shift: x is not on the map of C's rows");
  Qp y = qp;
  auto b = Teuchos::rcp(new MultiVector(*qp.b, Teuchos::Copy));
  qp.A->apply(*x0_, *b, Teuchos::NO_TRANS, -1.0, 1.0);  // b - A x0
  auto lower = Teuchos::rcp(new MultiVector(*qp.lower, Teuchos::Copy));
  lower->update(-1.0, *x0_, 1.0);  // -inf stays -inf
  auto x = Teuchos::rcp(new MultiVector(*qp.x, Teuchos::Copy));
  x->update(-1.0, *x0_, 1.0);
  y.b = b;
  y.lower = lower;
  y.x = x;
  if (!qp.upper.is_null()) {  // the box moves with the lifting as the lower bound does
    auto upper = Teuchos::rcp(new MultiVector(*qp.upper, Teuchos::Copy));
    upper->update(-1.0, *x0_, 1.0);  // +inf stays +inf
    y.upper = upper;
  }
  return y;
}

void EqualityConstraints::recover(const MultiVector& y, MultiVector& x) const {
  Tpetra::deep_copy(x, y);
  for (std::size_t c = 0; c < x.getNumVectors(); ++c)
    x.getVectorNonConst(c)->update(1.0, *x0_, 1.0);
}

double EqualityConstraints::residual(const MultiVector& x) const {
  const int m = static_cast<int>(C_->getNumVectors());
  auto local = Tpetra::createLocalMapWithNode<LO, GO, Node>(m, C_->getMap()->getComm());
  MultiVector cx(local, x.getNumVectors());
  cx.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, *C_, x, 0.0);
  double r = 0.0;
  auto v = cx.get2dView();
  for (std::size_t c = 0; c < x.getNumVectors(); ++c)
    for (int k = 0; k < m; ++k) r = std::max(r, std::abs(v[c][k] - d_[k]));
  return r;
}

}  // namespace tfeti
