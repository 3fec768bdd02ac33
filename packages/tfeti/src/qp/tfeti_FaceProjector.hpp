#pragma once
// The orthogonal projector onto a face of SMALBE's feasible set (docs/qp_solvers.md, "Face
// solve"): with Q the orthogonal projector onto the range of the equality rows (P = I - Q) and
// E_A the rows selecting the active components A (held at their bounds),
//   P_F = P - P E_A^T S^{-1} E_A P,   S = E_A P E_A^T = I - E_A Q E_A^T   (|A| x |A|),
// projects onto {x : Q x = 0, x_A = 0}. This is the constraint [G; E_A] handled through the
// existing projector Q plus a small dense Schur complement: S is built from |A| applications of
// Q to unit vectors, factorized by dense Cholesky and replicated on every rank (|A| is the
// number of active contact rows, a few hundred at most; a FaceGramian shares the applications
// among the faces of one solve). One application of P_F costs two of Q.
// S is singular when a combination of active unit vectors lies in range(Q) (the active rows
// together with the equality rows are dependent); valid() is false then and the face is not used.
#include <BelosMultiVecTraits.hpp>
#include <BelosOperatorTraits.hpp>
#include <Teuchos_LAPACK.hpp>
#include <Teuchos_RCP.hpp>

#include <vector>

#include "tfeti_BoundTraits.hpp"
#include "tfeti_FaceGramian.hpp"

namespace tfeti {

template <class S, class MV, class OP>
class FaceProjector {
 public:
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;
  using BT = BoundTraits<S, MV>;

  // active: sorted global indices (BoundTraits::activeIndices); like: a vector on the map.
  // gramian (optional): the columns of Q shared by the faces of one solve; the result is the same
  // with or without it.
  FaceProjector(Teuchos::RCP<const OP> Q, std::vector<long long> active, const MV& like,
                FaceGramian<S, MV, OP>* gramian = nullptr)
      : Q_(std::move(Q)), active_(std::move(active)), m_(static_cast<int>(active_.size())) {
    t1_ = MVT::Clone(like, 1);
    t2_ = MVT::Clone(like, 1);
    // S = I - E_A Q E_A^T, column by column (each a Q e_j gathered on the active rows).
    L_.assign(static_cast<std::size_t>(m_) * m_, S(0));
    if (gramian != nullptr && gramian->covers(active_)) {
      std::vector<std::size_t> at(active_.size());
      for (int i = 0; i < m_; ++i) at[i] = gramian->position(active_[i]);
      for (int j = 0; j < m_; ++j) {
        const std::vector<S>& col = gramian->column(active_[j]);
        for (int i = 0; i < m_; ++i) L_[j * m_ + i] = (i == j ? S(1) : S(0)) - col[at[i]];
      }
    } else {
      const std::vector<S> one{S(1)};
      for (int j = 0; j < m_; ++j) {
        MVT::MvInit(*t1_, S(0));
        BT::addAt({active_[j]}, one, S(1), *t1_);
        applyQ(*t1_, *t2_);
        const std::vector<S> col = BT::gatherAt(*t2_, active_);
        for (int i = 0; i < m_; ++i) L_[j * m_ + i] = (i == j ? S(1) : S(0)) - col[i];
      }
    }
    // Symmetrize against rounding, so that Cholesky sees the same matrix on every rank count.
    for (int j = 0; j < m_; ++j)
      for (int i = j + 1; i < m_; ++i) {
        const S s = S(0.5) * (L_[j * m_ + i] + L_[i * m_ + j]);
        L_[j * m_ + i] = L_[i * m_ + j] = s;
      }
    // The eigenvalues of S lie in [0, 1]; a pivot below kMinPivot means the active rows are
    // (nearly) dependent on the equality rows.
    int info = 0;
    if (m_ > 0) Teuchos::LAPACK<int, S>().POTRF('L', m_, L_.data(), m_, &info);
    valid_ = info == 0;
    for (int j = 0; valid_ && j < m_; ++j)
      if (!(L_[j * m_ + j] * L_[j * m_ + j] > kMinPivot)) valid_ = false;
  }

  bool valid() const { return valid_; }
  const std::vector<long long>& active() const { return active_; }
  long long projectorApplications() const { return qApplies_; }

  // sigma = S^{-1} E_A P g: the active rows' multipliers, with which
  // g = P_F g + E_A^T sigma + (a part in range(Q)).
  std::vector<S> activeMultipliers(const MV& g) const {
    applyP(g, *t1_);
    std::vector<S> s = BT::gatherAt(*t1_, active_);
    solveS(s);
    return s;
  }

  // y = P_F x (y may be x).
  void apply(const MV& x, MV& y) const {
    applyP(x, *t1_);
    std::vector<S> s = BT::gatherAt(*t1_, active_);
    solveS(s);
    // P_F x = P x - P E_A^T s
    MVT::MvInit(*t2_, S(0));
    BT::addAt(active_, s, S(1), *t2_);
    MVT::Assign(*t1_, y);
    applyP(*t2_, *t1_);
    MVT::MvAddMv(S(1), y, S(-1), *t1_, y);
  }

  // The point of {Q x = 0, x_A = r} nearest to x: P_F x + P E_A^T S^{-1} r.
  void projectAffine(const std::vector<S>& r, MV& x) const {
    apply(x, x);
    std::vector<S> s = r;
    solveS(s);
    MVT::MvInit(*t2_, S(0));
    BT::addAt(active_, s, S(1), *t2_);
    applyP(*t2_, *t1_);
    MVT::MvAddMv(S(1), x, S(1), *t1_, x);
  }

 private:
  static constexpr double kMinPivot = 1e-10;
  Teuchos::RCP<const OP> Q_;
  std::vector<long long> active_;
  int m_;
  std::vector<S> L_;  // Cholesky factor of S, column-major, lower triangle
  bool valid_ = false;
  Teuchos::RCP<MV> t1_, t2_;
  mutable long long qApplies_ = 0;

  void applyQ(const MV& x, MV& y) const {
    OPT::Apply(*Q_, x, y);
    ++qApplies_;
  }
  // y = x - Q x (y distinct from x)
  void applyP(const MV& x, MV& y) const {
    applyQ(x, y);
    MVT::MvAddMv(S(1), x, S(-1), y, y);
  }
  void solveS(std::vector<S>& s) const {
    if (m_ == 0) return;
    int info = 0;
    Teuchos::LAPACK<int, S>().POTRS('L', m_, 1, L_.data(), m_, s.data(), m_, &info);
  }
};

}  // namespace tfeti
