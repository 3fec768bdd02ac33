// FETI "Dual operator" = explicit (issue 29) on 1, 2 and 3 ranks:
//  - every dense local F_s equals B_s K_s+ B_s^T computed column by column (one solve per
//    column), in both storages, and again after the subdomain is refactorized with another
//    matrix (the operator notices the new factorization and reassembles by itself);
//  - the explicit F applies as the implicit one;
//  - explicit and implicit solves agree (iterations, solution to 1e-10) in 2D and 3D with the
//    lumped and Dirichlet preconditioners, also after update() and updateStiffness();
//  - after update() with other contact rows on the same factors, only the changed rows' columns
//    are solved for, and the blocks are still B_s K_s+ B_s^T;
//  - the Schur assembly (the default) and the solves' give the same blocks, also with K freed;
//  - "Dual operator" = auto chooses by the QP and the bytes;
//  - F_s that do not fit the node's available memory: explicit stops with an error naming the
//    parameter, auto falls back to implicit (TFETI_MEMINFO gives a node with room for the
//    subdomain factors alone);
//    every rank takes part in that check, also where only some assemble from scratch; the
//    blocks that update() assembles anew in part are checked too;
//  - an unknown "Dual operator" is an error listing the valid values.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "tfeti_FakeNodeMemory.hpp"
#include "tfeti_FetiSolver.hpp"
#include "tfeti_NodeMemory.hpp"
#include "tfeti_Test3d.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

Teuchos::ParameterList parameters(const std::string& dualOperator, const std::string& prec,
                                  const std::string& storage = "packed") {
  Teuchos::ParameterList params = tfeti_test::tightFetiParameters(prec, dualOperator);
  params.set("Explicit storage", storage);
  return params;
}

tfeti::StructuredRectangle square() {
  return tfeti::StructuredRectangle(0, 1, 0, 1, 4, 4, 4, 4);
}

std::vector<tfeti::SubdomainData> local2d(const tfeti_test::Physics& ph) {
  return tfeti_test::localSubdomains(square(), *Tpetra::getDefaultComm(), ph);
}

std::vector<tfeti::SubdomainData> local3d(const tfeti_test::Box3d& box, double E = 1.0) {
  tfeti_test::Material3d mat;
  mat.dofsPerNode = 3;
  mat.E = E;
  return tfeti_test::localBoxSubdomains(box, mat, {0.0, 0.0, -1.0}, *Tpetra::getDefaultComm());
}

// B_s K_s+ B_s^T of local subdomain i, one column at a time, rows in increasing global id.
std::vector<double> columnByColumn(const tfeti::FetiSolver& solver, std::size_t i) {
  const auto& entries = solver.tearing().subdomainRows[i];
  std::vector<tfeti::GO> rows;
  for (const auto& e : entries) rows.push_back(e.row);
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  const auto local = [&](tfeti::GO r) {
    return static_cast<int>(std::lower_bound(rows.begin(), rows.end(), r) - rows.begin());
  };
  tfeti::Subdomain& s = *solver.subdomains()[i];
  const int n = s.numDofs(), m = static_cast<int>(rows.size());
  std::vector<double> F(static_cast<std::size_t>(m) * m, 0.0), b(n), x(n);
  for (int c = 0; c < m; ++c) {
    std::fill(b.begin(), b.end(), 0.0);
    for (const auto& e : entries)
      if (local(e.row) == c) b[e.dof] += e.coef;
    s.applyPseudoInverse(b.data(), x.data());
    for (const auto& e : entries)
      F[static_cast<std::size_t>(c) * m + local(e.row)] += e.coef * x[e.dof];
  }
  return F;
}

double relativeDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0, s = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    d = std::max(d, std::abs(a[k] - b[k]));
    s = std::max(s, std::abs(b[k]));
  }
  return s > 0.0 ? d / s : d;
}

// max over ranks and local subdomains of |F_s - B_s K_s+ B_s^T| / max |.|.
double blockError(const tfeti::FetiSolver& solver, const tfeti::ExplicitDualOperator& ex) {
  double err = 0.0;
  for (std::size_t i = 0; i < solver.subdomains().size(); ++i) {
    const std::vector<double> expected = columnByColumn(solver, i);
    const std::vector<double> got = ex.fullBlock(i);
    if (got.size() != expected.size()) return 1.0;
    err = std::max(err, relativeDifference(got, expected));
  }
  return tfeti_test::globalMax(*solver.comm(), err);
}

