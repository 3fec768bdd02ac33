// Unit tests of tfeti::Subdomain: the kernel R (rigid body modes, orthonormal), the generalized
// inverse K+ from fixing-dof regularization (K K+ K = K, checked densely), the FETI elimination
// of Dirichlet dofs, and the preconditioner blocks (K_bb and the Schur complement). Subdomains
// are assembled with the plasticity Q1 kernels on StructuredRectangle subdomains of 6x5 elements
// and on a distorted L-shaped mesh; every check runs for each local solver type.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "tfeti_DenseUtils.hpp"
#include "tfeti_HeapTally.hpp"
#include "tfeti_Subdomain.hpp"
#include "tfeti_SubdomainChecks.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

using tfeti::Formulation;
using tfeti_test::checkGeneralizedInverse;
using tfeti_test::frobenius;
using tfeti_test::matmul;
using tfeti_test::Physics;

// 3x2 subdomains of 6x5 elements on (0,3)x(0,2): subdomain 0 touches the Dirichlet side x = 0,
// subdomain 4 (middle of the top row) touches no boundary condition.
tfeti::StructuredRectangle rectangle() {
  return tfeti::StructuredRectangle(0, 3, 0, 2, 3, 2, 6, 5);
}

// Subdomain 4 of the rectangle cut to an L (the 3x3 top-right elements removed), with its nodes
// moved by a smooth map: no two element edges stay parallel.
tfeti::SubdomainMesh distortedLShape() {
  const tfeti::SubdomainMesh block = rectangle().subdomain(4);
  const int ex = 6;
  tfeti::SubdomainMesh m;
  m.id = block.id;
  std::map<int, int> renumber;
  for (int e = 0; e < block.numElements(); ++e) {
    const int i = e % ex, j = e / ex;
    if (i >= 3 && j >= 2) continue;
    std::vector<int> quad;
    for (int a = 0; a < 4; ++a) {
      const int n = block.elements.nodes[4 * e + a];
      auto it = renumber.find(n);
      if (it == renumber.end()) {
        it = renumber.emplace(n, m.numNodes()).first;
        const double x = block.coords[2 * n], y = block.coords[2 * n + 1];
        m.coords.push_back(x + 0.06 * std::sin(3.0 * y) + 0.04 * x * y);
        m.coords.push_back(y + 0.05 * std::cos(2.5 * x) + 0.03 * x * x);
        m.globalNode.push_back(block.globalNode[n]);
      }
      quad.push_back(it->second);
    }
    m.elements.add(quad);
  }
  // The nodes that may be shared: those on the L's perimeter (an edge of one element only).
  std::map<std::pair<int, int>, int> edges;
  for (int e = 0; e < m.numElements(); ++e)
    for (int a = 0; a < 4; ++a) {
      const int p = m.elements.nodes[4 * e + a], q = m.elements.nodes[4 * e + (a + 1) % 4];
      ++edges[{std::min(p, q), std::max(p, q)}];
    }
  for (const auto& [edge, count] : edges)
    if (count == 1)
      m.interfaceCandidates.insert(m.interfaceCandidates.end(), {edge.first, edge.second});
  return m;
}

// Raw rigid body modes of the mesh (not orthonormalized), column-major.
std::vector<std::vector<double>> rawRigidModes(const std::vector<double>& coords, int dpn) {
  const int nodes = static_cast<int>(coords.size() / 2);
  if (dpn == 1) return {std::vector<double>(nodes, 1.0)};
  std::vector<std::vector<double>> R(3, std::vector<double>(2 * nodes, 0.0));
  for (int a = 0; a < nodes; ++a) {
    R[0][2 * a] = 1.0;
    R[1][2 * a + 1] = 1.0;
    R[2][2 * a] = -coords[2 * a + 1];
    R[2][2 * a + 1] = coords[2 * a];
  }
  return R;
}

