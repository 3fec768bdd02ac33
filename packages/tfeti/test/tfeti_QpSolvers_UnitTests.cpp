// Unit tests of the bound-constrained QP solvers (MPRGP, SMALBE-M) on 1, 2 and 3 ranks: problems
// with solutions known by construction (all / no / degenerate active bounds, infeasible initial
// guesses), a finite-difference obstacle problem against projected SOR computed here, an
// ill-conditioned problem (condition number checked by a dense eigenvalue solve), errors (an
// indefinite Hessian, NaN data, misspelt parameters), SMALBE with an equality constraint Q x = 0,
// and identical results on 1, 2, ... ranks through sub-communicators. Every solution is checked
// by the KKT conditions (checkKkt) with the tolerances stated at each use.
#include <BelosStatusTestCombo.hpp>
#include <BelosStatusTestMaxIters.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_LAPACK.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Import.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "tfeti_MprgpIteration_decl.hpp"
#include "tfeti_MprgpSolMgr_decl.hpp"
#include "tfeti_OperatorSum.hpp"
#include "tfeti_QpChecks.hpp"
#include "tfeti_QpProblem.hpp"
#include "tfeti_QpStatusTests.hpp"
#include "tfeti_QpTestHelpers.hpp"
#include "tfeti_SmalbeSolMgr_decl.hpp"
#include "tfeti_TestHelpers.hpp"
#include "tfeti_Types.hpp"

namespace {

using namespace qp_test;

// Note: TEST_EQUALITY and TEST_COMPARE evaluate their arguments twice, so solve() is always
// called on its own line (a second solve would restart from the solution).

// -Laplace on the m x m interior grid of the unit square (h = 1 / (m + 1)), 5-point stencil
// scaled by 1 / h^2, unknown i + m j at ((i + 1) h, (j + 1) h).
RCP<CrsMatrix> laplacian2D(const RCP<const Map>& map, int m) {
  const double s = (m + 1.0) * (m + 1.0);
  auto A = rcp(new CrsMatrix(map, 5));
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l) {
    const GO r = map->getGlobalElement(l);
    const int i = static_cast<int>(r % m), j = static_cast<int>(r / m);
    std::vector<GO> cols{r};
    std::vector<double> vals{4.0 * s};
    if (i > 0) cols.push_back(r - 1), vals.push_back(-s);
    if (i + 1 < m) cols.push_back(r + 1), vals.push_back(-s);
    if (j > 0) cols.push_back(r - m), vals.push_back(-s);
    if (j + 1 < m) cols.push_back(r + m), vals.push_back(-s);
    A->insertGlobalValues(r, Teuchos::arrayViewFromVector(cols),
                          Teuchos::arrayViewFromVector(vals));
  }
  A->fillComplete();
  return A;
}

// The KKT conditions (tfeti_QpChecks.hpp) of a problem with lower bounds only.
Kkt checkKkt(const Operator& A, const Vector& b, const Vector& l, const Vector& x,
             const Vector* mu = nullptr, const Operator* Q = nullptr) {
  return tfeti::qpKkt(A, b, l, nullptr, x, mu, Q);
}

// Multiplications by A of one MPRGP solve: the power iterations, one for the initial gradient,
// one per CG and proportioning step, two per expansion step (A p and the fresh gradient).
long long expectedMultiplications(const tfeti::QpCounters& c, int powerIterations) {
  return powerIterations + 1 + c.cgSteps + 2 * c.expansionSteps + c.proportioningSteps;
}

// A test problem with a solution known by construction on the 1D Laplacian: x* given, the
// constraints of kind(i) (0: free, bound 0.5 below; 1: free, no bound; 2: active with the
// multiplier lambda_i = 1 + 0.5 sin i; 3: active with zero multiplier, degenerate), and
// b = A x* - lambda.
struct KnownProblem {
  RCP<CrsMatrix> A;
  RCP<Vector> b, lower, x, exact;
  Qp qp() const { return Qp{A, b, lower, x}; }
};

KnownProblem knownProblem(const RCP<const tfeti::Comm>& comm, GO n,
                          const std::function<int(GO)>& kind) {
  KnownProblem p;
  auto map = uniformMap(n, comm);
  p.A = laplacian1D(map);
  p.exact = vectorOf(map, [](GO i) { return std::sin(0.1 * i) + 0.2 * std::cos(0.37 * i); });
  auto lambda = vectorOf(map, [&](GO i) { return kind(i) == 2 ? 1.0 + 0.5 * std::sin(i) : 0.0; });
  p.lower = vectorOf(map, [&](GO i) {
    const double xs = std::sin(0.1 * i) + 0.2 * std::cos(0.37 * i);
    switch (kind(i)) {
      case 0:
        return xs - 0.5;
      case 1:
        return -kInf;
      default:
        return xs;
    }
  });
  p.b = rcp(new Vector(map));
  p.A->apply(*p.exact, *p.b);
  p.b->update(-1.0, *lambda, 1.0);
  p.x = rcp(new Vector(map));  // 0, projected where infeasible
  return p;
}

// ---------------------------------------------------------------------------------------------
// 1. Known solutions.

TEUCHOS_UNIT_TEST(Mprgp, AllBoundsActive) {
  // Every bound active with a positive multiplier: the solution is x = l.
  auto p = knownProblem(world(), 60, [](GO) { return 2; });
  p.x->putScalar(2.0);  // feasible, away from the bounds
  Mprgp solver(p.qp(), mprgpParams(1e-10));
  const Belos::ReturnType solverResult = solver.solve();
  TEST_EQUALITY(solverResult, Belos::Converged);
  TEST_ASSERT(solver.counters().converged);
  TEST_COMPARE(maxAbsDiff(*p.x, *p.exact), <=, 1e-12);
  const double bNorm = p.b->norm2();
  expectKkt(checkKkt(*p.A, *p.b, *p.lower, *p.x), 1e-9 * bNorm, out, success);
  TEST_EQUALITY(solver.counters().hessianMultiplications,
                expectedMultiplications(solver.counters(), 20));
  out << solver.counters().message << "\n";
}

