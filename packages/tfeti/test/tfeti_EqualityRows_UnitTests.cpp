// The caller's equality rows with right-hand sides (FetiSolver's `equalities`), on 1, 2 and 3
// ranks, on plane-strain elasticity on the unit square (4 x 4 subdomains of 4 x 4 elements,
// clamped at x = 0, body force (0, -1)):
//  - a multi-point constraint (two dofs of different subdomains tied with an offset) and a
//    non-zero prescribed value, against a direct primal solve of the undecomposed problem with
//    the same two constraints by Lagrange multipliers (K^{-1} by CHOLMOD, the 2 x 2 Schur
//    complement of the multipliers): the solution, B_E u = c_E, and the rows' multipliers, for
//    PCPG (TFETI and FETI) and for the QP solvers (SMALBE and the penalty method);
//  - "Gluing" = none with the gluing passed as the caller's rows gives the automatic gluing's
//    solution, dual dimension and iteration count;
//  - malformed rows are an error naming the row on every rank.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

using tfeti::ConstraintEntry;
using tfeti::EqualityRow;

const double kTolerance = 1e-10;

tfeti::StructuredRectangle square() {
  return tfeti::StructuredRectangle(0, 1, 0, 1, 4, 4, 4, 4);
}

Teuchos::ParameterList parameters(const std::string& formulation, const std::string& dual) {
  Teuchos::ParameterList p;
  p.set("Formulation", formulation);
  p.set("Dual solver", dual);
  p.sublist("PCPG").set("Relative tolerance", kTolerance);
  p.sublist("PCPG").set("Maximum iterations", 300);
  p.sublist("SMALBE").set("Relative tolerance", kTolerance);
  p.sublist("SMALBE").set("Equality tolerance", kTolerance);
  p.sublist("MPRGP").set("Relative tolerance", kTolerance);
  p.sublist("MPRGP").set("Maximum iterations", 5000);
  return p;
}

// A constraint of the untorn problem: sum coef * u(untorn dof) = rhs.
struct UntornRow {
  std::vector<std::pair<int, double>> terms;  // (dpn * node + component, coef)
  double rhs;
};

// u of K u = f - C^T mu, C u = g (Dirichlet dofs x = 0 held at zero), by the Schur complement
// of the multipliers: (C K^{-1} C^T) mu = C K^{-1} f - g.
std::vector<double> lagrangeReference(const tfeti::StructuredRectangle& rect,
                                      const std::vector<UntornRow>& C, std::vector<double>& mu) {
  const tfeti_test::Physics ph = tfeti_test::elasticity();
  tfeti::SubdomainMesh whole = rect.wholeMesh();
  const int dpn = ph.dofsPerNode();
  const std::vector<int> fixed = whole.dirichletDofs(dpn);
  const auto solve = [&](std::vector<double> rhs) {
    tfeti::CsrMatrix K =
        plasticity::assembleStiffness(tfeti_test::quadMesh(whole), ph.field, ph.law);
    return tfeti_test::solveWithDirichlet(std::move(K), std::move(rhs), fixed);
  };
  const std::vector<double> f =
      plasticity::assembleBodyLoad(tfeti_test::quadMesh(whole), ph.field, ph.source);
  const std::size_t n = f.size(), m = C.size();
  const std::vector<double> u0 = solve(f);
  std::vector<std::vector<double>> KinvCt;
  for (const auto& row : C) {
    std::vector<double> c(n, 0.0);
    for (const auto& [dof, coef] : row.terms) c[dof] += coef;
    KinvCt.push_back(solve(c));
  }
  auto apply = [&](const UntornRow& row, const std::vector<double>& v) {
    double s = 0.0;
    for (const auto& [dof, coef] : row.terms) s += coef * v[dof];
    return s;
  };
  // Dense m x m system (m = 2) by Gaussian elimination with partial pivoting.
  std::vector<std::vector<double>> S(m, std::vector<double>(m + 1));
  for (std::size_t i = 0; i < m; ++i) {
    for (std::size_t j = 0; j < m; ++j) S[i][j] = apply(C[i], KinvCt[j]);
    S[i][m] = apply(C[i], u0) - C[i].rhs;
  }
  for (std::size_t k = 0; k < m; ++k) {
    std::size_t p = k;
    for (std::size_t i = k + 1; i < m; ++i)
      if (std::abs(S[i][k]) > std::abs(S[p][k])) p = i;
    std::swap(S[k], S[p]);
    for (std::size_t i = k + 1; i < m; ++i) {
      const double l = S[i][k] / S[k][k];
      for (std::size_t j = k; j <= m; ++j) S[i][j] -= l * S[k][j];
    }
  }
  mu.assign(m, 0.0);
  for (std::size_t k = m; k-- > 0;) {
    double s = S[k][m];
    for (std::size_t j = k + 1; j < m; ++j) s -= S[k][j] * mu[j];
    mu[k] = s / S[k][k];
  }
  std::vector<double> u = u0;
  for (std::size_t j = 0; j < m; ++j)
    for (std::size_t i = 0; i < n; ++i) u[i] -= mu[j] * KinvCt[j][i];
  return u;
}