// Floating subdomain (TFETI): the kernel spans exactly the rigid body modes.
void checkFloating(const tfeti::SubdomainMesh& mesh, const Physics& ph, const std::string& solver,
                   Teuchos::FancyOStream& out, bool& success) {
  out << ph.name() << ", " << solver << ", " << mesh.numElements() << " elements\n";
  const tfeti::SubdomainData data = tfeti_test::subdomainData(mesh, ph);
  const int dpn = ph.dofsPerNode();
  // TFETI ignores the Dirichlet dofs in K: pass some to check that.
  const std::vector<int> dir = {0, dpn * 3};
  tfeti::Subdomain sd(mesh.id, dpn, mesh.coords, data.K, data.f, dir, Formulation::TFETI, solver);
  TEST_COMPARE_ARRAYS(sd.stiffness().values, data.K.values);
  TEST_COMPARE_ARRAYS(sd.load(), data.f);
  const int k = dpn == 1 ? 1 : 3;
  checkGeneralizedInverse(sd, k, out, success);
  if (sd.kernelDim() != k) return;
  const int n = sd.numDofs();
  for (const auto& r : rawRigidModes(mesh.coords, dpn)) {
    std::vector<double> res = r;
    for (int q = 0; q < k; ++q) {
      double c = 0.0;
      for (int i = 0; i < n; ++i) c += sd.kernel()[std::size_t(q) * n + i] * r[i];
      for (int i = 0; i < n; ++i) res[i] -= c * sd.kernel()[std::size_t(q) * n + i];
    }
    TEST_COMPARE(tfeti_test::norm2(res) / tfeti_test::norm2(r), <, 1e-12);
  }
}

const Physics kPhysics[2] = {tfeti_test::poisson(), tfeti_test::elasticity()};

}  // namespace

TEUCHOS_UNIT_TEST(Subdomain, FloatingRectangle) {
  const tfeti::SubdomainMesh mesh = rectangle().subdomain(4);
  TEST_EQUALITY(mesh.numElements(), 30);
  TEST_ASSERT(mesh.dirichletNodes.empty());
  for (const auto& ph : kPhysics)
    for (const auto& solver : tfeti::localSolverTypes())
      checkFloating(mesh, ph, solver, out, success);
}

TEUCHOS_UNIT_TEST(Subdomain, FloatingDistortedLShape) {
  const tfeti::SubdomainMesh mesh = distortedLShape();
  TEST_EQUALITY(mesh.numElements(), 21);
  TEST_EQUALITY(mesh.numNodes(), 33);  // 7x6 grid nodes minus the 3x3 cut off
  for (const auto& ph : kPhysics)
    for (const auto& solver : tfeti::localSolverTypes())
      checkFloating(mesh, ph, solver, out, success);
}

