// SMALBE's "Stall window" (docs/qp_solvers.md, "When the equality constraints stall"): a QP whose
// bounds leave no point with Q x = 0 stops, not converged and saying so, after the window instead
// of at "Maximum outer iterations"; with the window 0 it runs to the limit as before; a feasible
// QP with the same equality constraint is not stopped.
#include "tfeti_QpTestHelpers.hpp"

namespace {

using namespace qp_test;

constexpr GO kN = 40;

// min 1/2 x^T A x - b^T x (A the 1D Laplacian) with sum x = 0 (Q: the projector onto the
// constants) and x >= lower.
struct MeanFreeQp {
  RCP<const Operator> A;
  RCP<Vector> b, lower, x;
  RCP<SpanProjector> Q;
  Qp qp() { return Qp{A, b, lower, x}; }
};

MeanFreeQp meanFreeQp(double lowerBound) {
  const auto map = uniformMap(kN, world());
  MeanFreeQp p;
  p.A = laplacian1D(map);
  p.b = vectorOf(map, [](GO i) { return std::sin(0.3 * double(i)); });
  p.lower = vectorOf(map, [lowerBound](GO) { return lowerBound; });
  p.x = vectorOf(map, [](GO) { return 0.0; });
  auto ones = vectorOf(map, [](GO) { return 1.0; });
  p.Q = rcp(new SpanProjector(*ones));
  return p;
}

Teuchos::ParameterList params(int window) {
  Teuchos::ParameterList pl = smalbeParams(1e-10);
  pl.set("Maximum outer iterations", 400);
  pl.set("Stall window", window);
  return pl;
}

// x >= 1 everywhere and sum x = 0: infeasible. ||Q x|| stays near sqrt(n) while mu grows.
TEUCHOS_UNIT_TEST(SmalbeStall, InfeasibleQpStopsAfterTheWindow) {
  MeanFreeQp p = meanFreeQp(1.0);
  Smalbe solver(p.qp(), p.Q, params(50));
  TEST_EQUALITY(solver.solve(), Belos::Unconverged);
  const auto& c = solver.counters();
  out << c.message << "\n";
  TEST_ASSERT(!c.converged);
  TEST_COMPARE(c.outerIterations, >=, 51);
  TEST_COMPARE(c.outerIterations, <=, 60);
  TEST_ASSERT(c.message.find("the equality constraints stalled") != std::string::npos);
  TEST_ASSERT(c.message.find("\"Stall window\"") != std::string::npos);
  // The bounds hold throughout.
  const auto x = gatherAll(*p.x);
  TEST_COMPARE(*std::min_element(x.begin(), x.end()), >=, 1.0);
}

// The window 0: the earlier behaviour, the limit of outer iterations.
TEUCHOS_UNIT_TEST(SmalbeStall, WindowZeroRunsToTheLimit) {
  MeanFreeQp p = meanFreeQp(1.0);
  Smalbe solver(p.qp(), p.Q, params(0));
  TEST_EQUALITY(solver.solve(), Belos::Unconverged);
  const auto& c = solver.counters();
  TEST_EQUALITY(c.outerIterations, 400);
  TEST_ASSERT(c.message.find("the limit of 400 outer iterations") != std::string::npos);
}

// x >= -0.05 and sum x = 0: feasible (x = 0), and the bounds bind where b < 0. SMALBE alone
// ("Face solve" none) converges within a few outer iterations, the window never reached.
TEUCHOS_UNIT_TEST(SmalbeStall, FeasibleQpIsNotStopped) {
  MeanFreeQp p = meanFreeQp(-0.05);
  Teuchos::ParameterList pl = params(5);
  pl.set("Face solve", "none");
  Smalbe solver(p.qp(), p.Q, pl);
  TEST_EQUALITY(solver.solve(), Belos::Converged);
  const auto& c = solver.counters();
  out << c.message << "\n";
  TEST_ASSERT(c.converged);
  TEST_COMPARE(c.outerIterations, <, 50);
  const auto mu = solver.getMultiplier()->getVector(0);
  const Kkt k = tfeti::qpKkt(*p.A, *p.b, *p.lower, nullptr, *p.x, mu.get(), p.Q.get());
  expectKkt(k, 1e-8 * p.b->norm2(), out, success);
  // The bounds bind somewhere: the constraint set is not the whole space.
  const auto x = gatherAll(*p.x);
  TEST_COMPARE(std::count_if(x.begin(), x.end(), [](double v) { return v == -0.05; }), >, 0);
}

}  // namespace
