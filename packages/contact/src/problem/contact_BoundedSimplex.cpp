// The primal simplex method with bounds on a few equality rows (contact_BoundedSimplex.hpp).
#include "contact_BoundedSimplex.hpp"

#include <Teuchos_LAPACK.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace contact {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

const double* column(const BoundedLp& lp, int j) {
  return &lp.matrix[static_cast<std::size_t>(j) * lp.rows];
}

double dot(const double* a, const double* b, int n) {
  double s = 0.0;
  for (int i = 0; i < n; ++i) s += a[i] * b[i];
  return s;
}

void checkSizes(const BoundedLp& lp) {
  const std::size_t n = lp.objective.size();
  if (lp.rows < 0 || lp.lower.size() != n || lp.upper.size() != n ||
      lp.matrix.size() != n * static_cast<std::size_t>(lp.rows))
    throw std::invalid_argument(
        "maximizeFromZero: the matrix, objective and bounds disagree in size");
  for (std::size_t j = 0; j < n; ++j)
    if (!(lp.lower[j] <= 0.0 && lp.upper[j] >= 0.0) || !std::isfinite(lp.objective[j]))
      throw std::invalid_argument("maximizeFromZero: column " + std::to_string(j) +
                                  " has bounds that leave out 0, or a non-finite cost");
}

// m linearly independent columns (the longest first) by Gram-Schmidt; fewer where M's columns
// do not span R^m.
std::vector<int> firstBasis(const BoundedLp& lp, const std::vector<double>& norm) {
  const int m = lp.rows, n = lp.columns();
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return norm[a] > norm[b]; });
  std::vector<std::vector<double>> q;
  std::vector<int> basis;
  for (const int j : order) {
    if (static_cast<int>(basis.size()) == m || !(norm[j] > 0.0)) break;
    std::vector<double> v(column(lp, j), column(lp, j) + m);
    for (int pass = 0; pass < 2; ++pass)
      for (const auto& e : q) {
        const double a = dot(e.data(), v.data(), m);
        for (int i = 0; i < m; ++i) v[i] -= a * e[i];
      }
    const double r = std::sqrt(dot(v.data(), v.data(), m));
    if (!(r > 1e-9 * norm[j])) continue;
    for (double& x : v) x /= r;
    q.push_back(std::move(v));
    basis.push_back(j);
  }
  return basis;
}

// The basis matrix's LU factors.
class BasisFactors {
 public:
  BasisFactors(const BoundedLp& lp, const std::vector<int>& basis)
      : m_(lp.rows), lu_(static_cast<std::size_t>(m_) * m_), pivots_(m_) {
    for (int i = 0; i < m_; ++i)
      std::copy(column(lp, basis[i]), column(lp, basis[i]) + m_, lu_.begin() + i * m_);
    int info = 0;
    lapack_.GETRF(m_, m_, lu_.data(), m_, pivots_.data(), &info);
    ok_ = info == 0;
  }
  bool ok() const { return ok_; }
  // B v = rhs ('N') or B^T v = rhs ('T'), in place.
  void solve(char trans, std::vector<double>& v) const {
    int info = 0;
    lapack_.GETRS(trans, m_, 1, lu_.data(), m_, pivots_.data(), v.data(), m_, &info);
  }

 private:
  int m_;
  std::vector<double> lu_;
  std::vector<int> pivots_;
  bool ok_ = false;
  Teuchos::LAPACK<int, double> lapack_;
};

// The basic values from the nonbasic ones (M x = 0), afresh each step against drift, kept within
// their bounds.
void setBasicValues(const BoundedLp& lp, const std::vector<int>& basis,
                    const std::vector<int>& position, const BasisFactors& factors,
                    std::vector<double>& x) {
  const int m = lp.rows;
  std::vector<double> xb(m, 0.0);
  for (int j = 0; j < lp.columns(); ++j)
    if (position[j] < 0 && x[j] != 0.0)
      for (int i = 0; i < m; ++i) xb[i] -= column(lp, j)[i] * x[j];
  factors.solve('N', xb);
  for (int i = 0; i < m; ++i)
    x[basis[i]] = std::clamp(xb[i], lp.lower[basis[i]], lp.upper[basis[i]]);
}

struct Entering {
  int column = -1;    // -1: none, x is optimal
  double sign = 0.0;  // +1: it increases, -1: it decreases
};

// Pricing: a nonbasic column whose reduced cost c_j - y^T M_j improves the objective in a
// direction its bounds leave open; the largest scaled one (Dantzig), or the first (Bland).
Entering price(const BoundedLp& lp, const std::vector<int>& position, const std::vector<double>& x,
               const std::vector<double>& y, const std::vector<double>& norm, bool bland) {
  const int m = lp.rows;
  const double yNorm = std::sqrt(dot(y.data(), y.data(), m));
  Entering best;
  double bestScore = 0.0;
  for (int j = 0; j < lp.columns(); ++j) {
    if (position[j] >= 0) continue;
    const double d = lp.objective[j] - dot(y.data(), column(lp, j), m);
    const double tol = 1e-10 * (std::abs(lp.objective[j]) + yNorm * norm[j]);
    const bool up = d > tol && x[j] < lp.upper[j], down = d < -tol && x[j] > lp.lower[j];
    if (!up && !down) continue;
    const double score = std::abs(d) / (norm[j] > 0.0 ? norm[j] : 1.0);
    if (best.column < 0 || score > bestScore) {
      best = {j, up ? 1.0 : -1.0};
      bestScore = score;
      if (bland) break;
    }
  }
  return best;
}