// The block of K+ on a set of dofs (the explicit dual operator's Schur assembly): the fixing
// dofs among them zero, the others as K+ applied to the unit columns, for every local solver
// (Amesos2's offer none: false); after releaseStiffness() there is none either.
TEUCHOS_UNIT_TEST(Subdomain, PseudoInverseBlockIsKplusOnTheDofs) {
  const tfeti::SubdomainMesh mesh = distortedLShape();
  const tfeti::SubdomainData data = tfeti_test::subdomainData(mesh, tfeti_test::elasticity());
  for (const auto& solver : tfeti::localSolverTypes()) {
    tfeti::Subdomain sd(mesh.id, 2, mesh.coords, data.K, data.f, {}, Formulation::TFETI, solver);
    const int n = sd.numDofs();
    // Every fixing dof, and every third other one, descending.
    std::vector<int> dofs;
    for (int d = n - 1; d >= 0; --d)
      if (d % 3 == 1 || std::count(sd.fixingDofs().begin(), sd.fixingDofs().end(), d))
        dofs.push_back(d);
    const int k = static_cast<int>(dofs.size());
    std::vector<double> block;
    const bool done = sd.pseudoInverseBlock(dofs, block);
    TEST_EQUALITY(done, solver.rfind("cholmod", 0) == 0);
    if (!done) {
      TEST_COMPARE(sd.predictInverseBlockMemory(dofs), <, 0);
      continue;
    }
    // What the block takes at its peak (the local solver's inverse block on K's copy with the
    // fixing dofs decoupled, and the vectors around it), as predicted, on the heap to the byte;
    // the block is what stays. With and without fixing dofs among the dofs (the solver's block
    // is then scattered into the whole one, or is the whole one).
    std::vector<int> free;
    for (int d : dofs)
      if (!std::count(sd.fixingDofs().begin(), sd.fixingDofs().end(), d)) free.push_back(d);
    for (const auto& on : {dofs, free}) {
      const std::ptrdiff_t predicted = sd.predictInverseBlockMemory(on);
      std::vector<double>().swap(block);
      const std::size_t before = tfeti_test::HeapTally::inUse();
      tfeti_test::HeapTally::reset();
      const bool again = sd.pseudoInverseBlock(on, block);  // alone between the counts
      const std::size_t peak = tfeti_test::HeapTally::peak() - before;
      const std::size_t held = tfeti_test::HeapTally::inUse() - before;
      out << solver << ", " << on.size() << " dofs: predicted " << predicted << " bytes, peak "
          << peak << "\n";
      TEST_ASSERT(again);
      TEST_EQUALITY(static_cast<std::size_t>(predicted), peak);
      TEST_EQUALITY(held, sizeof(double) * on.size() * on.size());
    }
    TEST_ASSERT(sd.pseudoInverseBlock(dofs, block));
    std::vector<double> unit(static_cast<std::size_t>(n) * k, 0.0), x(unit.size());
    for (int j = 0; j < k; ++j) unit[std::size_t(j) * n + dofs[j]] = 1.0;
    sd.applyPseudoInverse(unit.data(), x.data(), k);
    double diff = 0.0, size = 0.0, fixed = 0.0;
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        const double got = block[std::size_t(j) * k + i];
        diff = std::max(diff, std::abs(got - x[std::size_t(j) * n + dofs[i]]));
        size = std::max(size, std::abs(got));
        for (int f : sd.fixingDofs())
          if (dofs[i] == f || dofs[j] == f) fixed = std::max(fixed, std::abs(got));
      }
    out << solver << ": " << k << " dofs (" << sd.fixingDofs().size() << " fixing), max difference "
        << diff << " of " << size << "\n";
    TEST_EQUALITY(sd.fixingDofs().size(), 3u);
    TEST_EQUALITY(fixed, 0.0);
    TEST_COMPARE(diff, <=, 1e-12 * size);
    sd.releaseStiffness();
    TEST_ASSERT(!sd.pseudoInverseBlock(dofs, block));
  }
}

TEUCHOS_UNIT_TEST(Subdomain, FloatingInFetiWithoutDirichletDofs) {
  // In FETI a subdomain away from the Dirichlet side floats just as in TFETI.
  const tfeti::SubdomainMesh mesh = rectangle().subdomain(4);
  for (const auto& ph : kPhysics) {
    const tfeti::SubdomainData data = tfeti_test::subdomainData(mesh, ph);
    tfeti::Subdomain sd(mesh.id, ph.dofsPerNode(), mesh.coords, data.K, data.f, {},
                        Formulation::FETI, "cholmod");
    checkGeneralizedInverse(sd, ph.dofsPerNode() == 1 ? 1 : 3, out, success);
  }
}

