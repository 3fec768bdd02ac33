// Unit tests of MPRGP and SMALBE with two-sided (box) bounds l <= x <= u, on 1, 2 and 3 ranks:
// a problem with a solution known by construction in which every kind of component occurs (free
// inside a box, lower- or upper-bound active in a box, fixed by l = u, lower-only, upper-only,
// unbounded), solved with every expansion step and with preconditioning in face; a
// reaction-diffusion problem between two obstacles against projected Gauss-Seidel computed here;
// the mirror image of a lower-bound problem; upper bounds that change nothing (null, +infinity,
// far away: the same steps); SMALBE with an equality constraint and a box, also with the face
// solve (a face accepted, a wrong first face corrected, a rejected face handed back to SMALBE);
// bad bounds reported with the component; and identical results on sub-communicators of 1, 2, ...
// ranks. Every solution is checked by the KKT conditions of both sides (tfeti::qpKkt).
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "tfeti_QpChecks.hpp"
#include "tfeti_QpTestHelpers.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

using namespace qp_test;

// The kinds of component of the known problem, with x* the solution and g* = A x* - b + mu*
// the gradient there (the multipliers of the active sides).
enum Kind {
  kBoxFree,       // l = x* - 0.5 < x* < u = x* + 0.3, g* = 0
  kLowerFree,     // l = x* - 0.4, no upper bound, g* = 0
  kUnbounded,     // no bounds, g* = 0
  kBoxAtLower,    // l = x* < u = x* + 0.7, g* = 1 + 0.5 sin i > 0
  kBoxAtUpper,    // l = x* - 0.6 < u = x*, g* = -(1 + 0.5 cos i) < 0
  kFixed,         // l = u = x*, g* = 2 sin 3i of either sign
  kUpperAtUpper,  // no lower bound, u = x*, g* = -(0.5 + 0.25 sin i)
  kLowerAtLower,  // l = x*, no upper bound, g* = 0.8
  kNumKinds
};

// Every kind, interleaved irregularly over the indices (so that each rank holds several).
int mixedKind(GO i) {
  return static_cast<int>((5 * i + i / 8) % kNumKinds);
}

struct BoxProblem {
  RCP<CrsMatrix> A;
  RCP<Vector> b, lower, upper, x, exact, exactMu;
  Qp qp() const {
    Qp q{A, b, lower, x};
    q.upper = upper;
    return q;
  }
  Kkt kkt(const Vector* mu = nullptr, const Operator* Q = nullptr) const {
    return tfeti::qpKkt(*A, *b, *lower, upper.getRawPtr(), *x, mu, Q);
  }
};

// The known problem on the 1D Laplacian: x*_i = sin(0.1 i) + 0.2 cos(0.37 i) minus its mean
// when zeroMean (for SMALBE with Q = the projector onto constants), the bounds and g* of
// kind(i), mu* = muConstant * (1, ..., 1) and b = A x* + mu* - g*.
BoxProblem knownBoxProblem(const RCP<const tfeti::Comm>& comm, GO n,
                           const std::function<int(GO)>& kind, bool zeroMean = false,
                           double muConstant = 0.0) {
  auto f = [](GO i) { return std::sin(0.1 * i) + 0.2 * std::cos(0.37 * i); };
  double mean = 0.0;
  if (zeroMean) {
    for (GO i = 0; i < n; ++i) mean += f(i);
    mean /= static_cast<double>(n);
  }
  auto xs = [&](GO i) { return f(i) - mean; };
  auto gs = [&](GO i) {
    switch (kind(i)) {
      case kBoxAtLower:
        return 1.0 + 0.5 * std::sin(i);
      case kBoxAtUpper:
        return -(1.0 + 0.5 * std::cos(i));
      case kFixed:
        return 2.0 * std::sin(3.0 * i);
      case kUpperAtUpper:
        return -(0.5 + 0.25 * std::sin(i));
      case kLowerAtLower:
        return 0.8;
      default:
        return 0.0;
    }
  };
  auto lowerOf = [&](GO i) {
    switch (kind(i)) {
      case kBoxFree:
        return xs(i) - 0.5;
      case kLowerFree:
        return xs(i) - 0.4;
      case kBoxAtUpper:
        return xs(i) - 0.6;
      case kUnbounded:
      case kUpperAtUpper:
        return -kInf;
      default:
        return xs(i);
    }
  };
  auto upperOf = [&](GO i) {
    switch (kind(i)) {
      case kBoxFree:
        return xs(i) + 0.3;
      case kBoxAtLower:
        return xs(i) + 0.7;
      case kBoxAtUpper:
      case kFixed:
      case kUpperAtUpper:
        return xs(i);
      default:
        return kInf;
    }
  };
  BoxProblem p;
  auto map = uniformMap(n, comm);
  p.A = laplacian1D(map);
  p.exact = vectorOf(map, xs);
  p.exactMu = vectorOf(map, [&](GO) { return muConstant; });
  p.lower = vectorOf(map, lowerOf);
  p.upper = vectorOf(map, upperOf);
  p.b = rcp(new Vector(map));
  p.A->apply(*p.exact, *p.b);
  p.b->update(1.0, *p.exactMu, -1.0, *vectorOf(map, gs), 1.0);
  p.x = rcp(new Vector(map));  // 0, projected onto the box by the solver
  return p;
}

// How many components sit exactly on their lower / upper bound (l < u), or are fixed (l = u).
struct ActiveCounts {
  double atLower = 0, atUpper = 0, fixed = 0;
};