// ||F_explicit x - F_implicit x|| / ||F_implicit x|| for a random x.
double applyDifference(const tfeti::FetiSolver& solver, const tfeti::DualOperator& explicitF) {
  const auto& t = solver.tearing();
  auto Kplus = Teuchos::rcp(new tfeti::PseudoInverseOperator(t.primalMap, solver.subdomains()));
  tfeti::DualOperator implicitF(t.B, Kplus);
  tfeti::Vector x(t.multiplierMap), ye(t.multiplierMap), yi(t.multiplierMap);
  x.randomize();
  ye.putScalar(7.0);  // beta = 0 must ignore what Y held
  explicitF.apply(x, ye);
  implicitF.apply(x, yi);
  ye.update(-1.0, yi, 1.0);
  return ye.norm2() / yi.norm2();
}

}  // namespace

TEUCHOS_UNIT_TEST(ExplicitDual, BlocksAreBKplusBtColumnByColumn) {
  auto comm = Tpetra::getDefaultComm();
  for (const std::string storage : {"packed", "full"}) {
    tfeti::FetiSolver solver(comm, square().numSubdomains(), local2d(tfeti_test::elasticity()),
                             parameters("explicit", "dirichlet", storage));
    const auto& ex = solver.dualOperator()->explicitPart();
    TEST_ASSERT(ex != nullptr);
    if (!ex) return;
    const double err = blockError(solver, *ex);
    out << storage << ": max |F_s - B_s K_s+ B_s^T| / max |F_s| = " << err << "\n";
    TEST_COMPARE(err, <, 1e-12);
    TEST_COMPARE(applyDifference(solver, *solver.dualOperator()), <, 1e-12);
    // Bytes: m^2 or m(m+1)/2 doubles per block, summed over ranks; the largest rank's at most.
    unsigned long long mine = 0;
    for (const auto& b : ex->blocks()) {
      const unsigned long long m = static_cast<unsigned long long>(b.rows());
      mine += 8ULL * (storage == "packed" ? m * (m + 1) / 2 : m * m);
    }
    const auto bytes = solver.explicitDualBytes();
    TEST_EQUALITY(bytes.total, static_cast<unsigned long long>(
                                   tfeti_test::globalSum(*comm, static_cast<long long>(mine))));
    TEST_COMPARE(bytes.maxPerRank, <=, bytes.total);
    TEST_COMPARE(bytes.maxPerRank, >, 0ULL);
    TEST_EQUALITY(solver.dualOperatorKind(), std::string("explicit"));
  }
  tfeti::FetiSolver implicitSolver(comm, square().numSubdomains(), local2d(tfeti_test::poisson()),
                                   parameters("implicit", "lumped"));
  TEST_EQUALITY(implicitSolver.explicitDualBytes().total, 0ULL);
  TEST_EQUALITY(implicitSolver.dualOperatorKind(), std::string("implicit"));
}

// A subdomain refactorized under the operator (another material: the same rigid modes) makes
// its block stale: the next apply reassembles it, and only it.
TEUCHOS_UNIT_TEST(ExplicitDual, ReassembledAfterRefactorization) {
  auto comm = Tpetra::getDefaultComm();
  tfeti::FetiSolver solver(comm, square().numSubdomains(), local2d(tfeti_test::elasticity()),
                           parameters("explicit", "lumped"));
  auto ex =
      std::const_pointer_cast<tfeti::ExplicitDualOperator>(solver.dualOperator()->explicitPart());
  const long long before = ex->assemblies();
  std::vector<std::vector<double>> old;
  for (std::size_t i = 0; i < solver.subdomains().size(); ++i) old.push_back(ex->fullBlock(i));
  tfeti_test::Physics stiffer = tfeti_test::elasticity();
  stiffer.law = plasticity::ElasticLaw(3.7, 0.21);
  // The first local subdomain of every rank gets the new material.
  if (!solver.subdomains().empty())
    solver.subdomains()[0]->refactorize(
        tfeti_test::subdomainData(solver.data()[0].mesh, stiffer).K);
  TEST_EQUALITY(ex->assemblies(), before);  // nothing done until it is used
  TEST_COMPARE(applyDifference(solver, *solver.dualOperator()), <, 1e-12);
  TEST_EQUALITY(ex->assemblies(), before + (solver.subdomains().empty() ? 0 : 1));
  TEST_COMPARE(blockError(solver, *ex), <, 1e-12);
  if (!solver.subdomains().empty()) {
    TEST_COMPARE(relativeDifference(ex->fullBlock(0), old[0]), >, 0.1);
    for (std::size_t i = 1; i < old.size(); ++i) TEST_ASSERT(ex->fullBlock(i) == old[i]);
  }
}

