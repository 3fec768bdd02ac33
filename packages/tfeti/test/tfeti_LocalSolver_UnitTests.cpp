// Unit tests of the local (subdomain) direct solvers behind tfeti::LocalSolver: CHOLMOD, and
// Amesos2's KLU2 and Tacho. Each factorizes the 5-point 2D Laplacian plus a diagonal shift and
// must solve it to a relative residual below 1e-12, for one and several right-hand sides, and
// after a refactorization. Tacho only runs on small matrices (it segfaults at 5000+ rows in
// Trilinos 13.2, see the pitfalls notes).
#include <Teuchos_UnitTestHarness.hpp>

#include <malloc.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "tfeti_CsrMatrix.hpp"
#include "tfeti_HeapTally.hpp"
#include "tfeti_LocalSolver.hpp"

namespace {

// 5-point Laplacian on a g x g grid of interior points (Dirichlet closure) plus shift * I:
// SPD, n = g * g rows, eigenvalues in (shift, 8 + shift).
tfeti::CsrMatrix laplacian2d(int g, double shift) {
  std::vector<int> ri, ci;
  std::vector<double> v;
  auto add = [&](int i, int j, double a) {
    ri.push_back(i);
    ci.push_back(j);
    v.push_back(a);
  };
  for (int y = 0; y < g; ++y)
    for (int x = 0; x < g; ++x) {
      const int i = y * g + x;
      add(i, i, 4.0 + shift);
      if (x > 0) add(i, i - 1, -1.0);
      if (x + 1 < g) add(i, i + 1, -1.0);
      if (y > 0) add(i, i - g, -1.0);
      if (y + 1 < g) add(i, i + g, -1.0);
    }
  return tfeti::csrFromTriplets(g * g, g * g, ri, ci, v);
}

// The 27-point pattern on a g x g x g grid (a trilinear element's couplings), diagonally
// dominant: SPD, n = g^3 rows; large enough ones make CHOLMOD choose its supernodal kind.
tfeti::CsrMatrix laplacian3d(int g) {
  std::vector<int> ri, ci;
  std::vector<double> v;
  const auto id = [g](int x, int y, int z) { return (z * g + y) * g + x; };
  for (int z = 0; z < g; ++z)
    for (int y = 0; y < g; ++y)
      for (int x = 0; x < g; ++x)
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const int X = x + dx, Y = y + dy, Z = z + dz;
              if (X < 0 || Y < 0 || Z < 0 || X >= g || Y >= g || Z >= g) continue;
              ri.push_back(id(x, y, z));
              ci.push_back(id(X, Y, Z));
              v.push_back(dx || dy || dz ? -0.2 : 6.5);
            }
  return tfeti::csrFromTriplets(g * g * g, g * g * g, ri, ci, v);
}

// Deterministic pseudo-random values in [-1, 1).
std::vector<double> randomVector(std::size_t n, unsigned seed) {
  std::vector<double> x(n);
  unsigned long long s = 0x9E3779B97F4A7C15ull * (seed + 1);
  for (auto& xi : x) {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    xi = static_cast<double>(s >> 11) / static_cast<double>(1ull << 53) * 2.0 - 1.0;
  }
  return x;
}

double norm2(const double* x, int n) {
  double s = 0.0;
  for (int i = 0; i < n; ++i) s += x[i] * x[i];
  return std::sqrt(s);
}

struct Accuracy {
  double residual = 0.0;  // max over columns of ||b - A x|| / ||b||
  double error = 0.0;     // max over columns of ||x - x_true|| / ||x_true||
};

// Solves A X = A X_true for nrhs columns with the factorized solver.
Accuracy solveAndMeasure(tfeti::LocalSolver& solver, const tfeti::CsrMatrix& A, int nrhs,
                         unsigned seed) {
  const int n = A.rows;
  const std::vector<double> xt = randomVector(static_cast<std::size_t>(n) * nrhs, seed);
  std::vector<double> b(xt.size()), x(xt.size(), 0.0), r(n);
  for (int j = 0; j < nrhs; ++j) A.multiply(&xt[std::size_t(j) * n], &b[std::size_t(j) * n]);
  solver.solve(b.data(), x.data(), nrhs);
  Accuracy acc;
  for (int j = 0; j < nrhs; ++j) {
    const double* bj = &b[std::size_t(j) * n];
    const double* xj = &x[std::size_t(j) * n];
    const double* tj = &xt[std::size_t(j) * n];
    A.multiply(xj, r.data());
    for (int i = 0; i < n; ++i) r[i] = bj[i] - r[i];
    acc.residual = std::max(acc.residual, norm2(r.data(), n) / norm2(bj, n));
    for (int i = 0; i < n; ++i) r[i] = xj[i] - tj[i];
    acc.error = std::max(acc.error, norm2(r.data(), n) / norm2(tj, n));
  }
  return acc;
}

