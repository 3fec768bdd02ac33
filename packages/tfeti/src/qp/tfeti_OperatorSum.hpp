#pragma once
// OperatorSum<S, MV, OP>::build(A, a, B, b): an operator applying a A x + b B x without forming
// the sum. SMALBE uses it for the Hessian A + rho Q of its augmented Lagrangian, where A is a
// matrix or a FETI dual operator and Q a projector given only as an operator.
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
};

template <class S, class LO, class GO, class Node>
struct OperatorSum<S, Tpetra::MultiVector<S, LO, GO, Node>, Tpetra::Operator<S, LO, GO, Node>> {
  using MV = Tpetra::MultiVector<S, LO, GO, Node>;
  using OP = Tpetra::Operator<S, LO, GO, Node>;

  class Sum : public OP {
   public:
    Sum(Teuchos::RCP<const OP> A, S a, Teuchos::RCP<const OP> B, S b)
        : A_(std::move(A)), B_(std::move(B)), a_(a), b_(b) {}
    Teuchos::RCP<const Tpetra::Map<LO, GO, Node>> getDomainMap() const override {
      return A_->getDomainMap();
    }
    Teuchos::RCP<const Tpetra::Map<LO, GO, Node>> getRangeMap() const override {
      return A_->getRangeMap();
    }
    bool hasTransposeApply() const override {
      return A_->hasTransposeApply() && B_->hasTransposeApply();
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
      A_->apply(X, Y, mode, alpha * a_, beta);
      Y.update(alpha * b_, *work_, Teuchos::ScalarTraits<S>::one());
    }

   private:
    Teuchos::RCP<const OP> A_, B_;
    S a_, b_;
    mutable Teuchos::RCP<MV> work_;
  };

  static Teuchos::RCP<const OP> build(const Teuchos::RCP<const OP>& A, S a,
                                      const Teuchos::RCP<const OP>& B, S b) {
    return Teuchos::rcp(new Sum(A, a, B, b));
  }
};

}  // namespace tfeti