TEUCHOS_UNIT_TEST(Mprgp, NoBoundsActive) {
  // Bounds 0.5 below the solution or absent: the unconstrained minimizer.
  auto p = knownProblem(world(), 60, [](GO i) { return static_cast<int>(i % 2); });
  Mprgp solver(p.qp(), mprgpParams(1e-11));
  const Belos::ReturnType solverResult = solver.solve();
  TEST_EQUALITY(solverResult, Belos::Converged);
  // cond(A) ~ 1.5e3, ||b|| ~ 1: the error is below cond * tol * ||x|| by far.
  TEST_COMPARE(maxAbsDiff(*p.x, *p.exact), <=, 1e-8);
  const Kkt k = checkKkt(*p.A, *p.b, *p.lower, *p.x);
  expectKkt(k, 1e-10 * p.b->norm2(), out, success);
  // No component ends on its bound.
  Vector gap(*p.x, Teuchos::Copy);
  gap.update(-1.0, *p.lower, 1.0);
  auto gd = gap.getData();
  double minGap = kInf;
  for (std::size_t i = 0; i < gap.getLocalLength(); ++i) minGap = std::min(minGap, gd[i]);
  TEST_COMPARE(-tfeti_test::globalMax(*world(), -minGap), >=, 0.4);
}

TEUCHOS_UNIT_TEST(Mprgp, DegenerateBounds) {
  // All four kinds, including bounds that are active with a zero multiplier.
  auto p = knownProblem(world(), 80, [](GO i) { return static_cast<int>(i % 4); });
  Mprgp solver(p.qp(), mprgpParams(1e-11));
  const Belos::ReturnType solverResult = solver.solve();
  TEST_EQUALITY(solverResult, Belos::Converged);
  TEST_COMPARE(maxAbsDiff(*p.x, *p.exact), <=, 1e-8);
  expectKkt(checkKkt(*p.A, *p.b, *p.lower, *p.x), 1e-10 * p.b->norm2(), out, success);
  const auto& c = solver.counters();
  TEST_EQUALITY(c.hessianMultiplications, expectedMultiplications(c, 20));
  TEST_COMPARE(c.history.size(), ==, static_cast<std::size_t>(solver.getNumIters() + 1));
  TEST_COMPARE(c.history.back(), <=, 1e-11);
  out << c.message << "\n";
}

TEUCHOS_UNIT_TEST(Mprgp, InfeasibleInitialGuessIsProjected) {
  // All bounds active and x0 = l - 1: the projection of x0 is the solution, reached in 0 steps.
  auto p = knownProblem(world(), 50, [](GO) { return 2; });
  auto ones = vectorOf(p.x->getMap(), [](GO) { return 1.0; });
  p.x->update(1.0, *p.lower, -1.0, *ones, 0.0);
  Mprgp solver(p.qp(), mprgpParams(1e-10));
  const Belos::ReturnType solverResult = solver.solve();
  TEST_EQUALITY(solverResult, Belos::Converged);
  TEST_EQUALITY(solver.getNumIters(), 0);
  TEST_COMPARE(maxAbsDiff(*p.x, *p.exact), ==, 0.0);

  // Mixed problem from x0 = x* - 3 (infeasible on every finite bound).
  auto q = knownProblem(world(), 80, [](GO i) { return static_cast<int>(i % 4); });
  auto threes = vectorOf(q.x->getMap(), [](GO) { return 3.0; });
  q.x->update(1.0, *q.exact, -1.0, *threes, 0.0);
  Mprgp solver2(q.qp(), mprgpParams(1e-11));
  const Belos::ReturnType solver2Result = solver2.solve();
  TEST_EQUALITY(solver2Result, Belos::Converged);
  TEST_COMPARE(maxAbsDiff(*q.x, *q.exact), <=, 1e-8);
  expectKkt(checkKkt(*q.A, *q.b, *q.lower, *q.x), 1e-10 * q.b->norm2(), out, success);
}

TEUCHOS_UNIT_TEST(Mprgp, IterationWithBelosStatusTests) {
  // The iteration alone, stopped by Belos::StatusTestMaxIters OR the projected-gradient test.
  auto p = knownProblem(world(), 80, [](GO i) { return static_cast<int>(i % 4); });
  using Test = Belos::StatusTest<double, MultiVector, Operator>;
  auto maxIters = rcp(new Belos::StatusTestMaxIters<double, MultiVector, Operator>(5));
  auto grad = rcp(new tfeti::StatusTestProjectedGradient<double, MultiVector, Operator>(0.0));
  RCP<Test> combo = rcp(new Belos::StatusTestCombo<double, MultiVector, Operator>(
      Belos::StatusTestCombo<double, MultiVector, Operator>::OR, maxIters, grad));
  tfeti::MprgpIteration<double, MultiVector, Operator>::Options opts;
  opts.alphaBar = 1.9 / 4.0;  // ||A|| <= 4 for the 1D Laplacian
  tfeti::MprgpIteration<double, MultiVector, Operator> it(p.qp(), Teuchos::null, combo, opts);
  it.iterate();
  TEST_EQUALITY(it.getNumIters(), 5);
  TEST_EQUALITY(maxIters->getStatus(), Belos::Passed);
  TEST_EQUALITY(grad->getStatus(), Belos::Failed);
  TEST_ASSERT(it.getProblem().getLHS().get() == p.x.get());
  std::vector<double> norms(1);
  it.getNativeResiduals(&norms);
  TEST_EQUALITY(norms[0], grad->getProjectedGradientNorm());
  TEST_COMPARE(norms[0], >, 0.0);
}