// Nonzeros of the lower triangle (with the diagonal): a lower bound of any factor's entries.
std::size_t lowerNnz(const tfeti::CsrMatrix& A) {
  return (A.nnz() + A.rows) / 2;
}

void checkSolver(const std::string& type, int g, Teuchos::FancyOStream& out, bool& success) {
  const tfeti::CsrMatrix A = laplacian2d(g, 1.0);
  out << type << " on the " << g << "x" << g << " Laplacian (n = " << A.rows << ")\n";
  auto solver = tfeti::createLocalSolver(type);
  TEST_EQUALITY(solver->name(), type);
  solver->factorize(A);
  const Accuracy one = solveAndMeasure(*solver, A, 1, 1);
  TEST_COMPARE(one.residual, <, 1e-12);
  TEST_COMPARE(one.error, <, 1e-12);
  // Several right-hand sides in one call, then a different count on the same factorization.
  const Accuracy four = solveAndMeasure(*solver, A, 4, 2);
  TEST_COMPARE(four.residual, <, 1e-12);
  TEST_COMPARE(four.error, <, 1e-12);
  const Accuracy two = solveAndMeasure(*solver, A, 2, 3);
  TEST_COMPARE(two.residual, <, 1e-12);
  const Accuracy oneAgain = solveAndMeasure(*solver, A, 1, 4);
  TEST_COMPARE(oneAgain.residual, <, 1e-12);
  // Refactorization with another (worse conditioned) matrix of the same pattern on the same
  // object: the old factor must not be used.
  const tfeti::CsrMatrix A2 = laplacian2d(g, 1e-2);
  solver->factorize(A2);
  const Accuracy second = solveAndMeasure(*solver, A2, 3, 5);
  TEST_COMPARE(second.residual, <, 1e-12);
  TEST_COMPARE(second.error, <, 1e-10);
}

}  // namespace

TEUCHOS_UNIT_TEST(LocalSolver, TypesAreCholmodKlu2Tacho) {
  const std::vector<std::string> expected{"cholmod", "cholmod-simplicial", "cholmod-supernodal",
                                          "klu2", "tacho"};
  TEST_COMPARE_ARRAYS(tfeti::localSolverTypes(), expected);
}

TEUCHOS_UNIT_TEST(LocalSolver, CholmodSmall) {
  checkSolver("cholmod", 20, out, success);
}
TEUCHOS_UNIT_TEST(LocalSolver, CholmodLarge) {
  checkSolver("cholmod", 55, out, success);
}
// The forced kinds, each on the size where CHOLMOD's own flops / nnz(L) rule is the more likely
// to choose the other kind (simplicial on the large grid, supernodal on the small one).
TEUCHOS_UNIT_TEST(LocalSolver, CholmodSimplicialLarge) {
  checkSolver("cholmod-simplicial", 55, out, success);
}
TEUCHOS_UNIT_TEST(LocalSolver, CholmodSupernodalSmall) {
  checkSolver("cholmod-supernodal", 20, out, success);
}
TEUCHOS_UNIT_TEST(LocalSolver, Klu2Small) {
  checkSolver("klu2", 20, out, success);
}
TEUCHOS_UNIT_TEST(LocalSolver, Klu2Large) {
  checkSolver("klu2", 55, out, success);
}
TEUCHOS_UNIT_TEST(LocalSolver, TachoSmall) {
  checkSolver("tacho", 20, out, success);
}
TEUCHOS_UNIT_TEST(LocalSolver, TachoMedium) {
  checkSolver("tacho", 30, out, success);
}

TEUCHOS_UNIT_TEST(LocalSolver, OneByOneAndTinySystems) {
  // The smallest systems a subdomain (or a coarse problem) can produce.
  for (const auto& type : tfeti::localSolverTypes()) {
    const tfeti::CsrMatrix one = tfeti::csrFromTriplets(1, 1, {0}, {0}, {4.0});
    auto s = tfeti::createLocalSolver(type);
    s->factorize(one);
    double b = 2.0, x = 0.0;
    s->solve(&b, &x, 1);
    TEST_FLOATING_EQUALITY(x, 0.5, 1e-15);
    const tfeti::CsrMatrix A = laplacian2d(2, 0.5);
    s->factorize(A);
    const Accuracy acc = solveAndMeasure(*s, A, 3, 7);
    TEST_COMPARE(acc.residual, <, 1e-14);
  }
}

