// EqualityConstraints (C x = d for SMALBE) on 1, 2 and 3 ranks: the lifting meets C x0 = d, Q is
// the orthogonal projector onto range(C^T) (Q = Q^T = Q^2, Q C^T = C^T), and a QP with bounds and
// three equality rows (one of them dependent) solved by SMALBE through shift/recover meets the
// KKT conditions and equals the solution of the dense KKT system on its active set, which is
// itself checked to be a KKT point (multipliers of the active bounds >= 0, free entries above
// their bounds), so that it is the unique minimizer. Bad input: inconsistent d, wrong length.
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_LAPACK.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "tfeti_EqualityConstraints.hpp"
#include "tfeti_SmalbeSolMgr_decl.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

using Teuchos::RCP;
using Teuchos::rcp;
using tfeti::GO;
using tfeti::LO;
using tfeti::MultiVector;
using tfeti::Vector;
using tfeti_test::contains;
using tfeti_test::messageOf;

const int n = 30;
const double kInf = std::numeric_limits<double>::infinity();

// A = tridiag(-1, 2.5 + 0.05 i, -1), b_i = 1 + sin(0.7 i), a bound 0.15 + 0.05 cos(i) on every
// third entry. C: sum x = 2, x_0 - x_{n-1} = 0.25, and 2 row_0 + row_1 = 4.25 (dependent).
double a(int i, int j) {
  return i == j ? 2.5 + 0.05 * i : std::abs(i - j) == 1 ? -1.0 : 0.0;
}
double bOf(int i) {
  return 1.0 + std::sin(0.7 * i);
}
double lowerOf(int i) {
  return i % 3 == 0 ? 0.15 + 0.05 * std::cos(double(i)) : -kInf;
}
double c(int k, int i) {
  const double r0 = 1.0, r1 = i == 0 ? 1.0 : i == n - 1 ? -1.0 : 0.0;
  return k == 0 ? r0 : k == 1 ? r1 : 2.0 * r0 + r1;
}
const std::vector<double> d{2.0, 0.25, 4.25};

RCP<const tfeti::Map> map() {
  return rcp(new tfeti::Map(n, 0, Tpetra::getDefaultComm()));
}

RCP<Vector> vectorOf(const RCP<const tfeti::Map>& m, double (*f)(int)) {
  auto v = rcp(new Vector(m));
  for (LO l = 0; l < static_cast<LO>(m->getNodeNumElements()); ++l)
    v->replaceLocalValue(l, f(static_cast<int>(m->getGlobalElement(l))));
  return v;
}

RCP<MultiVector> rowsOfC(const RCP<const tfeti::Map>& m, int rows) {
  auto C = rcp(new MultiVector(m, rows));
  for (LO l = 0; l < static_cast<LO>(m->getNodeNumElements()); ++l)
    for (int k = 0; k < rows; ++k)
      C->replaceLocalValue(l, k, c(k, static_cast<int>(m->getGlobalElement(l))));
  return C;
}

RCP<tfeti::CrsMatrix> matrix(const RCP<const tfeti::Map>& m) {
  auto A = rcp(new tfeti::CrsMatrix(m, 3));
  for (LO l = 0; l < static_cast<LO>(m->getNodeNumElements()); ++l) {
    const int i = static_cast<int>(m->getGlobalElement(l));
    std::vector<GO> cols;
    std::vector<double> vals;
    for (int j = std::max(0, i - 1); j <= std::min(n - 1, i + 1); ++j)
      cols.push_back(j), vals.push_back(a(i, j));
    A->insertGlobalValues(i, Teuchos::arrayViewFromVector(cols),
                          Teuchos::arrayViewFromVector(vals));
  }
  A->fillComplete();
  return A;
}

std::vector<double> gathered(const Vector& v) {
  std::vector<double> all(n, 0.0), mine(n, 0.0);
  auto data = v.getData();
  for (LO l = 0; l < static_cast<LO>(v.getLocalLength()); ++l)
    mine[v.getMap()->getGlobalElement(l)] = data[l];
  Teuchos::reduceAll(*v.getMap()->getComm(), Teuchos::REDUCE_SUM, n, mine.data(), all.data());
  return all;
}