// Explicit against implicit: the same iterations and the solution to 1e-10, 2D and 3D, lumped
// and Dirichlet, then after update() (new loads: every block taken over, none assembled) and
// updateStiffness() (new factors: every block assembled again).
TEUCHOS_UNIT_TEST(ExplicitDual, SameSolveAsImplicit) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti_test::Box3d box(2, 2, 2, 3, 3, 3, false);
  for (const int dim : {2, 3})
    for (const std::string prec : {"lumped", "dirichlet"}) {
      const int N = dim == 2 ? square().numSubdomains() : box.numSubdomains();
      const auto make = [&](const std::string& kind) {
        return tfeti::FetiSolver(comm, N,
                                 dim == 2 ? local2d(tfeti_test::elasticity()) : local3d(box),
                                 parameters(kind, prec));
      };
      tfeti::FetiSolver im = make("implicit"), ex = make("explicit");
      const auto compare = [&](const std::string& what) {
        const tfeti::DualResult ri = im.solve(), re = ex.solve();
        double diff = 0.0, scale = 0.0;
        for (std::size_t i = 0; i < im.data().size(); ++i)
          for (std::size_t k = 0; k < im.solution(i).size(); ++k) {
            diff = std::max(diff, std::abs(im.solution(i)[k] - ex.solution(i)[k]));
            scale = std::max(scale, std::abs(im.solution(i)[k]));
          }
        diff = tfeti_test::globalMax(*comm, diff) / tfeti_test::globalMax(*comm, scale);
        out << dim << "D " << prec << " " << what << ": iterations " << ri.iterations << " / "
            << re.iterations << ", solution difference " << diff << "\n";
        TEST_ASSERT(ri.converged && re.converged);
        TEST_EQUALITY(ri.iterations, re.iterations);
        TEST_COMPARE(diff, <, 1e-10);
      };
      compare("set-up");
      const auto* blocks = ex.dualOperator()->explicitPart().get();
      const long long assembled = blocks->assemblies();
      TEST_EQUALITY(assembled, static_cast<long long>(ex.subdomains().size()));
      std::vector<std::vector<double>> loads;
      for (const auto& s : ex.subdomains()) {
        loads.push_back(s->load());
        for (double& v : loads.back()) v *= -2.0;
      }
      im.update(loads, {});
      ex.update(loads, {});
      TEST_EQUALITY(ex.dualOperator()->explicitPart()->assemblies(), 0LL);  // all taken over
      compare("update");
      std::vector<tfeti::CsrMatrix> K;
      std::vector<std::vector<double>> coords;
      const auto stiffer = dim == 2 ? local2d([] {
        tfeti_test::Physics p = tfeti_test::elasticity();
        p.law = plasticity::ElasticLaw(2.0, 0.3);
        return p;
      }())
                                    : local3d(box, 2.0);
      for (const auto& d : stiffer) {
        K.push_back(d.K);
        coords.push_back(d.mesh.coords);
      }
      im.updateStiffness(K, coords, loads, {});
      ex.updateStiffness(K, coords, loads, {});
      TEST_EQUALITY(ex.dualOperator()->explicitPart()->assemblies(),
                    static_cast<long long>(ex.subdomains().size()));
      compare("updateStiffness");
    }
}

namespace {

// Contact rows under the clamped box: -u_z <= 0 at the bottom nodes with x >= xMin, the
// coefficient -scale instead of -1 from x >= 9 on (tfeti_test::floorRows), keyed by the node.
std::vector<tfeti::InequalityRow> floorRows(const tfeti_test::Box3d& box, double xMin,
                                            double scale) {
  return tfeti_test::floorRows(
      box, [](double) { return 0.0; }, xMin, true,
      [scale](double x) { return x >= 9.0 ? -scale : -1.0; });
}

// The rows of a block as their (dof, coefficient) entries.
std::vector<std::vector<std::pair<int, double>>> rowEntries(
    const tfeti::ExplicitDualOperator::Block& b) {
  std::vector<std::vector<std::pair<int, double>>> rows(b.rows());
  for (std::size_t k = 0; k < b.entryRow.size(); ++k)
    rows[b.entryRow[k]].emplace_back(b.entryDof[k], b.entryCoef[k]);
  return rows;
}

}  // namespace