ActiveCounts activeCounts(const BoxProblem& p) {
  const auto x = gatherAll(*p.x), l = gatherAll(*p.lower), u = gatherAll(*p.upper);
  ActiveCounts c;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (l[i] == u[i])
      c.fixed += 1;
    else if (x[i] == l[i])
      c.atLower += 1;
    else if (x[i] == u[i])
      c.atUpper += 1;
  }
  return c;
}

// MPRGP with the given expansion step to relative tolerance tol; prints the step counts.
Belos::ReturnType solveWith(const BoxProblem& p, double tol, const std::string& expansion,
                            Teuchos::FancyOStream& out) {
  Teuchos::ParameterList params = mprgpParams(tol);
  params.set("Expansion step", expansion);
  Mprgp solver(p.qp(), params);
  const Belos::ReturnType result = solver.solve();
  const auto& c = solver.counters();
  out << expansion << ": " << c.message << "; " << c.cgSteps << " CG, " << c.expansionSteps
      << " expansion, " << c.proportioningSteps << " proportioning\n";
  return result;
}

// The bound KKT conditions with the tolerances of a solve to relative precision tol (the
// gradient within 10 tol ||b||), and the solution within 1e-6 of the known one (cond(A) ~ 3e3).
void expectKnownSolution(const BoxProblem& p, double tol, Teuchos::FancyOStream& out,
                         bool& success) {
  expectKkt(p.kkt(), 10 * tol * p.b->norm2(), out, success);
  const double err = maxAbsDiff(*p.x, *p.exact);
  out << "max |x - x*| = " << err << "\n";
  TEST_COMPARE(err, <=, 1e-6 * p.exact->normInf());
}

// ---------------------------------------------------------------------------------------------
// 1. The known problem: every kind of component, every expansion step, preconditioning in face.

TEUCHOS_UNIT_TEST(BoxQp, KnownSolutionWithEveryKindOfComponent) {
  for (const std::string expansion : {"fixed", "optimal", "projected CG"}) {
    auto p = knownBoxProblem(world(), 96, mixedKind);
    p.x->putScalar(1.5);  // above many upper bounds: projected onto the box first
    const Belos::ReturnType result = solveWith(p, 1e-10, expansion, out);
    TEST_EQUALITY(result, Belos::Converged);  // evaluated twice: not the solve itself
    expectKnownSolution(p, 1e-10, out, success);
    // Every kind is present, and the solver found each active side exactly.
    const ActiveCounts a = activeCounts(p);
    TEST_EQUALITY(a.atLower, 24.0);  // kBoxAtLower and kLowerAtLower: 12 each of 96
    TEST_EQUALITY(a.atUpper, 24.0);  // kBoxAtUpper and kUpperAtUpper
    TEST_EQUALITY(a.fixed, 12.0);
  }
}

TEUCHOS_UNIT_TEST(BoxQp, PreconditioningInFace) {
  // A scaled copy of the known problem (rows and columns scaled by D): Jacobi in face.
  auto p = knownBoxProblem(world(), 96, mixedKind);
  auto d = vectorOf(p.x->getMap(), [](GO i) { return 1.0 + 0.5 * (i % 3); });
  // A' = D A D, x' = D^{-1} x: bounds l' = D^{-1} l, u' = D^{-1} u, b' = D b.
  auto As = laplacian1D(p.x->getMap());
  As->leftScale(*d);
  As->rightScale(*d);
  auto dinv = rcp(new Vector(*d, Teuchos::Copy));
  dinv->reciprocal(*d);
  auto scaled = [](const Vector& s, const Vector& v) {
    auto r = rcp(new Vector(v.getMap()));
    r->elementWiseMultiply(1.0, s, v, 0.0);
    return r;
  };
  BoxProblem q = p;
  q.A = As;
  q.b = scaled(*d, *p.b);
  q.lower = scaled(*dinv, *p.lower);
  q.upper = scaled(*dinv, *p.upper);
  q.exact = scaled(*dinv, *p.exact);
  q.x = rcp(new Vector(p.x->getMap()));
  Teuchos::ParameterList params = mprgpParams(1e-10, 100000);
  params.set("Preconditioning in face", true);
  Mprgp solver(q.qp(), params, rcp(new DiagonalInverse(*As)));
  const Belos::ReturnType result = solver.solve();
  out << solver.counters().message << "\n";
  TEST_EQUALITY(result, Belos::Converged);
  expectKkt(q.kkt(), 1e-9 * q.b->norm2(), out, success);
  // Back in the original variables x = D x'.
  const double err = maxAbsDiff(*scaled(*d, *q.x), *p.exact);
  out << "max |D x' - x*| = " << err << "\n";
  // cond(D A D) <= 16 cond(A).
  TEST_COMPARE(err, <=, 1.6e-5 * p.exact->normInf());
  TEST_COMPARE(solver.counters().cgSteps, >, 0);
}

// Degenerate boxes only: x = l = u at once, with no step at all.
TEUCHOS_UNIT_TEST(BoxQp, EveryComponentFixed) {
  auto p = knownBoxProblem(world(), 30, [](GO) { return kFixed; });
  p.x->putScalar(-3.0);
  Mprgp solver(p.qp(), mprgpParams(1e-12));
  const Belos::ReturnType result = solver.solve();
  TEST_EQUALITY(result, Belos::Converged);
  TEST_EQUALITY(maxAbsDiff(*p.x, *p.exact), 0.0);
  TEST_EQUALITY(solver.getNumIters(), 0);
  TEST_EQUALITY(solver.counters().projectedGradientNorm, 0.0);
}

