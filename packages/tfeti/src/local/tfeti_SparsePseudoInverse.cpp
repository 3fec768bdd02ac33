#include "tfeti_SparsePseudoInverse.hpp"

#include <cholmod.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "tfeti_CholmodView.hpp"

namespace tfeti {
namespace {

// AMD's fill-reducing ordering of the symmetric matrix A (its upper part is read).
std::vector<int> amdOrdering(const CsrMatrix& A) {
  std::vector<int> perm(A.rows);
  if (A.rows == 0) return perm;
  cholmod_common c;
  cholmod_start(&c);
  c.print = 0;
  c.error_handler = nullptr;
  cholmod_sparse S;
  cholmodUpperView(A, S);
  const int ok = cholmod_amd(&S, nullptr, 0, perm.data(), &c);
  cholmod_finish(&c);
  if (!ok) throw std::runtime_error("SparsePseudoInverse: AMD ordering failed");
  return perm;
}

}  // namespace

SparsePseudoInverse::SparsePseudoInverse(const CsrMatrix& A, double relTol) : n_(A.rows) {
  if (A.rows != A.cols)
    throw std::invalid_argument("SparsePseudoInverse: the matrix is " + std::to_string(A.rows) +
                                " x " + std::to_string(A.cols) + ", not square");
  const int n = n_;
  perm_ = amdOrdering(A);
  std::vector<int> pinv(n);
  for (int k = 0; k < n; ++k) pinv[perm_[k]] = k;

  // Column k of the upper part of C = A(perm, perm): entries C(i, k), i <= k.
  auto forUpper = [&](int k, auto&& f) {
    const int row = perm_[k];
    for (int p = A.rowPtr[row]; p < A.rowPtr[row + 1]; ++p) {
      const int i = pinv[A.colInd[p]];
      if (i <= k) f(i, A.values[p]);
    }
  };

  // Elimination tree and column counts of L: row k of L is the set of nodes reached from the
  // entries of C(:, k) by walking up the tree until a node already visited for k.
  std::vector<int> parent(n, -1), flag(n), count(n, 0);
  for (int k = 0; k < n; ++k) {
    flag[k] = k;
    forUpper(k, [&](int i, double) {
      for (; flag[i] != k; i = parent[i]) {
        if (parent[i] < 0) parent[i] = k;
        ++count[i];
        flag[i] = k;
      }
    });
  }
  Lp_.assign(n + 1, 0);
  for (int k = 0; k < n; ++k) Lp_[k + 1] = Lp_[k] + count[k];
  Li_.assign(Lp_[n], 0);
  Lx_.assign(Lp_[n], 0.0);
  Dinv_.assign(n, 0.0);

  // Numerical factorization, row by row: row k of L solves L(0:k-1, 0:k-1) D y = C(0:k-1, k)
  // over the pattern found by the tree walks, in topological order.
  std::vector<double> y(n, 0.0);
  std::vector<int> filled(n, 0), pattern(n), stack(n);
  std::vector<int> droppedPivots;
  for (int k = 0; k < n; ++k) {
    int top = n;
    flag[k] = k;
    double diag = 0.0;
    forUpper(k, [&](int i, double v) {
      y[i] += v;
      if (i == k) diag += v;
      int len = 0;
      for (; flag[i] != k; i = parent[i]) {
        stack[len++] = i;
        flag[i] = k;
      }
      while (len > 0) pattern[--top] = stack[--len];
    });
    double d = y[k];
    y[k] = 0.0;
    for (; top < n; ++top) {
      const int i = pattern[top];
      const double yi = y[i];
      y[i] = 0.0;
      const int end = Lp_[i] + filled[i];
      for (int p = Lp_[i]; p < end; ++p) y[Li_[p]] -= Lx_[p] * yi;
      // A dropped pivot's column is zero (its y_i is rounding of an exact zero).
      const double lki = yi * Dinv_[i];
      d -= lki * yi;
      Li_[end] = k;
      Lx_[end] = lki;
      ++filled[i];
    }
    if (d > relTol * diag && diag > 0.0)
      Dinv_[k] = 1.0 / d;
    else
      droppedPivots.push_back(k);
  }

  // Kernel basis n_k = L^-T e_k (back substitution from k down; entries above k only).
  std::vector<double> z(n);
  for (int k : droppedPivots) {
    std::fill(z.begin(), z.end(), 0.0);
    z[k] = 1.0;
    for (int j = k - 1; j >= 0; --j) {
      double s = 0.0;
      for (int p = Lp_[j]; p < Lp_[j + 1]; ++p) s += Lx_[p] * z[Li_[p]];
      z[j] = -s;
    }
    for (int j = 0; j <= k; ++j)
      if (z[j] != 0.0) {
        nullIdx_.push_back(perm_[j]);
        nullVal_.push_back(z[j]);
      }
    nullPtr_.push_back(static_cast<int>(nullIdx_.size()));
  }
  // N^T N is at least the identity on the dropped pivots (n_k(j) = delta_kj there): Cholesky.
  const int m = nullity();
  if (m > 0) {
    std::vector<double> dense(n, 0.0);
    gramChol_.assign(static_cast<std::size_t>(m) * m, 0.0);
    for (int a = 0; a < m; ++a) {
      for (int p = nullPtr_[a]; p < nullPtr_[a + 1]; ++p) dense[nullIdx_[p]] = nullVal_[p];
      for (int b = 0; b <= a; ++b) {
        double s = 0.0;
        for (int p = nullPtr_[b]; p < nullPtr_[b + 1]; ++p) s += nullVal_[p] * dense[nullIdx_[p]];
        gramChol_[a * m + b] = s;
      }
      for (int p = nullPtr_[a]; p < nullPtr_[a + 1]; ++p) dense[nullIdx_[p]] = 0.0;
    }
    // In place: the lower triangle (row a, column b <= a) becomes the Cholesky factor.
    for (int j = 0; j < m; ++j) {
      double djj = gramChol_[j * m + j];
      for (int q = 0; q < j; ++q) djj -= gramChol_[j * m + q] * gramChol_[j * m + q];
      if (!(djj > 0.0))
        throw std::runtime_error("SparsePseudoInverse: the kernel basis is not independent");
      gramChol_[j * m + j] = std::sqrt(djj);
      for (int i = j + 1; i < m; ++i) {
        double s = gramChol_[i * m + j];
        for (int q = 0; q < j; ++q) s -= gramChol_[i * m + q] * gramChol_[j * m + q];
        gramChol_[i * m + j] = s / gramChol_[j * m + j];
      }
    }
  }
}

void SparsePseudoInverse::solveFactor(std::vector<double>& z) const {
  for (int j = 0; j < n_; ++j)
    for (int p = Lp_[j]; p < Lp_[j + 1]; ++p) z[Li_[p]] -= Lx_[p] * z[j];
  for (int j = 0; j < n_; ++j) z[j] *= Dinv_[j];
  for (int j = n_ - 1; j >= 0; --j) {
    double s = z[j];
    for (int p = Lp_[j]; p < Lp_[j + 1]; ++p) s -= Lx_[p] * z[Li_[p]];
    z[j] = s;
  }
}

void SparsePseudoInverse::project(std::vector<double>& v) const {
  const int m = nullity();
  if (m == 0) return;
  // c = (N^T N)^-1 N^T v by the two triangular solves with the Cholesky factor; v -= N c.
  std::vector<double> c(m);
  for (int a = 0; a < m; ++a) {
    double s = 0.0;
    for (int p = nullPtr_[a]; p < nullPtr_[a + 1]; ++p) s += nullVal_[p] * v[nullIdx_[p]];
    for (int q = 0; q < a; ++q) s -= gramChol_[a * m + q] * c[q];
    c[a] = s / gramChol_[a * m + a];
  }
  for (int a = m - 1; a >= 0; --a) {
    double s = c[a];
    for (int q = a + 1; q < m; ++q) s -= gramChol_[q * m + a] * c[q];
    c[a] = s / gramChol_[a * m + a];
  }
  for (int a = 0; a < m; ++a)
    for (int p = nullPtr_[a]; p < nullPtr_[a + 1]; ++p) v[nullIdx_[p]] -= nullVal_[p] * c[a];
}

void SparsePseudoInverse::apply(const double* x, double* y) const {
  std::vector<double> v(x, x + n_), z(n_);
  project(v);
  for (int k = 0; k < n_; ++k) z[k] = v[perm_[k]];
  solveFactor(z);
  for (int k = 0; k < n_; ++k) v[perm_[k]] = z[k];
  project(v);
  std::copy(v.begin(), v.end(), y);
}

}  // namespace tfeti
