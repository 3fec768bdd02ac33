#pragma once
// The operators of the dual contact QP (reference paper, "FETI domain decomposition method (III)
// and (IV)"): the projected dual operator P F P and the complementary projector Q = I - P onto
// the range of G^T, so that the equality constraint G lambda = 0 reads Q lambda = 0 and the
// penalized / augmented Hessian is P F P + rho Q.
#include "tfeti_CoarseSpace.hpp"

namespace tfeti {

class ProjectedDualOperator : public Operator {
 public:
  // coarse must outlive the operator.
  ProjectedDualOperator(Teuchos::RCP<const Operator> F, const CoarseSpace& coarse);
  Teuchos::RCP<const Map> getDomainMap() const override { return F_->getDomainMap(); }
  Teuchos::RCP<const Map> getRangeMap() const override { return F_->getRangeMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
             Scalar alpha = 1.0, Scalar beta = 0.0) const override;

 private:
  Teuchos::RCP<const Operator> F_;
  const CoarseSpace& coarse_;
  mutable Teuchos::RCP<MultiVector> px_, fpx_;
};

class ComplementProjector : public Operator {
 public:
  ComplementProjector(Teuchos::RCP<const Map> map, const CoarseSpace& coarse)
      : map_(std::move(map)), coarse_(coarse) {}
  Teuchos::RCP<const Map> getDomainMap() const override { return map_; }
  Teuchos::RCP<const Map> getRangeMap() const override { return map_; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
             Scalar alpha = 1.0, Scalar beta = 0.0) const override;

 private:
  Teuchos::RCP<const Map> map_;
  const CoarseSpace& coarse_;
  mutable Teuchos::RCP<MultiVector> px_;
};

}  // namespace tfeti
