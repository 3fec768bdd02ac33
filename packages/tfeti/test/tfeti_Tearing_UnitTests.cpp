// Unit tests of the tearing (tfeti::buildTearing) on 1, 2 and 3 ranks: the primal and dual
// dimensions of the reference paper's Poisson configurations (unit square, H = 1/2 .. 1/8,
// H/h = 2 and 4) for FETI and TFETI, and the structure of B: entries +-1, gluing rows joining
// two copies of one node and component, Dirichlet rows on x = 0, B (continuous field) = 0,
// m-1 (non-redundant) or m(m-1)/2 (redundant) gluing rows at a node shared by m subdomains,
// the B B^T group pseudo-inverses, and a row numbering that does not depend on the rank count.
#include <Teuchos_DefaultSerialComm.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "tfeti_DenseUtils.hpp"
#include "tfeti_Tearing.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

using tfeti::Formulation;
using tfeti::GO;
using tfeti::LO;

// One row of the paper's table: unit square, subs x subs subdomains of elems x elems elements
// (H = 1/subs, h = 1/(subs * elems)).
struct PaperCase {
  int subs, elems;
  GO primal, feti, tfeti;
};
const PaperCase kPaper[] = {{2, 2, 36, 11, 17},  {4, 2, 144, 63, 75},   {8, 2, 576, 287, 311},
                            {2, 4, 100, 19, 29}, {4, 4, 400, 111, 131}, {8, 4, 1600, 511, 551}};

tfeti::StructuredRectangle unitSquare(int subs, int elems) {
  return tfeti::StructuredRectangle(0, 1, 0, 1, subs, subs, elems, elems);
}

// What FetiSolver hands to buildTearing for one subdomain.
tfeti::TearingInput tearingInput(const tfeti::SubdomainMesh& mesh, int dpn) {
  tfeti::TearingInput in;
  in.id = mesh.id;
  in.numDofs = mesh.numNodes() * dpn;
  in.boundaryNodes = mesh.boundaryNodes();
  const std::vector<int> dir = mesh.dirichletMasks(dpn);
  for (int n : in.boundaryNodes) {
    in.boundaryGlobal.push_back(mesh.globalNode[n]);
    in.boundaryDirichlet.push_back(dir[n]);
  }
  return in;
}

tfeti::Tearing tear(const tfeti::StructuredRectangle& rect,
                    const Teuchos::RCP<const tfeti::Comm>& comm, const std::vector<int>& ids,
                    int dpn, const tfeti::TearingOptions& opts) {
  std::vector<tfeti::TearingInput> local;
  for (int s : ids) local.push_back(tearingInput(rect.subdomain(s), dpn));
  return tfeti::buildTearing(comm, rect.numSubdomains(), local, dpn, opts);
}

std::vector<int> myIds(const tfeti::StructuredRectangle& rect, const tfeti::Comm& comm) {
  return tfeti::subdomainsOfRank(comm.getRank(), rect.numSubdomains(), comm.getSize());
}

// The entries of a locally owned row of B: (global column, value).
std::vector<std::pair<GO, double>> rowEntries(const tfeti::CrsMatrix& B, LO row) {
  const std::size_t len = B.getNumEntriesInLocalRow(row);
  tfeti::CrsMatrix::nonconst_local_inds_host_view_type idx("idx", len);
  tfeti::CrsMatrix::nonconst_values_host_view_type val("val", len);
  std::size_t got = 0;
  B.getLocalRowCopy(row, idx, val, got);
  std::vector<std::pair<GO, double>> e;
  for (std::size_t k = 0; k < got; ++k)
    e.push_back({B.getColMap()->getGlobalElement(idx(k)), val(k)});
  std::sort(e.begin(), e.end());
  return e;
}