TEUCHOS_UNIT_TEST(Subdomain, FetiNonFloatingWithDirichletSide) {
  const tfeti::SubdomainMesh mesh = rectangle().subdomain(0);
  TEST_EQUALITY(static_cast<int>(mesh.dirichletNodes.size()), 6);  // the side x = 0: 5 elements
  for (const auto& ph : kPhysics)
    for (const auto& solver : tfeti::localSolverTypes()) {
      out << ph.name() << ", " << solver << "\n";
      const int dpn = ph.dofsPerNode();
      const tfeti::SubdomainData data = tfeti_test::subdomainData(mesh, ph);
      const std::vector<int> dir = tfeti_test::dirichletDofs(mesh, dpn);
      tfeti::Subdomain sd(mesh.id, dpn, mesh.coords, data.K, data.f, dir, Formulation::FETI,
                          solver);
      checkGeneralizedInverse(sd, 0, out, success);
      TEST_ASSERT(sd.fixingDofs().empty());
      // Dirichlet rows and columns are decoupled and keep their diagonal; the load is zero there;
      // every other entry is untouched.
      const tfeti::CsrMatrix& K = sd.stiffness();
      TEST_COMPARE_ARRAYS(K.colInd, data.K.colInd);
      std::vector<char> isDir(K.rows, 0);
      for (int d : dir) isDir[d] = 1;
      double offDiag = 0.0, changed = 0.0, diagChange = 0.0;
      for (int i = 0; i < K.rows; ++i)
        for (int p = K.rowPtr[i]; p < K.rowPtr[i + 1]; ++p) {
          const int j = K.colInd[p];
          if (isDir[i] || isDir[j]) {
            if (i == j)
              diagChange = std::max(diagChange, std::abs(K.values[p] - data.K.values[p]));
            else
              offDiag = std::max(offDiag, std::abs(K.values[p]));
          } else {
            changed = std::max(changed, std::abs(K.values[p] - data.K.values[p]));
          }
        }
      TEST_EQUALITY_CONST(offDiag, 0.0);
      TEST_EQUALITY_CONST(changed, 0.0);
      TEST_EQUALITY_CONST(diagChange, 0.0);
      double loadAtDirichlet = 0.0;
      for (int d : dir) loadAtDirichlet = std::max(loadAtDirichlet, std::abs(sd.load()[d]));
      TEST_EQUALITY_CONST(loadAtDirichlet, 0.0);
      // K is nonsingular: K+ = K^{-1}, so K+ K = I.
      const std::vector<double> Kd = tfeti_test::toDense(K);
      std::vector<double> X(Kd.size());
      sd.applyPseudoInverse(Kd.data(), X.data(), K.rows);
      double err = 0.0;
      for (int j = 0; j < K.rows; ++j)
        for (int i = 0; i < K.rows; ++i)
          err = std::max(err, std::abs(X[std::size_t(j) * K.rows + i] - (i == j ? 1.0 : 0.0)));
      TEST_COMPARE(err, <, 1e-10);
    }
}

TEUCHOS_UNIT_TEST(Subdomain, FetiPartialDirichletLeavesTheRemainingModes) {
  // Only the rigid modes that vanish on the Dirichlet dofs stay in the kernel.
  const tfeti::SubdomainMesh mesh = distortedLShape();
  const Physics el = tfeti_test::elasticity();
  const tfeti::SubdomainData data = tfeti_test::subdomainData(mesh, el);
  const int node = 7;
  struct Case {
    std::vector<int> dofs;
    int kernel;
  };
  // Both components of one node: the rotation about it. One component: 2 modes. Two nodes fully
  // fixed: none.
  const std::vector<Case> cases = {{{2 * node, 2 * node + 1}, 1},
                                   {{2 * node}, 2},
                                   {{2 * node, 2 * node + 1, 2 * 20, 2 * 20 + 1}, 0}};
  for (const auto& c : cases)
    for (const auto& solver : tfeti::localSolverTypes()) {
      out << c.dofs.size() << " Dirichlet dofs, " << solver << "\n";
      tfeti::Subdomain sd(mesh.id, 2, mesh.coords, data.K, data.f, c.dofs, Formulation::FETI,
                          solver);
      checkGeneralizedInverse(sd, c.kernel, out, success);
      double onDirichlet = 0.0;
      for (int q = 0; q < sd.kernelDim(); ++q)
        for (int d : c.dofs)
          onDirichlet =
              std::max(onDirichlet, std::abs(sd.kernel()[std::size_t(q) * sd.numDofs() + d]));
      TEST_COMPARE(onDirichlet, <, 1e-14);
    }
  // Poisson with one Dirichlet node: no kernel left.
  const tfeti::SubdomainData pd = tfeti_test::subdomainData(mesh, tfeti_test::poisson());
  tfeti::Subdomain sp(mesh.id, 1, mesh.coords, pd.K, pd.f, {node}, Formulation::FETI, "cholmod");
  checkGeneralizedInverse(sp, 0, out, success);
}