// ---------------------------------------------------------------------------------------------
// 2. Obstacle problem: -Laplace u = f on the unit square, u = 0 on the boundary, u >= psi
// (no obstacle for x < 0.2), against projected SOR.

constexpr int kObstacleM = 31;
double obstacleF(double, double) {
  return -20.0;
}
double obstaclePsi(double x, double y) {
  if (x < 0.2) return -kInf;
  return -0.1 - 0.5 * ((x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5)) + 0.05 * std::sin(7 * x);
}

struct Obstacle {
  RCP<CrsMatrix> A;
  RCP<Vector> b, lower, x;
  Qp qp() const { return Qp{A, b, lower, x}; }
};

Obstacle obstacle(const RCP<const tfeti::Comm>& comm, int m = kObstacleM,
                  double (*f)(double, double) = obstacleF) {
  Obstacle o;
  const double h = 1.0 / (m + 1);
  auto map = uniformMap(static_cast<GO>(m) * m, comm);
  o.A = laplacian2D(map, m);
  auto at = [&](GO r, double (*f)(double, double)) { return f((r % m + 1) * h, (r / m + 1) * h); };
  o.b = vectorOf(map, [&](GO r) { return at(r, f); });
  o.lower = vectorOf(map, [&](GO r) { return at(r, obstaclePsi); });
  o.x = rcp(new Vector(map));
  return o;
}

// Projected SOR (omega = 1.8) on the full grid, serial, until the largest update is below 1e-15.
std::vector<double> psor(int m) {
  const double h = 1.0 / (m + 1), s = 1.0 / (h * h), omega = 1.8;
  const int n = m * m;
  std::vector<double> u(n, 0.0), f(n), psi(n);
  for (int r = 0; r < n; ++r) {
    f[r] = obstacleF((r % m + 1) * h, (r / m + 1) * h);
    psi[r] = obstaclePsi((r % m + 1) * h, (r / m + 1) * h);
    u[r] = std::max(0.0, psi[r]);
  }
  for (int sweep = 0; sweep < 100000; ++sweep) {
    double change = 0.0;
    for (int r = 0; r < n; ++r) {
      const int i = r % m, j = r / m;
      double nb = 0.0;
      if (i > 0) nb += u[r - 1];
      if (i + 1 < m) nb += u[r + 1];
      if (j > 0) nb += u[r - m];
      if (j + 1 < m) nb += u[r + m];
      const double gs = (f[r] + s * nb) / (4.0 * s);
      const double next = std::max(psi[r], u[r] + omega * (gs - u[r]));
      change = std::max(change, std::abs(next - u[r]));
      u[r] = next;
    }
    if (change < 1e-15) break;
  }
  return u;
}

TEUCHOS_UNIT_TEST(Mprgp, ObstacleProblemMatchesProjectedSor) {
  auto o = obstacle(world());
  Mprgp solver(o.qp(), mprgpParams(1e-11));
  const Belos::ReturnType solverResult = solver.solve();
  TEST_EQUALITY(solverResult, Belos::Converged);
  const auto& c = solver.counters();
  out << c.message << "; " << c.cgSteps << " CG, " << c.expansionSteps << " expansion, "
      << c.proportioningSteps << " proportioning\n";
  TEST_EQUALITY(c.hessianMultiplications, expectedMultiplications(c, 20));
  expectKkt(checkKkt(*o.A, *o.b, *o.lower, *o.x), 1e-10 * o.b->norm2(), out, success);

  const std::vector<double> ref = psor(kObstacleM);
  const std::vector<double> u = gatherAll(*o.x);
  // The reference's own KKT residual, so that a wrong reference cannot pass silently.
  auto refVec = vectorOf(o.x->getMap(), [&](GO r) { return ref[r]; });
  expectKkt(checkKkt(*o.A, *o.b, *o.lower, *refVec), 1e-9 * o.b->norm2(), out, success);
  double diff = 0.0, active = 0.0;
  auto lower = gatherAll(*o.lower);
  for (std::size_t r = 0; r < u.size(); ++r) {
    diff = std::max(diff, std::abs(u[r] - ref[r]));
    if (u[r] == lower[r]) active += 1.0;
  }
  out << "max |u - u_PSOR| = " << diff << ", active " << active << " of " << u.size() << "\n";
  // ||A^{-1}|| ~ 1/(2 pi^2) times ||g^P|| <= 1e-11 ||f||: far below 1e-8.
  TEST_COMPARE(diff, <=, 1e-8 * tfeti_test::maxAbs(ref));
  TEST_COMPARE(active, >, 0.1 * u.size());  // a genuine contact problem
  TEST_COMPARE(active, <, 0.9 * u.size());
}

// The projected CG expansion (x = P(x - alphaCg p), fall-back to the fixed step when f is
// above f at the feasible half step) reaches the same solution; every expansion costs one
// multiplication more than a fixed one only when it falls back.
TEUCHOS_UNIT_TEST(Mprgp, ProjectedCgExpansionMatchesProjectedSor) {
  auto o = obstacle(world());
  Teuchos::ParameterList params = mprgpParams(1e-11);
  params.set("Expansion step", "projected CG");
  Mprgp solver(o.qp(), params);
  const Belos::ReturnType solverResult = solver.solve();  // TEST_EQUALITY evaluates twice
  TEST_EQUALITY(solverResult, Belos::Converged);
  const auto& c = solver.counters();
  out << c.message << "; " << c.cgSteps << " CG, " << c.expansionSteps << " expansion, "
      << c.proportioningSteps << " proportioning\n";
  TEST_COMPARE(c.expansionSteps, >, 0);
  TEST_COMPARE(c.hessianMultiplications, >=, expectedMultiplications(c, 20));
  TEST_COMPARE(c.hessianMultiplications, <=, expectedMultiplications(c, 20) + c.expansionSteps);
  expectKkt(checkKkt(*o.A, *o.b, *o.lower, *o.x), 1e-10 * o.b->norm2(), out, success);
  const std::vector<double> ref = psor(kObstacleM);
  const std::vector<double> u = gatherAll(*o.x);
  double diff = 0.0;
  for (std::size_t r = 0; r < u.size(); ++r) diff = std::max(diff, std::abs(u[r] - ref[r]));
  out << "max |u - u_PSOR| = " << diff << "\n";
  TEST_COMPARE(diff, <=, 1e-8 * tfeti_test::maxAbs(ref));
}

