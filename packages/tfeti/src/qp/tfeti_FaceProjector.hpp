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
//
// Discs (3D friction, tfeti_SeparableSet.hpp): a disc on its circle is a row n0 e_i + n1 e_{i+1}
// of E_A (its outward normal at the face's entry point), so that the face holds n . (x - c) = r
// and leaves the tangent free. Rows are the unit rows first, then the circles; they have unit
// norm and disjoint supports, so E_A E_A^T = I still and S = I - E_A Q E_A^T as above.
//
// With Q's factors Q = G^T (G G^T)^{-1} G (tfeti_ComplementFactors.hpp) one application of P_F
// costs one of Q: with a = (G G^T)^{-1} G x and s = S^{-1} E_A (x - G^T a),
//   P_F x = x - E_A^T s - G^T (a - (G G^T)^{-1} (G E_A^T) s),
// where G E_A^T s and (G^T a) at the rows come from G's columns at the rows.
#include <BelosMultiVecTraits.hpp>
#include <BelosOperatorTraits.hpp>
#include <Teuchos_BLAS.hpp>
#include <Teuchos_LAPACK.hpp>
#include <Teuchos_RCP.hpp>

#include <algorithm>
#include <vector>

#include "tfeti_BoundTraits.hpp"
#include "tfeti_ComplementFactors.hpp"
#include "tfeti_FaceGramian.hpp"

namespace tfeti {

// A circle row of a face: the disc's first component and its unit normal.
template <class S>
struct FaceCircle {
  long long index;
  S n0, n1;
};

template <class S, class MV, class OP>
class FaceProjector {
 public:
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;
  using BT = BoundTraits<S, MV>;

  // active: sorted global indices (BoundTraits::activeIndices); like: a vector on the map.
  // gramian (optional): the columns of Q shared by the faces of one solve; factors (optional):
  // Q's factors, for one application of Q per application of P_F. The result is the same, to
  // rounding, with or without either.
  FaceProjector(Teuchos::RCP<const OP> Q, std::vector<long long> active, const MV& like,
                FaceGramian<S, MV, OP>* gramian = nullptr, std::vector<FaceCircle<S>> circles = {},
                const ComplementFactors<S, MV>* factors = nullptr)
      : Q_(std::move(Q)),
        active_(std::move(active)),
        circles_(std::move(circles)),
        m_(static_cast<int>(active_.size() + circles_.size())),
        factors_(factors) {
    t1_ = MVT::Clone(like, 1);
    t2_ = MVT::Clone(like, 1);
    // The components the rows touch: the unit rows', then both of each circle's.
    idx_ = active_;
    for (const auto& c : circles_) idx_.push_back(c.index), idx_.push_back(c.index + 1);
    if (factors_ != nullptr) gColumns_ = factors_->columns(idx_);
    coarseSide_ = factors_ != nullptr && factors_->rows() > 0 &&
                  factors_->rows() <= kCoarseSideMaxRows && m_ > factors_->rows();
    if (coarseSide_)
      buildCoarseSide();
    else
      buildSchurComplement(gramian);
  }

  bool valid() const { return valid_; }
  // More rows than Q's factors have: P_F from G G^T instead of S (below).
  bool coarseSide() const { return coarseSide_; }
  // The unit rows (sorted global indices) and the circles; rows are numbered in this order.
  const std::vector<long long>& active() const { return active_; }
  const std::vector<FaceCircle<S>>& circles() const { return circles_; }
  int rows() const { return m_; }

  // The rows' values of v: v_i on a unit row, n . (v_i, v_{i+1}) on a circle (collective).
  std::vector<S> gatherRows(const MV& v) const { return combine(BT::gatherAt(v, idx_)); }
  // v += alpha E_A^T s.
  void addRows(const std::vector<S>& s, S alpha, MV& v) const {
    BT::addAt(idx_, expandRows(s), alpha, v);
  }
  long long projectorApplications() const { return qApplies_; }

  // sigma = S^{-1} E_A P g: the active rows' multipliers, with which
  // g = P_F g + E_A^T sigma + (a part in range(Q)).
  std::vector<S> activeMultipliers(const MV& g) const {
    if (coarseSide_) {
      std::vector<S> a;
      return coarseSideRows(g, a);
    }
    if (factors_ != nullptr) {
      std::vector<S> a;
      return projectedRows(g, a);
    }
    applyP(g, *t1_);
    std::vector<S> s = gatherRows(*t1_);
    solveS(s);
    return s;
  }

