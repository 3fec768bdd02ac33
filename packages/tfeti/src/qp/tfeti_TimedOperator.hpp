#pragma once
// TimedOperator<S, MV, OP>::wrap(A, timer): A applied under a Teuchos::TimeMonitor of `timer`, so
// that the solvers' "tfeti: Hessian apply" timer counts every multiplication by the Hessian
// (its number of calls equals the solvers' hessianMultiplications). The application itself is
// A's, with the same arguments: results are bitwise those of A.
// Operator types without a specialization are returned unwrapped (not timed).
#include <Teuchos_RCP.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Operator.hpp>

namespace tfeti {

template <class S, class MV, class OP>
struct TimedOperator {
  static Teuchos::RCP<const OP> wrap(const Teuchos::RCP<const OP>& A,
                                     const Teuchos::RCP<Teuchos::Time>&) {
    return A;
  }
};

template <class S, class LO, class GO, class Node>
struct TimedOperator<S, Tpetra::MultiVector<S, LO, GO, Node>, Tpetra::Operator<S, LO, GO, Node>> {
  using MV = Tpetra::MultiVector<S, LO, GO, Node>;
  using OP = Tpetra::Operator<S, LO, GO, Node>;

  class Timed : public OP {
   public:
    Timed(Teuchos::RCP<const OP> A, Teuchos::RCP<Teuchos::Time> timer)
        : A_(std::move(A)), timer_(std::move(timer)) {}
    Teuchos::RCP<const Tpetra::Map<LO, GO, Node>> getDomainMap() const override {
      return A_->getDomainMap();
    }
    Teuchos::RCP<const Tpetra::Map<LO, GO, Node>> getRangeMap() const override {
      return A_->getRangeMap();
    }
    bool hasTransposeApply() const override { return A_->hasTransposeApply(); }
    void apply(const MV& X, MV& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
               S alpha = Teuchos::ScalarTraits<S>::one(),
               S beta = Teuchos::ScalarTraits<S>::zero()) const override {
      Teuchos::TimeMonitor monitor(*timer_);
      A_->apply(X, Y, mode, alpha, beta);
    }

   private:
    Teuchos::RCP<const OP> A_;
    Teuchos::RCP<Teuchos::Time> timer_;
  };

  static Teuchos::RCP<const OP> wrap(const Teuchos::RCP<const OP>& A,
                                     const Teuchos::RCP<Teuchos::Time>& timer) {
    return Teuchos::rcp(new Timed(A, timer));
  }
};

}  // namespace tfeti