// Narrow boxes [0, 0.01] and a load of +-10 on alternate components, from x = 0: the chopped
// gradient -10 at the even components (on their lower bounds) makes a proportioning step whose
// minimizing length (0.5) would carry them 500 times past their upper bounds. It must stop at
// the upper bounds (length 0.001), which is the solution: x = u on even, l on odd components.
TEUCHOS_UNIT_TEST(BoxQp, ProportioningStepStopsAtTheOtherBound) {
  auto map = uniformMap(50, world());
  BoxProblem p;
  p.A = laplacian1D(map);
  p.b = vectorOf(map, [](GO i) { return i % 2 == 0 ? 10.0 : -10.0; });
  p.lower = vectorOf(map, [](GO) { return 0.0; });
  p.upper = vectorOf(map, [](GO) { return 0.01; });
  p.x = rcp(new Vector(map));
  Mprgp solver(p.qp(), mprgpParams(1e-12));
  const Belos::ReturnType result = solver.solve();
  out << solver.counters().message << "\n";
  TEST_EQUALITY(result, Belos::Converged);
  TEST_EQUALITY(solver.counters().proportioningSteps, 1);
  TEST_EQUALITY(solver.getNumIters(), 1);
  expectKkt(p.kkt(), 1e-12 * p.b->norm2(), out, success);
  auto exact = vectorOf(map, [](GO i) { return i % 2 == 0 ? 0.01 : 0.0; });
  TEST_EQUALITY(maxAbsDiff(*p.x, *exact), 0.0);
}

// ---------------------------------------------------------------------------------------------
// 2. Between two obstacles: reaction-diffusion -(c u')' + r u = f with a load that changes sign,
// components of every kind (lower-only, boxed, free, upper-only, fixed), against projected
// Gauss-Seidel.

constexpr GO kBandN = 120;

struct BandBounds {
  double lower, upper;
};

BandBounds bandBounds(GO i) {
  switch (i % 5) {
    case 0:
      return {-0.5, kInf};
    case 1:
      return {-0.6, 0.4};
    case 2:
      return {-0.3, 0.5};
    case 3:
      return {-kInf, kInf};
    default:
      return i % 10 == 4 ? BandBounds{0.1 * std::cos(i), 0.1 * std::cos(i)}
                         : BandBounds{-kInf, 0.45};
  }
}

double bandCoef(GO i) {
  return 1.0 + 0.5 * std::sin(0.3 * i);
}
constexpr double kBandReaction = 0.5;
double bandLoad(GO i) {
  return 1.2 * std::sin(4.0 * M_PI * i / kBandN) + 0.2;
}

BoxProblem bandProblem(const RCP<const tfeti::Comm>& comm) {
  BoxProblem p;
  auto map = uniformMap(kBandN, comm);
  auto A = diffusion1D(map, bandCoef);
  auto shift = vectorOf(map, [](GO) { return kBandReaction; });
  auto diag = rcp(new Vector(map));
  A->getLocalDiagCopy(*diag);
  diag->update(1.0, *shift, 1.0);
  A->resumeFill();
  auto dv = diag->getData();
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l) {
    const GO i = map->getGlobalElement(l);
    A->replaceGlobalValues(i, Teuchos::tuple<GO>(i), Teuchos::tuple<double>(dv[l]));
  }
  A->fillComplete();
  p.A = A;
  p.b = vectorOf(map, bandLoad);
  p.lower = vectorOf(map, [](GO i) { return bandBounds(i).lower; });
  p.upper = vectorOf(map, [](GO i) { return bandBounds(i).upper; });
  p.x = rcp(new Vector(map));
  return p;
}

// Projected Gauss-Seidel on the whole (serial) problem: x_i = clamp((b_i - sum_{j != i} a_ij
// x_j) / a_ii, l_i, u_i), swept until no entry changes by more than 1e-15 max|x| (its rate is
// about (2 max c / (2 min c + r))^2 < 1: the error is then below 1e-13 max|x|).
std::vector<double> projectedGaussSeidel() {
  const GO n = kBandN;
  std::vector<double> x(n, 0.0);
  for (int sweep = 0; sweep < 100000; ++sweep) {
    double change = 0.0;
    for (GO i = 0; i < n; ++i) {
      const double cl = bandCoef(i - 1), cr = bandCoef(i);
      double r = bandLoad(i);
      if (i > 0) r += cl * x[i - 1];
      if (i + 1 < n) r += cr * x[i + 1];
      const double next = std::min(std::max(r / (cl + cr + kBandReaction), bandBounds(i).lower),
                                   bandBounds(i).upper);
      change = std::max(change, std::abs(next - x[i]));
      x[i] = next;
    }
    if (change <= 1e-15 * tfeti_test::maxAbs(x)) break;
  }
  return x;
}