// Expected row counts from the node multiplicities of the structured mesh.
struct Expected {
  GO gluing = 0, dirichlet = 0;
};
Expected expectedRows(const tfeti::StructuredRectangle& rect, int dpn,
                      const tfeti::TearingOptions& opts) {
  std::map<GO, int> mult;
  std::map<GO, bool> dir;
  for (int s = 0; s < rect.numSubdomains(); ++s) {
    const tfeti::SubdomainMesh m = rect.subdomain(s);
    for (int n = 0; n < m.numNodes(); ++n) mult[m.globalNode[n]]++;
    for (int n : m.dirichletNodes) dir[m.globalNode[n]] = true;
  }
  Expected e;
  for (const auto& [node, m] : mult) {
    const bool d = dir.count(node) > 0;
    if (m > 1 && (!d || opts.gluingAtDirichletNodes))
      e.gluing += dpn * (opts.gluing == tfeti::Gluing::Redundant ? GO(m) * (m - 1) / 2 : GO(m - 1));
    if (d && opts.formulation == Formulation::TFETI) e.dirichlet += dpn * GO(m);
  }
  return e;
}

// Subdomain and local dof of a global primal dof.
std::pair<int, int> locate(const tfeti::Tearing& t, GO col) {
  const auto it = std::upper_bound(t.dofOffset.begin(), t.dofOffset.end(), col);
  const int s = static_cast<int>(it - t.dofOffset.begin()) - 1;
  return {s, static_cast<int>(col - t.dofOffset[s])};
}

// The dense matrix of scaling group g (whatever its storage), by applying it to unit vectors.
std::vector<double> groupMatrix(const tfeti::ScalingGroups& s, std::size_t g) {
  const int m = static_cast<int>(s.rows[g].size());
  tfeti::ScalingGroups one;
  one.rows.emplace_back(m);
  std::iota(one.rows[0].begin(), one.rows[0].end(), 0);
  one.dense = {s.dense[g]};
  one.sparse = {s.sparse[g]};
  std::vector<double> Q(std::size_t(m) * m, 0.0);
  for (int j = 0; j < m; ++j) {
    Q[std::size_t(j) * m + j] = 1.0;
    one.apply(&Q[std::size_t(j) * m]);
  }
  return Q;
}

// Every scaling group's Q is the Moore-Penrose pseudo-inverse of its block A of B B^T (the four
// Penrose conditions: A Q A = A, Q A Q = Q, Q and A Q symmetric, relative to the size of the
// products); every row is in exactly one group. Returns the largest group's size (over all ranks).
int checkGroupScalings(const tfeti::Tearing& t, const tfeti::Comm& c, Teuchos::FancyOStream& out,
                       bool& success) {
  double pinvErr = 0.0;
  long long groupedRows = 0;
  int largest = 0;
  for (std::size_t g = 0; g < t.scaling.rows.size(); ++g) {
    const auto& rows = t.scaling.rows[g];
    const int m = static_cast<int>(rows.size());
    largest = std::max(largest, m);
    groupedRows += m;
    std::vector<std::vector<std::pair<GO, double>>> e;
    for (LO r : rows) e.push_back(rowEntries(*t.B, r));
    std::vector<double> A(std::size_t(m) * m, 0.0);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j)
        for (const auto& [ci, vi] : e[i])
          for (const auto& [cj, vj] : e[j])
            if (ci == cj) A[std::size_t(j) * m + i] += vi * vj;
    const std::vector<double> Q = groupMatrix(t.scaling, g);
    auto mul = [m](const std::vector<double>& X, const std::vector<double>& Y) {
      std::vector<double> Z(std::size_t(m) * m, 0.0);
      for (int j = 0; j < m; ++j)
        for (int k = 0; k < m; ++k)
          for (int i = 0; i < m; ++i)
            Z[std::size_t(j) * m + i] += X[std::size_t(k) * m + i] * Y[std::size_t(j) * m + k];
      return Z;
    };
    double aMax = 0.0, qMax = 0.0;
    for (std::size_t k = 0; k < A.size(); ++k) {
      aMax = std::max(aMax, std::abs(A[k]));
      qMax = std::max(qMax, std::abs(Q[k]));
    }
    const auto AQ = mul(A, Q);
    const auto AQA = mul(AQ, A), QAQ = mul(mul(Q, A), Q);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) {
        const std::size_t k = std::size_t(j) * m + i, kt = std::size_t(i) * m + j;
        // Each residual relative to the size of its products (rounding grows with |A| |Q|).
        pinvErr =
            std::max({pinvErr, std::abs(AQA[k] - A[k]) / (aMax * std::max(aMax * qMax, 1.0)),
                      std::abs(QAQ[k] - Q[k]) / std::max(qMax * std::max(aMax * qMax, 1.0), 1e-300),
                      std::abs(Q[k] - Q[kt]) / std::max(qMax, 1e-300),
                      std::abs(AQ[k] - AQ[kt]) / std::max(aMax * qMax, 1e-300)});
      }
  }
  largest = static_cast<int>(tfeti_test::globalMax(c, double(largest)));
  out << "  scaling groups: largest " << largest << " rows, pseudo-inverse error "
      << tfeti_test::globalMax(c, pinvErr) << "\n";
  TEST_COMPARE(tfeti_test::globalMax(c, pinvErr), <, 1e-12);
  TEST_EQUALITY(tfeti_test::globalSum(c, groupedRows), static_cast<long long>(t.numRows));
  return largest;
}