TEUCHOS_UNIT_TEST(LocalSolver, UnknownTypeThrowsListingValidNames) {
  bool threw = false;
  try {
    tfeti::createLocalSolver("mumps");
  } catch (const std::invalid_argument& e) {
    threw = true;
    const std::string msg = e.what();
    out << "message: " << msg << "\n";
    TEST_INEQUALITY(msg.find("\"mumps\""), std::string::npos);
    for (const auto& t : tfeti::localSolverTypes()) TEST_INEQUALITY(msg.find(t), std::string::npos);
  }
  TEST_ASSERT(threw);
  TEST_THROW(tfeti::createLocalSolver(""), std::invalid_argument);
  TEST_THROW(tfeti::createLocalSolver("KLU2"), std::invalid_argument);  // names are lower case
}

// ------------------------------------------------------------------------------------------
// The interface's contract beyond solving: a solver object can be refactorized with a matrix of
// another size, factor sizes are reported (they are what the benchmarks measure), and a matrix
// that is not positive definite is refused (a wrongly regularized subdomain must not be solved
// silently).

// One solver object reused for matrices of different sizes (smaller, then larger), with the
// same number of right-hand sides each time: factorize() may be called again (the interface
// does not restrict it to one size).
void checkRefactorizeWithAnotherSize(const std::string& type, Teuchos::FancyOStream& out,
                                     bool& success) {
  auto s = tfeti::createLocalSolver(type);
  for (int g : {12, 7, 16}) {
    const tfeti::CsrMatrix A = laplacian2d(g, 0.5);
    s->factorize(A);
    const Accuracy acc = solveAndMeasure(*s, A, 2, static_cast<unsigned>(g));
    out << type << ", n = " << A.rows << ": residual " << acc.residual << "\n";
    TEST_COMPARE(acc.residual, <, 1e-12);
  }
}

TEUCHOS_UNIT_TEST(LocalSolver, CholmodRefactorizeWithAnotherSize) {
  checkRefactorizeWithAnotherSize("cholmod", out, success);
}
TEUCHOS_UNIT_TEST(LocalSolver, Klu2RefactorizeWithAnotherSize) {
  checkRefactorizeWithAnotherSize("klu2", out, success);
}
TEUCHOS_UNIT_TEST(LocalSolver, TachoRefactorizeWithAnotherSize) {
  checkRefactorizeWithAnotherSize("tacho", out, success);
}

TEUCHOS_UNIT_TEST(LocalSolver, FactorBytesAtLeastTheLowerTriangle) {
  // Any factor of A holds at least the values of its lower triangle (for the 2D Laplacian with
  // nested dissection, several times more).
  // Amesos2's Tacho adapter does not report its factor size, so Tacho is left out.
  for (const std::string type : {"cholmod", "cholmod-simplicial", "cholmod-supernodal", "klu2"}) {
    const tfeti::CsrMatrix A = laplacian2d(20, 1.0);
    auto s = tfeti::createLocalSolver(type);
    TEST_EQUALITY(s->factorBytes(), std::size_t(0));  // nothing factorized yet
    s->factorize(A);
    out << type << ": factorBytes = " << s->factorBytes() << "\n";
    TEST_COMPARE(s->factorBytes(), >=, lowerNnz(A) * sizeof(double));
  }
}

TEUCHOS_UNIT_TEST(LocalSolver, CholmodRejectsIndefiniteMatrixNamingItself) {
  // Symmetric but indefinite: the Laplacian minus 10 I. Every kind keeps L L^T (an L D L^T
  // factorization would accept it).
  const tfeti::CsrMatrix A = laplacian2d(5, -10.0);
  for (const std::string type : {"cholmod", "cholmod-simplicial", "cholmod-supernodal"}) {
    auto s = tfeti::createLocalSolver(type);
    bool threw = false;
    try {
      s->factorize(A);
    } catch (const std::runtime_error& e) {
      threw = true;
      out << type << " message: " << e.what() << "\n";
      TEST_INEQUALITY(std::string(e.what()).find("cholmod"), std::string::npos);
    }
    TEST_ASSERT(threw);
    // The same object is usable again after the failure.
    const tfeti::CsrMatrix B = laplacian2d(5, 1.0);
    s->factorize(B);
    TEST_COMPARE(solveAndMeasure(*s, B, 2, 9).residual, <, 1e-12);
  }
}

// ------------------------------------------------------------------------------------------
// CHOLMOD's factors of one sparsity pattern share its symbolic analysis while any of them is
// alive (subdomains of a structured mesh repeat a few patterns). Sharing must change nothing
// but the work: the same solution, bitwise, as a factor that made its own analysis.

namespace {

std::vector<double> solveOnce(tfeti::LocalSolver& s, const tfeti::CsrMatrix& A, unsigned seed) {
  const std::vector<double> b = randomVector(static_cast<std::size_t>(A.rows), seed);
  std::vector<double> x(b.size());
  s.solve(b.data(), x.data(), 1);
  return x;
}

}  // namespace

