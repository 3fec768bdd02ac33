#pragma once
// The operators of the dual contact QP (reference paper, "FETI domain decomposition method (III)
// and (IV)"): the projected dual operator P F P and the complementary projector Q = I - P onto
// the range of G^T, so that the equality constraint G lambda = 0 reads Q lambda = 0 and the
// penalized / augmented Hessian is P F P + rho Q.
#include "tfeti_CoarseSpace.hpp"
#include "tfeti_ComplementColumns.hpp"
#include "tfeti_ComplementFactors.hpp"

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

// The columns E_C Q E_J^T of Q = G^T (G G^T)^{-1} G at the bound components, for SMALBE's face
// solves: G's few entries in the columns C (gathered once per solve) and one coarse solve with
// a block of right-hand sides, instead of one application of Q (two passes over G, a coarse
// solve and two dual-vector updates) per column. At 64^3 step-42 (512 subdomains, 869 contact
// rows) a QP's faces ask for about 800 columns: one per open row, held at its bound.
class CoarseComplementColumns : public ComplementColumns<Scalar> {
 public:
  // coarse must outlive this.
  explicit CoarseComplementColumns(const CoarseSpace& coarse) : coarse_(coarse) {}
  void setCandidates(const std::vector<long long>& candidates) override;
  void columns(const std::vector<long long>& J, std::vector<Scalar>& out) const override;

 private:
  const CoarseSpace& coarse_;
  std::vector<long long> c_;
  std::vector<std::vector<std::pair<GO, double>>> g_;  // G's column of each candidate
};

// Q = G^T (G G^T)^{-1} G in its factors, for SMALBE's face projectors: one pass over G and one
// over G^T per application of P_F (tfeti_FaceProjector.hpp) instead of two of each, and two
// coarse solves on the replicated factor instead of two Imports and solves.
class CoarseComplementFactors : public ComplementFactors<Scalar, MultiVector> {
 public:
  // coarse must outlive this.
  explicit CoarseComplementFactors(const CoarseSpace& coarse) : coarse_(coarse) {}
  int rows() const override { return static_cast<int>(coarse_.dimension()); }
  void applyG(const MultiVector& x, std::vector<Scalar>& c) const override;
  const std::vector<Scalar>& gramianFactor() const override;
  void coefficients(const MultiVector& x, std::vector<Scalar>& a) const override;
  void addTranspose(const std::vector<Scalar>& a, Scalar alpha, MultiVector& y) const override;
  void solve(std::vector<Scalar>& b) const override;
  std::vector<std::vector<std::pair<int, Scalar>>> columns(
      const std::vector<long long>& ids) const override;

 private:
  const CoarseSpace& coarse_;
  mutable std::vector<Scalar> x_;
  mutable std::vector<Scalar> gramianFactor_;  // of the dense G G^T, when a face first asks
};

}  // namespace tfeti