// Every structural property of B on one configuration. All verdicts are global (reduced).
void checkStructure(const tfeti::StructuredRectangle& rect, int dpn,
                    const tfeti::TearingOptions& opts, Teuchos::FancyOStream& out, bool& success) {
  auto comm = Tpetra::getDefaultComm();
  const std::vector<int> ids = myIds(rect, *comm);
  const tfeti::Tearing t = tear(rect, comm, ids, dpn, opts);
  const Expected ex = expectedRows(rect, dpn, opts);
  out << "  rows " << t.numRows << " = " << t.numGluingRows << " gluing + " << t.numDirichletRows
      << " Dirichlet (expected " << ex.gluing << " + " << ex.dirichlet << ")\n";
  TEST_EQUALITY(t.numGluingRows, ex.gluing);
  TEST_EQUALITY(t.numDirichletRows, ex.dirichlet);
  TEST_EQUALITY(t.numRows, ex.gluing + ex.dirichlet);
  TEST_EQUALITY(static_cast<GO>(t.multiplierMap->getGlobalNumElements()), t.numRows);
  TEST_EQUALITY(static_cast<GO>(t.B->getGlobalNumRows()), t.numRows);
  TEST_EQUALITY(static_cast<GO>(t.B->getGlobalNumCols()), t.dofOffset.back());
  TEST_EQUALITY(t.dofOffset.front(), GO(0));

  std::vector<tfeti::SubdomainMesh> meshes;
  for (int s = 0; s < rect.numSubdomains(); ++s) meshes.push_back(rect.subdomain(s));
  for (int s = 0; s < rect.numSubdomains(); ++s)
    TEST_EQUALITY(t.dofOffset[s + 1] - t.dofOffset[s], GO(dpn) * meshes[s].numNodes());

  // Row by row.
  long long badValue = 0, badGluing = 0, badDirichlet = 0, otherSize = 0, ones = 0, twos = 0;
  long long duplicates = 0, disconnected = 0;
  std::set<std::pair<GO, GO>> pairs;
  std::map<std::pair<GO, int>, std::vector<std::pair<int, int>>> edges;  // (node, comp) -> subs
  const LO nLocal = static_cast<LO>(t.multiplierMap->getNodeNumElements());
  for (LO r = 0; r < nLocal; ++r) {
    const auto e = rowEntries(*t.B, r);
    for (const auto& [c, v] : e)
      if (v != 1.0 && v != -1.0) ++badValue;
    if (e.size() == 1) {
      ++ones;
      const auto [s, dof] = locate(t, e[0].first);
      const int node = dof / dpn;
      if (e[0].second != 1.0 || meshes[s].coords[2 * node] != 0.0) ++badDirichlet;
    } else if (e.size() == 2) {
      ++twos;
      const auto [sa, da] = locate(t, e[0].first);
      const auto [sb, db] = locate(t, e[1].first);
      const GO na = meshes[sa].globalNode[da / dpn], nb = meshes[sb].globalNode[db / dpn];
      if (sa == sb || na != nb || da % dpn != db % dpn || e[0].second + e[1].second != 0.0)
        ++badGluing;
      if (!pairs.insert({e[0].first, e[1].first}).second) ++duplicates;
      edges[{na, da % dpn}].push_back({sa, sb});
    } else {
      ++otherSize;
    }
  }
  // The gluing rows of every (node, component) group connect all copies of the node (groups are
  // owned by one rank, so the check is local).
  std::map<GO, std::vector<int>> copies;
  for (int s = 0; s < rect.numSubdomains(); ++s)
    for (GO g : meshes[s].globalNode) copies[g].push_back(s);
  for (const auto& [key, list] : edges) {
    std::map<int, int> parent;
    for (int s : copies[key.first]) parent[s] = s;
    std::function<int(int)> root = [&](int s) { return parent[s] == s ? s : root(parent[s]); };
    for (const auto& [a, b] : list) parent[root(a)] = root(b);
    std::set<int> roots;
    for (int s : copies[key.first]) roots.insert(root(s));
    if (roots.size() != 1) ++disconnected;
  }
  const tfeti::Comm& c = *comm;
  TEST_EQUALITY(tfeti_test::globalSum(c, badValue), 0LL);
  TEST_EQUALITY(tfeti_test::globalSum(c, badGluing), 0LL);
  TEST_EQUALITY(tfeti_test::globalSum(c, badDirichlet), 0LL);
  TEST_EQUALITY(tfeti_test::globalSum(c, otherSize), 0LL);
  TEST_EQUALITY(tfeti_test::globalSum(c, duplicates), 0LL);
  TEST_EQUALITY(tfeti_test::globalSum(c, disconnected), 0LL);
  TEST_EQUALITY(tfeti_test::globalSum(c, ones), static_cast<long long>(t.numDirichletRows));
  TEST_EQUALITY(tfeti_test::globalSum(c, twos), static_cast<long long>(t.numGluingRows));

  // B applied to fields on the subdomain copies (Tpetra apply: imports across ranks).
  tfeti::Vector u(t.primalMap), v(t.primalMap), Bu(t.multiplierMap), Bv(t.multiplierMap);
  {
    auto ud = u.getDataNonConst();
    auto vd = v.getDataNonConst();
    std::size_t off = 0;
    for (int s : ids)
      for (int n = 0; n < meshes[s].numNodes(); ++n)
        for (int k = 0; k < dpn; ++k, ++off) {
          const double x = meshes[s].coords[2 * n], y = meshes[s].coords[2 * n + 1];
          ud[off] = (1.0 + k) + x + (2.0 + k) * y * y;  // continuous, nonzero on x = 0
          vd[off] = 1.0 + s + 0.5 * k;                  // jumps by >= 1 across every interface
        }
    TEST_EQUALITY(off, static_cast<std::size_t>(t.primalMap->getNodeNumElements()));
  }
  t.B->apply(u, Bu);
  t.B->apply(v, Bv);
  double gluingU = 0.0, minDirichletU = 1e300, minGluingV = 1e300;
  {
    auto bu = Bu.getData();
    auto bv = Bv.getData();
    for (LO r = 0; r < nLocal; ++r) {
      if (t.B->getNumEntriesInLocalRow(r) == 2) {
        gluingU = std::max(gluingU, std::abs(bu[r]));
        minGluingV = std::min(minGluingV, std::abs(bv[r]));
      } else {
        minDirichletU = std::min(minDirichletU, std::abs(bu[r]));
      }
    }
  }
  TEST_EQUALITY_CONST(tfeti_test::globalMax(c, gluingU), 0.0);
  TEST_COMPARE(-tfeti_test::globalMax(c, -minGluingV), >=, 1.0);
  TEST_COMPARE(-tfeti_test::globalMax(c, -minDirichletU), >=, 1.0);

  // Rows touching each local subdomain: every nonzero of B exactly once over all ranks.
  long long entries = 0, badEntries = 0;
  for (std::size_t i = 0; i < ids.size(); ++i)
    for (const auto& e : t.subdomainRows[i]) {
      ++entries;
      if ((e.coef != 1.0 && e.coef != -1.0) || e.dof < 0 ||
          e.dof >= dpn * meshes[ids[i]].numNodes())
        ++badEntries;
    }
  TEST_EQUALITY(tfeti_test::globalSum(c, entries),
                static_cast<long long>(t.B->getGlobalNumEntries()));
  TEST_EQUALITY(tfeti_test::globalSum(c, badEntries), 0LL);

  checkGroupScalings(t, c, out, success);

  // The numbering does not depend on the rank count: a serial tearing of all subdomains has the
  // same rows under the same ids.
  std::vector<int> all(rect.numSubdomains());
  std::iota(all.begin(), all.end(), 0);
  auto serial = Teuchos::rcp(new Teuchos::SerialComm<int>());
  const tfeti::Tearing ts = tear(rect, serial, all, dpn, opts);
  TEST_EQUALITY(ts.numRows, t.numRows);
  long long mismatched = 0;
  for (LO r = 0; r < nLocal; ++r) {
    const GO row = t.multiplierMap->getGlobalElement(r);
    const LO rs = ts.multiplierMap->getLocalElement(row);
    if (rs < 0 || rowEntries(*t.B, r) != rowEntries(*ts.B, rs)) ++mismatched;
  }
  TEST_EQUALITY(tfeti_test::globalSum(c, mismatched), 0LL);
}

}  // namespace

