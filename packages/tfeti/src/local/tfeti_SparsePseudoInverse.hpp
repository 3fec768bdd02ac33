#pragma once
// Moore-Penrose pseudo-inverse of a sparse symmetric positive semi-definite matrix A, applied
// through a factorization: the preconditioner's scaling Q = (B B^T)^+ of a scaling group too
// large for a dense pseudo-inverse (a tied or contact surface whose node-to-face rows chain
// thousands of rows into one group; docs/qp_solvers.md, "Scaling groups").
//
// Method: a fill-reducing ordering (AMD, from CHOLMOD) and an up-looking L D L^T factorization
// of the permuted A. A = B B^T is a Gram matrix, so pivot k is the squared distance of row k of B
// from the span of the rows before it: a pivot below relTol times A(k,k) marks a row dependent
// on earlier ones (a redundant gluing row, a gluing row on a Dirichlet node) and is dropped
// (D(k) = 0, column k of L = 0). That gives a reflexive generalized inverse X = L^-T D^+ L^-1
// (A X A = A, X A X = X); the pseudo-inverse is A^+ = P X P with P the orthogonal projector
// onto range(A), since A^+ A = A A^+ = P. The kernel of A is spanned by n_k = L^-T e_k over the
// dropped pivots k (A n_k = L D e_k = 0); they are kept sparse and P = I - N (N^T N)^-1 N^T.
#include <cstddef>
#include <vector>

#include "tfeti_CsrMatrix.hpp"

namespace tfeti {

class SparsePseudoInverse {
 public:
  // A: square, symmetric (full pattern), positive semi-definite.
  explicit SparsePseudoInverse(const CsrMatrix& A, double relTol = 1e-10);
  // y = A^+ x (x and y of size n; they may not alias).
  void apply(const double* x, double* y) const;
  int size() const { return n_; }
  // Dimension of the kernel found (the number of dropped pivots).
  int nullity() const { return static_cast<int>(nullPtr_.size()) - 1; }
  // Nonzeros of L (without the unit diagonal) and of the kernel basis.
  std::size_t factorNonzeros() const { return Li_.size() + nullIdx_.size(); }

 private:
  void solveFactor(std::vector<double>& z) const;  // z = X z, in the permuted numbering
  void project(std::vector<double>& v) const;      // v = P v, in the original numbering
  int n_ = 0;
  std::vector<int> perm_;  // perm_[k]: the original index of the k-th pivot
  std::vector<int> Lp_, Li_;
  std::vector<double> Lx_, Dinv_;  // Dinv_ = 0 on dropped pivots
  // Kernel basis N by columns (original numbering) and the Cholesky factor of N^T N (dense).
  std::vector<int> nullPtr_{0}, nullIdx_;
  std::vector<double> nullVal_, gramChol_;
};

}  // namespace tfeti