// ---------------------------------------------------------------------------------------------
// 3. Ill-conditioned: 1D diffusion whose coefficient jumps from 1 to 1e4 in the middle.

constexpr GO kIllN = 100;
double illCoef(GO i) {
  return i < kIllN / 2 ? 1.0 : 1e4;
}

double illConditionNumber() {
  std::vector<double> D(kIllN * kIllN, 0.0);
  for (GO i = 0; i < kIllN; ++i) {
    D[i * kIllN + i] = illCoef(i - 1) + illCoef(i);
    if (i + 1 < kIllN) D[i * kIllN + i + 1] = D[(i + 1) * kIllN + i] = -illCoef(i);
  }
  std::vector<double> w(kIllN), work(4 * kIllN);
  int info = 0;
  Teuchos::LAPACK<int, double>().SYEV('N', 'U', kIllN, D.data(), kIllN, w.data(), work.data(),
                                      static_cast<int>(work.size()), &info);
  return info == 0 ? w.back() / w.front() : 0.0;
}

TEUCHOS_UNIT_TEST(Mprgp, IllConditioned) {
  const double cond = illConditionNumber();
  out << "condition number " << cond << "\n";
  TEST_COMPARE(cond, >=, 1e6);
  TEST_COMPARE(cond, <=, 1e8);
  auto map = uniformMap(kIllN, world());
  auto A = diffusion1D(map, illCoef);
  auto b = vectorOf(map, [](GO) { return -1.0; });
  // The soft half sags by ~ n^2 / 32 ~ 300; an obstacle at -100 there, none in the stiff half.
  auto lower = vectorOf(map, [](GO i) { return i < kIllN / 2 ? -100.0 + 0.1 * i : -kInf; });
  for (bool preconditioned : {false, true}) {
    auto x = rcp(new Vector(map));
    Teuchos::ParameterList params = mprgpParams(1e-9, 50000);
    params.set("Preconditioning in face", preconditioned);
    Mprgp solver(Qp{A, b, lower, x}, params, rcp(new DiagonalInverse(*A)));
    const Belos::ReturnType solverResult = solver.solve();
    TEST_EQUALITY(solverResult, Belos::Converged);
    const auto& c = solver.counters();
    out << (preconditioned ? "Jacobi in face: " : "plain: ") << c.message << "\n";
    TEST_EQUALITY(c.hessianMultiplications, expectedMultiplications(c, 20));
    const Kkt k = checkKkt(*A, *b, *lower, *x);
    expectKkt(k, 1e-8 * b->norm2(), out, success);
    TEST_COMPARE(k.gapRange, >, 0.0);
  }
}

// ---------------------------------------------------------------------------------------------
// 4. Errors.

using tfeti_test::contains;
using tfeti_test::messageOf;

TEUCHOS_UNIT_TEST(Mprgp, IndefiniteHessianIsReported) {
  // Laplacian with A(5,5) = -10, unconstrained, b = e_5: the first direction is -e_5 with
  // p^T A p = -10.
  auto map = uniformMap(20, world());
  auto A = rcp(new CrsMatrix(map, 3));
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l) {
    const GO i = map->getGlobalElement(l);
    std::vector<GO> cols{i};
    std::vector<double> vals{i == 5 ? -10.0 : 2.0};
    if (i > 0) cols.push_back(i - 1), vals.push_back(-1.0);
    if (i + 1 < 20) cols.push_back(i + 1), vals.push_back(-1.0);
    A->insertGlobalValues(i, Teuchos::arrayViewFromVector(cols),
                          Teuchos::arrayViewFromVector(vals));
  }
  A->fillComplete();
  auto b = vectorOf(map, [](GO i) { return i == 5 ? 1.0 : 0.0; });
  auto lower = vectorOf(map, [](GO) { return -kInf; });
  auto x = rcp(new Vector(map));
  Mprgp solver(Qp{A, b, lower, x}, mprgpParams(1e-8));
  const std::string msg = messageOf([&] { solver.solve(); });
  out << msg << "\n";
  TEST_ASSERT(contains(msg, "not positive definite on the free set"));

  // The same through a proportioning step: from x0 = l = 0 every component is on its bound,
  // only g_5 < 0, so the first step is proportioning along -e_5 with d^T A d = -10.
  auto lower2 = vectorOf(map, [](GO) { return 0.0; });
  auto b2 = vectorOf(map, [](GO i) { return i == 5 ? 1.0 : -1.0; });
  auto x2 = rcp(new Vector(map));
  Mprgp solver2(Qp{A, b2, lower2, x2}, mprgpParams(1e-8));
  const std::string msg2 = messageOf([&] { solver2.solve(); });
  out << msg2 << "\n";
  TEST_ASSERT(contains(msg2, "not positive definite on the free set"));
}

