#include "tfeti_CsrMatrix.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <numeric>
#include <sstream>
#include <string>

namespace tfeti {

long CsrMatrix::find(int i, int j) const {
  auto first = colInd.begin() + rowPtr[i];
  auto last = colInd.begin() + rowPtr[i + 1];
  auto it = std::lower_bound(first, last, j);
  if (it == last || *it != j) return -1;
  return static_cast<long>(it - colInd.begin());
}

void CsrMatrix::multiply(const double* x, double* y) const {
  for (int i = 0; i < rows; ++i) {
    double s = 0.0;
    for (int k = rowPtr[i]; k < rowPtr[i + 1]; ++k) s += values[k] * x[colInd[k]];
    y[i] = s;
  }
}

double CsrMatrix::maxAbs() const {
  double m = 0.0;
  for (double v : values) m = std::max(m, std::abs(v));
  return m;
}

double CsrMatrix::frobeniusNorm() const {
  double s = 0.0;
  for (double v : values) s += v * v;
  return std::sqrt(s);
}

namespace {
constexpr std::uint64_t kPrime1 = 0x9e3779b185ebca87ULL, kPrime2 = 0xc2b2ae3d27d4eb4fULL,
                        kPrime3 = 0x165667b19e3779f9ULL;

std::uint64_t rotl(std::uint64_t x, int r) {
  return (x << r) | (x >> (64 - r));
}

// SplitMix64's finalizer: every input bit moves every output bit.
std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Two 64-bit digests (seeds s0, s1) of `bytes` bytes in one pass, each in the manner of
// xxHash64: four independent lanes over 32-byte stripes (so the multiplications pipeline; a
// subdomain's K takes about a millisecond), the tail byte by byte, then a finalizer.
std::array<std::uint64_t, 2> digestBytes(const void* data, std::size_t bytes, std::uint64_t s0,
                                         std::uint64_t s1) {
  const auto* p = static_cast<const unsigned char*>(data);
  const std::uint64_t seed[2] = {s0, s1};
  std::uint64_t lane[2][4];
  for (int k = 0; k < 2; ++k) {
    lane[k][0] = seed[k] + kPrime1 + kPrime2;
    lane[k][1] = seed[k] + kPrime2;
    lane[k][2] = seed[k];
    lane[k][3] = seed[k] - kPrime1;
  }
  const auto round = [](std::uint64_t acc, std::uint64_t w) {
    return rotl(acc + w * kPrime2, 31) * kPrime1;
  };
  std::size_t at = 0;
  for (; at + 32 <= bytes; at += 32)
    for (int l = 0; l < 4; ++l) {
      std::uint64_t w;
      std::memcpy(&w, p + at + 8 * l, 8);
      lane[0][l] = round(lane[0][l], w);
      lane[1][l] = round(lane[1][l], w);
    }
  std::array<std::uint64_t, 2> d{};
  for (int k = 0; k < 2; ++k) {
    const std::uint64_t* v = lane[k];
    std::uint64_t h = rotl(v[0], 1) + rotl(v[1], 7) + rotl(v[2], 12) + rotl(v[3], 18);
    for (int l = 0; l < 4; ++l) h = (h ^ round(0, v[l])) * kPrime1 + kPrime3;
    for (std::size_t t = at; t < bytes; ++t) h = rotl(h ^ (p[t] * kPrime3), 11) * kPrime1;
    d[k] = mix64(h ^ bytes);
  }
  return d;
}
}  // namespace

std::array<std::uint64_t, 2> CsrMatrix::digest() const {
  // Two seeds, one pass over each array; the sizes and the arrays are chained into each digest.
  const std::uint64_t seeds[2] = {0x243f6a8885a308d3ULL, 0x13198a2e03707344ULL};
  std::array<std::uint64_t, 2> d{};
  for (int k = 0; k < 2; ++k)
    d[k] = mix64(seeds[k] ^ (static_cast<std::uint64_t>(rows) << 32) ^
                 static_cast<std::uint32_t>(cols));
  const auto chain = [&](const void* data, std::size_t bytes, std::uint64_t offset) {
    const auto h = digestBytes(data, bytes, seeds[0] + offset, seeds[1] + offset);
    for (int k = 0; k < 2; ++k) d[k] = mix64(d[k] ^ h[k]);
  };
  chain(rowPtr.data(), rowPtr.size() * sizeof(int), 0);
  chain(colInd.data(), colInd.size() * sizeof(int), 1);
  chain(values.data(), values.size() * sizeof(double), 2);
  return d;
}

bool CsrMatrix::isSymmetric(double tol) const {
  if (rows != cols) return false;
  const double scale = std::max(maxAbs(), 1e-300);
  for (int i = 0; i < rows; ++i)
    for (int k = rowPtr[i]; k < rowPtr[i + 1]; ++k) {
      const long t = find(colInd[k], i);
      const double vt = t < 0 ? 0.0 : values[t];
      if (std::abs(values[k] - vt) > tol * scale) return false;
    }
  return true;
}

CsrMatrix CsrMatrix::submatrix(const std::vector<int>& rowsKept,
                               const std::vector<int>& colsKept) const {
  std::vector<int> newCol(cols, -1);
  for (std::size_t j = 0; j < colsKept.size(); ++j) newCol[colsKept[j]] = static_cast<int>(j);
  CsrMatrix s;
  s.rows = static_cast<int>(rowsKept.size());
  s.cols = static_cast<int>(colsKept.size());
  s.rowPtr.assign(s.rows + 1, 0);
  for (int r = 0; r < s.rows; ++r) {
    const int i = rowsKept[r];
    for (int k = rowPtr[i]; k < rowPtr[i + 1]; ++k) {
      const int c = newCol[colInd[k]];
      if (c < 0) continue;
      s.colInd.push_back(c);
      s.values.push_back(values[k]);
    }
    s.rowPtr[r + 1] = static_cast<int>(s.colInd.size());
  }
  return s;
}

CsrMatrix csrFromTriplets(int rows, int cols, const std::vector<int>& ri,
                          const std::vector<int>& ci, const std::vector<double>& v) {
  std::vector<std::size_t> order(ri.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return ri[a] != ri[b] ? ri[a] < ri[b] : ci[a] < ci[b];
  });
  CsrMatrix m;
  m.rows = rows;
  m.cols = cols;
  m.rowPtr.assign(rows + 1, 0);
  int lastR = -1, lastC = -1;
  for (std::size_t k : order) {
    if (ri[k] == lastR && ci[k] == lastC) {
      m.values.back() += v[k];
      continue;
    }
    m.colInd.push_back(ci[k]);
    m.values.push_back(v[k]);
    m.rowPtr[ri[k] + 1]++;
    lastR = ri[k];
    lastC = ci[k];
  }
  for (int i = 0; i < rows; ++i) m.rowPtr[i + 1] += m.rowPtr[i];
  return m;
}