// update() with other contact rows on the same factors, as a nonlinear loop's contact rows move
// (rows added at 3 <= x < 6, the coefficients changed from x = 9 on, the rest kept): a block
// keeps the old block's values for its unchanged rows and solves only for the others, exactly
// as many columns as rows changed; every block is still B_s K_s+ B_s^T column by column.
TEUCHOS_UNIT_TEST(ExplicitDual, OnlyChangedRowsAreSolvedFor) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti_test::Box3d box(4, 2, 1, 3, 3, 3, false);
  for (const std::string storage : {"packed", "full"}) {
    tfeti::FetiSolver solver(comm, box.numSubdomains(), local3d(box),
                             parameters("explicit", "lumped", storage), floorRows(box, 6.0, 1.0));
    const auto before = solver.dualOperator()->explicitPart();
    TEST_COMPARE(blockError(solver, *before), <, 1e-12);
    std::vector<std::vector<double>> loads;
    for (const auto& s : solver.subdomains()) loads.push_back(s->load());
    solver.update(loads, floorRows(box, 3.0, 0.5));
    const auto after = solver.dualOperator()->explicitPart();
    // The columns to solve for: rows of a block that its old block does not have.
    long long changed = 0, blocksChanged = 0;
    for (std::size_t i = 0; i < after->blocks().size(); ++i) {
      const auto oldRows = rowEntries(before->blocks()[i]);
      const auto newRows = rowEntries(after->blocks()[i]);
      for (const auto& r : newRows)
        if (std::find(oldRows.begin(), oldRows.end(), r) == oldRows.end()) ++changed;
      blocksChanged += newRows != oldRows ? 1 : 0;
    }
    const double err = blockError(solver, *after);
    out << storage << ": " << tfeti_test::globalSum(*comm, after->assembledColumns())
        << " columns solved for in " << tfeti_test::globalSum(*comm, after->assemblies())
        << " blocks, of " << tfeti_test::globalSum(*comm, after->assembledRows())
        << " rows; max |F_s - B_s K_s+ B_s^T| / max |F_s| = " << err << "\n";
    TEST_EQUALITY(after->assembledColumns(), changed);
    TEST_EQUALITY(after->assemblies(), blocksChanged);
    TEST_COMPARE(tfeti_test::globalSum(*comm, changed), >, 0LL);
    // In part: fewer columns solved than the assembled blocks have rows.
    TEST_COMPARE(tfeti_test::globalSum(*comm, after->assembledColumns()), <,
                 tfeti_test::globalSum(*comm, after->assembledRows()));
    TEST_COMPARE(err, <, 1e-12);
    TEST_COMPARE(applyDifference(solver, *solver.dualOperator()), <, 1e-12);
  }
}

// The floor rows spread as mortar contact rows are, over several entries each: half of a row on
// its node's z dof, the other half shared by the z dofs of the subdomain's bottom nodes within one
// element. The Schur assembly forms such columns through w = Z C^T (schurColumns' second way),
// the one-entry rows entry by entry.
std::vector<tfeti::InequalityRow> spreadRows(const tfeti_test::Box3d& box,
                                             std::vector<tfeti::InequalityRow> rows) {
  for (auto& r : rows) {
    const tfeti::ConstraintEntry c = r.entries.front();
    const tfeti::SubdomainMesh m = box.subdomain(c.subdomain);
    const int node = c.dof / 3;
    std::vector<int> near;
    for (int n = 0; n < m.numNodes(); ++n)
      if (n != node && m.coords[3 * n + 2] == 0.0 &&
          std::abs(m.coords[3 * n] - m.coords[3 * node]) <= 1.0 &&
          std::abs(m.coords[3 * n + 1] - m.coords[3 * node + 1]) <= 1.0)
        near.push_back(n);
    r.entries = {{c.subdomain, c.dof, 0.5 * c.coef}};
    for (int n : near)
      r.entries.push_back(
          {c.subdomain, 3 * n + 2, 0.5 * c.coef / static_cast<double>(near.size())});
  }
  return rows;
}

