#pragma once
// OperatorSum<S, MV, OP>::build(A, a, B, b): an operator applying a A x + b B x without forming
// the sum. SMALBE uses it for the Hessian A + rho Q of its augmented Lagrangian, where A is a
// matrix or a FETI dual operator and Q a projector given only as an operator.
// OperatorSum<S, MV, OP>::shift(A, d): A x + d .* x (d a vector on A's domain map), the face
// Hessian of SMALBE's face solve with discs (the circles' curvature nu / r on their components).
#include <Teuchos_RCP.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Operator.hpp>

namespace tfeti {

template <class S, class MV, class OP>
struct OperatorSum {
  // Instantiating this means OperatorSum has no specialization for OP.
  static Teuchos::RCP<const OP> build(const Teuchos::RCP<const OP>& A, S a,
                                      const Teuchos::RCP<const OP>& B, S b) {
    return OP::this_type_is_missing_an_OperatorSum_specialization();
  }
  static Teuchos::RCP<const OP> shift(const Teuchos::RCP<const OP>& A,
                                      const Teuchos::RCP<const MV>& d) {
    return OP::this_type_is_missing_an_OperatorSum_specialization();
  }
};

template <class S, class LO, class GO, class Node>
struct OperatorSum<S, Tpetra::MultiVector<S, LO, GO, Node>, Tpetra::Operator<S, LO, GO, Node>> {
  using MV = Tpetra::MultiVector<S, LO, GO, Node>;
  using OP = Tpetra::Operator<S, LO, GO, Node>;

  // An operator on A's maps.
  class OnMapsOf : public OP {
   public:
    explicit OnMapsOf(Teuchos::RCP<const OP> A) : A_(std::move(A)) {}
    Teuchos::RCP<const Tpetra::Map<LO, GO, Node>> getDomainMap() const override {
      return A_->getDomainMap();
    }
    Teuchos::RCP<const Tpetra::Map<LO, GO, Node>> getRangeMap() const override {
      return A_->getRangeMap();
    }

   protected:
    Teuchos::RCP<const OP> A_;
  };

  class Sum : public OnMapsOf {
   public:
    Sum(Teuchos::RCP<const OP> A, S a, Teuchos::RCP<const OP> B, S b)
        : OnMapsOf(std::move(A)), B_(std::move(B)), a_(a), b_(b) {}
    bool hasTransposeApply() const override {
      return this->A_->hasTransposeApply() && B_->hasTransposeApply();
    }
    void apply(const MV& X, MV& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
               S alpha = Teuchos::ScalarTraits<S>::one(),
               S beta = Teuchos::ScalarTraits<S>::zero()) const override {
      // The work vector is kept (SMALBE applies the sum once per MPRGP step); comparing map
      // pointers avoids the collective Map::isSameAs.
      if (work_.is_null() || work_->getNumVectors() != X.getNumVectors() ||
          work_->getMap().get() != Y.getMap().get())
        work_ = Teuchos::rcp(new MV(Y.getMap(), X.getNumVectors(), false));
      B_->apply(X, *work_, mode);
      this->A_->apply(X, Y, mode, alpha * a_, beta);
      Y.update(alpha * b_, *work_, Teuchos::ScalarTraits<S>::one());
    }

   private:
    Teuchos::RCP<const OP> B_;
    S a_, b_;
    mutable Teuchos::RCP<MV> work_;
  };

  class Shift : public OnMapsOf {
   public:
    Shift(Teuchos::RCP<const OP> A, Teuchos::RCP<const MV> d)
        : OnMapsOf(std::move(A)), d_(std::move(d)) {}
    bool hasTransposeApply() const override { return this->A_->hasTransposeApply(); }
    // Y = alpha (A + diag(d)) X + beta Y (the diagonal is the same for every mode).
    void apply(const MV& X, MV& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
               S alpha = Teuchos::ScalarTraits<S>::one(),
               S beta = Teuchos::ScalarTraits<S>::zero()) const override {
      this->A_->apply(X, Y, mode, alpha, beta);
      auto dv = d_->getData(0);
      for (std::size_t j = 0; j < X.getNumVectors(); ++j) {
        auto xv = X.getData(j);
        auto yv = Y.getDataNonConst(j);
        for (std::size_t i = 0; i < X.getLocalLength(); ++i) yv[i] += alpha * dv[i] * xv[i];
      }
    }

   private:
    Teuchos::RCP<const MV> d_;
  };

  static Teuchos::RCP<const OP> build(const Teuchos::RCP<const OP>& A, S a,
                                      const Teuchos::RCP<const OP>& B, S b) {
    return Teuchos::rcp(new Sum(A, a, B, b));
  }
  static Teuchos::RCP<const OP> shift(const Teuchos::RCP<const OP>& A,
                                      const Teuchos::RCP<const MV>& d) {
    return Teuchos::rcp(new Shift(A, d));
  }
};

}  // namespace tfeti