TEUCHOS_UNIT_TEST(EqualityConstraints, LiftingAndProjector) {
  auto m = map();
  tfeti::EqualityConstraints eq(rowsOfC(m, 3), d);
  TEST_EQUALITY(eq.rank(), 2);
  TEST_COMPARE(eq.residual(*eq.lifting()), <=, 1e-13);
  // Q C^T = C^T, Q^2 = Q, Q symmetric (u^T Q v = v^T Q u), and Q v = 0 for v in ker C.
  auto C = rowsOfC(m, 3);
  MultiVector QC(m, 3);
  eq.projector()->apply(*C, QC);
  QC.update(-1.0, *C, 1.0);
  std::vector<double> err(3);
  QC.normInf(err);
  for (double e : err) TEST_COMPARE(e, <=, 1e-13);
  auto u = vectorOf(m, [](int i) { return std::sin(1.3 * i); });
  auto v = vectorOf(m, [](int i) { return std::cos(0.4 * i) + 0.1 * i; });
  Vector Qu(m), Qv(m), QQu(m);
  eq.projector()->apply(*u, Qu);
  eq.projector()->apply(*v, Qv);
  eq.projector()->apply(Qu, QQu);
  QQu.update(-1.0, Qu, 1.0);
  TEST_COMPARE(QQu.normInf(), <=, 1e-13);
  TEST_COMPARE(std::abs(u->dot(Qv) - v->dot(Qu)), <=, 1e-12);
  Vector kerC(*v, Teuchos::Copy), QkerC(m);
  kerC.update(-1.0, Qv, 1.0);  // (I - Q) v is in ker C
  eq.projector()->apply(kerC, QkerC);
  TEST_COMPARE(QkerC.normInf(), <=, 1e-13);
  // The lifting is the least-norm solution: in range(C^T).
  Vector Qx0(m);
  eq.projector()->apply(*eq.lifting(), Qx0);
  Qx0.update(-1.0, *eq.lifting(), 1.0);
  TEST_COMPARE(Qx0.normInf(), <=, 1e-13);
}