// "Explicit assembly": schur (the default) assembles every block from the Schur complement of
// K_reg onto the dofs B_s touches (fixing dofs among them in 3D: the box's Dirichlet rows),
// solves by the columns of B_s^T; both give B_s K_s+ B_s^T column by column, in 2D, and in 3D
// with contact rows of one entry each and spread over several (spreadRows). With "Keep subdomain
// matrices" = false the Schur assembly still takes place, and K is freed after it.
TEUCHOS_UNIT_TEST(ExplicitDual, SchurAndSolvesAssembliesAgree) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti_test::Box3d box(4, 2, 1, 3, 3, 3, false);
  for (const std::string rowKind : {"2D", "3D floor", "3D spread floor"}) {
    const int dim = rowKind == "2D" ? 2 : 3;
    const std::vector<tfeti::InequalityRow> rows =
        rowKind == "2D"         ? std::vector<tfeti::InequalityRow>{}
        : rowKind == "3D floor" ? floorRows(box, 3.0, 0.5)
                                : spreadRows(box, floorRows(box, 3.0, 0.5));
    std::vector<std::vector<double>> blocks[2];
    for (const std::string assembly : {"schur", "solves"})
      for (const bool keep : {true, false}) {
        Teuchos::ParameterList params = parameters("explicit", "dirichlet");
        params.set("Explicit assembly", assembly);
        params.set("Keep subdomain matrices", keep);
        tfeti::FetiSolver solver(comm, dim == 2 ? square().numSubdomains() : box.numSubdomains(),
                                 dim == 2 ? local2d(tfeti_test::elasticity()) : local3d(box),
                                 params, rows);
        const auto ex = solver.dualOperator()->explicitPart();
        long long nonEmpty = 0;
        for (const auto& b : ex->blocks()) nonEmpty += b.rows() > 0 ? 1 : 0;
        const double err = blockError(solver, *ex);
        out << rowKind << ", " << assembly << (keep ? "" : ", K freed") << ": "
            << tfeti_test::globalSum(*comm, ex->schurAssemblies()) << " of "
            << tfeti_test::globalSum(*comm, ex->assemblies())
            << " blocks from the Schur complement; max |F_s - B_s K_s+ B_s^T| / max |F_s| = " << err
            << "\n";
        TEST_COMPARE(err, <, 1e-12);
        TEST_EQUALITY(ex->schurAssemblies(), assembly == "schur" ? nonEmpty : 0LL);
        TEST_EQUALITY(solver.explicitAssembly().schurBlocks,
                      assembly == "schur" ? tfeti_test::globalSum(*comm, nonEmpty) : 0LL);
        for (const auto& sub : solver.subdomains()) TEST_EQUALITY(sub->hasStiffness(), keep);
        if (keep)
          for (std::size_t i = 0; i < ex->blocks().size(); ++i)
            blocks[assembly == "schur" ? 0 : 1].push_back(ex->fullBlock(i));
      }
    double diff = 0.0;
    TEST_EQUALITY(blocks[0].size(), blocks[1].size());
    for (std::size_t i = 0; i < blocks[0].size() && i < blocks[1].size(); ++i)
      diff = std::max(diff, relativeDifference(blocks[0][i], blocks[1][i]));
    out << rowKind << ": schur against solves, max relative difference "
        << tfeti_test::globalMax(*comm, diff) << "\n";
    TEST_COMPARE(tfeti_test::globalMax(*comm, diff), <, 1e-12);
  }
}

// "Dual operator" = auto: explicit exactly where the dual problem is a QP and the F_s take fewer
// bytes than the factors. The bytes it compared are the F_s an explicit run holds and the
// factors the solver reports; a linear problem stays implicit, a QP goes either way with how much
// of the subdomains' surface carries rows (3D, 2^3 elements each: two subdomains glued on one
// face, F_s smaller than their factors; 3 x 3 x 3 of them, larger).
TEUCHOS_UNIT_TEST(ExplicitDual, AutoChoosesByQpAndBytes) {
  auto comm = Tpetra::getDefaultComm();
  {
    tfeti::FetiSolver solver(comm, square().numSubdomains(), local2d(tfeti_test::elasticity()),
                             parameters("auto", "dirichlet"));
    const auto& c = solver.dualOperatorChoice();
    TEST_ASSERT(c.automatic);
    TEST_ASSERT(!c.qp);
    TEST_EQUALITY(c.chosen, std::string("implicit"));
    TEST_EQUALITY(solver.dualOperatorKind(), std::string("implicit"));
  }
  std::vector<std::string> chosen;
  for (const int s : {2, 3}) {
    const tfeti_test::Box3d box(s, s == 2 ? 1 : s, s == 2 ? 1 : s, 2, 2, 2, false);
    const auto rows = tfeti_test::floorRows(
        box, [](double) { return 0.0; }, 0.0, true);
    tfeti::FetiSolver solver(comm, box.numSubdomains(), local3d(box), parameters("auto", "lumped"),
                             rows);
    const auto c = solver.dualOperatorChoice();
    tfeti::FetiSolver forced(comm, box.numSubdomains(), local3d(box),
                             parameters("explicit", "lumped"), rows);
    out << box.numSubdomains() << " subdomains: qp " << c.qp << ", F_s " << c.explicitBytes
        << " bytes, factors " << c.factorBytes << " bytes: " << c.chosen << "\n";
    TEST_ASSERT(c.automatic && c.qp);
    TEST_EQUALITY(c.explicitBytes, static_cast<double>(forced.explicitDualBytes().total));
    TEST_EQUALITY(c.factorBytes, static_cast<double>(solver.globalFactorBytes()));
    const std::string expected = c.explicitBytes < c.factorBytes ? "explicit" : "implicit";
    TEST_EQUALITY(c.chosen, expected);
    TEST_EQUALITY(solver.dualOperatorKind(), expected);
    chosen.push_back(c.chosen);
  }
  TEST_EQUALITY(chosen.front(), std::string("explicit"));
  TEST_EQUALITY(chosen.back(), std::string("implicit"));
}