TEUCHOS_UNIT_TEST(Tearing, PaperTableThroughFetiSolver) {
  auto comm = Tpetra::getDefaultComm();
  for (const auto& pc : kPaper) {
    const tfeti::StructuredRectangle rect = unitSquare(pc.subs, pc.elems);
    for (const std::string form : {"FETI", "TFETI"}) {
      Teuchos::ParameterList params;
      params.set("Formulation", form);
      params.set("Preconditioner", "none");
      tfeti::FetiSolver solver(comm, rect.numSubdomains(),
                               tfeti_test::localSubdomains(rect, *comm, tfeti_test::poisson()),
                               params);
      const GO dual = form == "FETI" ? pc.feti : pc.tfeti;
      out << "H = 1/" << pc.subs << ", h = 1/" << pc.subs * pc.elems << ", " << form << ": primal "
          << solver.primalDimension() << ", dual " << solver.dualDimension() << "\n";
      TEST_EQUALITY(solver.primalDimension(), pc.primal);
      TEST_EQUALITY(solver.dualDimension(), dual);
      TEST_EQUALITY(static_cast<GO>(solver.tearing().primalMap->getGlobalNumElements()), pc.primal);
      TEST_EQUALITY(static_cast<GO>(solver.tearing().multiplierMap->getGlobalNumElements()), dual);
      TEST_EQUALITY(solver.gluingRows(), pc.feti);
      TEST_EQUALITY(solver.dirichletRows(), form == "FETI" ? GO(0) : pc.tfeti - pc.feti);
      // One constant kernel vector per floating subdomain; in FETI the column of subdomains on
      // x = 0 does not float.
      const GO N = rect.numSubdomains();
      TEST_EQUALITY(solver.coarseDimension(), form == "FETI" ? N - pc.subs : N);
    }
  }
}

