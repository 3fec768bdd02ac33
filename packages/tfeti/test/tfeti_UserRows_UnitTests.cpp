// The caller's equality rows for what the automatic gluing cannot express (issue 17), through
// FetiSolver end to end on 1, 2 and 3 ranks:
//  - periodic pairs: u(x, 0) = u(x, 1) for every x on a Poisson problem whose load depends on y
//    (so that the rows change the solution), against a direct solve of the untorn mesh with the
//    periodic nodes identified;
//  - a non-matching interface: two subdomains meshed with different element heights, tied with
//    "Gluing" = none by rows that interpolate the coarse side at the fine side's nodes, u = 1 on
//    x = 0 by rows with right-hand side 1, a uniform flux out of x = 2: the exact solution is
//    linear, lies in the constrained space, and must come out to the solver's tolerance. The
//    flux crosses the interface, so the rows' multipliers carry it: rows that did not preserve
//    the interface mean of a test function (e.g. a fine node tied to one coarse node) would
//    give another solution.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

using tfeti::GO;

Teuchos::ParameterList tight() {
  Teuchos::ParameterList p;
  p.set("Preconditioner", "dirichlet");
  p.sublist("PCPG").set("Relative tolerance", 1e-11);
  return p;
}

// -Laplace u = f with f = 1 + y (per node, times the consistent load of 1), clamped at x = 0.
std::vector<double> yLoad(const tfeti::SubdomainMesh& m, std::vector<double> f) {
  for (int n = 0; n < m.numNodes(); ++n) f[n] *= 1.0 + m.coords[2 * n + 1];
  return f;
}

TEUCHOS_UNIT_TEST(UserRows, PeriodicPairsAgainstTheIdentifiedMesh) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti::StructuredRectangle rect(0, 2, 0, 1, 3, 2, 4, 4);
  const int nx = rect.elementsX(), ny = rect.elementsY();
  auto local = tfeti_test::localSubdomains(rect, *comm, tfeti_test::poisson());
  for (auto& sd : local) sd.f = yLoad(sd.mesh, sd.f);
  // u(x, 0) - u(x, 1) = 0 for x > 0 (x = 0 is clamped): the copy of each node in the subdomain
  // holding it, rank 0 passing every row.
  std::vector<tfeti::EqualityRow> rows;
  if (comm->getRank() == 0)
    for (int i = 1; i <= nx; ++i) {
      const auto [s0, n0] = rect.copyOfNode(i, 0);
      const auto [s1, n1] = rect.copyOfNode(i, ny);
      rows.push_back({{{s0, n0, 1.0}, {s1, n1, -1.0}}, 0.0});
    }
  tfeti::FetiSolver solver(comm, rect.numSubdomains(), std::move(local), tight(), {}, rows);
  const tfeti::DualResult r = solver.solve();
  TEST_ASSERT(r.converged);
  TEST_EQUALITY(solver.userEqualityRows(), static_cast<GO>(nx));

  // The untorn mesh with node (i, ny) identified with (i, 0): K and f summed onto the kept
  // nodes, then the clamped nodes held at zero.
  const tfeti::SubdomainMesh whole = rect.wholeMesh();
  const auto ph = tfeti_test::poisson();
  const tfeti::CsrMatrix K =
      plasticity::assembleStiffness(tfeti_test::quadMesh(whole), ph.field, ph.law);
  const std::vector<double> f =
      yLoad(whole, plasticity::assembleBodyLoad(tfeti_test::quadMesh(whole), ph.field, ph.source));
  const int n = whole.numNodes();
  auto keep = [&](int g) { return g >= ny * (nx + 1) ? g - ny * (nx + 1) : g; };  // top -> bottom
  std::vector<int> ri, ci;
  std::vector<double> v;
  std::vector<double> fp(n, 0.0);
  for (int i = 0; i < n; ++i) {
    fp[keep(i)] += f[i];
    for (int k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k) {
      ri.push_back(keep(i));
      ci.push_back(keep(K.colInd[k]));
      v.push_back(K.values[k]);
    }
  }
  // Top nodes are unused after the identification: identity rows keep the matrix regular
  // (their diagonal entered into the pattern, where solveWithDirichlet puts the 1).
  std::vector<int> held = whole.dirichletDofs(1);
  for (int i = ny * (nx + 1); i < n; ++i) {
    held.push_back(i);
    ri.push_back(i);
    ci.push_back(i);
    v.push_back(0.0);
  }
  const std::vector<double> u =
      tfeti_test::solveWithDirichlet(tfeti::csrFromTriplets(n, n, ri, ci, v), fp, held);

  double err = 0.0, periodic = 0.0;
  for (std::size_t s = 0; s < solver.data().size(); ++s) {
    const auto& mesh = solver.data()[s].mesh;
    for (int a = 0; a < mesh.numNodes(); ++a)
      err = std::max(err, std::abs(solver.solution(s)[a] - u[keep(mesh.globalNode[a])]));
  }
  // The rows matter: without them u(x, 0) and u(x, 1) differ (checked on the reference's
  // unconstrained counterpart, the direct solve of the plain mesh with the same load).
  const std::vector<double> plain = tfeti_test::solveWithDirichlet(K, f, whole.dirichletDofs(1));
  for (int i = 1; i <= nx; ++i)
    periodic = std::max(periodic, std::abs(plain[i] - plain[ny * (nx + 1) + i]));
  err = tfeti_test::globalMax(*comm, err) / tfeti_test::maxAbs(u);
  out << r.iterations << " PCPG iterations, error " << err << ", equality residual "
      << solver.constraintReport().equalityResidual << ", unconstrained |u(x,0) - u(x,1)| "
      << periodic << "\n";
  TEST_COMPARE(err, <, 1e-9);
  TEST_COMPARE(solver.constraintReport().equalityResidual, <, 1e-9);
  TEST_COMPARE(periodic, >, 1e-3 * tfeti_test::maxAbs(plain));
}