void expectMatchesGaussSeidel(const BoxProblem& p, double tol, Teuchos::FancyOStream& out,
                              bool& success) {
  const std::vector<double> ref = projectedGaussSeidel();
  auto refVec = vectorOf(p.x->getMap(), [&](GO i) { return ref[i]; });
  // The reference's own KKT conditions, so that a wrong reference cannot pass.
  expectKkt(tfeti::qpKkt(*p.A, *p.b, *p.lower, p.upper.getRawPtr(), *refVec), 1e-13 * p.b->norm2(),
            out, success);
  expectKkt(p.kkt(), 10 * tol * p.b->norm2(), out, success);
  const double diff = maxAbsDiff(*p.x, *refVec);
  out << "max |x - x_PGS| = " << diff << "\n";
  // ||A^{-1}|| <= 1 / r = 2, times ||g^P|| <= tol ||b||.
  TEST_COMPARE(diff, <=, 2.0 * 10 * tol * p.b->norm2());
}

TEUCHOS_UNIT_TEST(BoxQp, BetweenTwoObstaclesMatchesProjectedGaussSeidel) {
  for (const std::string expansion : {"fixed", "optimal", "projected CG"}) {
    auto p = bandProblem(world());
    const Belos::ReturnType result = solveWith(p, 1e-12, expansion, out);
    TEST_EQUALITY(result, Belos::Converged);  // evaluated twice: not the solve itself
    expectMatchesGaussSeidel(p, 1e-12, out, success);
    const ActiveCounts a = activeCounts(p);
    out << a.atLower << " at lower, " << a.atUpper << " at upper, " << a.fixed << " fixed\n";
    // A genuine two-sided problem: both obstacles touched, most components free.
    TEST_COMPARE(a.atLower, >=, 5.0);
    TEST_COMPARE(a.atUpper, >=, 5.0);
    TEST_EQUALITY(a.fixed, 12.0);
    TEST_COMPARE(a.atLower + a.atUpper + a.fixed, <, 0.8 * kBandN);
  }
}

// ---------------------------------------------------------------------------------------------
// 3. Paths: an upper-bound problem is the mirror image of a lower-bound one (x -> -x), and
// upper bounds that cannot be reached do not change a single step.

TEUCHOS_UNIT_TEST(BoxQp, UpperBoundsMirrorLowerBounds) {
  auto p =
      knownBoxProblem(world(), 90, [](GO i) { return i % 3 == 0 ? kLowerAtLower : kLowerFree; });
  p.upper = Teuchos::null;
  Mprgp lowerSolver(p.qp(), mprgpParams(1e-11));
  lowerSolver.solve();
  // min 1/2 y^T A y + b^T y subject to y <= -l: y = -x.
  BoxProblem m = p;
  m.b = rcp(new Vector(*p.b, Teuchos::Copy));
  m.b->scale(-1.0);
  m.upper = rcp(new Vector(*p.lower, Teuchos::Copy));
  m.upper->scale(-1.0);
  m.lower = vectorOf(p.x->getMap(), [](GO) { return -kInf; });
  m.x = rcp(new Vector(p.x->getMap()));
  Mprgp upperSolver(m.qp(), mprgpParams(1e-11));
  const Belos::ReturnType result = upperSolver.solve();
  TEST_EQUALITY(result, Belos::Converged);
  expectKkt(m.kkt(), 1e-10 * m.b->norm2(), out, success);
  const auto& a = lowerSolver.counters();
  const auto& b = upperSolver.counters();
  out << "lower: " << a.message << "\nupper: " << b.message << "\n";
  TEST_EQUALITY(b.cgSteps, a.cgSteps);
  TEST_EQUALITY(b.expansionSteps, a.expansionSteps);
  TEST_EQUALITY(b.proportioningSteps, a.proportioningSteps);
  TEST_EQUALITY(b.hessianMultiplications, a.hessianMultiplications);
  Vector sum(*m.x, Teuchos::Copy);
  sum.update(1.0, *p.x, 1.0);
  TEST_COMPARE(sum.normInf(), <=, 1e-14 * p.x->normInf());
}

TEUCHOS_UNIT_TEST(BoxQp, UnreachableUpperBoundsChangeNoStep) {
  // The lower-bound problem of the known solution (kinds without an upper bound), solved with
  // no upper vector, with +infinity and with upper bounds far above the solution.
  auto kind = [](GO i) {
    return i % 3 == 0 ? kLowerAtLower : i % 3 == 1 ? kLowerFree : kUnbounded;
  };
  struct Run {
    tfeti::QpCounters c;
    std::vector<double> x;
  };
  auto run = [&](const std::function<RCP<Vector>(const RCP<const Map>&)>& upper) {
    auto p = knownBoxProblem(world(), 90, kind);
    p.upper = upper(p.x->getMap());
    Teuchos::ParameterList params = mprgpParams(1e-11);
    params.set("Expansion step", "projected CG");
    Mprgp solver(p.qp(), params);
    solver.solve();
    return Run{solver.counters(), gatherAll(*p.x)};
  };
  const Run none = run([](const RCP<const Map>&) { return RCP<Vector>(); });
  const Run inf =
      run([](const RCP<const Map>& map) { return vectorOf(map, [](GO) { return kInf; }); });
  const Run far =
      run([](const RCP<const Map>& map) { return vectorOf(map, [](GO) { return 1e6; }); });
  out << none.c.message << "\n";
  TEST_ASSERT(none.c.converged);
  for (const Run* r : {&inf, &far}) {
    TEST_EQUALITY(r->c.cgSteps, none.c.cgSteps);
    TEST_EQUALITY(r->c.expansionSteps, none.c.expansionSteps);
    TEST_EQUALITY(r->c.proportioningSteps, none.c.proportioningSteps);
    TEST_EQUALITY(r->c.hessianMultiplications, none.c.hessianMultiplications);
    TEST_ASSERT(r->x == none.x);  // bit for bit
  }
}

