#pragma once
// A small linear program with few equality rows and many bounded columns, by the primal simplex
// method with bounds:
//
//   maximize c^T x  subject to  M x = 0,  lower <= x <= upper,
//
// where x = 0 is feasible (every lower <= 0 <= upper; bounds may be infinite). It is what the
// rigid motions' load limit (contact_RigidMotions.hpp) solves: M has a row per rigid motion
// the supports leave free (a few) and a column per contact or friction row (thousands), so the
// basis is a small dense matrix factorized afresh at every step.
//
// A nonbasic column may rest anywhere within its bounds (x starts at 0, which for a friction
// multiplier lies inside its interval): it enters by moving whichever way its reduced cost
// improves the objective, and stays nonbasic where it reaches its own bound first. Pricing is
// Dantzig's (largest scaled reduced cost) until a run of degenerate steps, then Bland's rule,
// which cannot cycle.
#include <vector>

namespace contact {

struct BoundedLp {
  int rows = 0;                                 // m
  std::vector<double> matrix;                   // M, m x n, column-major (column j at j * m)
  std::vector<double> objective, lower, upper;  // c, bounds: n each

  int columns() const { return static_cast<int>(objective.size()); }
};

struct BoundedLpSolution {
  enum class Status {
    optimal,
    unbounded,       // the objective grows without bound
    rankDeficient,   // the columns of M do not span its rows' space: no basis
    iterationLimit,  // cannot happen in exact arithmetic (Bland's rule); rounding
  };
  Status status = Status::rankDeficient;
  std::vector<double> x;  // n
  // The simplex multipliers y: column j's reduced cost is c_j - y^T M_j. At an optimum a column
  // strictly inside its bounds has reduced cost 0, one at its upper bound >= 0, at its lower <= 0
  // (to the tolerance).
  std::vector<double> y;  // m
  double value = 0.0;     // c^T x
  int iterations = 0;
};

// Throws std::invalid_argument where the sizes disagree or x = 0 is not within the bounds.
BoundedLpSolution maximizeFromZero(const BoundedLp& lp);

}  // namespace contact