TEUCHOS_UNIT_TEST(Subdomain, PreconditionerBlocksAreKbbAndTheSchurComplement) {
  const tfeti::SubdomainMesh mesh = distortedLShape();
  const std::vector<int> boundary = mesh.boundaryNodes();
  TEST_EQUALITY(static_cast<int>(boundary.size()), 22);  // the perimeter of the L has 22 edges
  for (const auto& ph : kPhysics)
    for (const auto& solver : tfeti::localSolverTypes()) {
      out << ph.name() << ", " << solver << "\n";
      const int dpn = ph.dofsPerNode();
      const tfeti::SubdomainData data = tfeti_test::subdomainData(mesh, ph);
      std::vector<int> bdofs;
      for (int nd : boundary)
        for (int c = 0; c < dpn; ++c) bdofs.push_back(dpn * nd + c);
      std::vector<int> idofs;
      for (int i = 0; i < data.K.rows; ++i)
        if (!std::binary_search(bdofs.begin(), bdofs.end(), i)) idofs.push_back(i);
      const int nb = static_cast<int>(bdofs.size()), ni = static_cast<int>(idofs.size());
      // Reference Schur complement, dense: S = K_bb - K_bi K_ii^{-1} K_ib (CHOLMOD on K_ii).
      const std::vector<double> Kbb = tfeti_test::toDense(data.K.submatrix(bdofs, bdofs));
      const std::vector<double> Kib = tfeti_test::toDense(data.K.submatrix(idofs, bdofs));
      const std::vector<double> Kbi = tfeti_test::toDense(data.K.submatrix(bdofs, idofs));
      auto Kii = tfeti::createLocalSolver("cholmod");
      Kii->factorize(data.K.submatrix(idofs, idofs));
      std::vector<double> Z(Kib.size());
      Kii->solve(Kib.data(), Z.data(), nb);
      std::vector<double> S = matmul(Kbi, Z, nb, ni, nb);
      for (std::size_t i = 0; i < S.size(); ++i) S[i] = Kbb[i] - S[i];

      for (auto type : {tfeti::PreconditionerType::Lumped, tfeti::PreconditionerType::Dirichlet}) {
        tfeti::Subdomain sd(mesh.id, dpn, mesh.coords, data.K, data.f, {}, Formulation::TFETI,
                            solver);
        // Interface given unsorted: the subdomain sorts it.
        std::vector<int> shuffled(bdofs.rbegin(), bdofs.rend());
        sd.setupPreconditioner(shuffled, type, solver);
        TEST_COMPARE_ARRAYS(sd.interfaceDofs(), bdofs);
        const std::vector<double>& ref = type == tfeti::PreconditionerType::Lumped ? Kbb : S;
        std::vector<double> e(nb, 0.0), y(nb);
        double err = 0.0;
        for (int j = 0; j < nb; ++j) {
          e[j] = 1.0;
          sd.applyPreconditionerBlock(e.data(), y.data());
          e[j] = 0.0;
          for (int i = 0; i < nb; ++i)
            err = std::max(err, std::abs(y[i] - ref[std::size_t(j) * nb + i]));
        }
        TEST_COMPARE(err, <, 1e-12 * tfeti_test::maxAbs(Kbb));
        // Every unit column at once (one interior solve with nb right-hand sides): the same
        // block, column by column.
        std::vector<double> I(std::size_t(nb) * nb, 0.0), Y(I.size());
        for (int j = 0; j < nb; ++j) I[std::size_t(j) * nb + j] = 1.0;
        sd.applyPreconditionerBlock(I.data(), Y.data(), nb);
        double blockErr = 0.0;
        for (std::size_t i = 0; i < Y.size(); ++i)
          blockErr = std::max(blockErr, std::abs(Y[i] - ref[i]));
        TEST_COMPARE(blockErr, <, 1e-12 * tfeti_test::maxAbs(Kbb));
        // The Schur complement annihilates the rigid modes' traces; K_bb does not.
        for (const auto& r : rawRigidModes(mesh.coords, dpn)) {
          std::vector<double> rb(nb);
          for (int k = 0; k < nb; ++k) rb[k] = r[bdofs[k]];
          sd.applyPreconditionerBlock(rb.data(), y.data());
          const double rel = tfeti_test::norm2(y) / (frobenius(Kbb) * tfeti_test::norm2(rb));
          if (type == tfeti::PreconditionerType::Dirichlet) {
            TEST_COMPARE(rel, <, 1e-12);
          } else {
            TEST_COMPARE(rel, >, 1e-3);
          }
        }
      }
      // None: no block is set up.
      tfeti::Subdomain none(mesh.id, dpn, mesh.coords, data.K, data.f, {}, Formulation::TFETI,
                            solver);
      none.setupPreconditioner(bdofs, tfeti::PreconditionerType::None, solver);
      TEST_EQUALITY(none.preconditionerFactorBytes(), std::size_t(0));
    }
}

