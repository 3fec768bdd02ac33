#pragma once
// EqualityConstraints: a user's equality constraints C x = d turned into what SmalbeSolMgr takes.
// SMALBE solves  min 1/2 x^T A x - b^T x  s.t.  x >= l,  Q x = 0  with Q an orthogonal projector.
// For C x = d write x = x0 + y with the lifting x0 = C^T (C C^T)^+ d (the least-norm solution,
// C x0 = d) and Q = C^T (C C^T)^+ C, the orthogonal projector onto range(C^T) = (ker C)^perp:
// then C x = d  <=>  Q y = 0, and the problem in y is
//   min 1/2 y^T A y - (b - A x0)^T y  s.t.  y >= l - x0,  Q y = 0   (shift()),
// whose solution gives x = x0 + y (recover()). SMALBE's multiplier mu (in range(Q) = range(C^T))
// is then that of the original problem: A x - b + mu = the bounds' multipliers.
//
// C is given by its rows as the columns of a MultiVector on the map of x (C^T; m small: the
// m x m Gram matrix C C^T is formed and decomposed on every rank). Dependent rows are allowed
// when consistent (the rank is that of C C^T, eigenvalues below rankTolerance times the largest
// dropped); an inconsistent d, a zero C, or d of the wrong length is std::invalid_argument.
#include <vector>

#include "tfeti_QpProblem.hpp"
#include "tfeti_Types.hpp"

namespace tfeti {

class EqualityConstraints {
 public:
  using Qp = BoundConstrainedQp<Scalar, MultiVector, Operator>;

  // rowsOfC: column k is row k of C; d: the m right-hand sides, the same on every rank.
  EqualityConstraints(Teuchos::RCP<const MultiVector> rowsOfC, std::vector<double> d,
                      double rankTolerance = 1e-12);

  // x0 with C x0 = d (least norm).
  Teuchos::RCP<const Vector> lifting() const { return x0_; }
  // Q, the orthogonal projector onto range(C^T) (SmalbeSolMgr's Q).
  Teuchos::RCP<const Operator> projector() const { return Q_; }
  // The number of independent rows.
  int rank() const { return rank_; }

  // The problem in y = x - x0 (new b, lower, upper if any, and x; the initial guess shifted; A
  // shared).
  Qp shift(const Qp& qp) const;
  // x = y + x0.
  void recover(const MultiVector& y, MultiVector& x) const;
  // max_k |(C x - d)_k| (every rank).
  double residual(const MultiVector& x) const;

 private:
  Teuchos::RCP<const MultiVector> C_;
  std::vector<double> d_;
  Teuchos::RCP<Vector> x0_;
  Teuchos::RCP<const Operator> Q_;
  int rank_ = 0;
};

}  // namespace tfeti