  // y = P_F x (y may be x).
  void apply(const MV& x, MV& y) const {
    if (coarseSide_) {
      std::vector<S> a;
      const std::vector<S> sigma = coarseSideRows(x, a);
      subtractRowsAndTranspose(x, a, sigma, y);
      return;
    }
    if (factors_ != nullptr) {
      std::vector<S> a;
      const std::vector<S> s = projectedRows(x, a);
      subtractRowsAndRange(x, a, s, y);
      return;
    }
    applyP(x, *t1_);
    std::vector<S> s = gatherRows(*t1_);
    solveS(s);
    // P_F x = P x - P E_A^T s
    MVT::MvInit(*t2_, S(0));
    addRows(s, S(1), *t2_);
    MVT::Assign(*t1_, y);
    applyP(*t2_, *t1_);
    MVT::MvAddMv(S(1), y, S(-1), *t1_, y);
  }

  // The point of {Q x = 0, E_A x = r} nearest to x: P_F x + P E_A^T S^{-1} r.
  void projectAffine(const std::vector<S>& r, MV& x) const {
    if (coarseSide_) {
      // P_F x + E_A^T r - Pi G^T b with b = H^{-1} G E_A^T r (the least-norm step onto the
      // rows): P_F x's formula with a + b for a and sigma - r - (G E_A^T)^T b for sigma.
      std::vector<S> a;
      std::vector<S> sigma = coarseSideRows(x, a);
      std::vector<S> b = rowsToCoarse(r);
      solveH(b);
      const std::vector<S> cb = coarseToRows(b);
      for (std::size_t k = 0; k < sigma.size(); ++k) sigma[k] -= r[k] + cb[k];
      for (std::size_t k = 0; k < a.size(); ++k) a[k] += b[k];
      subtractRowsAndTranspose(x, a, sigma, x);
      return;
    }
    if (factors_ != nullptr) {
      // P_F x + P E_A^T t, t = S^{-1} r: P_F x's formula with s - t for s.
      std::vector<S> a, t = r;
      std::vector<S> s = projectedRows(x, a);
      solveS(t);
      for (std::size_t k = 0; k < s.size(); ++k) s[k] -= t[k];
      subtractRowsAndRange(x, a, s, x);
      return;
    }
    apply(x, x);
    std::vector<S> s = r;
    solveS(s);
    MVT::MvInit(*t2_, S(0));
    addRows(s, S(1), *t2_);
    applyP(*t2_, *t1_);
    MVT::MvAddMv(S(1), x, S(1), *t1_, x);
  }