TEUCHOS_UNIT_TEST(Subdomain, InvalidDofsPerNodeThrowsNamingTheSubdomain) {
  const tfeti::SubdomainMesh mesh = rectangle().subdomain(4);
  const tfeti::SubdomainData data = tfeti_test::subdomainData(mesh, tfeti_test::poisson());
  bool threw = false;
  try {
    tfeti::Subdomain sd(17, 3, mesh.coords, data.K, data.f, {}, Formulation::TFETI, "cholmod");
  } catch (const std::invalid_argument& e) {
    threw = true;
    TEST_INEQUALITY(std::string(e.what()).find("subdomain 17"), std::string::npos);
  }
  TEST_ASSERT(threw);
}

// refactorize() keeps the factor of a K equal to the one factorized (the elastic subdomains of a
// plastic body get the same tangent at every Newton iteration) and renews it for any other: a
// scaled K, and a K that differs from it in one value by one unit in the last place.
TEUCHOS_UNIT_TEST(Subdomain, RefactorizeKeepsTheFactorOfAnUnchangedK) {
  const tfeti::SubdomainMesh mesh = distortedLShape();
  const tfeti::SubdomainData data = tfeti_test::subdomainData(mesh, tfeti_test::elasticity());
  tfeti::Subdomain sd(mesh.id, 2, mesh.coords, data.K, data.f, {}, Formulation::TFETI, "cholmod");
  const auto first = sd.factorVersion();
  TEST_ASSERT(!sd.refactorize(data.K));
  TEST_EQUALITY(sd.factorVersion(), first);

  tfeti::CsrMatrix doubled = data.K;
  for (double& v : doubled.values) v *= 2.0;
  TEST_ASSERT(sd.refactorize(doubled));
  const auto second = sd.factorVersion();
  TEST_INEQUALITY(second, first);
  checkGeneralizedInverse(sd, 3, out, success);
  TEST_ASSERT(!sd.refactorize(doubled));
  TEST_EQUALITY(sd.factorVersion(), second);

  // One diagonal value one ulp larger (and the matrix still symmetric).
  tfeti::CsrMatrix nudged = doubled;
  const long k = nudged.find(7, 7);
  TEST_COMPARE(k, >=, 0L);
  nudged.values[k] = std::nextafter(nudged.values[k], 2.0 * nudged.values[k]);
  TEST_ASSERT(nudged.digest() != doubled.digest());
  TEST_ASSERT(sd.refactorize(nudged));
  TEST_INEQUALITY(sd.factorVersion(), second);

  // The digest covers the pattern too: an explicit zero added to a row is another matrix.
  const auto identity = tfeti::csrFromTriplets(2, 2, {0, 1}, {0, 1}, {1.0, 1.0}).digest();
  TEST_ASSERT(identity !=
              tfeti::csrFromTriplets(2, 2, {0, 0, 1}, {0, 1, 1}, {1.0, 0.0, 1.0}).digest());
  TEST_ASSERT(identity == tfeti::csrFromTriplets(2, 2, {1, 0}, {1, 0}, {1.0, 1.0}).digest());
}

