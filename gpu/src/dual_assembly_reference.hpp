#pragma once
// The host side of the assembly check (gpu/README.md, "Assembly"):
//  - BandCholesky: K_reg = L Lᵀ in long double within the band that the structured numbering
//    gives (O(n b²)), and K⁺ by it: the reference columns of F_s = B_s K⁺ B_sᵀ;
//  - denseDualBlock: the device's algorithm on the host, in double (dense Cholesky of the
//    reordered K_reg, Y = L⁻¹ E, F_s = Yᵀ Y), to check its algebra without a device;
//  - subdomainChecks: the subdomain itself (rigid modes in ker K, the patch test, K K⁺ K = K).
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "hex8_subdomain.hpp"

namespace gpucheck {

class BandCholesky {
 public:
  explicit BandCholesky(const Csr& a) : n_(a.n) {
    for (int i = 0; i < n_; ++i)
      for (int e = a.rowPtr[i]; e < a.rowPtr[i + 1]; ++e) bw_ = std::max(bw_, i - a.col[e]);
    L_.assign(static_cast<std::size_t>(n_) * (bw_ + 1), 0.0L);
    for (int i = 0; i < n_; ++i)
      for (int e = a.rowPtr[i]; e < a.rowPtr[i + 1]; ++e)
        if (a.col[e] <= i) at(i, a.col[e]) = a.val[e];
    for (int i = 0; i < n_; ++i)
      for (int j = std::max(0, i - bw_); j <= i; ++j) {
        long double s = at(i, j);
        for (int k = std::max(0, i - bw_); k < j; ++k) s -= at(i, k) * at(j, k);
        if (j < i) {
          at(i, j) = s / at(j, j);
        } else {
          if (!(s > 0.0L))
            throw std::runtime_error("K_reg is not positive definite at row " + std::to_string(i));
          at(i, i) = std::sqrt(s);
        }
      }
  }
  int bandwidth() const { return bw_; }

  // K_reg⁻¹ b.
  std::vector<long double> solve(std::vector<long double> b) const {
    for (int i = 0; i < n_; ++i) {
      long double s = b[i];
      for (int k = std::max(0, i - bw_); k < i; ++k) s -= at(i, k) * b[k];
      b[i] = s / at(i, i);
    }
    for (int i = n_ - 1; i >= 0; --i) {
      b[i] /= at(i, i);
      for (int k = std::max(0, i - bw_); k < i; ++k) b[k] -= at(i, k) * b[i];
    }
    return b;
  }