TEUCHOS_UNIT_TEST(LocalSolver, CholmodFactorsOfOnePatternShareTheAnalysis) {
  for (const std::string type : {"cholmod", "cholmod-simplicial", "cholmod-supernodal"}) {
    out << type << "\n";
    const tfeti::CsrMatrix A1 = laplacian2d(24, 1.0), A2 = laplacian2d(24, 1e-2);
    const tfeti::CsrMatrix other = laplacian2d(25, 1.0);
    const tfeti::LocalAnalysisCounts start = tfeti::localAnalysisCounts();
    std::vector<double> shared;
    {
      auto first = tfeti::createLocalSolver(type), second = tfeti::createLocalSolver(type);
      first->factorize(A1);
      second->factorize(A2);  // A1's pattern: analysed once, shared
      tfeti::LocalAnalysisCounts c = tfeti::localAnalysisCounts();
      TEST_EQUALITY(c.made - start.made, 1);
      TEST_EQUALITY(c.shared - start.shared, 1);
      TEST_COMPARE(solveAndMeasure(*first, A1, 2, 11).residual, <, 1e-12);
      TEST_COMPARE(solveAndMeasure(*second, A2, 2, 12).residual, <, 1e-12);
      shared = solveOnce(*second, A2, 13);
      // Another pattern is analysed anew; refactorizing in place analyses nothing.
      auto third = tfeti::createLocalSolver(type);
      third->factorize(other);
      first->factorize(A2);
      c = tfeti::localAnalysisCounts();
      TEST_EQUALITY(c.made - start.made, 2);
      TEST_EQUALITY(c.shared - start.shared, 1);
      TEST_COMPARE(solveAndMeasure(*third, other, 1, 14).residual, <, 1e-12);
      TEST_COMPARE_FLOATING_ARRAYS(solveOnce(*first, A2, 13), shared, 0.0);
      // A factor that moves to the other pattern leaves the first one's analysis to the others.
      second->factorize(other);
      TEST_EQUALITY(tfeti::localAnalysisCounts().shared - start.shared, 2);
      TEST_COMPARE(solveAndMeasure(*second, other, 1, 15).residual, <, 1e-12);
      TEST_COMPARE_FLOATING_ARRAYS(solveOnce(*first, A2, 13), shared, 0.0);
    }
    // Every factor gone: the analysis went with them, and a new factor makes its own, which
    // solves bitwise as the shared one did.
    auto alone = tfeti::createLocalSolver(type);
    alone->factorize(A2);
    TEST_EQUALITY(tfeti::localAnalysisCounts().made - start.made, 3);
    TEST_COMPARE_FLOATING_ARRAYS(solveOnce(*alone, A2, 13), shared, 0.0);
  }
  // The kinds do not share: a simplicial analysis is no supernodal one.
  const tfeti::CsrMatrix A = laplacian2d(24, 1.0);
  const tfeti::LocalAnalysisCounts start = tfeti::localAnalysisCounts();
  auto simplicial = tfeti::createLocalSolver("cholmod-simplicial");
  auto supernodal = tfeti::createLocalSolver("cholmod-supernodal");
  simplicial->factorize(A);
  supernodal->factorize(A);
  TEST_EQUALITY(tfeti::localAnalysisCounts().made - start.made, 2);
  TEST_EQUALITY(tfeti::localAnalysisCounts().shared - start.shared, 0);
}