// Max over every local copy of |u - reference| / max |reference|, over all ranks.
double errorAgainst(const tfeti::FetiSolver& solver, const std::vector<double>& reference,
                    int dpn) {
  double err = 0.0;
  for (std::size_t i = 0; i < solver.data().size(); ++i) {
    const auto& mesh = solver.data()[i].mesh;
    for (int nd = 0; nd < mesh.numNodes(); ++nd)
      for (int c = 0; c < dpn; ++c)
        err = std::max(err, std::abs(solver.solution(i)[nd * dpn + c] -
                                     reference[mesh.globalNode[nd] * dpn + c]));
  }
  return tfeti_test::globalMax(*solver.comm(), err) / tfeti_test::maxAbs(reference);
}

// Untorn node (i, j) of the 17 x 17 grid.
int node(int i, int j) {
  return j * 17 + i;
}

TEUCHOS_UNIT_TEST(EqualityRows, MultiPointConstraintAndPrescribedValueAgainstLagrangeSolve) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti::StructuredRectangle rect = square();
  const tfeti_test::Physics ph = tfeti_test::elasticity();
  // u_y(A) - u_y(B) = 0.05 between A = (0.375, 0.625) and B = (0.875, 0.3125), nodes interior to
  // two different subdomains; u_x(P) = 0.02 at P = (1, 0.5), on the edge between two subdomains
  // (prescribed on its lowest copy only: the gluing carries it to the other).
  const int A = node(6, 10), B = node(14, 5), P = node(16, 8);
  const std::vector<UntornRow> C = {{{{2 * A + 1, 1.0}, {2 * B + 1, -1.0}}, 0.05},
                                    {{{2 * P, 1.0}}, 0.02}};
  std::vector<double> mu;
  const std::vector<double> reference = lagrangeReference(rect, C, mu);
  out << "Lagrange reference: mu = {" << mu[0] << ", " << mu[1] << "}, max |u| "
      << tfeti_test::maxAbs(reference) << "\n";
  // The torn rows on one copy of each node; every rank passes them (rank 0's only would do as
  // well): passed twice they would be duplicates, so only rank 0 does.
  auto copyOf = [&](int n) { return rect.copyOfNode(n % 17, n / 17); };
  std::vector<EqualityRow> rows;
  if (comm->getRank() == 0) {
    const auto a = copyOf(A), b = copyOf(B), p = copyOf(P);
    TEST_INEQUALITY(a.first, b.first);
    rows.push_back({{{a.first, 2 * a.second + 1, 1.0}, {b.first, 2 * b.second + 1, -1.0}}, 0.05});
    rows.push_back({{{p.first, 2 * p.second, 1.0}}, 0.02});
  }
  struct Case {
    std::string formulation, dual;
    double tolerance;  // on the solution error and the constraint residual
  };
  // The penalty method meets Q mu = 0 only to O(1/rho) (about 1e-5 relative at rho = 1e4).
  for (const Case& k : {Case{"TFETI", "PCPG", 1e-8}, Case{"FETI", "PCPG", 1e-8},
                        Case{"TFETI", "SMALBE", 1e-7}, Case{"TFETI", "penalty", 1e-3}}) {
    tfeti::FetiSolver solver(comm, rect.numSubdomains(),
                             tfeti_test::localSubdomains(rect, *comm, ph),
                             parameters(k.formulation, k.dual), {}, rows);
    TEST_EQUALITY(solver.userEqualityRows(), 2);
    const tfeti::DualResult r = solver.solve();
    const tfeti::ConstraintReport report = solver.constraintReport();
    const double err = errorAgainst(solver, reference, 2);
    // The rows in canonical order: the multipliers must be the reference's mu (B has full rank
    // on these rows: their multipliers are unique).
    const std::vector<double> lambda = solver.userEqualityMultipliers();
    double muErr = 0.0;
    for (std::size_t q = 0; q < lambda.size(); ++q) {
      const auto& row = solver.tearing().userEqualityRows[q];
      const int ref = row.entries.size() == 2 ? 0 : 1;
      muErr = std::max(muErr, std::abs(lambda[q] - mu[ref]) / std::abs(mu[ref]));
    }
    out << k.formulation << " " << k.dual << ": " << (r.converged ? "converged" : "NOT converged")
        << " (" << r.iterations << " steps), error " << err << ", max |B_E u - c_E| "
        << report.equalityResidual << ", multiplier error " << muErr << "\n";
    TEST_ASSERT(r.converged);
    TEST_COMPARE(err, <, k.tolerance);
    TEST_COMPARE(report.equalityResidual, <, k.tolerance * tfeti_test::maxAbs(reference));
    TEST_COMPARE(muErr, <, k.dual == "penalty" ? 1e-2 : 1e-6);
  }
}

