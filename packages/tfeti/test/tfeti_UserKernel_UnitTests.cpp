// A kernel supplied per subdomain (issue 17), through FetiSolver end to end on 1, 2 and 3 ranks:
//  - SubdomainData::kernel: two uncoupled scalar fields per
//    node, whose kernel (a constant per field) is not the rigid modes the solver would assume
//    for two dofs per node in 2D. With the kernel given, the solution is the Poisson solution
//    per field (against a direct solve); without it, the assumed rigid rotation fails ||K R||
//    and every rank gets the same error naming the subdomain.
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

}  // namespace
