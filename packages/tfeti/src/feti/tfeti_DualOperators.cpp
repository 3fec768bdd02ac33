#include "tfeti_DualOperators.hpp"

#include <algorithm>
#include <stdexcept>

namespace tfeti {

namespace {
// Reuses a work vector when it already has the right map and column count.
void ensure(Teuchos::RCP<MultiVector>& v, const Teuchos::RCP<const Map>& map, std::size_t cols) {
  if (v.is_null() || v->getNumVectors() != cols) v = Teuchos::rcp(new MultiVector(map, cols));
}
}  // namespace

PseudoInverseOperator::PseudoInverseOperator(Teuchos::RCP<const Map> primalMap,
                                             SubdomainList subdomains)
    : map_(std::move(primalMap)), subdomains_(std::move(subdomains)) {}

void PseudoInverseOperator::apply(const MultiVector& X, MultiVector& Y,
                                  Teuchos::ETransp /*mode: symmetric*/, Scalar alpha,
                                  Scalar beta) const {
  for (std::size_t j = 0; j < X.getNumVectors(); ++j) {
    auto x = X.getData(j);
    auto y = Y.getDataNonConst(j);
    std::size_t offset = 0;
    for (const auto& s : subdomains_) {
      const int n = s->numDofs();
      out_.resize(n);
      s->applyPseudoInverse(x.getRawPtr() + offset, out_.data());
      for (int i = 0; i < n; ++i)
        y[offset + i] = alpha * out_[i] + (beta == 0.0 ? 0.0 : beta * y[offset + i]);
      offset += n;
    }
  }
}

DualOperator::DualOperator(Teuchos::RCP<const CrsMatrix> B, Teuchos::RCP<const Operator> Kplus,
                           std::shared_ptr<const ExplicitDualOperator> explicitDual)
    : B_(std::move(B)), Kplus_(std::move(Kplus)), explicit_(std::move(explicitDual)) {}

void DualOperator::apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp /*mode: symmetric*/,
                         Scalar alpha, Scalar beta) const {
  applies_ += static_cast<long long>(X.getNumVectors());
  if (explicit_) {
    explicit_->apply(X, Y, alpha, beta);
    return;
  }
  // One primal work vector: K+ applies in place (each subdomain's block is read before it is
  // written), which saves a vector of the primal size.
  ensure(p1_, B_->getDomainMap(), X.getNumVectors());
  B_->apply(X, *p1_, Teuchos::TRANS);
  Kplus_->apply(*p1_, *p1_);
  B_->apply(*p1_, Y, Teuchos::NO_TRANS, alpha, beta);
}

DualPreconditioner::DualPreconditioner(const Tearing& tearing, SubdomainList subdomains)
    : B_(tearing.B), subdomains_(std::move(subdomains)), scaling_(tearing.scaling) {}

void DualPreconditioner::scale(MultiVector& X) const {
  for (std::size_t j = 0; j < X.getNumVectors(); ++j)
    scaling_.apply(X.getDataNonConst(j).getRawPtr());
}

void DualPreconditioner::apply(const MultiVector& X, MultiVector& Y,
                               Teuchos::ETransp /*mode: symmetric*/, Scalar alpha,
                               Scalar beta) const {
  const std::size_t nv = X.getNumVectors();
  ensure(q_, B_->getRangeMap(), nv);
  ensure(p1_, B_->getDomainMap(), nv);
  Tpetra::deep_copy(*q_, X);
  scale(*q_);
  B_->apply(*q_, *p1_, Teuchos::TRANS);
  // In place, one primal work vector: a subdomain's interface values are read before its block
  // is overwritten (zero off the interface). The columns of a subdomain go through its block
  // together (one interior solve with nv right-hand sides).
  std::vector<Teuchos::ArrayRCP<Scalar>> y(nv);
  for (std::size_t j = 0; j < nv; ++j) y[j] = p1_->getDataNonConst(j);
  std::size_t offset = 0;
  for (const auto& s : subdomains_) {
    const auto& b = s->interfaceDofs();
    const std::size_t nb = b.size();
    vb_.resize(nb * nv);
    yb_.resize(nb * nv);
    for (std::size_t j = 0; j < nv; ++j)
      for (std::size_t k = 0; k < nb; ++k) vb_[j * nb + k] = y[j][offset + b[k]];
    s->applyPreconditionerBlock(vb_.data(), yb_.data(), static_cast<int>(nv));
    for (std::size_t j = 0; j < nv; ++j) {
      std::fill(y[j].getRawPtr() + offset, y[j].getRawPtr() + offset + s->numDofs(), 0.0);
      for (std::size_t k = 0; k < nb; ++k) y[j][offset + b[k]] = yb_[j * nb + k];
    }
    offset += s->numDofs();
  }
  y.clear();
  B_->apply(*p1_, *q_);
  scale(*q_);
  Y.update(alpha, *q_, beta);
}

}  // namespace tfeti
