#pragma once
// Small vector and matrix measures the plasticity tests share.
#include <algorithm>
#include <cmath>
#include <vector>

#include "tfeti_CsrMatrix.hpp"
#include "tfeti_DenseUtils.hpp"
#include "tfeti_LocalSolver.hpp"

namespace plasticity_test {

// K u = 0 on the free dofs, u kept on the others (prescribed values): overwrites u's free entries
// with the discrete solution (CHOLMOD on K restricted to the free dofs).
inline void solveFreeDofs(const tfeti::CsrMatrix& K, const std::vector<int>& free,
                          std::vector<double>& u) {
  std::vector<double> r(K.rows);
  K.multiply(u.data(), r.data());
  std::vector<double> rhs(free.size()), x(free.size());
  for (std::size_t i = 0; i < free.size(); ++i) rhs[i] = -r[free[i]];
  auto solver = tfeti::createLocalSolver("cholmod");
  solver->factorize(K.submatrix(free, free));
  solver->solve(rhs.data(), x.data());
  for (std::size_t i = 0; i < free.size(); ++i) u[free[i]] = x[i];
}

inline double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

inline double norm2(const std::vector<double>& v) {
  return std::sqrt(dot(v, v));
}

inline double maxAbs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// max |K_ij - K_ji| / max |K_ij| over the full pattern.
inline double asymmetry(const tfeti::CsrMatrix& K) {
  double worst = 0.0;
  for (int i = 0; i < K.rows; ++i)
    for (int k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k) {
      const long t = K.find(K.colInd[k], i);
      worst = std::max(worst, std::abs(K.values[k] - (t < 0 ? 0.0 : K.values[t])));
    }
  return worst / K.maxAbs();
}

inline std::vector<double> multiply(const tfeti::CsrMatrix& K, const std::vector<double>& x) {
  std::vector<double> y(K.rows);
  K.multiply(x.data(), y.data());
  return y;
}

// Eigenvalues of a small matrix, ascending.
inline std::vector<double> eigenvalues(const tfeti::CsrMatrix& K) {
  std::vector<double> A(static_cast<std::size_t>(K.rows) * K.rows, 0.0);
  for (int i = 0; i < K.rows; ++i)
    for (int k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k) A[K.colInd[k] * K.rows + i] = K.values[k];
  std::vector<double> w, V;
  tfeti::dense::symmetricEigen(K.rows, A, w, V);
  std::sort(w.begin(), w.end());
  return w;
}

// Rigid body modes of plane elasticity at the given nodes (x, y per node): 2 translations and
// the rotation (-y, x).
inline std::vector<std::vector<double>> rigidModes(const std::vector<double>& coords) {
  const std::size_t n = coords.size() / 2;
  std::vector<std::vector<double>> R(3, std::vector<double>(2 * n, 0.0));
  for (std::size_t i = 0; i < n; ++i) {
    R[0][2 * i] = 1.0;
    R[1][2 * i + 1] = 1.0;
    R[2][2 * i] = -coords[2 * i + 1];
    R[2][2 * i + 1] = coords[2 * i];
  }
  return R;
}

}  // namespace plasticity_test