TEUCHOS_UNIT_TEST(Mprgp, NonFiniteDataIsReported) {
  auto p = knownProblem(world(), 30, [](GO i) { return static_cast<int>(i % 4); });
  auto badB = vectorOf(p.b->getMap(), [](GO i) { return i == 17 ? std::nan("") : 1.0; });
  Mprgp s1(Qp{p.A, badB, p.lower, p.x}, mprgpParams(1e-8));
  const std::string m1 = messageOf([&] { s1.solve(); });
  out << m1 << "\n";
  TEST_ASSERT(contains(m1, "right-hand side b contains NaN"));

  auto badX = vectorOf(p.b->getMap(), [](GO i) { return i == 3 ? kInf : 0.0; });
  Mprgp s2(Qp{p.A, p.b, p.lower, badX}, mprgpParams(1e-8));
  const std::string m2 = messageOf([&] { s2.solve(); });
  out << m2 << "\n";
  TEST_ASSERT(contains(m2, "initial guess x contains NaN"));

  auto badL = vectorOf(p.b->getMap(), [](GO i) { return i == 29 ? std::nan("") : -kInf; });
  Mprgp s3(Qp{p.A, p.b, badL, p.x}, mprgpParams(1e-8));
  const std::string m3 = messageOf([&] { s3.solve(); });
  out << m3 << "\n";
  TEST_ASSERT(contains(m3, "lower bounds contain NaN"));
}

TEUCHOS_UNIT_TEST(Mprgp, InvalidParametersAreReported) {
  auto p = knownProblem(world(), 10, [](GO) { return 0; });
  Teuchos::ParameterList bad;
  bad.set("Relative tolerence", 1e-8);
  const std::string m1 = messageOf([&] { Mprgp s(p.qp(), bad); });
  TEST_ASSERT(contains(m1, "Relative tolerence"));
  TEST_ASSERT(contains(m1, "Relative tolerance"));  // Teuchos lists the valid names

  Teuchos::ParameterList badStep;
  badStep.set("Step length factor", 2.5);
  TEST_THROW(Mprgp(p.qp(), badStep), std::invalid_argument);

  Teuchos::ParameterList noPrec;
  noPrec.set("Preconditioning in face", true);
  TEST_THROW(Mprgp(p.qp(), noPrec), std::invalid_argument);

  auto Q = rcp(new SpanProjector(*vectorOf(p.x->getMap(), [](GO) { return 1.0; })));
  Teuchos::ParameterList badSmalbe;
  badSmalbe.set("Penality", 2.0);
  const std::string m2 = messageOf([&] { Smalbe s(p.qp(), Q, badSmalbe); });
  TEST_ASSERT(contains(m2, "Penality"));
  Teuchos::ParameterList badInner;
  badInner.sublist("MPRGP").set("Gama", 1.0);
  const std::string m3 = messageOf([&] { Smalbe s(p.qp(), Q, badInner); });
  TEST_ASSERT(contains(m3, "Gama"));
  out << m1 << "\n" << m2 << "\n" << m3 << "\n";
}

// ---------------------------------------------------------------------------------------------
// 5. SMALBE: bounds and Q x = 0, Q the projector onto span{1, i} (zero sum and zero first
// moment). The solution is known by construction: x* = z - Q z, the kinds of knownProblem for
// the bounds, an equality multiplier mu* = U y in range(Q), and b = A x* + mu* - lambda.

struct EqualityProblem {
  RCP<CrsMatrix> A;
  RCP<SpanProjector> Q;
  RCP<Vector> b, lower, x, exact, exactMu;
  Qp qp() const { return Qp{A, b, lower, x}; }
};

EqualityProblem equalityProblem(const RCP<const tfeti::Comm>& comm, GO n) {
  EqualityProblem p;
  auto map = uniformMap(n, comm);
  p.A = laplacian1D(map);
  MultiVector V(map, 2);
  V.getVectorNonConst(0)->putScalar(1.0);
  V.getVectorNonConst(1)->update(1.0, *vectorOf(map, [](GO i) { return double(i); }), 0.0);
  p.Q = rcp(new SpanProjector(V));
  auto z = vectorOf(map, [](GO i) { return std::sin(0.1 * i) + 0.2 * std::cos(0.37 * i); });
  p.exact = rcp(new Vector(map));
  p.Q->apply(*z, *p.exact);
  p.exact->update(1.0, *z, -1.0);  // z - Q z
  p.exactMu = rcp(new Vector(map));
  p.exactMu->update(2.0, *p.Q->basis().getVector(0), -1.5, *p.Q->basis().getVector(1), 0.0);
  auto xs = p.exact->getData();
  auto kind = [](GO i) { return static_cast<int>(i % 5); };  // 0, 1 free; 2, 3 active; 4 none
  auto lambda = rcp(new Vector(map));
  p.lower = rcp(new Vector(map));
  {
    auto lv = p.lower->getDataNonConst();
    auto mv = lambda->getDataNonConst();
    for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l) {
      const GO i = map->getGlobalElement(l);
      const int k = kind(i);
      lv[l] = k == 4 ? -kInf : (k == 2 || k == 3) ? xs[l] : xs[l] - 0.3;
      mv[l] = k == 2 ? 1.0 + 0.5 * std::sin(double(i)) : 0.0;  // kind 3: degenerate
    }
  }
  p.b = rcp(new Vector(map));
  p.A->apply(*p.exact, *p.b);
  p.b->update(1.0, *p.exactMu, -1.0, *lambda, 1.0);
  p.x = rcp(new Vector(map));
  return p;
}