TEUCHOS_UNIT_TEST(Tearing, PaperTableThroughBuildTearing) {
  auto comm = Tpetra::getDefaultComm();
  for (const auto& pc : kPaper) {
    const tfeti::StructuredRectangle rect = unitSquare(pc.subs, pc.elems);
    for (Formulation f : {Formulation::FETI, Formulation::TFETI}) {
      tfeti::TearingOptions opts;
      opts.formulation = f;
      const tfeti::Tearing t = tear(rect, comm, myIds(rect, *comm), 1, opts);
      TEST_EQUALITY(t.dofOffset.back(), pc.primal);
      TEST_EQUALITY(t.numRows, f == Formulation::FETI ? pc.feti : pc.tfeti);
      // Elasticity: twice the dofs and twice the rows.
      const tfeti::Tearing t2 = tear(rect, comm, myIds(rect, *comm), 2, opts);
      TEST_EQUALITY(t2.dofOffset.back(), 2 * pc.primal);
      TEST_EQUALITY(t2.numRows, 2 * (f == Formulation::FETI ? pc.feti : pc.tfeti));
    }
  }
}

TEUCHOS_UNIT_TEST(Tearing, StructureNonRedundant) {
  for (int dpn : {1, 2})
    for (Formulation f : {Formulation::TFETI, Formulation::FETI})
      for (const auto& [subs, elems] : {std::pair<int, int>{2, 2}, {4, 2}, {3, 3}}) {
        out << "dofs/node " << dpn << ", " << (f == Formulation::FETI ? "FETI" : "TFETI") << ", "
            << subs << "x" << subs << " subdomains of " << elems << "x" << elems << "\n";
        tfeti::TearingOptions opts;
        opts.formulation = f;
        checkStructure(unitSquare(subs, elems), dpn, opts, out, success);
      }
}

