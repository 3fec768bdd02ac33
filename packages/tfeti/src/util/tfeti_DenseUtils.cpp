#include "tfeti_DenseUtils.hpp"

#include <algorithm>
#include <cmath>

namespace tfeti {
namespace dense {

void symmetricEigen(int n, std::vector<double> A, std::vector<double>& w, std::vector<double>& V) {
  V.assign(n * n, 0.0);
  for (int i = 0; i < n; ++i) V[i * n + i] = 1.0;
  auto a = [&](int i, int j) -> double& { return A[j * n + i]; };
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off = 0.0, diag = 0.0;
    for (int i = 0; i < n; ++i) {
      diag += a(i, i) * a(i, i);
      for (int j = i + 1; j < n; ++j) off += a(i, j) * a(i, j);
    }
    if (off <= 1e-30 * diag || off == 0.0) break;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        if (a(p, q) == 0.0) continue;
        const double theta = (a(q, q) - a(p, p)) / (2.0 * a(p, q));
        const double t =
            (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < n; ++k) {  // A <- A J
          const double akp = a(k, p), akq = a(k, q);
          a(k, p) = c * akp - s * akq;
          a(k, q) = s * akp + c * akq;
        }
        for (int k = 0; k < n; ++k) {  // A <- J^T A
          const double apk = a(p, k), aqk = a(q, k);
          a(p, k) = c * apk - s * aqk;
          a(q, k) = s * apk + c * aqk;
        }
        for (int k = 0; k < n; ++k) {
          const double vkp = V[p * n + k], vkq = V[q * n + k];
          V[p * n + k] = c * vkp - s * vkq;
          V[q * n + k] = s * vkp + c * vkq;
        }
      }
  }
  w.resize(n);
  for (int i = 0; i < n; ++i) w[i] = a(i, i);
}

std::vector<double> pseudoInverseSpd(int n, const std::vector<double>& A, double relTol) {
  std::vector<double> w, V;
  symmetricEigen(n, A, w, V);
  double wmax = 0.0;
  for (double x : w) wmax = std::max(wmax, std::abs(x));
  std::vector<double> P(n * n, 0.0);
  for (int k = 0; k < n; ++k) {
    if (w[k] <= relTol * wmax) continue;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) P[j * n + i] += V[k * n + i] * V[k * n + j] / w[k];
  }
  return P;
}

int orthonormalizeColumns(int n, int k, std::vector<double>& M, double relTol) {
  int kept = 0;
  for (int j = 0; j < k; ++j) {
    double* v = &M[static_cast<std::size_t>(j) * n];
    double norm0 = 0.0;
    for (int i = 0; i < n; ++i) norm0 += v[i] * v[i];
    norm0 = std::sqrt(norm0);
    for (int pass = 0; pass < 2; ++pass)
      for (int q = 0; q < kept; ++q) {
        const double* u = &M[static_cast<std::size_t>(q) * n];
        double dot = 0.0;
        for (int i = 0; i < n; ++i) dot += u[i] * v[i];
        for (int i = 0; i < n; ++i) v[i] -= dot * u[i];
      }
    double norm = 0.0;
    for (int i = 0; i < n; ++i) norm += v[i] * v[i];
    norm = std::sqrt(norm);
    if (norm <= relTol * norm0 || norm == 0.0) continue;
    double* dst = &M[static_cast<std::size_t>(kept) * n];
    for (int i = 0; i < n; ++i) dst[i] = v[i] / norm;
    ++kept;
  }
  M.resize(static_cast<std::size_t>(kept) * n);
  return kept;
}

}  // namespace dense
}  // namespace tfeti