TEUCHOS_UNIT_TEST(Smalbe, KnownSolutionWithEqualityConstraint) {
  auto p = equalityProblem(world(), 90);
  Smalbe solver(p.qp(), p.Q, smalbeParams(1e-10));
  const Belos::ReturnType solverResult = solver.solve();
  TEST_EQUALITY(solverResult, Belos::Converged);
  const auto& c = solver.counters();
  out << c.message << "\n";
  TEST_ASSERT(c.converged);
  TEST_COMPARE(c.outerIterations, >=, 1);
  TEST_COMPARE(c.hessianMultiplications, >=, c.cgSteps + c.expansionSteps + c.proportioningSteps);
  // One entry per outer iteration, and one for a face solve that ended it.
  const tfeti::FaceCounters& face = solver.faceCounters();
  TEST_COMPARE(c.history.size(), ==,
               static_cast<std::size_t>(c.outerIterations) + (face.accepted ? 1 : 0));
  TEST_COMPARE(c.history.back(), <=, 1e-10);
  // Every multiplication accounted for: the 20 power iterations, the first inner gradient (the
  // later ones reused), one per CG and proportioning step and two per (fixed) expansion step,
  // and per face solve its CG steps plus the gradients at its start and at its final test.
  TEST_EQUALITY(c.hessianMultiplications, 20 + 1 + c.cgSteps + 2 * c.expansionSteps +
                                              c.proportioningSteps + face.iterations +
                                              2 * face.solves);
  // Solution and multiplier: cond(A) ~ 3e3, both tolerances 1e-10 relative.
  const double xScale = p.exact->normInf();
  TEST_COMPARE(maxAbsDiff(*p.x, *p.exact), <=, 1e-6 * xScale);
  TEST_COMPARE(maxAbsDiff(*solver.getMultiplier()->getVector(0), *p.exactMu), <=,
               1e-6 * p.exactMu->normInf());
  // KKT with the multiplier: g = A x - b + mu.
  const auto muView = solver.getMultiplier()->getVector(0);
  const Vector& mu = *muView;
  const Kkt k = checkKkt(*p.A, *p.b, *p.lower, *p.x, &mu, p.Q.get());
  const double bNorm = p.b->norm2();
  expectKkt(k, 1e-9 * bNorm, out, success);
  TEST_COMPARE(solver.getNormOfA() * k.equalityResidual, <=, 1e-10 * bNorm * (1 + 1e-6));
  TEST_COMPARE(c.equalityResidualNorm, ==, k.equalityResidual);
  // mu stays in range(Q).
  Vector qmu(mu.getMap());
  p.Q->apply(mu, qmu);
  TEST_COMPARE(maxAbsDiff(qmu, mu), <=, 1e-12 * mu.normInf());
  TEST_COMPARE(solver.projectorApplications(), >, c.outerIterations);
}

TEUCHOS_UNIT_TEST(Smalbe, ObstacleWithZeroMeanMatchesPenalty) {
  // The obstacle problem with the extra constraint sum u = 0 (Q: projector onto constants) and
  // a load that changes sign (a constant one would give u = 0), against MPRGP on the penalized
  // Hessian A + rho Q with rho = 1e6 ||A|| (error O(1/rho)).
  auto o = obstacle(world(), 15, [](double x, double) { return 60.0 * (x - 0.65); });
  auto ones = vectorOf(o.x->getMap(), [](GO) { return 1.0; });
  auto Q = rcp(new SpanProjector(*ones));
  Smalbe solver(o.qp(), Q, smalbeParams(1e-9));
  const Belos::ReturnType solverResult = solver.solve();
  TEST_EQUALITY(solverResult, Belos::Converged);
  const auto& c = solver.counters();
  out << c.message << "\n";
  TEST_COMPARE(c.hessianMultiplications, >=, c.cgSteps + c.expansionSteps + c.proportioningSteps);
  const auto muView = solver.getMultiplier()->getVector(0);
  const Vector& mu = *muView;
  const Kkt k = checkKkt(*o.A, *o.b, *o.lower, *o.x, &mu, Q.get());
  expectKkt(k, 1e-8 * o.b->norm2(), out, success);
  TEST_COMPARE(k.equalityResidual * solver.getNormOfA(), <=, 1e-9 * o.b->norm2() * (1 + 1e-6));
  TEST_COMPARE(mu.normInf(), >, 0.0);  // the constraint is active
  const Kkt unconstrained = checkKkt(*o.A, *o.b, *o.lower, *o.x);
  TEST_COMPARE(unconstrained.freeGradient, >, 1e-3 * o.b->norm2());  // and matters
  TEST_COMPARE(k.gapRange, >, 0.0);

  const double rho = 1e6 * solver.getNormOfA();
  RCP<const Operator> H =
      tfeti::OperatorSum<double, MultiVector, Operator>::build(o.A, 1.0, Q, rho);
  auto xp = rcp(new Vector(o.x->getMap()));
  Teuchos::ParameterList pp = mprgpParams(1e-13, 200000);
  pp.set("Norm of A", solver.getNormOfA() + rho);
  Mprgp penalty(Qp{H, o.b, o.lower, xp}, pp);
  penalty.solve();  // its precision is limited by cond(H) ~ 1e8; the comparison below decides
  const double diff = maxAbsDiff(*xp, *o.x);
  out << "max |u - u_penalty| = " << diff << " (penalty: " << penalty.counters().message << ")\n";
  TEST_COMPARE(diff, <=, 1e-6 * o.x->normInf());
}