// predictFactorMemory tells, from the symbolic analysis alone, the bytes the factorization then
// allocates by CHOLMOD's own count, to the byte: for a new pattern (the analysis made by the
// prediction and not again by factorize), for a second factor of that pattern (shared), and 0 for
// a refactorization in place; predictFactorTransient the bytes it allocates beyond at its peak
// and frees (CHOLMOD's peak count, Common->memory_usage), to the byte, on 2D and 3D patterns of
// both kinds. Amesos2's solvers cannot tell.
TEUCHOS_UNIT_TEST(LocalSolver, CholmodPredictsItsFactor) {
  std::vector<std::pair<tfeti::CsrMatrix, tfeti::CsrMatrix>> cases;
  for (const int g : {12, 40}) cases.emplace_back(laplacian2d(g, 1.0), laplacian2d(g, 2.0));
  for (const int g : {8, 14}) {
    tfeti::CsrMatrix B = laplacian3d(g);
    for (double& v : B.values) v *= 2.0;
    cases.emplace_back(laplacian3d(g), B);
  }
  for (const std::string type : {"cholmod", "cholmod-simplicial", "cholmod-supernodal"}) {
    for (const auto& [A, B] : cases) {
      const tfeti::LocalAnalysisCounts start = tfeti::localAnalysisCounts();
      auto first = tfeti::createLocalSolver(type), second = tfeti::createLocalSolver(type);
      // A first factorization of this size grows CHOLMOD's workspace: not the factor's bytes.
      auto warm = tfeti::createLocalSolver(type);
      warm->factorize(A);
      for (auto* s : {first.get(), second.get()}) {
        const std::ptrdiff_t predicted = s->predictFactorMemory(A);
        const std::ptrdiff_t transient = s->predictFactorTransient(A);
        const std::size_t before = tfeti::localSolverMemoryInUse();
        tfeti::localSolverMemoryPeak(true);
        s->factorize(A);
        const std::size_t after = tfeti::localSolverMemoryInUse();
        const std::size_t peak = tfeti::localSolverMemoryPeak();
        out << type << " " << A.rows << " rows: predicted " << predicted << " + " << transient
            << ", allocated " << after - before << ", peak " << peak - before << ", factorBytes "
            << s->factorBytes() << "\n";
        TEST_EQUALITY(static_cast<std::size_t>(predicted), after - before);
        TEST_EQUALITY(static_cast<std::size_t>(predicted + transient), peak - before);
        TEST_EQUALITY(s->factorMemory(), after - before);
        TEST_COMPARE(static_cast<std::size_t>(predicted), >=, s->factorBytes());
      }
      // One analysis made per kind and pattern (by the first factor), the later ones sharing it
      // as before: the predictions made none.
      TEST_EQUALITY(tfeti::localAnalysisCounts().made - start.made, 1);
      TEST_EQUALITY(tfeti::localAnalysisCounts().shared - start.shared, 2);
      TEST_EQUALITY(first->predictFactorMemory(B), 0);
      TEST_COMPARE(first->predictFactorTransient(B), <, 0);
      const std::size_t before = tfeti::localSolverMemoryInUse();
      first->factorize(B);
      TEST_EQUALITY(tfeti::localSolverMemoryInUse(), before);
      TEST_COMPARE(solveAndMeasure(*first, B, 2, 21).residual, <, 1e-12);
      TEST_COMPARE(solveAndMeasure(*second, A, 2, 22).residual, <, 1e-12);
    }
  }
  // A prediction for a matrix that is then not factorized is dropped by the next factorization.
  const tfeti::CsrMatrix A = laplacian2d(20, 1.0), other = laplacian2d(21, 1.0);
  auto s = tfeti::createLocalSolver("cholmod");
  TEST_COMPARE(s->predictFactorMemory(other), >, 0);
  s->factorize(A);
  TEST_COMPARE(solveAndMeasure(*s, A, 1, 23).residual, <, 1e-12);
  for (const std::string type : {"klu2", "tacho"}) {
    TEST_COMPARE(tfeti::createLocalSolver(type)->predictFactorMemory(A), <, 0);
    TEST_COMPARE(tfeti::createLocalSolver(type)->predictFactorTransient(A), <, 0);
  }
}

