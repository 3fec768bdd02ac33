#pragma once
// The checks every subdomain of the tfeti unit tests must pass, whatever its dimension: K R = 0,
// R^T R = I, well-conditioned fixing dofs and K K+ K = K (checked densely).
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "tfeti_DenseUtils.hpp"
#include "tfeti_Subdomain.hpp"
#include "tfeti_TestHelpers.hpp"

namespace tfeti_test {

// Dense column-major product C = A B (A m x k, B k x n).
inline std::vector<double> matmul(const std::vector<double>& A, const std::vector<double>& B, int m,
                                  int k, int n) {
  std::vector<double> C(static_cast<std::size_t>(m) * n, 0.0);
  for (int j = 0; j < n; ++j)
    for (int p = 0; p < k; ++p) {
      const double b = B[static_cast<std::size_t>(j) * k + p];
      if (b == 0.0) continue;
      for (int i = 0; i < m; ++i)
        C[static_cast<std::size_t>(j) * m + i] += A[std::size_t(p) * m + i] * b;
    }
  return C;
}

inline double frobenius(const std::vector<double>& A) {
  return tfeti_test::norm2(A);
}

// The checks every subdomain must pass: K R = 0, R^T R = I, K K+ K = K. Returns nothing; the
// expected kernel dimension is given.
inline void checkGeneralizedInverse(tfeti::Subdomain& sd, int expectedKernelDim,
                                    Teuchos::FancyOStream& out, bool& success) {
  const tfeti::CsrMatrix& K = sd.stiffness();
  const int n = K.rows, k = sd.kernelDim();
  TEST_EQUALITY(k, expectedKernelDim);
  TEST_EQUALITY(sd.numDofs(), n);
  TEST_EQUALITY(static_cast<int>(sd.kernel().size()), n * k);
  const std::vector<double> Kd = tfeti_test::toDense(K);
  const double normK = frobenius(Kd);

  // K R = 0 relative to ||K|| (R has orthonormal columns).
  if (k > 0) {
    const std::vector<double> KR = matmul(Kd, sd.kernel(), n, n, k);
    const double rel = frobenius(KR) / normK;
    out << "||K R|| / ||K|| = " << rel << "\n";
    TEST_COMPARE(rel, <, 1e-12);
  }
  // R^T R = I.
  double orth = 0.0;
  for (int p = 0; p < k; ++p)
    for (int q = 0; q < k; ++q) {
      double s = 0.0;
      for (int i = 0; i < n; ++i)
        s += sd.kernel()[std::size_t(p) * n + i] * sd.kernel()[std::size_t(q) * n + i];
      orth = std::max(orth, std::abs(s - (p == q ? 1.0 : 0.0)));
    }
  TEST_COMPARE(orth, <, 1e-12);

  // Fixing dofs: kernelDim() distinct sorted dofs with R(F, :) well conditioned.
  const auto& F = sd.fixingDofs();
  TEST_EQUALITY(static_cast<int>(F.size()), k);
  TEST_ASSERT(std::is_sorted(F.begin(), F.end()));
  TEST_ASSERT(std::adjacent_find(F.begin(), F.end()) == F.end());
  if (k > 0 && static_cast<int>(F.size()) == k) {
    std::vector<double> RF(std::size_t(k) * k), RtR(std::size_t(k) * k, 0.0);
    for (int q = 0; q < k; ++q)
      for (int p = 0; p < k; ++p)
        RF[std::size_t(q) * k + p] = sd.kernel()[std::size_t(q) * n + F[p]];
    for (int a = 0; a < k; ++a)
      for (int b = 0; b < k; ++b)
        for (int p = 0; p < k; ++p)
          RtR[std::size_t(b) * k + a] += RF[std::size_t(a) * k + p] * RF[std::size_t(b) * k + p];
    std::vector<double> w, V;
    tfeti::dense::symmetricEigen(k, RtR, w, V);
    const double cond =
        std::sqrt(*std::max_element(w.begin(), w.end()) / *std::min_element(w.begin(), w.end()));
    out << "cond R(F,:) = " << cond << "\n";
    TEST_COMPARE(cond, <, 100.0);
  }

  // K K+ K = K: K+ applied to all columns of K at once (multiple right-hand sides).
  std::vector<double> X(Kd.size());
  sd.applyPseudoInverse(Kd.data(), X.data(), n);
  const std::vector<double> KXK = matmul(Kd, X, n, n, n);
  std::vector<double> diff(Kd.size());
  for (std::size_t i = 0; i < Kd.size(); ++i) diff[i] = KXK[i] - Kd[i];
  const double relGi = frobenius(diff) / normK;
  out << "||K K+ K - K|| / ||K|| = " << relGi << "\n";
  TEST_COMPARE(relGi, <, 1e-10);
  // Column by column (nrhs = 1) gives the same result.
  std::vector<double> x1(n);
  double colDiff = 0.0;
  for (int j = 0; j < n; j += 7) {
    sd.applyPseudoInverse(&Kd[std::size_t(j) * n], x1.data(), 1);
    for (int i = 0; i < n; ++i)
      colDiff = std::max(colDiff, std::abs(x1[i] - X[std::size_t(j) * n + i]));
  }
  TEST_COMPARE(colDiff, <, 1e-12 * tfeti_test::maxAbs(X));
  // K+ is not the zero matrix in disguise: K+ K is a projector of rank n - k.
  double trace = 0.0;
  for (int i = 0; i < n; ++i) trace += X[std::size_t(i) * n + i];
  TEST_FLOATING_EQUALITY(trace, double(n - k), 1e-9);
}

}  // namespace tfeti_test