// ---------------------------------------------------------------------------------------------
// 4. SMALBE: the known problem with sum x = 0 (Q: the projector onto constants) and a box.

TEUCHOS_UNIT_TEST(BoxQp, SmalbeEqualityConstraintAndBox) {
  for (const std::string expansion : {"fixed", "projected CG"}) {
    auto p = knownBoxProblem(world(), 96, mixedKind, true, 0.7);
    auto Q = rcp(new SpanProjector(*vectorOf(p.x->getMap(), [](GO) { return 1.0; })));
    Teuchos::ParameterList params = smalbeParams(1e-10);
    params.sublist("MPRGP").set("Expansion step", expansion);
    Smalbe solver(p.qp(), Q, params);
    const Belos::ReturnType result = solver.solve();
    const auto& c = solver.counters();
    out << expansion << ": " << c.message << "\n";
    TEST_EQUALITY(result, Belos::Converged);
    const auto muView = solver.getMultiplier()->getVector(0);
    const Kkt k = p.kkt(muView.getRawPtr(), Q.get());
    const double bNorm = p.b->norm2();
    expectKkt(k, 1e-9 * bNorm, out, success);
    TEST_COMPARE(solver.getNormOfA() * k.equalityResidual, <=, 1e-10 * bNorm * (1 + 1e-6));
    TEST_COMPARE(maxAbsDiff(*p.x, *p.exact), <=, 1e-6 * p.exact->normInf());
    TEST_COMPARE(maxAbsDiff(*muView, *p.exactMu), <=, 1e-6 * p.exactMu->normInf());
    const ActiveCounts a = activeCounts(p);
    TEST_EQUALITY(a.atLower, 24.0);
    TEST_EQUALITY(a.atUpper, 24.0);
  }
}

// ---------------------------------------------------------------------------------------------
// 5. Bad bounds: the same error on every rank, naming the component.

TEUCHOS_UNIT_TEST(BoxQp, BadBoundsAreReported) {
  auto comm = world();
  auto p = knownBoxProblem(comm, 40, mixedKind);
  auto messageWithUpper = [&](RCP<Vector> upper) {
    return tfeti_test::messageOf([&] {
      BoxProblem q = p;
      q.upper = upper;
      Mprgp solver(q.qp(), mprgpParams(1e-8));
      solver.solve();
    });
  };
  auto withEntry = [&](GO index, double value) {
    auto u = rcp(new Vector(*p.upper, Teuchos::Copy));
    const LO l = u->getMap()->getLocalElement(index);
    if (l != Teuchos::OrdinalTraits<LO>::invalid()) u->getDataNonConst()[l] = value;
    return u;
  };
  std::string m = messageWithUpper(withEntry(27, std::nan("")));
  out << m << "\n";
  TEST_ASSERT(
      tfeti_test::contains(m, "MPRGP: the upper bounds contain NaN or -Inf: component 27 is nan"));
  m = messageWithUpper(withEntry(33, -kInf));
  out << m << "\n";
  TEST_ASSERT(tfeti_test::contains(
      m, "component 33 is -inf (use +Inf for a component without upper bound)"));
  // Component 5 is kLowerFree: l_5 = x*_5 - 0.4 > -2.
  const double l5 = std::sin(0.5) + 0.2 * std::cos(0.37 * 5) - 0.4;
  m = messageWithUpper(withEntry(5, -2.0));
  out << m << "\n";
  std::ostringstream expected;
  expected << "MPRGP: the bounds cross at component 5: lower " << l5 << " > upper -2";
  TEST_ASSERT(tfeti_test::contains(m, expected.str()));
  // SMALBE checks the same before anything else.
  m = tfeti_test::messageOf([&] {
    BoxProblem q = p;
    q.upper = withEntry(5, -2.0);
    auto Q = rcp(new SpanProjector(*vectorOf(p.x->getMap(), [](GO) { return 1.0; })));
    Smalbe solver(q.qp(), Q, smalbeParams(1e-8));
    solver.solve();
  });
  out << m << "\n";
  TEST_ASSERT(tfeti_test::contains(m, expected.str()));
  // An upper bound vector on another map.
  auto shorter = vectorOf(uniformMap(39, comm), [](GO) { return 1.0; });
  m = messageWithUpper(shorter);
  out << m << "\n";
  TEST_ASSERT(tfeti_test::contains(m, "MPRGP: the upper bound vector has 39 entries, x has 40"));
}

// ---------------------------------------------------------------------------------------------
// 6. SMALBE's face solve ("Face solve" = pcpg): once MPRGP has found the active set, PCPG on the
// face with the face's projector; the result is SMALBE's only when it passes the final test.

// SMALBE on the known problem with sum x = 0 and the box, with the face solve.
struct FaceRun {
  BoxProblem p;
  RCP<SpanProjector> Q{};
  Belos::ReturnType result = Belos::Unconverged;
  tfeti::QpCounters c{};
  tfeti::FaceCounters face{};
  RCP<Vector> mu{};
  double normA = 0;
};