TEUCHOS_UNIT_TEST(EqualityConstraints, SmalbeSolvesBoundsAndEqualities) {
  auto m = map();
  tfeti::EqualityConstraints eq(rowsOfC(m, 3), d);
  tfeti::EqualityConstraints::Qp qp;
  qp.A = matrix(m);
  qp.b = vectorOf(m, bOf);
  qp.lower = vectorOf(m, lowerOf);
  qp.x = rcp(new Vector(m));
  const auto shifted = eq.shift(qp);
  Teuchos::ParameterList params;
  params.set("Relative tolerance", 1e-11);
  params.set("Equality tolerance", 1e-11);
  tfeti::SmalbeSolMgr<double, MultiVector, tfeti::Operator> smalbe(shifted, eq.projector(), params);
  const Belos::ReturnType r = smalbe.solve();
  out << smalbe.counters().message << "\n";
  TEST_EQUALITY(r, Belos::Converged);
  Vector x(m);
  eq.recover(*shifted.x, x);
  TEST_COMPARE(eq.residual(x), <=, 1e-9);

  // KKT of the original problem with SMALBE's multiplier: g = A x - b + mu.
  const std::vector<double> xs = gathered(x);
  const std::vector<double> mu = gathered(*smalbe.getMultiplier()->getVector(0));
  std::vector<double> g(n);
  for (int i = 0; i < n; ++i) {
    g[i] = -bOf(i) + mu[i];
    for (int j = 0; j < n; ++j) g[i] += a(i, j) * xs[j];
  }
  std::vector<int> freeSet, activeSet;
  for (int i = 0; i < n; ++i) {
    TEST_COMPARE(xs[i], >=, lowerOf(i) - 1e-14);  // x0 + (l - x0) is l to rounding
    (xs[i] - lowerOf(i) > 1e-8 ? freeSet : activeSet).push_back(i);
  }
  out << activeSet.size() << " active bounds of " << (n + 2) / 3 << "\n";
  TEST_COMPARE(activeSet.size(), >=, 2u);
  TEST_COMPARE(activeSet.size(), <, std::size_t((n + 2) / 3));
  for (int i : freeSet) TEST_COMPARE(std::abs(g[i]), <=, 1e-8);
  for (int i : activeSet) TEST_COMPARE(g[i], >=, -1e-8);

  // The reference: the dense KKT system on the active set,
  //   [A_FF  C_F^T] [x_F]   [b_F - A_FA l_A]
  //   [C_F     0  ] [nu ] = [d - C_A l_A    ]   (rows 0 and 1 of C, independent),
  // then the active bounds' multipliers (A x - b + C^T nu)_A >= 0 and x_F >= l_F.
  const int nf = static_cast<int>(freeSet.size()), dim = nf + 2;
  std::vector<double> K(dim * dim, 0.0), rhs(dim, 0.0);
  for (int p = 0; p < nf; ++p) {
    const int i = freeSet[p];
    rhs[p] = bOf(i);
    for (int q = 0; q < nf; ++q) K[p + q * dim] = a(i, freeSet[q]);
    for (int j : activeSet) rhs[p] -= a(i, j) * lowerOf(j);
    for (int k = 0; k < 2; ++k) K[p + (nf + k) * dim] = K[nf + k + p * dim] = c(k, i);
  }
  for (int k = 0; k < 2; ++k) {
    rhs[nf + k] = d[k];
    for (int j : activeSet) rhs[nf + k] -= c(k, j) * lowerOf(j);
  }
  std::vector<int> piv(dim);
  int info = 0;
  Teuchos::LAPACK<int, double>().GESV(dim, 1, K.data(), dim, piv.data(), rhs.data(), dim, &info);
  TEST_EQUALITY(info, 0);
  std::vector<double> ref(n);
  for (int j : activeSet) ref[j] = lowerOf(j);
  for (int p = 0; p < nf; ++p) ref[freeSet[p]] = rhs[p];
  const double nu[2] = {rhs[nf], rhs[nf + 1]};
  for (int i : freeSet) TEST_COMPARE(ref[i], >, lowerOf(i));
  for (int i : activeSet) {
    double lambda = -bOf(i) + nu[0] * c(0, i) + nu[1] * c(1, i);
    for (int j = 0; j < n; ++j) lambda += a(i, j) * ref[j];
    TEST_COMPARE(lambda, >=, 0.0);
  }
  double dx = 0.0, dmu = 0.0, scale = 0.0;
  for (int i = 0; i < n; ++i) {
    dx = std::max(dx, std::abs(xs[i] - ref[i]));
    dmu = std::max(dmu, std::abs(mu[i] - nu[0] * c(0, i) - nu[1] * c(1, i)));
    scale = std::max(scale, std::abs(ref[i]));
  }
  out << "max |x - x_ref| = " << dx << ", max |mu - C^T nu| = " << dmu << "\n";
  TEST_COMPARE(dx, <=, 1e-8 * scale);
  TEST_COMPARE(dmu, <=, 1e-7);
}

TEUCHOS_UNIT_TEST(EqualityConstraints, BadInput) {
  auto m = map();
  std::vector<double> inconsistent = d;
  inconsistent[2] = 5.0;  // 2 * 2 + 0.25 = 4.25 needed
  const std::string m1 =
      messageOf([&] { tfeti::EqualityConstraints e(rowsOfC(m, 3), inconsistent); });
  out << m1 << "\n";
  TEST_ASSERT(contains(m1, "no solution") && contains(m1, "rank 2 of 3"));
  const std::string m2 = messageOf([&] { tfeti::EqualityConstraints e(rowsOfC(m, 2), d); });
  TEST_ASSERT(contains(m2, "C has 2 rows, d has 3 entries"));
  auto zero = rcp(new MultiVector(m, 1));
  TEST_ASSERT(contains(messageOf([&] { tfeti::EqualityConstraints e(zero, {1.0}); }), "C is zero"));
}

}  // namespace