// The block of A^{-1} on a set of dofs (the explicit dual operator's Schur assembly) takes a
// second factorization with the dofs last. predictInverseBlockMemory tells what inverseBlock will
// allocate at its peak, its result included, from that analysis alone: CHOLMOD's allocations and
// the solver's own vectors, counted together on the heap (HeapTally), to the byte. Once CHOLMOD's
// workspace has grown for it (a first call), the peak is the prediction's; the result is all
// that stays. The prediction may be made before the factorization (the dry run's), from
// predictFactorMemory's analysis, and is then not below it. The counts of a set of dofs are
// kept with the pattern's analysis: another subdomain of that pattern is told them unanalysed.
TEUCHOS_UNIT_TEST(LocalSolver, CholmodPredictsItsInverseBlock) {
  using tfeti_test::HeapTally;
  std::vector<std::pair<tfeti::CsrMatrix, std::vector<int>>> cases;
  for (const int g : {12, 40}) {
    std::vector<int> dofs;  // two sides and every seventh other dof, descending
    for (int i = g * g - 1; i >= 0; --i)
      if (i < g || i % g == 0 || i % 7 == 3) dofs.push_back(i);
    cases.emplace_back(laplacian2d(g, 1.0), dofs);
  }
  for (const int g : {8, 14}) {
    std::vector<int> dofs;  // two faces
    for (int i = 0; i < g * g * g; ++i)
      if (i < g * g || i % g == 0) dofs.push_back(i);
    cases.emplace_back(laplacian3d(g), dofs);
  }
  for (const std::string type : {"cholmod", "cholmod-simplicial", "cholmod-supernodal"}) {
    for (const auto& [A, dofs] : cases) {
      auto s = tfeti::createLocalSolver(type);
      const std::ptrdiff_t ahead = s->predictInverseBlockMemory(A, dofs);
      s->factorize(A);
      std::vector<double> inv;
      TEST_ASSERT(s->inverseBlock(A, dofs, inv));
      const std::vector<double> first = inv;
      std::vector<double>().swap(inv);
      const std::ptrdiff_t predicted = s->predictInverseBlockMemory(A, dofs);
      // Nothing but the call between the counts (a test macro's output grows its stream).
      const std::size_t before = HeapTally::inUse();
      HeapTally::reset();
      const bool again = s->inverseBlock(A, dofs, inv);
      const std::size_t peak = HeapTally::peak() - before, held = HeapTally::inUse() - before;
      TEST_ASSERT(again);
      out << type << " " << A.rows << " rows, " << dofs.size() << " dofs: predicted " << predicted
          << " (before the factorization " << ahead << "), peak " << peak << ", held " << held
          << "\n";
      TEST_EQUALITY(static_cast<std::size_t>(predicted), peak);
      TEST_EQUALITY(held, sizeof(double) * dofs.size() * dofs.size());
      TEST_COMPARE(ahead, >=, predicted);
      TEST_COMPARE_FLOATING_ARRAYS(inv, first, 0.0);
      // Another solver of the pattern, the same dofs in another order: the shared analysis's
      // memo answers, with no analysis made (CHOLMOD allocates nothing); other dofs are analysed.
      auto other = tfeti::createLocalSolver(type);
      const std::vector<int> reversed(dofs.rbegin(), dofs.rend());
      const std::size_t inUse = tfeti::localSolverMemoryInUse();
      tfeti::localSolverMemoryPeak(true);
      TEST_EQUALITY(other->predictInverseBlockMemory(A, reversed), predicted);
      TEST_EQUALITY(tfeti::localSolverMemoryPeak(), inUse);
      const std::vector<int> fewer(dofs.begin() + 1, dofs.end());
      TEST_COMPARE(other->predictInverseBlockMemory(A, fewer), >, 0);
      TEST_COMPARE(tfeti::localSolverMemoryPeak(), >, inUse);
      // The last eight sets are kept: after eight others the first is analysed again, the
      // eighth is not.
      for (std::size_t drop = 2; drop < 9; ++drop) {
        std::vector<int> other8 = dofs;
        other8.erase(other8.begin() + drop);
        other->predictInverseBlockMemory(A, other8);
      }
      tfeti::localSolverMemoryPeak(true);
      other->predictInverseBlockMemory(A, fewer);  // the oldest of the eight kept
      TEST_EQUALITY(tfeti::localSolverMemoryPeak(), inUse);
      TEST_EQUALITY(other->predictInverseBlockMemory(A, dofs), predicted);  // dropped, analysed
      TEST_COMPARE(tfeti::localSolverMemoryPeak(), >, inUse);
    }
  }
  const tfeti::CsrMatrix A = laplacian2d(20, 1.0);
  for (const std::string type : {"klu2", "tacho"})
    TEST_COMPARE(tfeti::createLocalSolver(type)->predictInverseBlockMemory(A, {0, 1}), <, 0);
}

// ------------------------------------------------------------------------------------------
// Supernodal factors are kept packed for one right-hand side at a time
// (tfeti_PackedSupernodal.hpp); more than eight go through CHOLMOD's own solve on its own layout,
// the factor unpacked for it and packed again after. Both must give the same solution to
// rounding, and a round trip through CHOLMOD's layout must leave the packed values as they were.
TEUCHOS_UNIT_TEST(LocalSolver, CholmodPackedSolvesAgreeWithCholmodsOwn) {
  for (const double shift : {1.0, 1e-3}) {
    // 55 x 55: supernodes of many widths, most not a multiple of the four-column panels.
    const tfeti::CsrMatrix A = laplacian2d(55, shift);
    const int n = A.rows, many = 9;
    auto s = tfeti::createLocalSolver("cholmod-supernodal");
    s->factorize(A);
    const std::vector<double> b = randomVector(static_cast<std::size_t>(n) * many, 21);
    std::vector<double> one(static_cast<std::size_t>(n) * many), all(one.size());
    for (int j = 0; j < many; ++j) s->solve(&b[std::size_t(j) * n], &one[std::size_t(j) * n], 1);
    s->solve(b.data(), all.data(), many);  // CHOLMOD's layout and solve
    double diff = 0.0, size = 0.0;
    for (std::size_t i = 0; i < all.size(); ++i) {
      diff = std::max(diff, std::abs(one[i] - all[i]));
      size = std::max(size, std::abs(all[i]));
    }
    out << "shift " << shift << ": packed against CHOLMOD's solve, max difference " << diff
        << " of " << size << "\n";
    TEST_COMPARE(diff, <=, 1e-13 * size);
    // Packed again after CHOLMOD's solve: bitwise the same single solves.
    std::vector<double> again(static_cast<std::size_t>(n));
    s->solve(b.data(), again.data(), 1);
    TEST_COMPARE_FLOATING_ARRAYS(again, std::vector<double>(one.begin(), one.begin() + n), 0.0);
    TEST_COMPARE(solveAndMeasure(*s, A, many, 22).residual, <, 1e-12);
    TEST_COMPARE(solveAndMeasure(*s, A, 1, 23).residual, <, 1e-12);
    // A refactorization writes over the packed values.
    s->factorize(laplacian2d(55, 10 * shift));
    TEST_COMPARE(solveAndMeasure(*s, laplacian2d(55, 10 * shift), 1, 24).residual, <, 1e-12);
    TEST_COMPARE(solveAndMeasure(*s, laplacian2d(55, 10 * shift), many, 25).residual, <, 1e-12);
  }
}