// A rectangle [x0, x0 + ex hx] x [0, ey hy] of ex x ey Q1 elements as subdomain `id`, Poisson;
// its nodes get the global ids firstId + local (no node shared with another subdomain, so that
// nothing is glued automatically). Local node (a, j) = j (ex + 1) + a.
tfeti::SubdomainData rectangleSubdomain(int id, double x0, int ex, int ey, double hx, double hy,
                                        GO firstId) {
  tfeti::SubdomainData d;
  d.mesh.id = id;
  for (int j = 0; j <= ey; ++j)
    for (int a = 0; a <= ex; ++a) {
      d.mesh.coords.push_back(x0 + a * hx);
      d.mesh.coords.push_back(j * hy);
      d.mesh.globalNode.push_back(firstId + j * (ex + 1) + a);
    }
  for (int j = 0; j < ey; ++j)
    for (int a = 0; a < ex; ++a)
      d.mesh.elements.add({j * (ex + 1) + a, j * (ex + 1) + a + 1, (j + 1) * (ex + 1) + a + 1,
                           (j + 1) * (ex + 1) + a});
  const auto ph = tfeti_test::poisson();
  d.K = plasticity::assembleStiffness(tfeti_test::quadMesh(d.mesh), ph.field, ph.law);
  d.f.assign(d.mesh.numNodes(), 0.0);
  return d;
}

TEUCHOS_UNIT_TEST(UserRows, NonMatchingInterfaceReproducesTheLinearSolution) {
  auto comm = Tpetra::getDefaultComm();
  // Left: (0, 1)^2 in 4 x 4 elements; right: (1, 2) x (0, 1) in 4 x 8 (twice as many nodes on
  // the interface x = 1).
  const int ex = 4, eyLeft = 4, eyRight = 8;
  const double flux = 0.25;  // u = 1 - flux x
  std::vector<tfeti::SubdomainData> local;
  for (int s : tfeti::subdomainsOfRank(comm->getRank(), 2, comm->getSize())) {
    if (s == 0) {
      local.push_back(rectangleSubdomain(0, 0.0, ex, eyLeft, 0.25, 0.25, 0));
    } else {
      tfeti::SubdomainData d = rectangleSubdomain(1, 1.0, ex, eyRight, 0.25, 0.125, 1000);
      for (int j = 0; j <= eyRight; ++j)  // the flux out of x = 2, consistent (h/2 at the ends)
        d.f[j * (ex + 1) + ex] = -flux * 0.125 * (j == 0 || j == eyRight ? 0.5 : 1.0);
      local.push_back(std::move(d));
    }
  }
  std::vector<tfeti::EqualityRow> rows;
  if (comm->getRank() == comm->getSize() - 1) {  // any one rank passes each row: here the last
    auto left = [&](int j) { return j * (ex + 1) + ex; };  // interface nodes of each side
    auto right = [&](int j) { return j * (ex + 1); };
    for (int j = 0; j <= eyLeft; ++j) rows.push_back({{{0, j * (ex + 1), 1.0}}, 1.0});  // u = 1
    for (int j = 0; j <= eyRight; ++j) {
      tfeti::EqualityRow r{{{1, right(j), 1.0}}, 0.0};
      if (j % 2 == 0) {
        r.entries.push_back({0, left(j / 2), -1.0});
      } else {  // midway between two coarse nodes: their mean
        r.entries.push_back({0, left(j / 2), -0.5});
        r.entries.push_back({0, left(j / 2 + 1), -0.5});
      }
      rows.push_back(r);
    }
  }
  Teuchos::ParameterList params = tight();
  params.set("Gluing", "none");
  tfeti::FetiSolver solver(comm, 2, std::move(local), params, {}, rows);
  const tfeti::DualResult r = solver.solve();
  TEST_ASSERT(r.converged);
  TEST_EQUALITY(solver.gluingRows(), static_cast<GO>(0));
  TEST_EQUALITY(solver.userEqualityRows(), static_cast<GO>(eyLeft + 1 + eyRight + 1));
  double err = 0.0;
  for (std::size_t i = 0; i < solver.data().size(); ++i) {
    const auto& mesh = solver.data()[i].mesh;
    for (int n = 0; n < mesh.numNodes(); ++n)
      err = std::max(err, std::abs(solver.solution(i)[n] - (1.0 - flux * mesh.coords[2 * n])));
  }
  err = tfeti_test::globalMax(*comm, err);
  out << r.iterations << " PCPG iterations, max |u - (1 - Q x)| " << err << ", equality residual "
      << solver.constraintReport().equalityResidual << "\n";
  TEST_COMPARE(err, <, 1e-9);
  TEST_COMPARE(solver.constraintReport().equalityResidual, <, 1e-9);
}

}  // namespace