FaceRun faceRun(const RCP<const tfeti::Comm>& comm, const Teuchos::ParameterList& extra, double tol,
                Teuchos::FancyOStream& out) {
  FaceRun r{knownBoxProblem(comm, 96, mixedKind, true, 0.7)};
  r.Q = rcp(new SpanProjector(*vectorOf(r.p.x->getMap(), [](GO) { return 1.0; })));
  Teuchos::ParameterList params = smalbeParams(tol);
  params.set("Face solve", "pcpg");
  params.setParameters(extra);
  Smalbe solver(r.p.qp(), r.Q, params);
  r.result = solver.solve();
  r.c = solver.counters();
  r.face = solver.faceCounters();
  r.mu = rcp(new Vector(*solver.getMultiplier()->getVector(0), Teuchos::Copy));
  r.normA = solver.getNormOfA();
  out << r.c.message << "; " << r.c.hessianMultiplications << " multiplications, " << r.face.solves
      << " face solves (" << r.face.iterations << " CG steps), " << r.face.activeSetChanges
      << " active-set changes, accepted " << r.face.accepted << "\n";
  return r;
}

// The KKT conditions of the bound- and equality-constrained problem, and the known x, mu and
// active sides.
void expectKnownFaceSolution(const FaceRun& r, double tol, Teuchos::FancyOStream& out,
                             bool& success) {
  TEST_EQUALITY(r.result, Belos::Converged);
  const double bNorm = r.p.b->norm2();
  const Kkt k = r.p.kkt(r.mu.getRawPtr(), r.Q.get());
  expectKkt(k, tol * bNorm, out, success);
  TEST_COMPARE(r.normA * k.equalityResidual, <=, tol * bNorm);
  TEST_COMPARE(maxAbsDiff(*r.p.x, *r.p.exact), <=, 1e-6 * r.p.exact->normInf());
  TEST_COMPARE(maxAbsDiff(*r.mu, *r.p.exactMu), <=, 1e-6 * r.p.exactMu->normInf());
  const ActiveCounts a = activeCounts(r.p);
  TEST_EQUALITY(a.atLower, 24.0);
  TEST_EQUALITY(a.atUpper, 24.0);
  TEST_EQUALITY(a.fixed, 12.0);
}

TEUCHOS_UNIT_TEST(BoxQp, FaceSolveAfterTheActiveSetSettles) {
  const FaceRun r = faceRun(world(), Teuchos::ParameterList(), 1e-10, out);
  expectKnownFaceSolution(r, 1e-10, out, success);
  // The face solve ended the solve, at its first attempt.
  TEST_ASSERT(r.face.accepted);
  TEST_EQUALITY(r.face.solves, 1);
  TEST_COMPARE(r.face.iterations, >, 0);
  // Fewer multiplications than SMALBE alone on the same problem.
  auto p = knownBoxProblem(world(), 96, mixedKind, true, 0.7);
  auto Q = rcp(new SpanProjector(*vectorOf(p.x->getMap(), [](GO) { return 1.0; })));
  Teuchos::ParameterList aloneParams = smalbeParams(1e-10);
  aloneParams.set("Face solve", "none");
  Smalbe alone(p.qp(), Q, aloneParams);
  alone.solve();
  out << "SMALBE alone: " << alone.counters().hessianMultiplications << " multiplications, "
      << alone.counters().outerIterations << " outer iterations\n";
  TEST_ASSERT(!alone.faceCounters().accepted);
  TEST_EQUALITY(alone.faceCounters().solves, 0);
  TEST_COMPARE(r.c.hessianMultiplications, <, alone.counters().hessianMultiplications);
}

// A face guessed right after the first outer iteration (before the active set has settled) is
// wrong: the active-set step has to correct it, or SMALBE goes on.
Teuchos::ParameterList wrongFirstFace() {
  Teuchos::ParameterList extra;
  extra.set("Face settle iterations", 0);
  return extra;
}

TEUCHOS_UNIT_TEST(BoxQp, WrongFirstFaceIsCorrected) {
  const FaceRun r = faceRun(world(), wrongFirstFace(), 1e-10, out);
  expectKnownFaceSolution(r, 1e-10, out, success);
  TEST_ASSERT(r.face.accepted);
  TEST_COMPARE(r.face.solves, >=, 2);  // the first face was rejected
}

TEUCHOS_UNIT_TEST(BoxQp, RejectedFaceFallsBackToSmalbe) {
  Teuchos::ParameterList extra = wrongFirstFace();
  extra.set("Maximum face solves", 1);
  const FaceRun r = faceRun(world(), extra, 1e-10, out);
  expectKnownFaceSolution(r, 1e-10, out, success);
  TEST_EQUALITY(r.face.solves, 1);
  TEST_ASSERT(!r.face.accepted);  // SMALBE's own iterations converged
}

TEUCHOS_UNIT_TEST(BoxQp, FaceSolveParametersAreValidated) {
  auto p = knownBoxProblem(world(), 16, mixedKind, true, 0.7);
  auto Q = rcp(new SpanProjector(*vectorOf(p.x->getMap(), [](GO) { return 1.0; })));
  Teuchos::ParameterList params = smalbeParams(1e-8);
  params.set("Face solve", "newton");
  TEST_THROW(Smalbe(p.qp(), Q, params), std::exception);
  params.set("Face solve", "pcpg");
  params.set("Face settle iterations", -1);
  TEST_THROW(Smalbe(p.qp(), Q, params), std::exception);
  params.set("Face settle iterations", 1);
  for (double bad : {0.0, -0.1, 1.5}) {
    params.set("Face relative tolerance", bad);
    TEST_THROW(Smalbe(p.qp(), Q, params), std::exception);
  }
  // SMALBE alone is the default (the face CG's multiplier drifts along dependent rows,
  // docs/qp_solvers.md); the face CG stops two orders below SMALBE's tolerance.
  const Teuchos::ParameterList& valid = *Smalbe::getValidParameters();
  TEST_EQUALITY(valid.get<std::string>("Face solve"), "none");
  TEST_EQUALITY(valid.get<double>("Face relative tolerance"), 0.01);
}