 private:
  long double& at(int i, int j) {
    return L_[static_cast<std::size_t>(i) * (bw_ + 1) + j - i + bw_];
  }
  long double at(int i, int j) const {
    return L_[static_cast<std::size_t>(i) * (bw_ + 1) + j - i + bw_];
  }
  int n_ = 0, bw_ = 0;
  std::vector<long double> L_;  // row i holds L(i, i - bw .. i)
};

// K⁺ b: the fixing dofs' part of b dropped, K_reg solved (its fixing rows are diagonal only, so
// the solution is zero there).
inline std::vector<long double> pseudoInverse(const Hex8Subdomain& s, const BandCholesky& c,
                                              std::vector<long double> b) {
  for (int f : s.fixing) b[f] = 0.0L;
  return c.solve(std::move(b));
}

// Columns `cols` of F_s (m values each, column after column), in long double.
inline std::vector<long double> referenceColumns(const Hex8Subdomain& s, const BandCholesky& c,
                                                 const std::vector<int>& cols) {
  const int m = s.dualRows();
  std::vector<long double> f;
  f.reserve(cols.size() * m);
  for (int l : cols) {
    std::vector<long double> b(s.n, 0.0L);
    b[s.dualDof[l]] = 1.0L;
    const std::vector<long double> x = pseudoInverse(s, c, std::move(b));
    for (int k = 0; k < m; ++k) f.push_back(x[s.dualDof[k]]);
  }
  return f;
}

// max |F(:, cols) - ref| / max |ref|, F full and column-major (m × m).
inline double columnsError(const double* F, int m, const std::vector<int>& cols,
                           const std::vector<long double>& ref) {
  long double d = 0.0L, r = 0.0L;
  for (std::size_t q = 0; q < cols.size(); ++q)
    for (int k = 0; k < m; ++k) {
      const long double want = ref[q * m + k];
      d = std::max(d, std::fabs(F[k + static_cast<std::size_t>(cols[q]) * m] - want));
      r = std::max(r, std::fabs(want));
    }
  return static_cast<double>(r > 0.0L ? d / r : d);
}

// The device's algorithm on the host: F_s (m × m, full, column-major).
inline std::vector<double> denseDualBlock(const Hex8Subdomain& s, Ordering o) {
  const int n = s.n, m = s.dualRows();
  const std::vector<int> p = positions(s, o);
  const Csr a = permuted(s.Kreg, p);
  std::vector<double> L(static_cast<std::size_t>(n) * n, 0.0);
  for (int i = 0; i < n; ++i)
    for (int e = a.rowPtr[i]; e < a.rowPtr[i + 1]; ++e)
      L[i + static_cast<std::size_t>(a.col[e]) * n] = a.val[e];
  for (int j = 0; j < n; ++j) {  // right-looking, lower triangle
    double* cj = &L[static_cast<std::size_t>(j) * n];
    cj[j] = std::sqrt(cj[j]);
    for (int i = j + 1; i < n; ++i) cj[i] /= cj[j];
    for (int c = j + 1; c < n; ++c) {
      double* cc = &L[static_cast<std::size_t>(c) * n];
      for (int i = c; i < n; ++i) cc[i] -= cj[i] * cj[c];
    }
  }
  // Y = L⁻¹ E, on the trailing rows where E lives (all rows in natural order).
  const int first = o == Ordering::Natural ? 0 : n - m, rows = n - first;
  const std::vector<int> unit = unitPositions(s, p);
  std::vector<double> Y(static_cast<std::size_t>(rows) * m, 0.0);
  for (int k = 0; k < m; ++k) {
    if (unit[k] < 0) continue;
    double* y = &Y[static_cast<std::size_t>(k) * rows];
    y[unit[k] - first] = 1.0;
    for (int j = 0; j < rows; ++j) {
      const double* cj = &L[static_cast<std::size_t>(first + j) * n + first];
      y[j] /= cj[j];
      for (int i = j + 1; i < rows; ++i) y[i] -= cj[i] * y[j];
    }
  }
  std::vector<double> F(static_cast<std::size_t>(m) * m);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i <= j; ++i) {
      double v = 0.0;
      for (int r = 0; r < rows; ++r)
        v += Y[r + static_cast<std::size_t>(i) * rows] * Y[r + static_cast<std::size_t>(j) * rows];
      F[i + static_cast<std::size_t>(j) * m] = F[j + static_cast<std::size_t>(i) * m] = v;
    }
  return F;
}

// y = K x (long double).
inline std::vector<long double> multiply(const Csr& a, const std::vector<long double>& x) {
  std::vector<long double> y(a.n, 0.0L);
  for (int i = 0; i < a.n; ++i)
    for (int e = a.rowPtr[i]; e < a.rowPtr[i + 1]; ++e) y[i] += a.val[e] * x[a.col[e]];
  return y;
}

// u(p, d) at every node p (in element units), component d, as a vector of dofs.
template <class U>
std::vector<long double> nodalField(const Hex8Subdomain& s, U&& u) {
  const int N = s.nodesPerEdge();
  std::vector<long double> x(s.n);
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i) {
        const long double p[3] = {1.0L * i, 1.0L * j, 1.0L * k};
        for (int d = 0; d < 3; ++d) x[3 * s.node(i, j, k) + d] = u(p, d);
      }
  return x;
}

inline long double largestEntry(const Csr& K) {
  long double m = 0.0L;
  for (double v : K.val) m = std::max(m, std::fabs(static_cast<long double>(v)));
  return m;
}

