// The bounded primal simplex (contact_BoundedSimplex.hpp): closed-form optima, the multipliers'
// optimality conditions and strong duality on generated programs (degenerate ones among them),
// unbounded and rank-deficient programs, and the errors.
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "contact_BoundedSimplex.hpp"

namespace {

using contact::BoundedLp;
using contact::BoundedLpSolution;
constexpr double kInf = std::numeric_limits<double>::infinity();

// max sum_j max over [l_j, u_j] of d_j x_j with d_j = c_j - y^T M_j: the dual value, equal to
// the optimum where y is optimal (finite bounds).
double dualValue(const BoundedLp& lp, const std::vector<double>& y) {
  double v = 0.0;
  for (int j = 0; j < lp.columns(); ++j) {
    double d = lp.objective[j];
    for (int i = 0; i < lp.rows; ++i) d -= y[i] * lp.matrix[j * lp.rows + i];
    v += d > 0.0 ? d * lp.upper[j] : d * lp.lower[j];
  }
  return v;
}

// ||M x||_inf and the largest bound violation.
double residual(const BoundedLp& lp, const std::vector<double>& x) {
  double worst = 0.0;
  for (int i = 0; i < lp.rows; ++i) {
    double s = 0.0;
    for (int j = 0; j < lp.columns(); ++j) s += lp.matrix[j * lp.rows + i] * x[j];
    worst = std::max(worst, std::abs(s));
  }
  for (int j = 0; j < lp.columns(); ++j)
    worst = std::max({worst, lp.lower[j] - x[j], x[j] - lp.upper[j]});
  return worst;
}

// A reproducible generator (no <random>: the same numbers on every library).
struct Lcg {
  unsigned long long s;
  double next() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(s >> 11) / 9007199254740992.0;  // [0, 1)
  }
};

// max t subject to lambda_1 + lambda_2 = t, lambda_1 in [-1, 1], lambda_2 in [0, 2]: t = 3, both
// at their upper bounds, and y = -1 (t's reduced cost 1 + y is 0).
TEUCHOS_UNIT_TEST(BoundedSimplex, TwoBoxesAddUp) {
  BoundedLp lp;
  lp.rows = 1;
  lp.matrix = {1.0, 1.0, -1.0};
  lp.objective = {0.0, 0.0, 1.0};
  lp.lower = {-1.0, 0.0, 0.0};
  lp.upper = {1.0, 2.0, 10.0};
  const BoundedLpSolution s = contact::maximizeFromZero(lp);
  TEST_ASSERT(s.status == BoundedLpSolution::Status::optimal);
  TEST_FLOATING_EQUALITY(s.value, 3.0, 1e-14);
  TEST_FLOATING_EQUALITY(s.x[0], 1.0, 1e-14);
  TEST_FLOATING_EQUALITY(s.x[1], 2.0, 1e-14);
  TEST_FLOATING_EQUALITY(s.y[0], -1.0, 1e-14);
}

// A contact multiplier (lambda >= 0) against a load that pulls: lambda = -t leaves only t = 0;
// the multipliers still certify it (t's reduced cost 1 - y <= 0 at its lower bound).
TEUCHOS_UNIT_TEST(BoundedSimplex, PushOnlyRowAgainstPullIsZero) {
  BoundedLp lp;
  lp.rows = 1;
  lp.matrix = {1.0, 1.0};
  lp.objective = {0.0, 1.0};
  lp.lower = {0.0, 0.0};
  lp.upper = {kInf, 5.0};
  const BoundedLpSolution s = contact::maximizeFromZero(lp);
  TEST_ASSERT(s.status == BoundedLpSolution::Status::optimal);
  TEST_EQUALITY(s.value, 0.0);
  TEST_ASSERT(1.0 - s.y[0] <= 1e-14);
}

// Nothing bounds the objective: lambda = t with lambda >= 0 and t unbounded above.
TEUCHOS_UNIT_TEST(BoundedSimplex, UnboundedIsSaid) {
  BoundedLp lp;
  lp.rows = 1;
  lp.matrix = {1.0, -1.0};
  lp.objective = {0.0, 1.0};
  lp.lower = {0.0, 0.0};
  lp.upper = {kInf, kInf};
  TEST_ASSERT(contact::maximizeFromZero(lp).status == BoundedLpSolution::Status::unbounded);
}

// A row no column touches: no basis.
TEUCHOS_UNIT_TEST(BoundedSimplex, RankDeficientIsSaid) {
  BoundedLp lp;
  lp.rows = 2;
  lp.matrix = {1.0, 0.0, -1.0, 0.0};
  lp.objective = {0.0, 1.0};
  lp.lower = {-1.0, 0.0};
  lp.upper = {1.0, 9.0};
  TEST_ASSERT(contact::maximizeFromZero(lp).status == BoundedLpSolution::Status::rankDeficient);
}

TEUCHOS_UNIT_TEST(BoundedSimplex, BadDataThrows) {
  BoundedLp lp;
  lp.rows = 1;
  lp.matrix = {1.0, -1.0};
  lp.objective = {0.0, 1.0};
  lp.lower = {0.5, 0.0};  // leaves out x = 0
  lp.upper = {1.0, 1.0};
  TEST_THROW(contact::maximizeFromZero(lp), std::invalid_argument);
  lp.lower = {0.0, 0.0};
  lp.matrix = {1.0};
  TEST_THROW(contact::maximizeFromZero(lp), std::invalid_argument);
}

// Generated programs with 1 to 6 rows and up to 400 columns, among them repeated columns and
// zero bounds (degenerate vertices): every solve is optimal, feasible, and its multipliers give
// the same value by duality and meet the reduced costs' sign conditions.
TEUCHOS_UNIT_TEST(BoundedSimplex, GeneratedProgramsMeetDuality) {
  Lcg g{12345};
  for (int trial = 0; trial < 60; ++trial) {
    BoundedLp lp;
    lp.rows = 1 + trial % 6;
    const int n = 2 * lp.rows + static_cast<int>(g.next() * 400);
    for (int j = 0; j < n; ++j) {
      const bool repeat = j > 0 && g.next() < 0.2;
      for (int i = 0; i < lp.rows; ++i)
        lp.matrix.push_back(repeat ? lp.matrix[(j - 1) * lp.rows + i] : 2.0 * g.next() - 1.0);
      lp.objective.push_back(g.next() < 0.5 ? 0.0 : 2.0 * g.next() - 1.0);
      const double kind = g.next();
      lp.lower.push_back(kind < 0.3 ? 0.0 : -1.0 - g.next());
      lp.upper.push_back(kind > 0.8 ? 0.0 : 1.0 + g.next());
    }
    const BoundedLpSolution s = contact::maximizeFromZero(lp);
    TEST_ASSERT(s.status == BoundedLpSolution::Status::optimal);
    if (s.status != BoundedLpSolution::Status::optimal) continue;
    TEST_COMPARE(residual(lp, s.x), <, 1e-12 * n);
    TEST_COMPARE(std::abs(dualValue(lp, s.y) - s.value), <, 1e-10 * (1.0 + std::abs(s.value)));
    for (int j = 0; j < n; ++j) {
      double d = lp.objective[j];
      for (int i = 0; i < lp.rows; ++i) d -= s.y[i] * lp.matrix[j * lp.rows + i];
      const double tol = 1e-9 * (1.0 + std::abs(d));
      if (s.x[j] < lp.upper[j] - 1e-12) TEST_COMPARE(d, <=, tol);
      if (s.x[j] > lp.lower[j] + 1e-12) TEST_COMPARE(d, >=, -tol);
    }
  }
}

}  // namespace