TEUCHOS_UNIT_TEST(Tearing, StructureRedundant) {
  // A node shared by m subdomains gets m(m-1)/2 gluing rows: 6 at every cross point.
  for (int dpn : {1, 2})
    for (Formulation f : {Formulation::TFETI, Formulation::FETI}) {
      tfeti::TearingOptions opts;
      opts.formulation = f;
      opts.gluing = tfeti::Gluing::Redundant;
      checkStructure(unitSquare(4, 2), dpn, opts, out, success);
      // By hand for 4x4 subdomains of 2x2 elements: 36 nodes on 2 subdomains, 9 cross points.
      auto comm = Tpetra::getDefaultComm();
      const tfeti::StructuredRectangle rect = unitSquare(4, 2);
      const tfeti::Tearing t = tear(rect, comm, myIds(rect, *comm), dpn, opts);
      TEST_EQUALITY(t.numGluingRows, GO(dpn) * (36 * 1 + 9 * 6));
    }
  // A non-square subdomain grid on a rectangle.
  tfeti::TearingOptions opts;
  opts.gluing = tfeti::Gluing::Redundant;
  checkStructure(tfeti::StructuredRectangle(0, 2, 0, 1, 3, 2, 2, 3), 2, opts, out, success);
}

TEUCHOS_UNIT_TEST(Tearing, StructureWithoutGluingAtDirichletNodes) {
  for (auto gluing : {tfeti::Gluing::NonRedundant, tfeti::Gluing::Redundant}) {
    tfeti::TearingOptions opts;
    opts.gluing = gluing;
    opts.gluingAtDirichletNodes = false;
    checkStructure(unitSquare(4, 2), 1, opts, out, success);
    // Paper case (1/4, 1/8) without the 3 gluing rows on x = 0: 75 - 3 rows.
    auto comm = Tpetra::getDefaultComm();
    const tfeti::StructuredRectangle rect = unitSquare(4, 2);
    const tfeti::Tearing t = tear(rect, comm, myIds(rect, *comm), 1, opts);
    if (gluing == tfeti::Gluing::NonRedundant) TEST_EQUALITY(t.numRows, GO(75 - 3));
  }
}

namespace {

// Rows with multiplier bounds (friction rows: a box [-g, g]) keep their bounds through the
// gathering, each with its own row whatever rank passed it, in an order independent of the rank
// count; an empty box or a non-finite closed side is refused on every rank.
TEUCHOS_UNIT_TEST(Tearing, BoundedRowsKeepTheirBounds) {
  const auto comm = Tpetra::getDefaultComm();
  const tfeti::StructuredRectangle rect = unitSquare(2, 2);
  std::vector<tfeti::TearingInput> local;
  for (int s : myIds(rect, *comm)) local.push_back(tearingInput(rect.subdomain(s), 2));
  const double inf = std::numeric_limits<double>::infinity();
  // Row k on subdomain k % 4, dof 2k: normal rows (default bounds) and boxes of half-width k.
  auto rowK = [&](int k) {
    tfeti::InequalityRow r;
    r.entries = {{k % 4, 2 * k, 1.0}};
    r.gap = 0.1 * k;
    if (k % 2) {
      r.lowerBound = -k;
      r.upperBound = k;
    }
    return r;
  };
  std::vector<tfeti::InequalityRow> mine;
  for (int k = 0; k < 8; ++k)
    if (k % comm->getSize() == comm->getRank()) mine.push_back(rowK(k));
  const tfeti::Tearing t = tfeti::buildTearing(comm, rect.numSubdomains(), local, 2, {}, mine);
  TEST_EQUALITY(t.numInequalityRows, 8);
  TEST_EQUALITY(t.inequalityRows.size(), 8u);
  int boxes = 0;
  for (const auto& r : t.inequalityRows) {
    const int k = static_cast<int>(std::lround(r.gap * 10));
    const tfeti::InequalityRow expected = rowK(k);
    TEST_EQUALITY(r.entries.size(), 1u);
    TEST_EQUALITY(r.entries[0].dof, 2 * k);
    TEST_EQUALITY(r.lowerBound, expected.lowerBound);
    TEST_EQUALITY(r.upperBound, expected.upperBound);
    TEST_EQUALITY(r.isNonPenetration(), k % 2 == 0);
    boxes += r.isNonPenetration() ? 0 : 1;
    if (k % 2 == 0) TEST_EQUALITY(r.upperBound, inf);
  }
  TEST_EQUALITY(boxes, 4);
  // boundActive: exact at 0, to 1e-10 relative at a non-zero bound.
  const tfeti::InequalityRow box = rowK(3);
  TEST_EQUALITY(box.boundActive(3.0 * (1 - 1e-12)), 1);
  TEST_EQUALITY(box.boundActive(-3.0), -1);
  TEST_EQUALITY(box.boundActive(2.9), 0);
  TEST_EQUALITY(rowK(2).boundActive(0.0), -1);
  TEST_EQUALITY(rowK(2).boundActive(1e-300), 0);
  for (const auto& [lo, up] :
       {std::pair<double, double>{1.0, -1.0}, {inf, inf}, {0.0, -inf}, {std::nan(""), 1.0}}) {
    std::vector<tfeti::InequalityRow> bad;
    if (comm->getRank() == 0) {
      bad.push_back(rowK(1));
      bad.back().lowerBound = lo;
      bad.back().upperBound = up;
    }
    TEST_THROW(tfeti::buildTearing(comm, rect.numSubdomains(), local, 2, {}, bad),
               std::invalid_argument);
  }
}

}  // namespace