namespace {

// The explicit operator's error where its F_s do not fit a node with `available` bytes.
void checkDoesNotFitError(const std::string& msg, double available, Teuchos::FancyOStream& out,
                          bool& success) {
  out << msg << "\n";
  TEST_ASSERT(tfeti_test::contains(msg, "\"Dual operator\" = explicit"));
  TEST_ASSERT(tfeti_test::contains(msg, "do not fit"));
  TEST_ASSERT(tfeti_test::contains(msg, tfeti::bytesText(available) + " available (MemAvailable)"));
  TEST_ASSERT(tfeti_test::contains(msg, "implicit"));
}

// auto fallen back to implicit solves as the implicit solver: the same iterations, the same
// solution to rounding.
void checkSolvesAsImplicit(tfeti::FetiSolver& fallback, tfeti::FetiSolver& implicit,
                           Teuchos::FancyOStream& out, bool& success) {
  TEST_EQUALITY(fallback.dualOperatorKind(), std::string("implicit"));
  TEST_ASSERT(!fallback.dualOperatorChoice().fitsMemory);
  const tfeti::DualResult rf = fallback.solve(), ri = implicit.solve();
  TEST_ASSERT(rf.converged && ri.converged);
  TEST_EQUALITY(rf.iterations, ri.iterations);
  for (std::size_t i = 0; i < fallback.data().size(); ++i)
    TEST_COMPARE_FLOATING_ARRAYS(fallback.solution(i), implicit.solution(i), 1e-14);
}

}  // namespace