// SMALBE's variants: the Lagrangian test (Dostal / shifted), the reuse of the inner gradient and
// the expansion step change the path, not the solution (SMALBE's own outer loop: "Face solve" =
// none, set explicitly; the face solve last). With the gradient reused, every outer
// iteration after the first saves the initial multiplication of MPRGP. The published test
// reduces M less often than the shifted one.
TEUCHOS_UNIT_TEST(Smalbe, VariantsReachTheSameSolution) {
  auto o = obstacle(world(), 15, [](double x, double) { return 60.0 * (x - 0.65); });
  auto ones = vectorOf(o.x->getMap(), [](GO) { return 1.0; });
  auto Q = rcp(new SpanProjector(*ones));
  struct Run {
    std::vector<double> u;
    tfeti::QpCounters c;
    double M;
    tfeti::FaceCounters face;
  };
  auto run = [&](const std::string& test, bool reuse, const std::string& expansion, double penalty,
                 const std::string& face = "none") {
    Teuchos::ParameterList p = smalbeParams(1e-9);
    p.set("Face solve", face);
    p.set("Lagrangian test", test);
    p.set("Reuse gradient", reuse);
    p.set("Penalty", penalty);
    p.sublist("MPRGP").set("Expansion step", expansion);
    o.x->putScalar(0.0);
    Smalbe solver(o.qp(), Q, p);
    const Belos::ReturnType result = solver.solve();
    const auto muView = solver.getMultiplier()->getVector(0);
    const Kkt k = checkKkt(*o.A, *o.b, *o.lower, *o.x, muView.getRawPtr(), Q.get());
    out << test << (reuse ? ", reuse" : ", no reuse") << ", " << expansion << ", rho/||A|| "
        << penalty << ": " << solver.counters().message << ", "
        << solver.counters().hessianMultiplications << " multiplications, M/||A|| "
        << solver.getM() / solver.getNormOfA() << "\n";
    TEST_EQUALITY(result, Belos::Converged);
    expectKkt(k, 1e-8 * o.b->norm2(), out, success);
    return Run{gatherAll(*o.x), solver.counters(), solver.getM(), solver.faceCounters()};
  };
  const Run ref = run("Dostal", true, "fixed", 1.0);
  const double scale = tfeti_test::maxAbs(ref.u);
  auto same = [&](const Run& r) {
    double d = 0.0;
    for (std::size_t i = 0; i < ref.u.size(); ++i) d = std::max(d, std::abs(r.u[i] - ref.u[i]));
    TEST_COMPARE(d, <=, 1e-6 * scale);
  };
  // 20 power iterations, one per CG and proportioning step, two per (fixed) expansion step, and
  // the initial gradient of every inner solve, or of the first only when it is reused. (The
  // paths themselves may differ in rounding, and with them the discrete choices of MPRGP.)
  auto steps = [](const tfeti::QpCounters& c) {
    return 20 + c.cgSteps + 2 * c.expansionSteps + c.proportioningSteps;
  };
  TEST_EQUALITY(ref.c.hessianMultiplications, steps(ref.c) + 1);
  const Run noReuse = run("Dostal", false, "fixed", 1.0);
  same(noReuse);
  TEST_EQUALITY(noReuse.c.hessianMultiplications, steps(noReuse.c) + noReuse.c.outerIterations);
  const Run shifted = run("shifted", false, "fixed", 1.0);
  same(shifted);
  TEST_COMPARE(ref.M, >=, shifted.M);
  same(run("Dostal", true, "projected CG", 1.0));
  same(run("Dostal", true, "projected CG", 100.0));
  same(run("shifted", false, "fixed", 100.0));
  // The face solve ends at the same solution; its multiplications are its CG
  // steps and two gradients per face solve on top of SMALBE's own.
  const Run face = run("Dostal", true, "fixed", 1.0, "pcpg");
  same(face);
  TEST_ASSERT(face.face.accepted);
  TEST_EQUALITY(face.c.hessianMultiplications,
                steps(face.c) + 1 + face.face.iterations + 2 * face.face.solves);
  TEST_COMPARE(face.c.outerIterations, <, ref.c.outerIterations);
}

// The face solve's stopping rule ("Face relative tolerance") on the obstacle problem with zero
// mean: the face CG's ||P_F g|| is the gradient of the Lagrangian on the free components (what
// FETI's primal residual B u - c is on the rows that hold with equality), so its largest entry
// is below the fraction of SMALBE's tolerance that the parameter sets; a tighter fraction costs
// more face CG steps from the same SMALBE iterate, not outer iterations.
TEUCHOS_UNIT_TEST(Smalbe, FaceToleranceBoundsTheFreeGradient) {
  auto o = obstacle(world(), 15, [](double x, double) { return 60.0 * (x - 0.65); });
  auto ones = vectorOf(o.x->getMap(), [](GO) { return 1.0; });
  auto Q = rcp(new SpanProjector(*ones));
  const double tol = 1e-8, bNorm = o.b->norm2();
  std::vector<tfeti::QpCounters> c;
  std::vector<tfeti::FaceCounters> face;
  for (double fraction : {0.5, 0.01}) {
    Teuchos::ParameterList p = smalbeParams(tol);
    p.set("Face solve", "pcpg");
    p.set("Face relative tolerance", fraction);
    o.x->putScalar(0.0);
    Smalbe solver(o.qp(), Q, p);
    const Belos::ReturnType result = solver.solve();
    c.push_back(solver.counters());
    face.push_back(solver.faceCounters());
    out << "fraction " << fraction << ": " << c.back().message << "\n";
    TEST_EQUALITY(result, Belos::Converged);
    TEST_ASSERT(face.back().accepted);
    const auto muView = solver.getMultiplier()->getVector(0);
    const Kkt k = checkKkt(*o.A, *o.b, *o.lower, *o.x, muView.getRawPtr(), Q.get());
    // The CG's recursive gradient met the bound; the recomputed one differs by rounding.
    expectKkt(k, fraction * tol * bNorm * (1 + 1e-6) + 1e-14 * bNorm, out, success);
    TEST_COMPARE(c.back().history.back(), <=, fraction * tol * (1 + 1e-6) + 1e-14);
  }
  TEST_COMPARE(face[1].iterations, >, face[0].iterations);
  TEST_EQUALITY(c[1].outerIterations, c[0].outerIterations);
  TEST_COMPARE(c[1].history.back(), <, c[0].history.back());
}

// P F P with P = I - Q, the Hessian of a projected dual problem (FETI's P F P).
class Projected : public Operator {
 public:
  Projected(RCP<const Operator> F, RCP<const Operator> Q) : F_(std::move(F)), Q_(std::move(Q)) {}
  RCP<const Map> getDomainMap() const override { return F_->getDomainMap(); }
  RCP<const Map> getRangeMap() const override { return F_->getRangeMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp = Teuchos::NO_TRANS,
             double alpha = 1.0, double beta = 0.0) const override {
    MultiVector px(X, Teuchos::Copy), fpx(X.getMap(), X.getNumVectors());
    Q_->apply(X, px, Teuchos::NO_TRANS, -1.0, 1.0);
    F_->apply(px, fpx);
    Q_->apply(fpx, fpx, Teuchos::NO_TRANS, -1.0, 1.0);
    Y.update(alpha, fpx, beta);
  }