// ---------------------------------------------------------------------------------------------
// 7. The rank count does not change the results: the two-obstacle problem (MPRGP) and the box
// problem with an equality constraint (SMALBE) on sub-communicators of 1, 2, ..., P ranks.

TEUCHOS_UNIT_TEST(BoxQp, SameResultsOnEveryRankCount) {
  out << "MPRGP, two obstacles:\n";
  expectSameRuns(onEveryRankCount([](RCP<const tfeti::Comm> sub) {
                   auto p = bandProblem(sub);
                   Mprgp m(p.qp(), mprgpParams(1e-12));
                   m.solve();
                   return rankRun(m.counters(), *p.x);
                 }),
                 out, success);
  out << "SMALBE, equality and box:\n";
  expectSameRuns(onEveryRankCount([](RCP<const tfeti::Comm> sub) {
                   auto p = knownBoxProblem(sub, 96, mixedKind, true, 0.7);
                   auto Q =
                       rcp(new SpanProjector(*vectorOf(p.x->getMap(), [](GO) { return 1.0; })));
                   Smalbe s(p.qp(), Q, smalbeParams(1e-10));
                   s.solve();
                   return rankRun(s.counters(), *p.x);
                 }),
                 out, success);
  out << "SMALBE with the face solve, a wrong first face:\n";
  expectSameRuns(onEveryRankCount([&](RCP<const tfeti::Comm> sub) {
                   const FaceRun r = faceRun(sub, wrongFirstFace(), 1e-10, out);
                   RankRun run = rankRun(r.c, *r.p.x);
                   run.face[0] = r.face.solves;
                   run.face[1] = r.face.iterations;
                   return run;
                 }),
                 out, success);
}

// ---------------------------------------------------------------------------------------------
// 8. "Initial face" = levels: before the first outer iteration, the face is searched among the
// level sets {i : level_i > tau} of levels the caller gives (FETI: the contact rows' gaps), by
// bisection with loose face solves, then solved and corrected like a settled face.

// Lower bounds only, like contact rows: free, at the bound, and unbounded components.
int lowerKind(GO i) {
  static const int kinds[] = {kLowerFree, kLowerAtLower, kUnbounded, kLowerAtLower, kLowerFree};
  return kinds[(3 * i + i / 7) % 5];
}

// Levels that order the face: every component at its bound above every free one.
double orderingLevel(GO i) {
  return lowerKind(i) == kLowerAtLower ? 2.0 + std::sin(1.3 * i) : 0.5 * std::cos(0.7 * i);
}

// Levels like the gaps of a smooth punch pressed into a body by a prescribed depth d: the
// solution's free (contact) components lie below -d/2 (Hertz), the ones at their bound above it.
// Here the lowest level is between -1 and -0.6, so half of it between -0.5 and -0.3.
double indentationLevel(GO i) {
  return lowerKind(i) == kLowerAtLower ? -0.25 + 0.5 * (1 + std::sin(1.3 * i))
                                       : -1.0 + 0.2 * (1 + std::cos(0.7 * i));
}

FaceRun levelRun(const RCP<const tfeti::Comm>& comm, const std::function<double(GO)>& level,
                 Teuchos::FancyOStream& out, const std::string& start = "half lowest") {
  FaceRun r{knownBoxProblem(comm, 96, lowerKind, true, 0.7)};
  r.Q = rcp(new SpanProjector(*vectorOf(r.p.x->getMap(), [](GO) { return 1.0; })));
  Teuchos::ParameterList params = smalbeParams(1e-10);
  params.set("Face solve", "pcpg");
  params.set("Initial face", "levels");
  params.set("Level search start", start);
  Smalbe solver(r.p.qp(), r.Q, params);
  // The unbounded components have no level.
  solver.setFaceLevels(vectorOf(r.p.x->getMap(), [&](GO i) {
    return lowerKind(i) == kUnbounded ? std::numeric_limits<double>::quiet_NaN() : level(i);
  }));
  r.result = solver.solve();
  r.c = solver.counters();
  r.face = solver.faceCounters();
  r.mu = rcp(new Vector(*solver.getMultiplier()->getVector(0), Teuchos::Copy));
  r.normA = solver.getNormOfA();
  out << r.c.message << "; " << r.c.hessianMultiplications << " multiplications, "
      << r.c.outerIterations << " outer iterations\n";
  return r;
}

// KKT, the known x and mu, and the known active set (every kLowerAtLower component at its bound).
void expectKnownLowerSolution(const FaceRun& r, Teuchos::FancyOStream& out, bool& success) {
  TEST_EQUALITY(r.result, Belos::Converged);
  const double bNorm = r.p.b->norm2();
  const Kkt k = r.p.kkt(r.mu.getRawPtr(), r.Q.get());
  expectKkt(k, 1e-10 * bNorm, out, success);
  TEST_COMPARE(r.normA * k.equalityResidual, <=, 1e-10 * bNorm);
  TEST_COMPARE(maxAbsDiff(*r.p.x, *r.p.exact), <=, 1e-6 * r.p.exact->normInf());
  TEST_COMPARE(maxAbsDiff(*r.mu, *r.p.exactMu), <=, 1e-6 * r.p.exactMu->normInf());
  double expected = 0;
  for (GO i = 0; i < 96; ++i) expected += lowerKind(i) == kLowerAtLower ? 1 : 0;
  TEST_EQUALITY(activeCounts(r.p).atLower, expected);
}