TEUCHOS_UNIT_TEST(ExplicitDual, FsBeyondTheNodesMemory) {
  auto comm = Tpetra::getDefaultComm();
  // A 3D QP whose F_s take fewer bytes than the factors: auto chooses explicit
  // (AutoChoosesByQpAndBytes).
  const tfeti_test::Box3d box(2, 1, 1, 2, 2, 2, false);
  const auto rows = tfeti_test::floorRows(
      box, [](double) { return 0.0; }, 0.0, true);
  const auto make = [&](const std::string& kind, bool keep, const std::string& solver) {
    Teuchos::ParameterList params = parameters(kind, "lumped");
    params.set("Keep subdomain matrices", keep);
    params.set("Local solver", solver);
    return tfeti::FetiSolver(comm, box.numSubdomains(), local3d(box), params, rows);
  };
  // A node that has room for the subdomain factors and then, one KiB short, not for the F_s:
  // its available bytes come from a source that gives plenty to the factors' check
  // (tfeti_MemoryCheck_UnitTests.cpp) and too little to this one.
  long long kib = 0;
  {
    const tfeti::FetiSolver roomy = make("auto", true, "cholmod");
    const auto& c = roomy.dualOperatorChoice();
    out << "this machine: " << c.nodeNeedBytes << " of " << c.nodeAvailableBytes << " bytes\n";
    TEST_EQUALITY(c.chosen, std::string("explicit"));
    TEST_ASSERT(c.fitsMemory);
    // Every rank on this one node: all the F_s, and each rank's transient on top (K is kept).
    TEST_COMPARE(c.nodeNeedBytes, >, c.explicitBytes);
    TEST_COMPARE(c.nodeAvailableBytes, >, c.nodeNeedBytes);
    kib = tfeti_test::kibAtLeast(c.nodeNeedBytes) - 1;
  }
  // With K freed as the blocks are assembled, the F_s of this small problem need less than its
  // factors. KLU2's factors are not checked (it cannot tell their bytes before it factorizes):
  // its first read of the node's memory is the F_s' check, with 1 KiB.
  struct Case {
    bool keep;
    std::string solver;
    long long kib;
    int plentyReads;  // the checks before the F_s' (the factors'; lumped: no preconditioner's)
  };
  for (const Case& k : {Case{true, "cholmod", kib, 1}, Case{false, "klu2", 1, 0}}) {
    out << "K kept " << k.keep << ", " << k.solver << ", " << k.kib << " KiB available\n";
    int reads = 0;
    tfeti::setAvailableBytesSource(
        [&] { return ++reads <= k.plentyReads ? 1e15 : 1024.0 * static_cast<double>(k.kib); });
    checkDoesNotFitError(tfeti_test::messageOf([&] { make("explicit", k.keep, k.solver); }),
                         1024.0 * k.kib, out, success);
    reads = 0;
    tfeti::FetiSolver fallback = make("auto", k.keep, k.solver);
    tfeti::setAvailableBytesSource({});
    tfeti::FetiSolver implicit = make("implicit", k.keep, k.solver);
    TEST_EQUALITY(fallback.dualOperatorChoice().chosen, std::string("implicit"));
    TEST_EQUALITY(fallback.dualOperatorChoice().nodeAvailableBytes, 1024.0 * k.kib);
    // The K kept for the Schur assembly are freed as the implicit operator would have.
    for (std::size_t i = 0; i < fallback.subdomains().size(); ++i)
      TEST_EQUALITY(fallback.subdomains()[i]->hasStiffness(),
                    implicit.subdomains()[i]->hasStiffness());
    checkSolvesAsImplicit(fallback, implicit, out, success);
  }
}

// updateStiffness() with a new K on rank 0's subdomains only: rank 0 assembles its blocks from
// scratch, the others take theirs over, and the memory check, which is collective, must still
// be reached by every rank (it once hung there); the solve then matches implicit's.
TEUCHOS_UNIT_TEST(ExplicitDual, MemoryCheckWhenOnlySomeRanksAssembleAnew) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti_test::Box3d box(2, 2, 2, 2, 2, 2, false);
  const auto make = [&](const std::string& kind) {
    return tfeti::FetiSolver(comm, box.numSubdomains(), local3d(box), parameters(kind, "lumped"));
  };
  tfeti::FetiSolver im = make("implicit"), ex = make("explicit");
  const auto changed = local3d(box, comm->getRank() == 0 ? 2.0 : 1.0);
  const tfeti_test::StiffnessUpdate up = tfeti_test::stiffnessUpdate(changed);
  im.updateStiffness(up.K, up.coords, up.loads, {});
  ex.updateStiffness(up.K, up.coords, up.loads, {});
  const long long assembled = ex.dualOperator()->explicitPart()->assemblies();
  out << "rank " << comm->getRank() << ": " << assembled << " blocks assembled anew\n";
  TEST_EQUALITY(assembled, comm->getRank() == 0 || comm->getSize() == 1
                               ? static_cast<long long>(ex.subdomains().size())
                               : 0LL);
  TEST_ASSERT(ex.dualOperatorChoice().fitsMemory);
  TEST_COMPARE(ex.dualOperatorChoice().nodeAvailableBytes, >, 0.0);
  const tfeti::DualResult ri = im.solve(), re = ex.solve();
  TEST_ASSERT(ri.converged && re.converged);
  TEST_EQUALITY(ri.iterations, re.iterations);
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < im.data().size(); ++i)
    for (std::size_t k = 0; k < im.solution(i).size(); ++k) {
      diff = std::max(diff, std::abs(im.solution(i)[k] - ex.solution(i)[k]));
      scale = std::max(scale, std::abs(im.solution(i)[k]));
    }
  TEST_COMPARE(tfeti_test::globalMax(*comm, diff) / tfeti_test::globalMax(*comm, scale), <, 1e-10);
}