// The block of A^{-1} on a set of dofs (the explicit dual operator's Schur assembly): against
// the solves with the unit columns, for dofs in any order, the boundary of a grid (what a
// subdomain's dual rows touch) and scattered ones; the factor of factorize() stays as it was.
TEUCHOS_UNIT_TEST(LocalSolver, CholmodInverseBlockIsTheSolvesBlock) {
  const int g = 40;
  for (const std::string type : {"cholmod", "cholmod-simplicial", "cholmod-supernodal"})
    for (const double shift : {1.0, 1e-4}) {
      const tfeti::CsrMatrix A = laplacian2d(g, shift);
      const int n = A.rows;
      auto s = tfeti::createLocalSolver(type);
      s->factorize(A);
      std::vector<int> boundary, scattered;
      for (int i = 0; i < n; ++i) {
        const int x = i % g, y = i / g;
        if (x == 0 || y == 0 || x == g - 1 || y == g - 1) boundary.push_back(i);
        if (i % 37 == 5) scattered.push_back(i);
      }
      std::reverse(scattered.begin(), scattered.end());  // not in increasing order
      for (const auto& dofs : {boundary, scattered, std::vector<int>{n - 1}}) {
        const int k = static_cast<int>(dofs.size());
        std::vector<double> inv, unit(static_cast<std::size_t>(n) * k, 0.0), x(unit.size());
        TEST_ASSERT(s->inverseBlock(A, dofs, inv));
        TEST_EQUALITY(inv.size(), static_cast<std::size_t>(k) * k);
        for (int j = 0; j < k; ++j) unit[std::size_t(j) * n + dofs[j]] = 1.0;
        s->solve(unit.data(), x.data(), k);
        double diff = 0.0, size = 0.0;
        for (int j = 0; j < k; ++j)
          for (int i = 0; i < k; ++i) {
            const double ref = x[std::size_t(j) * n + dofs[i]];
            diff = std::max(diff, std::abs(inv[std::size_t(j) * k + i] - ref));
            size = std::max(size, std::abs(ref));
          }
        out << type << ", shift " << shift << ", " << k << " dofs: max difference " << diff
            << " of " << size << "\n";
        TEST_COMPARE(diff, <=, 1e-12 * size);
      }
      // The factor of factorize() is untouched: its solves are as accurate as before.
      TEST_COMPARE(solveAndMeasure(*s, A, 1, 31).residual, <, 1e-12);
      TEST_COMPARE(solveAndMeasure(*s, A, 12, 32).residual, <, 1e-12);
      std::vector<double> inv;
      TEST_THROW(s->inverseBlock(A, {3, 7, 3}, inv), std::logic_error);
      TEST_THROW(s->inverseBlock(A, {n}, inv), std::logic_error);
      // Another matrix than the one factorized (another pattern): not done, the caller solves.
      TEST_ASSERT(!s->inverseBlock(laplacian2d(g - 1, shift), {0, 1}, inv));
    }
  // Amesos2's solvers offer none: the caller takes the solves.
  auto klu = tfeti::createLocalSolver("klu2");
  const tfeti::CsrMatrix A = laplacian2d(10, 1.0);
  klu->factorize(A);
  std::vector<double> inv;
  TEST_ASSERT(!klu->inverseBlock(A, {0, 5}, inv));
}

