#pragma once
// Belos status tests of the bound-constrained QP solvers. Both read the projected gradient norm
// ||g^P|| through Iteration::getNativeResiduals (MprgpIteration puts it in norms[0]), so they
// work with any iteration following that convention. Combine them with Belos::StatusTestMaxIters
// through Belos::StatusTestCombo (OR).
#include <BelosIteration.hpp>
#include <BelosLinearProblem.hpp>
#include <BelosMultiVecTraits.hpp>
#include <BelosOperatorTraits.hpp>
#include <BelosStatusTest.hpp>

#include <algorithm>
#include <ostream>
#include <vector>

namespace tfeti {

namespace detail {
template <class S, class MV, class OP>
typename Teuchos::ScalarTraits<S>::magnitudeType projectedGradientNorm(
    Belos::Iteration<S, MV, OP>* it) {
  std::vector<typename Teuchos::ScalarTraits<S>::magnitudeType> norms(1);
  it->getNativeResiduals(&norms);
  return norms[0];
}
}  // namespace detail

// Passed when ||g^P|| <= tolerance (absolute).
template <class S, class MV, class OP>
class StatusTestProjectedGradient : public Belos::StatusTest<S, MV, OP> {
 public:
  using magnitude_type = typename Teuchos::ScalarTraits<S>::magnitudeType;

  explicit StatusTestProjectedGradient(magnitude_type tolerance = 0) : tol_(tolerance) {}

  void setTolerance(magnitude_type tolerance) { tol_ = tolerance; }
  // tolerance = relative * ||b||; the scale used when ||b|| = 0 is the caller's choice.
  void setRelativeTolerance(magnitude_type relative, magnitude_type rhsNorm) {
    tol_ = relative * rhsNorm;
  }
  magnitude_type getTolerance() const { return tol_; }
  magnitude_type getProjectedGradientNorm() const { return gp_; }

  Belos::StatusType checkStatus(Belos::Iteration<S, MV, OP>* it) override {
    gp_ = detail::projectedGradientNorm(it);
    status_ = gp_ <= tol_ ? Belos::Passed : Belos::Failed;
    return status_;
  }
  Belos::StatusType getStatus() const override { return status_; }
  void reset() override {
    status_ = Belos::Undefined;
    gp_ = 0;
  }
  void print(std::ostream& os, int indent = 0) const override {
    os << std::string(indent, ' ');
    this->printStatus(os, status_);
    os << "||g^P|| = " << gp_ << " <= " << tol_ << "\n";
  }

 private:
  magnitude_type tol_;
  magnitude_type gp_ = 0;
  Belos::StatusType status_ = Belos::Undefined;
};

// SMALBE's inner stopping rule at the current iterate x (Q the equality projector):
//   Passed when ||g^P|| <= min(M ||Q x||, eta)                          (adaptive precision)
//           or  ||g^P|| <= gradientTol and ||Q x|| <= equalityTol       (SMALBE's final test).
// The iterate is read from the iteration's problem (getProblem().getLHS()) and Q is applied to
// it at every check; those applications are counted separately from the Hessian's.
template <class S, class MV, class OP>
class StatusTestSmalbeInner : public Belos::StatusTest<S, MV, OP> {
 public:
  using magnitude_type = typename Teuchos::ScalarTraits<S>::magnitudeType;

  StatusTestSmalbeInner(Teuchos::RCP<const OP> Q, magnitude_type M, magnitude_type eta,
                        magnitude_type gradientTol, magnitude_type equalityTol)
      : Q_(std::move(Q)), M_(M), eta_(eta), gTol_(gradientTol), eTol_(equalityTol) {}

  void setM(magnitude_type M) { M_ = M; }
  magnitude_type getM() const { return M_; }
  // ||g^P|| and ||Q x|| of the last check.
  magnitude_type getProjectedGradientNorm() const { return gp_; }
  magnitude_type getEqualityResidualNorm() const { return qx_; }
  // True when the last check met SMALBE's final test (not only the adaptive precision).
  bool finalTestMet() const { return final_; }
  long long projectorApplications() const { return qApplies_; }

  Belos::StatusType checkStatus(Belos::Iteration<S, MV, OP>* it) override {
    using MVT = Belos::MultiVecTraits<S, MV>;
    gp_ = detail::projectedGradientNorm(it);
    Teuchos::RCP<const MV> x = it->getProblem().getLHS();
    if (work_.is_null()) work_ = MVT::Clone(*x, 1);
    Belos::OperatorTraits<S, MV, OP>::Apply(*Q_, *x, *work_);
    ++qApplies_;
    std::vector<magnitude_type> n(1);
    MVT::MvNorm(*work_, n);
    qx_ = n[0];
    final_ = gp_ <= gTol_ && qx_ <= eTol_;
    status_ = (gp_ <= std::min(M_ * qx_, eta_) || final_) ? Belos::Passed : Belos::Failed;
    return status_;
  }
  Belos::StatusType getStatus() const override { return status_; }
  void reset() override {
    status_ = Belos::Undefined;
    final_ = false;
  }
  void print(std::ostream& os, int indent = 0) const override {
    os << std::string(indent, ' ');
    this->printStatus(os, status_);
    os << "||g^P|| = " << gp_ << " <= min(M ||Qx|| = " << M_ * qx_ << ", eta = " << eta_
       << ") or (||g^P|| <= " << gTol_ << " and ||Qx|| = " << qx_ << " <= " << eTol_ << ")\n";
  }

 private:
  Teuchos::RCP<const OP> Q_;
  magnitude_type M_, eta_, gTol_, eTol_;
  magnitude_type gp_ = 0, qx_ = 0;
  bool final_ = false;
  long long qApplies_ = 0;
  Teuchos::RCP<MV> work_;
  Belos::StatusType status_ = Belos::Undefined;
};

}  // namespace tfeti