// update() with other contact rows on the same factors (the coefficients changed from x = 9 on:
// the blocks of the subdomains at 6 <= x <= 12): those blocks are assembled anew (in part) while
// the old operator still holds its values, so they are checked too, needing less than the first
// assembly of all of them; a node without room for them stops explicit with the error and makes
// auto go on implicitly, as the implicit solver does.
TEUCHOS_UNIT_TEST(ExplicitDual, PartialReassemblyIsChecked) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti_test::Box3d box(4, 2, 1, 3, 3, 3, false);
  const auto make = [&](const std::string& kind) {
    return tfeti::FetiSolver(comm, box.numSubdomains(), local3d(box), parameters(kind, "lumped"),
                             floorRows(box, 6.0, 1.0));
  };
  const auto update = [&](tfeti::FetiSolver& solver) {
    std::vector<std::vector<double>> loads;
    for (const auto& s : solver.subdomains()) loads.push_back(s->load());
    solver.update(loads, floorRows(box, 6.0, 0.5));
  };
  {
    tfeti::FetiSolver roomy = make("explicit");
    const double first = roomy.dualOperatorChoice().nodeNeedBytes;
    const auto before = roomy.dualOperator()->explicitPart();
    update(roomy);
    const auto& c = roomy.dualOperatorChoice();
    // The plan the check counted is what the update did: the blocks it assembled, the columns
    // it solved for (the factors are the same: planned now from the old operator, it is the
    // check's).
    const auto plan = tfeti::ExplicitDualOperator::plannedBlocks(
        roomy.tearing(), roomy.subdomains(), before->storage(), before.get());
    long long assembled = 0, columns = 0;
    for (const auto& p : plan) {
      assembled += p.takenOver ? 0 : 1;
      columns += p.takenOver ? 0 : p.solved;
    }
    out << "first assembly needs " << first << " bytes, the partial one " << c.nodeNeedBytes
        << "\n";
    TEST_ASSERT(c.fitsMemory);
    TEST_COMPARE(c.nodeNeedBytes, >, 0.0);
    TEST_COMPARE(c.nodeNeedBytes, <, first);
    const auto after = roomy.dualOperator()->explicitPart();
    TEST_COMPARE(tfeti_test::globalSum(*comm, after->assemblies()), <,
                 static_cast<long long>(box.numSubdomains()));
    TEST_COMPARE(tfeti_test::globalSum(*comm, after->assemblies()), >, 0LL);
    TEST_EQUALITY(after->assemblies(), assembled);
    TEST_EQUALITY(after->assembledColumns(), columns);
    TEST_COMPARE(tfeti_test::globalSum(*comm, columns), <,
                 tfeti_test::globalSum(*comm, after->assembledRows()));
    TEST_COMPARE(c.nodeAvailableBytes, >, 0.0);
  }
  tfeti::FetiSolver ex = make("explicit"), au = make("auto"), im = make("implicit");
  out << "auto chose " << au.dualOperatorKind() << "\n";
  TEST_EQUALITY(au.dualOperatorKind(), std::string("explicit"));
  tfeti::setAvailableBytesSource([] { return 1024.0; });
  const std::string msg = tfeti_test::messageOf([&] { update(ex); });
  update(au);
  tfeti::setAvailableBytesSource({});
  update(im);
  checkDoesNotFitError(msg, 1024.0, out, success);
  checkSolvesAsImplicit(au, im, out, success);
}

TEUCHOS_UNIT_TEST(ExplicitDual, UnknownValueIsAnError) {
  auto comm = Tpetra::getDefaultComm();
  const std::string msg = tfeti_test::messageOf([&] {
    tfeti::FetiSolver solver(comm, square().numSubdomains(), local2d(tfeti_test::poisson()),
                             parameters("gpu", "lumped"));
  });
  out << msg << "\n";
  TEST_ASSERT(tfeti_test::contains(msg, "Dual operator"));
  TEST_ASSERT(tfeti_test::contains(msg, "gpu"));
  TEST_ASSERT(tfeti_test::contains(msg, "implicit"));
  TEST_ASSERT(tfeti_test::contains(msg, "explicit"));
  Teuchos::ParameterList params = parameters("explicit", "lumped");
  params.set("Explicit assembly", "schurr");
  const std::string typo = tfeti_test::messageOf([&] {
    tfeti::FetiSolver solver(comm, square().numSubdomains(), local2d(tfeti_test::poisson()),
                             params);
  });
  out << typo << "\n";
  TEST_ASSERT(tfeti_test::contains(typo, "Explicit assembly"));
  TEST_ASSERT(tfeti_test::contains(typo, "schurr"));
  TEST_ASSERT(tfeti_test::contains(typo, "solves"));
}
