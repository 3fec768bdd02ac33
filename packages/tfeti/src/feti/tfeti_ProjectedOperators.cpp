#include "tfeti_ProjectedOperators.hpp"

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
  ensureColumns(px_, X.getMap(), 1);
  ensureColumns(apx_, X.getMap(), 1);
  for (std::size_t j = 0; j < X.getNumVectors(); ++j) {
    auto px = px_->getVectorNonConst(0);
    auto apx = apx_->getVectorNonConst(0);
    const auto x = X.getVector(j);
    coarse_.project(*x, *px);
    A_->apply(*px, *apx);
    coarse_.project(*apx, *apx);
    // y = alpha (P A P x + c (x - P x)) + beta y
    auto y = Y.getVectorNonConst(j);
    y->update(alpha, *apx, alpha * c_, *x, beta);
    y->update(-alpha * c_, *px, 1.0);
  }
}

}  // namespace tfeti