namespace {

// (subdomain, local node) of every copy of every node, and the untorn nodes on y = 1 by x.
struct Copies {
  std::map<GO, std::vector<std::pair<int, int>>> of;
  std::map<double, GO> top;
};
Copies copiesOf(const tfeti::StructuredRectangle& rect) {
  Copies c;
  for (int s = 0; s < rect.numSubdomains(); ++s) {
    const tfeti::SubdomainMesh m = rect.subdomain(s);
    for (int n = 0; n < m.numNodes(); ++n) {
      c.of[m.globalNode[n]].push_back({s, n});
      if (m.coords[2 * n + 1] == 1.0) c.top[m.coords[2 * n]] = m.globalNode[n];
    }
  }
  return c;
}

// The global rows of the (local) scaling group holding global row `row`, or empty.
std::vector<GO> groupOfRow(const tfeti::Tearing& t, GO row) {
  for (const auto& lids : t.scaling.rows) {
    std::vector<GO> rows;
    for (LO l : lids) rows.push_back(t.multiplierMap->getGlobalElement(l));
    if (std::find(rows.begin(), rows.end(), row) != rows.end()) return rows;
  }
  return {};
}

}  // namespace

// Issue 13: a row against a rigid plane (or a tied row) on a node that a cut shares between two
// subdomains names one copy of the node; it shares that dof with the node's gluing row, so it
// joins its group and Q is (B B^T)^+ of the pair (Separate: the row alone, weight 1/||row||^2).
TEUCHOS_UNIT_TEST(Tearing, InequalityRowOnACutNodeJoinsItsGluingGroup) {
  const auto comm = Tpetra::getDefaultComm();
  const tfeti::StructuredRectangle rect = unitSquare(2, 2);
  const Copies copies = copiesOf(rect);
  const GO node = copies.top.at(0.5);  // on the vertical cut x = 1/2
  TEST_EQUALITY(copies.of.at(node).size(), 2u);
  const auto [sub, localNode] = copies.of.at(node).front();
  std::vector<tfeti::TearingInput> local;
  for (int s : myIds(rect, *comm)) local.push_back(tearingInput(rect.subdomain(s), 2));
  std::vector<tfeti::InequalityRow> mine;
  if (comm->getRank() == 0) mine.push_back({{{sub, 2 * localNode + 1, 1.0}}, 0.0});
  for (auto mode : {tfeti::TearingOptions::InequalityScaling::Joined,
                    tfeti::TearingOptions::InequalityScaling::Separate}) {
    tfeti::TearingOptions opts;
    opts.inequalityScaling = mode;
    const tfeti::Tearing t = tfeti::buildTearing(comm, rect.numSubdomains(), local, 2, opts, mine);
    const std::vector<GO> group = groupOfRow(t, t.firstInequalityRow);
    const double size = tfeti_test::globalMax(*comm, static_cast<double>(group.size()));
    // The other row of a joined group is the gluing row of component y at the node.
    double gluingOfTheNode = 0.0;
    if (group.size() == 2) {
      const GO other = group[0] == t.firstInequalityRow ? group[1] : group[0];
      const LO l = t.multiplierMap->getLocalElement(other);
      const GO col = t.dofOffset[sub] + 2 * localNode + 1;
      for (const auto& [c, v] : rowEntries(*t.B, l))
        if (c == col && std::abs(v) == 1.0 && !t.isInequality(other)) gluingOfTheNode = 1.0;
    }
    const bool joined = mode == tfeti::TearingOptions::InequalityScaling::Joined;
    out << (joined ? "joined" : "separate") << ": the row's group has " << size << " rows\n";
    TEST_EQUALITY(size, joined ? 2.0 : 1.0);
    TEST_EQUALITY(tfeti_test::globalMax(*comm, gluingOfTheNode), joined ? 1.0 : 0.0);
    checkGroupScalings(t, *comm, out, success);
  }
}

