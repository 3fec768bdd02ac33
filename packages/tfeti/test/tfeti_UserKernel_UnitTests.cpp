// Issue 17's remaining cases of general constraints and kernels, through FetiSolver end to end on
// 1, 2 and 3 ranks:
//  - a kernel supplied per subdomain (SubdomainData::kernel): two uncoupled scalar fields per
//    node, whose kernel (a constant per field) is not the rigid modes the solver would assume
//    for two dofs per node in 2D. With the kernel given, the solution is the Poisson solution
//    per field (against a direct solve); without it, the assumed rigid rotation fails ||K R||
//    and every rank gets the same error naming the subdomain.
//  - periodic pairs as the caller's equality rows: u(x, 0) = u(x, 1) for every x on a Poisson
//    problem whose load depends on y (so that the rows change the solution), against a direct
//    solve of the untorn mesh with the periodic nodes identified.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

using tfeti::GO;
using tfeti_test::contains;

tfeti::StructuredRectangle rectangle() {
  return tfeti::StructuredRectangle(0, 2, 0, 1, 3, 2, 4, 4);
}

Teuchos::ParameterList tight() {
  Teuchos::ParameterList p;
  p.set("Preconditioner", "dirichlet");
  p.sublist("PCPG").set("Relative tolerance", 1e-11);
  return p;
}

// Two copies of a scalar problem interleaved: dof 2 n + c is field c of node n; field 1 carries
// twice the load of field 0. `withKernel`: the constant of each field as the subdomain's kernel.
tfeti::SubdomainData twoFields(const tfeti::SubdomainData& scalar, bool withKernel) {
  tfeti::SubdomainData d;
  d.mesh = scalar.mesh;
  d.dofsPerNode = 2;
  const tfeti::CsrMatrix& K = scalar.K;
  std::vector<int> ri, ci;
  std::vector<double> v;
  for (int i = 0; i < K.rows; ++i)
    for (int k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k)
      for (int c = 0; c < 2; ++c) {
        ri.push_back(2 * i + c);
        ci.push_back(2 * K.colInd[k] + c);
        v.push_back(K.values[k]);
      }
  d.K = tfeti::csrFromTriplets(2 * K.rows, 2 * K.rows, ri, ci, v);
  for (double fi : scalar.f) {
    d.f.push_back(fi);
    d.f.push_back(2 * fi);
  }
  if (withKernel) {
    d.kernel.assign(4 * static_cast<std::size_t>(K.rows), 0.0);  // column-major 2n x 2
    for (int i = 0; i < K.rows; ++i) {
      d.kernel[2 * i] = 1.0;
      d.kernel[2 * K.rows + 2 * i + 1] = 1.0;
    }
  }
  return d;
}

// The subdomains of this rank with the two-field problem; clamped (x = 0) like the Poisson one.
std::vector<tfeti::SubdomainData> twoFieldSubdomains(bool withKernel) {
  auto comm = Tpetra::getDefaultComm();
  std::vector<tfeti::SubdomainData> local;
  for (const auto& sd : tfeti_test::localSubdomains(rectangle(), *comm, tfeti_test::poisson()))
    local.push_back(twoFields(sd, withKernel));
  return local;
}

TEUCHOS_UNIT_TEST(UserKernel, SuppliedKernelOfTwoScalarFields) {
  auto comm = Tpetra::getDefaultComm();
  const auto rect = rectangle();
  const std::vector<double> reference = tfeti_test::referenceSolution(rect, tfeti_test::poisson());
  tfeti::FetiSolver solver(comm, rect.numSubdomains(), twoFieldSubdomains(true), tight());
  const tfeti::DualResult r = solver.solve();
  TEST_ASSERT(r.converged);
  TEST_EQUALITY(solver.coarseDimension(), 2 * rect.numSubdomains());
  double err = 0.0, scale = tfeti_test::maxAbs(reference);
  for (std::size_t i = 0; i < solver.data().size(); ++i) {
    const auto& mesh = solver.data()[i].mesh;
    for (int n = 0; n < mesh.numNodes(); ++n)
      for (int c = 0; c < 2; ++c)
        err = std::max(
            err, std::abs(solver.solution(i)[2 * n + c] - (c + 1) * reference[mesh.globalNode[n]]));
  }
  err = tfeti_test::globalMax(*comm, err) / scale;
  out << r.iterations << " PCPG iterations, error " << err << "\n";
  TEST_COMPARE(err, <, 1e-9);
}

TEUCHOS_UNIT_TEST(UserKernel, TwoFieldsWithoutTheirKernelAreAnErrorOnEveryRank) {
  auto comm = Tpetra::getDefaultComm();
  std::string message;
  bool collective = false;
  try {
    tfeti::FetiSolver solver(comm, rectangle().numSubdomains(), twoFieldSubdomains(false), tight());
  } catch (const tfeti::CollectiveError& e) {
    collective = true;
    message = e.what();
  } catch (const std::exception& e) {
    message = e.what();
  }
  out << message << "\n";
  TEST_ASSERT(collective);
  TEST_ASSERT(contains(message, "subdomain "));
  TEST_ASSERT(contains(message, "not in the kernel of K"));
  // Every rank caught it and can go on communicating.
  TEST_EQUALITY(tfeti_test::globalSum(*comm, collective ? 1LL : 0LL),
                static_cast<long long>(comm->getSize()));
}

// -Laplace u = f with f = 1 + y (per node, times the consistent load of 1), clamped at x = 0.
std::vector<double> yLoad(const tfeti::SubdomainMesh& m, std::vector<double> f) {
  for (int n = 0; n < m.numNodes(); ++n) f[n] *= 1.0 + m.coords[2 * n + 1];
  return f;
}

TEUCHOS_UNIT_TEST(UserKernel, PeriodicPairsAgainstTheIdentifiedMesh) {
  auto comm = Tpetra::getDefaultComm();
  const auto rect = rectangle();
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

}  // namespace
