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

// P A P + c Q with two coarse projections instead of three (P x is shared): the penalized or
// augmented dual Hessian P F P + rho Q (A = F, c = rho), and its in-face preconditioner
// P M P + Q / rho (A = M, c = 1/rho).
class ProjectedPlusComplement : public Operator {
 public:
  ProjectedPlusComplement(Teuchos::RCP<const Operator> A, const CoarseSpace& coarse, double c)
      : A_(std::move(A)), coarse_(coarse), c_(c) {}
  Teuchos::RCP<const Map> getDomainMap() const override { return A_->getDomainMap(); }
  Teuchos::RCP<const Map> getRangeMap() const override { return A_->getRangeMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
             Scalar alpha = 1.0, Scalar beta = 0.0) const override;

 private:
  Teuchos::RCP<const Operator> A_;
  const CoarseSpace& coarse_;
  double c_;
  mutable Teuchos::RCP<MultiVector> px_, apx_;
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