std::string csrError(const CsrMatrix& A, const std::string& what) {
  if (A.rows < 0 || A.cols < 0)
    return what + " is " + std::to_string(A.rows) + " x " + std::to_string(A.cols);
  if (A.rowPtr.size() != static_cast<std::size_t>(A.rows) + 1)
    return what + " has " + std::to_string(A.rows) + " rows but rowPtr has " +
           std::to_string(A.rowPtr.size()) + " entries (rows + 1 expected)";
  if (A.colInd.size() != A.values.size())
    return what + " has " + std::to_string(A.colInd.size()) + " column indices but " +
           std::to_string(A.values.size()) + " values";
  if (A.rowPtr.front() != 0 || A.rowPtr.back() != static_cast<long long>(A.colInd.size()))
    return what + ": rowPtr runs from " + std::to_string(A.rowPtr.front()) + " to " +
           std::to_string(A.rowPtr.back()) + ", expected 0 to the " +
           std::to_string(A.colInd.size()) + " entries";
  for (int i = 0; i < A.rows; ++i) {
    if (A.rowPtr[i + 1] < A.rowPtr[i])
      return what + ": rowPtr decreases at row " + std::to_string(i);
    for (int k = A.rowPtr[i]; k < A.rowPtr[i + 1]; ++k) {
      const int j = A.colInd[k];
      if (j < 0 || j >= A.cols)
        return what + ": row " + std::to_string(i) + " has column " + std::to_string(j) +
               ", outside 0 .. " + std::to_string(A.cols - 1);
      if (k > A.rowPtr[i] && j <= A.colInd[k - 1])
        return what + ": the column indices of row " + std::to_string(i) +
               " are not strictly increasing (sort them and sum duplicates)";
      if (!std::isfinite(A.values[k]))
        return what + "(" + std::to_string(i) + ", " + std::to_string(j) + ") is not finite";
    }
  }
  return "";
}

std::string asymmetryError(const CsrMatrix& A, const std::string& what, double tol) {
  if (A.rows != A.cols) return "";  // only a square matrix can be symmetric: checked elsewhere
  const double scale = A.maxAbs();
  double worst = 0.0;
  int wi = 0, wj = 0;
  for (int i = 0; i < A.rows; ++i)
    for (int k = A.rowPtr[i]; k < A.rowPtr[i + 1]; ++k) {
      const int j = A.colInd[k];
      if (j <= i) continue;
      const long t = A.find(j, i);
      const double d = std::abs(A.values[k] - (t < 0 ? 0.0 : A.values[t]));
      if (d > worst) {
        worst = d;
        wi = i;
        wj = j;
      }
    }
  if (!(scale > 0.0) || worst <= tol * scale) return "";
  const long t = A.find(wj, wi);
  std::ostringstream s;
  s << std::setprecision(6) << what << " is not symmetric: " << what << "(" << wi << ", " << wj
    << ") = " << A.values[A.find(wi, wj)] << " but " << what << "(" << wj << ", " << wi
    << ") = " << (t < 0 ? 0.0 : A.values[t]) << std::scientific << std::setprecision(2)
    << " (difference " << worst / scale << " of max |" << what << "|)";
  return s.str();
}

}  // namespace tfeti