// max |K r| / (|K| |r|) over the three translations and the three rotations.
inline long double rigidModesResidual(const Hex8Subdomain& s) {
  const long double kmax = largestEntry(s.K);
  long double worst = 0.0L;
  for (int mode = 0; mode < 6; ++mode) {
    const std::vector<long double> r = nodalField(s, [&](const long double* p, int d) {
      if (mode < 3) return d == mode ? 1.0L : 0.0L;
      const int a = mode - 3, b = (a + 1) % 3, e = (a + 2) % 3;  // rotation about axis a
      return d == b ? -p[e] : d == e ? p[b] : 0.0L;
    });
    long double rmax = 0.0L;
    for (long double v : r) rmax = std::max(rmax, std::fabs(v));
    for (long double v : multiply(s.K, r)) worst = std::max(worst, std::fabs(v) / (kmax * rmax));
  }
  return worst;
}

// The patch test: a linear displacement field leaves no force at the interior nodes,
// max |(K u)_interior| / (|K| N).
inline long double patchTestResidual(const Hex8Subdomain& s) {
  static const long double A[3][3] = {
      {0.3L, -0.7L, 0.2L}, {1.1L, 0.4L, -0.5L}, {0.6L, 0.9L, -0.8L}};
  const int N = s.nodesPerEdge();
  const std::vector<long double> f =
      multiply(s.K, nodalField(s, [&](const long double* p, int d) {
                 return A[d][0] * p[0] + A[d][1] * p[1] + A[d][2] * p[2];
               }));
  const long double kmax = largestEntry(s.K);
  long double worst = 0.0L;
  for (int k = 1; k + 1 < N; ++k)
    for (int j = 1; j + 1 < N; ++j)
      for (int i = 1; i + 1 < N; ++i)
        for (int d = 0; d < 3; ++d)
          worst = std::max(worst, std::fabs(f[3 * s.node(i, j, k) + d]) / (kmax * N));
  return worst;
}

// |K K⁺ K − K| / |K|, column by column (O(n) solves: small subdomains only).
inline long double generalizedInverseResidual(const Hex8Subdomain& s, const BandCholesky& c) {
  const long double kmax = largestEntry(s.K);
  long double worst = 0.0L;
  for (int col = 0; col < s.n; ++col) {
    std::vector<long double> e(s.n, 0.0L);
    e[col] = 1.0L;
    const std::vector<long double> kcol = multiply(s.K, e);
    const std::vector<long double> kkk = multiply(s.K, pseudoInverse(s, c, kcol));
    for (int i = 0; i < s.n; ++i) worst = std::max(worst, std::fabs(kkk[i] - kcol[i]) / kmax);
  }
  return worst;
}

// The subdomain's own checks, printed; false when one fails:
//  - the sizes: 3 (ne+1)³ dofs and 3 ((ne+1)³ − (ne−1)³) dual rows (the surface nodes');
//  - the six rigid modes in the kernel of K, |K R| / (|K| |R|) <= 1e-13;
//  - the patch test, <= 1e-13;
//  - K⁺ a generalized inverse, |K K⁺ K − K| / |K| <= 1e-11 (up to 1000 dofs).
inline bool subdomainChecks(const Hex8Subdomain& s, const BandCholesky& c) {
  const int N = s.nodesPerEdge(), inner = std::max(0, N - 2);
  const bool sizes =
      s.n == 3 * N * N * N && s.dualRows() == 3 * (N * N * N - inner * inner * inner);
  const long double rigid = rigidModesResidual(s), patch = patchTestResidual(s);
  bool ok = sizes && rigid <= 1e-13L && patch <= 1e-13L;
  std::printf(
      "subdomain %d³ elements: %d dofs, %d dual rows%s, band %d; |K R| %.1e, patch test %.1e",
      s.elements, s.n, s.dualRows(), sizes ? "" : " (NOT the surface's)", c.bandwidth(),
      static_cast<double>(rigid), static_cast<double>(patch));
  if (s.n <= 1000) {
    const long double g = generalizedInverseResidual(s, c);
    ok = ok && g <= 1e-11L;
    std::printf(", |K K+ K - K| %.1e", static_cast<double>(g));
  }
  std::printf("%s\n", ok ? "" : "  FAILED");
  return ok;
}

}  // namespace gpucheck
