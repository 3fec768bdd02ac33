#pragma once
// The operators of the dual problem, as Tpetra operators on the multiplier map:
//   PseudoInverseOperator  K+ = diag(K_s+)           (primal map -> primal map)
//   DualOperator           F  = B K+ B^T              (multipliers -> multipliers), implicit
//                                                      (B^T, K+ by the factors, B) or explicit
//                                                      (dense local F_s, ExplicitDualOperator)
//   DualPreconditioner     M^{-1} = Q B S B^T Q       (S: Schur complements or K_bb blocks;
//                                                      Q = (B B^T)^+, block diagonal by group)
// Communication is Tpetra's: B's transposed apply exports, its apply imports.
#include <memory>
#include <vector>

#include "tfeti_ExplicitDualOperator.hpp"
#include "tfeti_Subdomain.hpp"
#include "tfeti_Tearing.hpp"
#include "tfeti_Types.hpp"

namespace tfeti {

using SubdomainList = std::vector<std::shared_ptr<Subdomain>>;

class PseudoInverseOperator : public Operator {
 public:
  PseudoInverseOperator(Teuchos::RCP<const Map> primalMap, SubdomainList subdomains);
  Teuchos::RCP<const Map> getDomainMap() const override { return map_; }
  Teuchos::RCP<const Map> getRangeMap() const override { return map_; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
             Scalar alpha = 1.0, Scalar beta = 0.0) const override;

 private:
  Teuchos::RCP<const Map> map_;
  SubdomainList subdomains_;
  mutable std::vector<double> in_, out_;
};

class DualOperator : public Operator {
 public:
  // explicitDual null: implicit, F x = B (K+ (B^T x)); otherwise the explicit local operators
  // apply F (B and K+ are kept for the callers that use them elsewhere).
  DualOperator(Teuchos::RCP<const CrsMatrix> B, Teuchos::RCP<const Operator> Kplus,
               std::shared_ptr<const ExplicitDualOperator> explicitDual = nullptr);
  Teuchos::RCP<const Map> getDomainMap() const override { return B_->getRangeMap(); }
  Teuchos::RCP<const Map> getRangeMap() const override { return B_->getRangeMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
             Scalar alpha = 1.0, Scalar beta = 0.0) const override;
  long long numApplies() const { return applies_; }
  // Null when implicit.
  const std::shared_ptr<const ExplicitDualOperator>& explicitPart() const { return explicit_; }

 private:
  Teuchos::RCP<const CrsMatrix> B_;
  Teuchos::RCP<const Operator> Kplus_;
  std::shared_ptr<const ExplicitDualOperator> explicit_;
  mutable Teuchos::RCP<MultiVector> p1_;
  mutable long long applies_ = 0;
};

class DualPreconditioner : public Operator {
 public:
  DualPreconditioner(const Tearing& tearing, SubdomainList subdomains);
  Teuchos::RCP<const Map> getDomainMap() const override { return B_->getRangeMap(); }
  Teuchos::RCP<const Map> getRangeMap() const override { return B_->getRangeMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
             Scalar alpha = 1.0, Scalar beta = 0.0) const override;

 private:
  void scale(MultiVector& X) const;
  Teuchos::RCP<const CrsMatrix> B_;
  SubdomainList subdomains_;
  ScalingGroups scaling_;
  mutable Teuchos::RCP<MultiVector> p1_, q_;
  mutable std::vector<double> vb_, yb_;
};

}  // namespace tfeti