struct Step {
  double theta = kInf;  // how far the entering column moves
  int leaving = -1;     // the basis position that leaves, or -1: a bound flip
  double rate = 0.0;    // the leaving value's rate of change
};

// Ratio test: the entering column's own bound, or the first basic value to reach one; `w` is
// B^-1 M_entering.
Step ratioTest(const BoundedLp& lp, const std::vector<int>& basis, const std::vector<double>& x,
               const std::vector<double>& w, const Entering& in, bool bland) {
  double wMax = 0.0;
  for (const double v : w) wMax = std::max(wMax, std::abs(v));
  const double wTol = 1e-11 * wMax;
  Step step;
  step.theta =
      in.sign > 0.0 ? lp.upper[in.column] - x[in.column] : x[in.column] - lp.lower[in.column];
  for (int i = 0; i < lp.rows; ++i) {
    const int k = basis[i];
    const double rate = -in.sign * w[i];  // d x_k / d theta
    double room;
    if (rate < -wTol)
      room = (x[k] - lp.lower[k]) / -rate;
    else if (rate > wTol)
      room = (lp.upper[k] - x[k]) / rate;
    else
      continue;
    room = std::max(room, 0.0);
    // Ties (to rounding) go to Bland's smallest index, or else to the largest rate (the stabler
    // pivot); the step is the smaller of the two, so that nothing overshoots.
    const bool tie = step.leaving >= 0 && std::abs(room - step.theta) <= 1e-12 * (1.0 + step.theta);
    const bool better =
        tie ? (bland ? k < basis[step.leaving] : std::abs(rate) > std::abs(step.rate))
            : room < step.theta;
    if (better) step = {tie ? std::min(step.theta, room) : room, i, rate};
  }
  return step;
}

// Moves x by the step and, unless it is a bound flip, swaps the leaving column out of the basis
// (onto the bound it reached) and the entering one in.
void pivot(const BoundedLp& lp, const Entering& in, const Step& step, const std::vector<double>& w,
           std::vector<int>& basis, std::vector<int>& position, std::vector<double>& x) {
  x[in.column] += in.sign * step.theta;
  for (int i = 0; i < lp.rows; ++i) x[basis[i]] -= in.sign * step.theta * w[i];
  if (step.leaving < 0) {  // a bound flip: exactly onto the entering column's own bound
    x[in.column] = in.sign > 0.0 ? lp.upper[in.column] : lp.lower[in.column];
    return;
  }
  const int k = basis[step.leaving];
  x[k] = step.rate < 0.0 ? lp.lower[k] : lp.upper[k];
  position[k] = -1;
  basis[step.leaving] = in.column;
  position[in.column] = step.leaving;
}

}  // namespace

BoundedLpSolution maximizeFromZero(const BoundedLp& lp) {
  checkSizes(lp);
  const int m = lp.rows, n = lp.columns();
  BoundedLpSolution out;
  out.x.assign(n, 0.0);
  out.y.assign(m, 0.0);
  std::vector<double> norm(n);
  for (int j = 0; j < n; ++j) norm[j] = std::sqrt(dot(column(lp, j), column(lp, j), m));
  std::vector<int> basis = firstBasis(lp, norm);
  if (static_cast<int>(basis.size()) < m) return out;  // rankDeficient
  std::vector<int> position(n, -1);                    // in the basis, or -1
  for (int i = 0; i < m; ++i) position[basis[i]] = i;

  std::vector<double>& x = out.x;
  std::vector<double>& y = out.y;
  std::vector<double> w(m);
  bool bland = false;
  int degenerateRun = 0;
  const int limit = 10 * (n + m) + 1000;
  for (out.iterations = 0; out.iterations < limit; ++out.iterations) {
    const BasisFactors factors(lp, basis);
    if (!factors.ok()) {
      out.status = BoundedLpSolution::Status::rankDeficient;
      return out;
    }
    setBasicValues(lp, basis, position, factors, x);
    for (int i = 0; i < m; ++i) y[i] = lp.objective[basis[i]];
    factors.solve('T', y);
    const Entering in = price(lp, position, x, y, norm, bland);
    if (in.column < 0) {
      out.status = BoundedLpSolution::Status::optimal;
      out.value = dot(lp.objective.data(), x.data(), n);
      return out;
    }
    std::copy(column(lp, in.column), column(lp, in.column) + m, w.begin());
    factors.solve('N', w);
    const Step step = ratioTest(lp, basis, x, w, in, bland);
    if (step.theta == kInf) {
      out.status = BoundedLpSolution::Status::unbounded;
      return out;
    }
    const double start = x[in.column];
    pivot(lp, in, step, w, basis, position, x);
    // Degenerate steps (no progress) can cycle under Dantzig's pricing: after a run of them,
    // Bland's rule for the rest of the solve.
    degenerateRun = step.theta > 1e-12 * (1.0 + std::abs(start)) ? 0 : degenerateRun + 1;
    if (degenerateRun > 50) bland = true;
  }
  out.status = BoundedLpSolution::Status::iterationLimit;
  return out;
}

}  // namespace contact