TEUCHOS_UNIT_TEST(BoxQp, LevelsThatOrderTheFaceGiveItBeforeAnyOuterIteration) {
  const FaceRun r = levelRun(world(), orderingLevel, out);
  expectKnownLowerSolution(r, out, success);
  TEST_ASSERT(r.face.accepted);
  TEST_EQUALITY(r.c.outerIterations, 0);  // no MPRGP step at all
  TEST_EQUALITY(r.c.cgSteps + r.c.expansionSteps + r.c.proportioningSteps, 0);
  TEST_COMPARE(r.face.levelSolves, >, 0);
  TEST_EQUALITY(r.face.solves, 1);  // the face the bisection found was the solution's
  // (On this 1D Laplacian without a preconditioner the face CG needs more steps than SMALBE's
  // inner solves; the counts on contact problems are in docs/qp_solvers.md.)
}

TEUCHOS_UNIT_TEST(BoxQp, HalfTheLowestLevelIsTheFirstTrialFace) {
  // A prescribed indentation: the first trial face, the levels at or below half the lowest, is
  // the solution's. (Its loose solve, 2 CG steps on this unpreconditioned 1D Laplacian, still
  // shows 4 free rows outside the box, so the search holds 4 more, sees the other side and
  // comes back: 3 level solves.) From the middle the bisection takes 7.
  const FaceRun r = levelRun(world(), indentationLevel, out);
  expectKnownLowerSolution(r, out, success);
  TEST_ASSERT(r.face.accepted);
  TEST_EQUALITY(r.face.solves, 1);
  const FaceRun m = levelRun(world(), indentationLevel, out, "middle");
  expectKnownLowerSolution(m, out, success);
  out << "level solves: half lowest " << r.face.levelSolves << ", middle " << m.face.levelSolves
      << "\n";
  TEST_COMPARE(r.face.levelSolves, <=, 3);
  TEST_COMPARE(r.face.levelSolves, <, m.face.levelSolves);
}

TEUCHOS_UNIT_TEST(BoxQp, HalfTheLowestLevelWalksOutFromAWrongGuess) {
  // Levels that order the face but whose lowest half is far from it (every free component's
  // level below -1, the lowest -5, the bound ones above -1): the count steps from the guess
  // (doubled while the other side is unknown) and the bisection find the face, then it is solved
  // as before.
  const FaceRun r = levelRun(
      world(),
      [](GO i) {
        return lowerKind(i) == kLowerAtLower ? -1.0 + std::sin(1.3 * i) * std::sin(1.3 * i)
                                             : -5.0 + 3.9 * (0.5 + 0.5 * std::cos(0.7 * i));
      },
      out);
  expectKnownLowerSolution(r, out, success);
  TEST_ASSERT(r.face.accepted);
  TEST_COMPARE(r.face.levelSolves, >, 1);
  TEST_EQUALITY(r.face.solves, 1);
}

TEUCHOS_UNIT_TEST(BoxQp, MisleadingLevelsStillConverge) {
  // Levels unrelated to the face: the bisection ends somewhere, the active-set steps and then
  // SMALBE's own iterations finish the solve.
  const FaceRun r = levelRun(
      world(), [](GO i) { return std::sin(1.7 * i); }, out);
  expectKnownLowerSolution(r, out, success);
  TEST_COMPARE(r.face.levelSolves, >, 0);
}

TEUCHOS_UNIT_TEST(BoxQp, OneLevelSearchesNothing) {
  // Every level equal (the two membranes: every gap zero): no information, no level search.
  const FaceRun r = levelRun(
      world(), [](GO) { return 0.0; }, out);
  expectKnownLowerSolution(r, out, success);
  TEST_EQUALITY(r.face.levelSolves, 0);
  TEST_COMPARE(r.c.outerIterations, >, 0);
}

TEUCHOS_UNIT_TEST(BoxQp, InitialFaceParameterIsValidated) {
  auto p = knownBoxProblem(world(), 16, lowerKind, true, 0.7);
  auto Q = rcp(new SpanProjector(*vectorOf(p.x->getMap(), [](GO) { return 1.0; })));
  Teuchos::ParameterList params = smalbeParams(1e-8);
  params.set("Initial face", "gaps");
  TEST_THROW(Smalbe(p.qp(), Q, params), std::exception);
  params.set("Initial face", "levels");
  params.set("Level search start", "hertz");
  TEST_THROW(Smalbe(p.qp(), Q, params), std::exception);
}

TEUCHOS_UNIT_TEST(BoxQp, LevelSearchGivesTheSameResultsOnEveryRankCount) {
  for (auto level :
       {std::function<double(GO)>(orderingLevel), std::function<double(GO)>(indentationLevel),
        std::function<double(GO)>([](GO i) { return std::sin(1.7 * i); })})
    expectSameRuns(onEveryRankCount([&](RCP<const tfeti::Comm> sub) {
                     const FaceRun r = levelRun(sub, level, out);
                     RankRun run = rankRun(r.c, *r.p.x);
                     run.face[0] = r.face.solves + 1000 * r.face.levelSolves;
                     run.face[1] = r.face.iterations;
                     return run;
                   }),
                   out, success);
}

}  // namespace