// A chain of node-to-face-like rows along y = 1 (each row couples a node with its neighbour, as
// a slave node's row couples it with the master face's nodes) is one group of more rows than the
// dense limit, with the gluing and Dirichlet rows of the nodes it touches: it is factorized
// sparsely, and Q is still the pseudo-inverse of its (here singular: a duplicated row) block.
TEUCHOS_UNIT_TEST(Tearing, ChainLongerThanTheDenseLimitIsFactorizedSparsely) {
  const auto comm = Tpetra::getDefaultComm();
  const tfeti::StructuredRectangle rect(0, 1, 0, 1, 6, 3, 8, 2);
  const Copies copies = copiesOf(rect);
  std::vector<GO> top;
  for (const auto& [x, node] : copies.top) top.push_back(node);
  TEST_EQUALITY(top.size(), 49u);
  std::vector<tfeti::InequalityRow> rows;
  auto dofOf = [&](GO node, int copy, int comp) {
    const auto& cs = copies.of.at(node);
    const auto& [s, n] = cs[copy % cs.size()];
    return tfeti::ConstraintEntry{s, 2 * n + comp, 1.0};
  };
  for (std::size_t i = 0; i + 1 < top.size(); ++i) {
    // y of node i (its last copy) against x and y of node i + 1 (its first copy), and x of node
    // i against y of node i.
    auto a = dofOf(top[i], 1, 1), b = dofOf(top[i + 1], 0, 1), c = dofOf(top[i + 1], 0, 0);
    b.coef = -0.6, c.coef = -0.3;
    rows.push_back({{a, b, c}, 0.01});
    auto d = dofOf(top[i], 0, 0), e = dofOf(top[i], 0, 1);
    e.coef = -0.5;
    rows.push_back({{d, e}, 0.0});
  }
  rows.push_back(rows[7]);  // a duplicate: B B^T of the group is singular
  std::vector<tfeti::InequalityRow> mine;
  for (std::size_t k = 0; k < rows.size(); ++k)
    if (static_cast<int>(k) % comm->getSize() == comm->getRank()) mine.push_back(rows[k]);
  std::vector<tfeti::TearingInput> local;
  for (int s : myIds(rect, *comm)) local.push_back(tearingInput(rect.subdomain(s), 2));
  const tfeti::Tearing t = tfeti::buildTearing(comm, rect.numSubdomains(), local, 2, {}, mine);
  TEST_EQUALITY(t.numInequalityRows, GO(2 * 48 + 1));
  out << "groups " << t.numScalingGroups << ", largest " << t.largestScalingGroup << ", sparse "
      << t.numSparseScalingGroups << "\n";
  TEST_COMPARE(t.largestScalingGroup, >, GO(2 * 48 + 1));
  TEST_EQUALITY(t.numSparseScalingGroups, GO(1));
  const int largest = checkGroupScalings(t, *comm, out, success);
  TEST_EQUALITY(GO(largest), t.largestScalingGroup);
  double nullity = 0.0;
  for (const auto& s : t.scaling.sparse)
    if (s) nullity = std::max(nullity, static_cast<double>(s->nullity()));
  TEST_COMPARE(tfeti_test::globalMax(*comm, nullity), >=, 1.0);
}