// The automatic gluing's rows, built by the caller: u_a - u_b = 0 between consecutive copies of
// every node shared by subdomains (ascending subdomain id), for every component. Each rank
// passes the rows whose first copy is one of its subdomains.
std::vector<EqualityRow> gluingRows(const tfeti::StructuredRectangle& rect, int dpn, int rank,
                                    int ranks) {
  std::map<long long, std::vector<std::pair<int, int>>> copies;  // node -> (subdomain, local)
  for (int s = 0; s < rect.numSubdomains(); ++s) {
    const tfeti::SubdomainMesh m = rect.subdomain(s);
    for (int n = 0; n < m.numNodes(); ++n) copies[m.globalNode[n]].push_back({s, n});
  }
  std::vector<EqualityRow> rows;
  for (const auto& [node, list] : copies) {
    if (tfeti::ownerOfSubdomain(list.front().first, rect.numSubdomains(), ranks) != rank) continue;
    for (std::size_t k = 0; k + 1 < list.size(); ++k)
      for (int c = 0; c < dpn; ++c)
        rows.push_back({{{list[k].first, dpn * list[k].second + c, 1.0},
                         {list[k + 1].first, dpn * list[k + 1].second + c, -1.0}},
                        0.0});
  }
  return rows;
}

TEUCHOS_UNIT_TEST(EqualityRows, CallersGluingEqualsTheAutomaticGluing) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti::StructuredRectangle rect = square();
  for (const tfeti_test::Physics& ph : {tfeti_test::poisson(), tfeti_test::elasticity()}) {
    const int dpn = ph.dofsPerNode();
    Teuchos::ParameterList automatic = parameters("TFETI", "PCPG"), none = automatic;
    none.set("Gluing", "none");
    tfeti::FetiSolver a(comm, rect.numSubdomains(), tfeti_test::localSubdomains(rect, *comm, ph),
                        automatic);
    tfeti::FetiSolver b(comm, rect.numSubdomains(), tfeti_test::localSubdomains(rect, *comm, ph),
                        none, {}, gluingRows(rect, dpn, comm->getRank(), comm->getSize()));
    const auto ra = a.solve(), rb = b.solve();
    double diff = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < a.data().size(); ++i)
      for (std::size_t d = 0; d < a.solution(i).size(); ++d) {
        diff = std::max(diff, std::abs(a.solution(i)[d] - b.solution(i)[d]));
        scale = std::max(scale, std::abs(a.solution(i)[d]));
      }
    diff = tfeti_test::globalMax(*comm, diff) / tfeti_test::globalMax(*comm, scale);
    out << ph.name() << ": automatic " << a.gluingRows() << " gluing rows, " << ra.iterations
        << " iterations; caller's " << b.userEqualityRows() << " rows, " << rb.iterations
        << " iterations; max difference " << diff << "\n";
    TEST_ASSERT(ra.converged && rb.converged);
    TEST_EQUALITY(b.gluingRows(), 0);
    TEST_EQUALITY(b.userEqualityRows(), a.gluingRows());
    TEST_EQUALITY(b.dualDimension(), a.dualDimension());
    // The same rows and scaling groups in another order: the same Krylov space.
    TEST_COMPARE(std::abs(ra.iterations - rb.iterations), <=, 1);
    TEST_COMPARE(diff, <, 1e-8);
    TEST_COMPARE(b.constraintReport().equalityResidual, <, 1e-10 * scale + 1e-300);
  }
}

TEUCHOS_UNIT_TEST(EqualityRows, MalformedRowsAreAnErrorOnEveryRank) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti::StructuredRectangle rect = square();
  const tfeti_test::Physics ph = tfeti_test::poisson();
  const int last = comm->getSize() - 1;  // a row passed by one rank only
  auto attempt = [&](const EqualityRow& row, const std::string& formulation = "TFETI") {
    std::vector<EqualityRow> rows;
    if (comm->getRank() == last) rows.push_back(row);
    return tfeti_test::messageOf([&] {
      tfeti::FetiSolver s(comm, rect.numSubdomains(), tfeti_test::localSubdomains(rect, *comm, ph),
                          parameters(formulation, "PCPG"), {}, rows);
    });
  };
  const std::string unknownDof = attempt({{{3, 25, 1.0}}, 1.0});
  const std::string unknownSubdomain = attempt({{{16, 0, 1.0}}, 1.0});
  const std::string zero = attempt({{{3, 0, 0.0}}, 1.0});
  const std::string empty = attempt({{}, 1.0});
  const std::string infinite = attempt({{{3, 0, 1.0}}, std::nan("")});
  // FETI eliminates the Dirichlet dofs (node 0 of subdomain 0 is at x = 0).
  const std::string eliminated = attempt({{{0, 0, 1.0}}, 1.0}, "FETI");
  for (const auto& m : {unknownDof, unknownSubdomain, zero, empty, infinite, eliminated})
    out << m << "\n";
  TEST_ASSERT(tfeti_test::contains(unknownDof, "dof 25 of subdomain 3, which has 25 dofs"));
  TEST_ASSERT(tfeti_test::contains(unknownSubdomain, "subdomain 16, which does not exist"));
  TEST_ASSERT(tfeti_test::contains(zero, "only zero coefficients"));
  TEST_ASSERT(tfeti_test::contains(empty, "no entries"));
  TEST_ASSERT(tfeti_test::contains(infinite, "not finite"));
  TEST_ASSERT(tfeti_test::contains(eliminated, "FETI formulation eliminates"));
}

}  // namespace