// The Dirichlet preconditioner factorizes K(interior, interior) taken by CsrMatrix::submatrix:
// every kept entry in its place, in the order of the rows, and nothing else.
TEUCHOS_UNIT_TEST(CsrMatrix, SubmatrixKeepsTheChosenRowsAndColumns) {
  const int g = 9;
  const tfeti::CsrMatrix A = laplacian2d(g, 0.25);
  std::vector<int> rows, cols;
  for (int i = 0; i < A.rows; ++i) {
    if (i % 3 != 1) rows.push_back(i);
    if (i % 4 != 2) cols.push_back(i);
  }
  const tfeti::CsrMatrix S = A.submatrix(rows, cols);
  TEST_EQUALITY(S.rows, static_cast<int>(rows.size()));
  TEST_EQUALITY(S.cols, static_cast<int>(cols.size()));
  TEST_EQUALITY(S.rowPtr.size(), rows.size() + 1);
  TEST_EQUALITY(S.colInd.size(), S.values.size());
  TEST_EQUALITY(static_cast<int>(S.colInd.size()), S.rowPtr.back());
  std::size_t expected = 0;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    int last = -1;
    for (int k = S.rowPtr[r]; k < S.rowPtr[r + 1]; ++k) {
      TEST_COMPARE(S.colInd[k], >, last);  // increasing columns
      last = S.colInd[k];
      const long at = A.find(rows[r], cols[S.colInd[k]]);
      TEST_COMPARE(at, >=, 0);
      if (at >= 0) TEST_EQUALITY(S.values[k], A.values[at]);
    }
    for (int c : cols) expected += A.find(rows[r], c) >= 0;
  }
  TEST_EQUALITY(S.colInd.size(), expected);
  const tfeti::CsrMatrix none = A.submatrix({}, cols);
  TEST_EQUALITY(none.rows, 0);
  TEST_EQUALITY(none.rowPtr.size(), std::size_t(1));
  TEST_EQUALITY(none.colInd.size(), std::size_t(0));
}

// A solve with many right-hand sides (the explicit dual operator's assembly: 128 columns at a
// time, every subdomain) must not leave copies of them with the solver: kept per subdomain, they
// added up over a rank's subdomains to more than its F_s, uncounted by the memory check. Counted
// by malloc's own tally (Kokkos, under Amesos2, allocates with malloc, which HeapTally does not
// see), after each solve against before it. CHOLMOD's solve vectors are the process's, shared by
// every subdomain: the first solve of a size grows them (two n x 128 arrays), a second keeps
// nothing. KLU2 keeps a few vectors of n, once. Tacho keeps a workspace of the largest nrhs it
// has solved for (one n x 128 array), once per factor, as its solveKeeps tells beforehand (the
// memory check counts it). Before 2026-12-07 KLU2 kept three n x 128 arrays after every such
// solve, until its next one-column solve.
TEUCHOS_UNIT_TEST(LocalSolver, ManyColumnSolvesKeepNothing) {
  const auto inUse = [] {
    const struct mallinfo2 m = mallinfo2();
    return static_cast<double>(m.uordblks + m.hblkhd);
  };
  for (const std::string type :
       {"cholmod", "cholmod-simplicial", "cholmod-supernodal", "klu2", "tacho"}) {
    const tfeti::CsrMatrix A = laplacian3d(type == "tacho" ? 10 : 16);
    const int n = A.rows, w = 128;
    const double array = 8.0 * n * w;  // one n x 128 array of doubles
    auto s = tfeti::createLocalSolver(type);
    s->factorize(A);
    for (int rep = 0; rep < 3; ++rep) {
      // What the solver says the solve will leave with it: Tacho's workspace, the first time.
      const double told = static_cast<double>(s->solveKeeps(static_cast<std::size_t>(n), w));
      TEST_EQUALITY(told, type == "tacho" && rep == 0 ? array : 0.0);
      const double before = inUse();
      const Accuracy acc = solveAndMeasure(*s, A, w, 5 + rep);  // its vectors freed on return
      const double kept = inUse() - before;
      out << type << " " << n << " rows, solve " << rep << " of " << w << " columns: kept "
          << kept / array << " n x " << w << " arrays (told " << told / array << "), residual "
          << acc.residual << "\n";
      // The first solve may grow what stays for every later one: CHOLMOD's shared X and Y (the
      // process's, not the factor's), Tacho's workspace (told), KLU2's few vectors of n.
      const double allowed = rep > 0 ? 0.02 : type.rfind("cholmod", 0) == 0 ? 2.1 : 0.05;
      TEST_COMPARE(kept, <=, told + allowed * array);
      TEST_COMPARE(kept, >=, told - 0.02 * array);
      TEST_COMPARE(acc.residual, <, 1e-12);
    }
    // A new factorization replaces the workspace with the Amesos2 solver: the next solve's is
    // told again.
    s->factorize(A);
    TEST_EQUALITY(s->solveKeeps(static_cast<std::size_t>(n), w), type == "tacho" ? array : 0.0);
  }
}
