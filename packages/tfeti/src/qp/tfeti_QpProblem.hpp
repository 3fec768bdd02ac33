#pragma once
// The bound-constrained quadratic program of the MPRGP and SMALBE solvers,
//   min 1/2 x^T A x - b^T x  subject to  lower <= x <= upper,
// (SMALBE adds Q x = 0 with Q an orthogonal projector, given to its solver manager), and the
// work counters both solvers report. With disc constraints (`discs`) the feasible set is a
// product of intervals and discs, and the MPRGP iteration runs MPGP (tfeti_SeparableSet.hpp). The
// upper bound is optional: a null `upper` (the default) or +infinity entries mean no upper bound,
// and then both solvers take exactly the steps of the lower-bound-only algorithm. A box component
// with lower == upper is fixed.
#include <Teuchos_RCP.hpp>

#include <string>
#include <vector>

namespace tfeti {

template <class S, class MV, class OP>
struct BoundConstrainedQp {
  Teuchos::RCP<const OP> A;      // symmetric, positive definite on the free sets visited
  Teuchos::RCP<const MV> b;      // linear term
  Teuchos::RCP<const MV> lower;  // lower bounds; -infinity: unconstrained component
  Teuchos::RCP<MV> x;            // initial guess in (projected onto the bounds), solution out
  // Upper bounds; null: none; +infinity: no upper bound on that component. Last, so that the
  // aggregate initializations {A, b, lower, x} of lower-bound problems stay valid.
  Teuchos::RCP<const MV> upper = Teuchos::null;
  // Disc constraints |(x_i, x_{i+1})| <= r (MPGP; tfeti_SeparableSet.hpp): r >= 0 at the first
  // component of each disc, -1 at its second, NaN elsewhere; null: none. The two components of
  // a disc are owned by one rank and have no interval bounds.
  Teuchos::RCP<const MV> discs = Teuchos::null;
  // The discs' centres c, |(x_i, x_{i+1}) - (c_i, c_{i+1})| <= r (read at both components of a
  // disc); null: the origin.
  Teuchos::RCP<const MV> discCenters = Teuchos::null;
};

struct QpCounters {
  bool converged = false;
  int outerIterations = 0;               // SMALBE outer iterations (MPRGP: 0)
  long long hessianMultiplications = 0;  // every application of the Hessian, power iterations too
  long long cgSteps = 0;                 // MPRGP conjugate gradient steps
  long long expansionSteps = 0;          // MPRGP expansion steps (feasible + projected step)
  long long proportioningSteps = 0;      // MPRGP proportioning steps (along the chopped gradient)
  double projectedGradientNorm = 0;      // final ||g^P||
  double equalityResidualNorm = 0;       // final ||Q x|| (SMALBE, penalty)
  double equalityProjectionNorm = 0;     // penalty: ||Q x|| removed by the equality projection
  double rhsNorm = 0;                    // ||b||, the scale of the relative tolerances
  std::vector<double> history;           // ||g^P|| / ||b|| per MPRGP step (first: initial guess)
  std::string message;                   // why the solver stopped
};

}  // namespace tfeti
