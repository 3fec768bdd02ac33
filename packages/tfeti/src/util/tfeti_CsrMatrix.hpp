#pragma once
// A serial sparse matrix in compressed sparse row form: the storage of one subdomain's
// stiffness matrix. Subdomain matrices live on one rank and are factorized there, so they
// need no Tpetra map; the local solvers read these arrays directly.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tfeti {

struct CsrMatrix {
  int rows = 0;
  int cols = 0;
  std::vector<int> rowPtr;  // size rows + 1
  std::vector<int> colInd;  // sorted within each row
  std::vector<double> values;

  std::size_t nnz() const { return colInd.size(); }
  // The bytes of its arrays (values, column indices, row offsets): what freeing it returns.
  std::size_t bytes() const {
    return values.size() * sizeof(double) + colInd.size() * sizeof(int) +
           rowPtr.size() * sizeof(int);
  }
  // Index of entry (i, j) in colInd/values, or -1 when (i, j) is not in the pattern.
  long find(int i, int j) const;
  // y = A x (y resized to rows).
  void multiply(const double* x, double* y) const;
  // Largest absolute entry.
  double maxAbs() const;
  // Frobenius norm.
  double frobeniusNorm() const;
  bool isSymmetric(double tol) const;
  // Two 64-bit digests (different seeds) of the sizes, the pattern and every value's bits. Two
  // matrices with the same digest are taken to be equal: Subdomain::refactorize keeps the factor
  // of an unchanged K by it, without holding a copy of K.
  std::array<std::uint64_t, 2> digest() const;
  // The submatrix A(rowsKept, colsKept); index lists must be sorted ascending. withValues =
  // false: its pattern alone (values empty), all a symbolic analysis reads.
  CsrMatrix submatrix(const std::vector<int>& rowsKept, const std::vector<int>& colsKept,
                      bool withValues = true) const;
};

// Builds a CSR matrix from (row, col, value) triplets, summing duplicates.
CsrMatrix csrFromTriplets(int rows, int cols, const std::vector<int>& ri,
                          const std::vector<int>& ci, const std::vector<double>& v);

// The CSR arrays of a square or rectangular matrix: rowPtr of rows + 1 non-decreasing offsets
// from 0 to nnz, column indices in range and strictly increasing within a row, finite values.
// Empty when they are consistent; otherwise what is wrong, prefixed by `what` (e.g. "K").
std::string csrError(const CsrMatrix& A, const std::string& what);

// The largest |A(i,j) - A(j,i)| relative to max |A|, where it is, as text when it exceeds tol
// (empty when A is symmetric to tol, or not square). A must pass csrError.
std::string asymmetryError(const CsrMatrix& A, const std::string& what, double tol);

}  // namespace tfeti