// Factorization::Deferred: the subdomain is built (kernel, fixing dofs) without its factor;
// predictFactorMemory tells the factor's bytes (CHOLMOD, exactly what factorize() then
// allocates, and its peak beyond: CHOLMOD's transient and the decoupled copy of K; negative for
// Amesos2's), K+ is an error before factorize(), and after it K+ is the one the immediate
// construction gives, bitwise.
TEUCHOS_UNIT_TEST(Subdomain, DeferredFactorizationIsTheSame) {
  const tfeti::SubdomainMesh mesh = distortedLShape();
  const tfeti::SubdomainData data = tfeti_test::subdomainData(mesh, tfeti_test::elasticity());
  for (const auto& solver : tfeti::localSolverTypes()) {
    tfeti::Subdomain now(mesh.id, 2, mesh.coords, data.K, data.f, {}, Formulation::TFETI, solver);
    tfeti::KernelOptions kernel;
    tfeti::Subdomain later(mesh.id, 2, mesh.coords, kernel, data.K, data.f, {}, Formulation::TFETI,
                           solver, tfeti::Factorization::Deferred);
    TEST_ASSERT(now.factorized() && !later.factorized());
    TEST_ASSERT(later.fixingDofs() == now.fixingDofs());
    const int n = later.numDofs();
    std::vector<double> b(n), x(n), y(n);
    for (int i = 0; i < n; ++i) b[i] = std::sin(1.0 + i);
    const std::string msg =
        tfeti_test::messageOf([&] { later.applyPseudoInverse(b.data(), x.data()); });
    TEST_ASSERT(tfeti_test::contains(msg, "before factorize()"));
    const tfeti::MemoryPrediction predicted = later.predictFactorMemory();
    const std::size_t before = tfeti::localSolverMemoryInUse();
    tfeti::localSolverMemoryPeak(true);
    later.factorize();
    const std::size_t allocated = tfeti::localSolverMemoryInUse() - before;
    const std::size_t peak = tfeti::localSolverMemoryPeak() - before;
    // The transient beyond CHOLMOD's: the copy of K with the fixing dofs decoupled.
    const std::ptrdiff_t copy = static_cast<std::ptrdiff_t>(later.stiffness().bytes());
    out << solver << ": predicted " << predicted.held << " + " << predicted.transient
        << " bytes, CHOLMOD allocated " << allocated << " (peak " << peak << ") and K's copy "
        << copy << "\n";
    if (solver.rfind("cholmod", 0) == 0) {
      TEST_ASSERT(!later.fixingDofs().empty());
      TEST_EQUALITY(static_cast<std::size_t>(predicted.held), allocated);
      TEST_EQUALITY(static_cast<std::size_t>(predicted.held + predicted.transient - copy), peak);
    } else {
      TEST_ASSERT(!predicted.known());
    }
    // Factorized: nothing more to allocate.
    TEST_EQUALITY(later.predictFactorMemory().held, 0);
    TEST_EQUALITY(later.predictFactorMemory().transient, 0);
    now.applyPseudoInverse(b.data(), x.data());
    later.applyPseudoInverse(b.data(), y.data());
    TEST_COMPARE_FLOATING_ARRAYS(x, y, 0.0);
  }
}