 private:
  static constexpr double kMinPivot = 1e-10;
  // The coarse side (below) holds dense matrices of G's rows squared: used up to
  // kDenseGramianMaxRows rows, where its factorization (rows^3 / 3 flops per face) is cheap
  // next to S's (|A|^3 / 3).
  static constexpr int kCoarseSideMaxRows = kDenseGramianMaxRows;
  Teuchos::RCP<const OP> Q_;
  std::vector<long long> active_;
  std::vector<FaceCircle<S>> circles_;
  int m_;
  const ComplementFactors<S, MV>* factors_;
  std::vector<std::vector<std::pair<int, S>>> gColumns_;  // G's column at each of idx_
  std::vector<long long> idx_;  // the unit rows, then each circle's two components
  // The coarse side: more face rows than G has (FETI: large contact zones on few subdomains).
  // With Pi = I - E_A^T E_A (E_A's rows are orthonormal), the face is range(Pi) and ker G,
  //   P_F = Pi - Pi G^T H^{-1} G Pi,   H = G Pi G^T = G G^T - C C^T,   C = G E_A^T,
  // and H (rows of G squared) takes the place of S (|A| squared). With r = E_A x,
  // a = H^{-1} (G x - C r) and sigma = r - C^T a: P_F x = x - E_A^T sigma - G^T a, and sigma
  // is S^{-1} E_A P x, the rows' multipliers. H is factorized as L T L^T, G G^T = L L^T and
  // T = I - L^{-1} C C^T L^{-T}, whose spectrum is S's but for eigenvalues 1: its pivots
  // judge the face as S's do.
  bool coarseSide_ = false;
  const std::vector<S>* gramL_ = nullptr;  // Cholesky factor of G G^T (the factors' own)
  std::vector<S> gramT_;                   // Cholesky factor of T (column-major, lower)
  std::vector<S> L_;                       // Cholesky factor of S, column-major, lower triangle
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
  // Row values from the values at idx_.
  std::vector<S> combine(const std::vector<S>& atIdx) const {
    std::vector<S> r(atIdx.begin(), atIdx.begin() + active_.size());
    for (std::size_t k = 0; k < circles_.size(); ++k) {
      const std::size_t i = active_.size() + 2 * k;
      r.push_back(circles_[k].n0 * atIdx[i] + circles_[k].n1 * atIdx[i + 1]);
    }
    return r;
  }
  // S = I - E_A Q E_A^T and its Cholesky factor; valid_ unless a pivot is below kMinPivot.
  void buildSchurComplement(FaceGramian<S, MV, OP>* gramian) {
    std::vector<long long> sorted = idx_;
    std::sort(sorted.begin(), sorted.end());
    // Column by column (each a Q c_j gathered on the rows).
    L_.assign(static_cast<std::size_t>(m_) * m_, S(0));
    if (gramian != nullptr && gramian->covers(sorted)) {
      std::vector<std::size_t> at(idx_.size());
      for (std::size_t i = 0; i < idx_.size(); ++i) at[i] = gramian->position(idx_[i]);
      // E_C Q c_j over the candidates C: a column of the gramian, or two combined (a circle).
      gramian->prefetch(idx_);
      std::vector<S> qc;
      for (int j = 0; j < m_; ++j) {
        if (j < static_cast<int>(active_.size())) {
          qc = gramian->column(active_[j]);
        } else {
          const auto& c = circles_[j - active_.size()];
          qc = gramian->column(c.index);
          const std::vector<S>& second = gramian->column(c.index + 1);
          for (std::size_t i = 0; i < qc.size(); ++i) qc[i] = c.n0 * qc[i] + c.n1 * second[i];
        }
        std::vector<S> atRows(idx_.size());
        for (std::size_t i = 0; i < idx_.size(); ++i) atRows[i] = qc[at[i]];
        const std::vector<S> col = combine(atRows);
        for (int i = 0; i < m_; ++i) L_[j * m_ + i] = (i == j ? S(1) : S(0)) - col[i];
      }
    } else {
      for (int j = 0; j < m_; ++j) {
        MVT::MvInit(*t1_, S(0));
        std::vector<S> e(m_, S(0));
        e[j] = S(1);
        addRows(e, S(1), *t1_);
        applyQ(*t1_, *t2_);
        const std::vector<S> col = gatherRows(*t2_);
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
  // H = L T L^T (class comment): T from C C^T and the factor L of G G^T (one per solve, from
  // the factors); valid_ unless a pivot of T is below kMinPivot.
  void buildCoarseSide() {
    const int n = factors_->rows();
    gramL_ = &factors_->gramianFactor();
    gramT_.assign(static_cast<std::size_t>(n) * n, S(0));
    for (int k = 0; k < m_; ++k) {
      const std::vector<std::pair<int, S>> c = rowColumn(k);
      for (const auto& ei : c)
        for (const auto& ej : c) gramT_[ej.first * n + ei.first] += ei.second * ej.second;
    }
    // T = I - L^{-1} (C C^T) L^{-T}, symmetrized against rounding.
    Teuchos::BLAS<int, S> blas;
    blas.TRSM(Teuchos::LEFT_SIDE, Teuchos::LOWER_TRI, Teuchos::NO_TRANS, Teuchos::NON_UNIT_DIAG, n,
              n, S(1), gramL_->data(), n, gramT_.data(), n);
    blas.TRSM(Teuchos::RIGHT_SIDE, Teuchos::LOWER_TRI, Teuchos::TRANS, Teuchos::NON_UNIT_DIAG, n, n,
              S(1), gramL_->data(), n, gramT_.data(), n);
    for (int j = 0; j < n; ++j)
      for (int i = j; i < n; ++i) {
        const S t = (i == j ? S(1) : S(0)) - S(0.5) * (gramT_[j * n + i] + gramT_[i * n + j]);
        gramT_[j * n + i] = gramT_[i * n + j] = t;
      }
    int info = 0;
    Teuchos::LAPACK<int, S>().POTRF('L', n, gramT_.data(), n, &info);
    valid_ = info == 0;
    for (int j = 0; valid_ && j < n; ++j)
      if (!(gramT_[j * n + j] * gramT_[j * n + j] > kMinPivot)) valid_ = false;
  }
  // G's column of face row k (a unit row's, or a circle's two combined), sorted by G's row.
  std::vector<std::pair<int, S>> rowColumn(int k) const {
    if (k < static_cast<int>(active_.size())) return gColumns_[k];
    const std::size_t i = active_.size() + 2 * (k - active_.size());
    const auto& c = circles_[k - active_.size()];
    std::vector<std::pair<int, S>> out;
    for (const auto& e : gColumns_[i]) out.emplace_back(e.first, c.n0 * e.second);
    for (const auto& e : gColumns_[i + 1]) out.emplace_back(e.first, c.n1 * e.second);
    return out;
  }
  // C r = G E_A^T r (G's rows), and G^T a at idx_ (E_A G^T a = combine of it).
  std::vector<S> rowsToCoarse(const std::vector<S>& r) const {
    std::vector<S> c(static_cast<std::size_t>(factors_->rows()), S(0));
    const std::vector<S> v = expandRows(r);
    for (std::size_t i = 0; i < idx_.size(); ++i)
      for (const auto& e : gColumns_[i]) c[e.first] += e.second * v[i];
    return c;
  }
  std::vector<S> transposeAtIdx(const std::vector<S>& a) const {
    std::vector<S> at(idx_.size(), S(0));
    for (std::size_t i = 0; i < idx_.size(); ++i)
      for (const auto& e : gColumns_[i]) at[i] += e.second * a[e.first];
    return at;
  }
  std::vector<S> coarseToRows(const std::vector<S>& a) const { return combine(transposeAtIdx(a)); }
  // b = H^{-1} b = L^{-T} T^{-1} L^{-1} b.
  void solveH(std::vector<S>& b) const {
    const int n = factors_->rows();
    Teuchos::BLAS<int, S> blas;
    blas.TRSM(Teuchos::LEFT_SIDE, Teuchos::LOWER_TRI, Teuchos::NO_TRANS, Teuchos::NON_UNIT_DIAG, n,
              1, S(1), gramL_->data(), n, b.data(), n);
    int info = 0;
    Teuchos::LAPACK<int, S>().POTRS('L', n, 1, gramT_.data(), n, b.data(), n, &info);
    blas.TRSM(Teuchos::LEFT_SIDE, Teuchos::LOWER_TRI, Teuchos::TRANS, Teuchos::NON_UNIT_DIAG, n, 1,
              S(1), gramL_->data(), n, b.data(), n);
  }
  // The coarse side's sigma = S^{-1} E_A P x and a = H^{-1} G Pi x (one pass over G).
  std::vector<S> coarseSideRows(const MV& x, std::vector<S>& a) const {
    const std::vector<S> r = gatherRows(x);
    factors_->applyG(x, a);
    ++qApplies_;
    const std::vector<S> cr = rowsToCoarse(r);
    for (std::size_t k = 0; k < a.size(); ++k) a[k] -= cr[k];
    solveH(a);
    std::vector<S> sigma = coarseToRows(a);
    for (std::size_t k = 0; k < sigma.size(); ++k) sigma[k] = r[k] - sigma[k];
    return sigma;
  }
  // y = x - E_A^T sigma - G^T a (one pass over G^T; y may be x).
  void subtractRowsAndTranspose(const MV& x, const std::vector<S>& a, const std::vector<S>& sigma,
                                MV& y) const {
    if (&x != &y) MVT::Assign(x, y);
    addRows(sigma, S(-1), y);
    factors_->addTranspose(a, S(-1), y);
  }
  // With factors: s = S^{-1} E_A P x, and a = (G G^T)^{-1} G x (one pass over G).
  std::vector<S> projectedRows(const MV& x, std::vector<S>& a) const {
    factors_->coefficients(x, a);
    ++qApplies_;
    std::vector<S> at = BT::gatherAt(x, idx_);
    const std::vector<S> qx = transposeAtIdx(a);
    for (std::size_t i = 0; i < idx_.size(); ++i) at[i] -= qx[i];
    std::vector<S> s = combine(at);
    solveS(s);
    return s;
  }
  // y = x - E_A^T s - G^T (a - (G G^T)^{-1} G E_A^T s) (one pass over G^T; y may be x).
  void subtractRowsAndRange(const MV& x, std::vector<S> a, const std::vector<S>& s, MV& y) const {
    std::vector<S> c = rowsToCoarse(s);
    factors_->solve(c);
    for (std::size_t k = 0; k < a.size(); ++k) a[k] -= c[k];
    if (&x != &y) MVT::Assign(x, y);
    addRows(s, S(-1), y);
    factors_->addTranspose(a, S(-1), y);
  }
  // E_A^T s at idx_.
  std::vector<S> expandRows(const std::vector<S>& s) const {
    std::vector<S> values(s.begin(), s.begin() + active_.size());
    for (std::size_t k = 0; k < circles_.size(); ++k) {
      const S sk = s[active_.size() + k];
      values.push_back(circles_[k].n0 * sk);
      values.push_back(circles_[k].n1 * sk);
    }
    return values;
  }
  void solveS(std::vector<S>& s) const {
    if (m_ == 0) return;
    int info = 0;
    Teuchos::LAPACK<int, S>().POTRS('L', m_, 1, L_.data(), m_, s.data(), m_, &info);
  }
};

}  // namespace tfeti