 private:
  RCP<const Operator> F_, Q_;
};

// The face solves' in-face Hessian (setInFaceOperators): on the obstacle problem with zero mean,
// the Hessian P F P with F the Laplacian, the face CG applying F itself (F v - P F P v is in
// range(Q) for Q v = 0) reaches the solution of the CG that applies P F P, in as many
// multiplications.
TEUCHOS_UNIT_TEST(Smalbe, InFaceHessianReachesTheSameSolution) {
  auto o = obstacle(world(), 15, [](double x, double) { return 60.0 * (x - 0.65); });
  auto ones = vectorOf(o.x->getMap(), [](GO) { return 1.0; });
  auto Q = rcp(new SpanProjector(*ones));
  const RCP<const Operator> PFP = rcp(new Projected(o.A, Q));
  std::vector<std::vector<double>> u;
  std::vector<long long> mults;
  for (bool inFace : {false, true}) {
    Teuchos::ParameterList p = smalbeParams(1e-10);
    p.set("Face solve", "pcpg");
    o.x->putScalar(0.0);
    Smalbe solver(Qp{PFP, o.b, o.lower, o.x}, Q, p);
    if (inFace) solver.setInFaceOperators(o.A, Teuchos::null);
    const Belos::ReturnType result = solver.solve();
    out << (inFace ? "in-face F: " : "P F P:     ") << solver.counters().message << "\n";
    TEST_EQUALITY(result, Belos::Converged);
    TEST_ASSERT(solver.faceCounters().accepted);
    TEST_COMPARE(solver.faceCounters().iterations, >, 0);
    const auto muView = solver.getMultiplier()->getVector(0);
    const Kkt k = checkKkt(*PFP, *o.b, *o.lower, *o.x, muView.getRawPtr(), Q.get());
    expectKkt(k, 1e-9 * o.b->norm2(), out, success);
    u.push_back(gatherAll(*o.x));
    mults.push_back(solver.counters().hessianMultiplications);
  }
  const double scale = tfeti_test::maxAbs(u[0]);
  double d = 0.0;
  for (std::size_t i = 0; i < u[0].size(); ++i) d = std::max(d, std::abs(u[1][i] - u[0][i]));
  out << "max |u_F - u_PFP| / max |u| = " << d / scale << "\n";
  TEST_COMPARE(d, <=, 1e-8 * scale);
  TEST_EQUALITY(mults[1], mults[0]);
}

// ---------------------------------------------------------------------------------------------
// 6. The rank count does not change the results: the obstacle problem (MPRGP) and the equality
// problem (SMALBE) on sub-communicators of 1, 2, ..., P ranks.

TEUCHOS_UNIT_TEST(QpSolvers, SameResultsOnEveryRankCount) {
  const auto comm = world();
  std::vector<std::vector<double>> uM, uS;
  std::vector<long long> itM, itS, outerS;
  for (int size = 1; size <= comm->getSize(); ++size) {
    const int rank = comm->getRank();
    auto sub = comm->split(rank < size ? 0 : 1, rank);
    std::vector<double> um, us;
    long long stats[3] = {0, 0, 0};
    if (rank < size) {
      auto o = obstacle(sub);
      Mprgp m(o.qp(), mprgpParams(1e-11));
      m.solve();
      um = gatherAll(*o.x);
      stats[0] = m.getNumIters();
      auto e = equalityProblem(sub, 90);
      Smalbe s(e.qp(), e.Q, smalbeParams(1e-10));
      s.solve();
      us = gatherAll(*e.x);
      stats[1] =
          s.counters().cgSteps + s.counters().expansionSteps + s.counters().proportioningSteps;
      stats[2] = s.counters().outerIterations;
    }
    // Rank 0 takes part in every size: broadcast its results.
    std::size_t nm = um.size(), ns = us.size();
    Teuchos::broadcast(*comm, 0, &nm);
    Teuchos::broadcast(*comm, 0, &ns);
    um.resize(nm);
    us.resize(ns);
    Teuchos::broadcast(*comm, 0, static_cast<int>(nm), um.data());
    Teuchos::broadcast(*comm, 0, static_cast<int>(ns), us.data());
    Teuchos::broadcast(*comm, 0, 3, stats);
    uM.push_back(um);
    uS.push_back(us);
    itM.push_back(stats[0]);
    itS.push_back(stats[1]);
    outerS.push_back(stats[2]);
    out << size << " ranks: MPRGP " << stats[0] << " steps, SMALBE " << stats[2] << " outer / "
        << stats[1] << " inner steps\n";
  }
  for (std::size_t s = 1; s < uM.size(); ++s) {
    TEST_EQUALITY(itM[s], itM[0]);
    TEST_EQUALITY(itS[s], itS[0]);
    TEST_EQUALITY(outerS[s], outerS[0]);
    double dm = 0.0, ds = 0.0;
    for (std::size_t i = 0; i < uM[0].size(); ++i) dm = std::max(dm, std::abs(uM[s][i] - uM[0][i]));
    for (std::size_t i = 0; i < uS[0].size(); ++i) ds = std::max(ds, std::abs(uS[s][i] - uS[0][i]));
    TEST_COMPARE(dm, <=, 1e-12 * tfeti_test::maxAbs(uM[0]));
    TEST_COMPARE(ds, <=, 1e-12 * tfeti_test::maxAbs(uS[0]));
  }
}

}  // namespace
