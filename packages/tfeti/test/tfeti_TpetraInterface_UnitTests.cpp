// Tpetra at FetiSolver's interfaces (issue 17) on 1, 2 and 3 ranks: the subdomain matrices of
// Poisson and plane-strain elasticity handed in as Tpetra::CrsMatrix (on a serial communicator,
// each on the rank that holds the subdomain), the solution returned as a Tpetra::MultiVector on
// the caller's untorn map (distributed cyclically, so unlike any subdomain ownership) and
// compared with the direct solve of the undecomposed problem to 1e-10 relative; the same
// iterations and solution as with CSR arrays. Bad input: a CrsMatrix with other row ids, both
// forms given, a map without some dofs or with a dof of no subdomain.
#include <Teuchos_DefaultSerialComm.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <string>
#include <vector>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

using Teuchos::RCP;
using Teuchos::rcp;
using tfeti::GO;
using tfeti::LO;
using tfeti_test::contains;
using tfeti_test::messageOf;

tfeti::StructuredRectangle rectangle() {
  return tfeti::StructuredRectangle(0, 2, 0, 1, 3, 2, 4, 4);
}

// K as a CrsMatrix on a serial communicator, row ids base .. base + n - 1.
RCP<const tfeti::CrsMatrix> toTpetra(const tfeti::CsrMatrix& K, GO base = 0) {
  RCP<const tfeti::Comm> self = rcp(new Teuchos::SerialComm<int>());
  auto map = rcp(new tfeti::Map(K.rows, base, self));
  auto A = rcp(new tfeti::CrsMatrix(map, 18));  // Q1 elasticity: at most 9 nodes x 2 dofs a row
  for (int i = 0; i < K.rows; ++i) {
    std::vector<GO> cols;
    std::vector<double> vals;
    for (int k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k)
      cols.push_back(K.colInd[k] + base), vals.push_back(K.values[k]);
    A->insertGlobalValues(i + base, Teuchos::arrayViewFromVector(cols),
                          Teuchos::arrayViewFromVector(vals));
  }
  A->fillComplete();
  return A;
}

// The untorn dofs 0 .. n-1, dof g on rank g mod P (skipping `drop`, adding `extra`).
RCP<const tfeti::Map> cyclicMap(GO n, GO drop = -1, GO extra = -1) {
  auto comm = Tpetra::getDefaultComm();
  std::vector<GO> mine;
  for (GO g = comm->getRank(); g < n; g += comm->getSize())
    if (g != drop) mine.push_back(g);
  if (extra >= 0 && comm->getRank() == 0) mine.push_back(extra);
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  return rcp(new tfeti::Map(invalid, Teuchos::arrayViewFromVector(mine), 0, comm));
}

Teuchos::ParameterList tight() {
  Teuchos::ParameterList p;
  p.set("Preconditioner", "dirichlet");
  p.sublist("PCPG").set("Relative tolerance", 1e-11);
  return p;
}

void runPhysics(const tfeti_test::Physics& ph, Teuchos::FancyOStream& out, bool& success) {
  auto comm = Tpetra::getDefaultComm();
  const auto rect = rectangle();
  const std::vector<double> reference = tfeti_test::referenceSolution(rect, ph);
  const GO n = static_cast<GO>(reference.size());
  auto csr = tfeti_test::localSubdomains(rect, *comm, ph);
  auto tpetra = csr;
  for (auto& sd : tpetra) {
    sd.tpetraK = toTpetra(sd.K);
    sd.K = tfeti::CsrMatrix{};
  }
  tfeti::FetiSolver byCsr(comm, rect.numSubdomains(), csr, tight());
  tfeti::FetiSolver byTpetra(comm, rect.numSubdomains(), tpetra, tight());
  const tfeti::DualResult a = byCsr.solve(), b = byTpetra.solve();
  TEST_ASSERT(a.converged && b.converged);
  TEST_EQUALITY(a.iterations, b.iterations);
  TEST_ASSERT(a.history == b.history);

  const auto map = cyclicMap(n);
  RCP<tfeti::MultiVector> u = byTpetra.solution(map);
  TEST_ASSERT(u->getMap()->isSameAs(*map));
  TEST_EQUALITY(u->getNumVectors(), 1u);
  double err = 0.0;
  auto uv = u->getData(0);
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l)
    err = std::max(err, std::abs(uv[l] - reference[map->getGlobalElement(l)]));
  err = tfeti_test::globalMax(*comm, err);
  const double scale = tfeti_test::maxAbs(reference);
  out << ph.name() << ": " << b.iterations
      << " iterations, max |u - u_direct| / max |u| = " << err / scale << "\n";
  TEST_COMPARE(scale, >, 1e-3);
  TEST_COMPARE(err, <=, 1e-10 * scale);
}

TEUCHOS_UNIT_TEST(TpetraInterface, PoissonAgainstDirectSolve) {
  runPhysics(tfeti_test::poisson(), out, success);
}

TEUCHOS_UNIT_TEST(TpetraInterface, ElasticityAgainstDirectSolve) {
  runPhysics(tfeti_test::elasticity(), out, success);
}

TEUCHOS_UNIT_TEST(TpetraInterface, BadInput) {
  auto comm = Tpetra::getDefaultComm();
  const auto rect = rectangle();
  const auto ph = tfeti_test::poisson();
  auto local = tfeti_test::localSubdomains(rect, *comm, ph);
  // Row ids not 0 .. n-1 (on the rank of the first subdomain only: the error reaches every rank).
  auto shifted = local;
  if (comm->getRank() == 0) {
    shifted.front().tpetraK = toTpetra(shifted.front().K, 5);
    shifted.front().K = tfeti::CsrMatrix{};
  }
  const std::string m1 =
      messageOf([&] { tfeti::FetiSolver s(comm, rect.numSubdomains(), shifted, tight()); });
  out << m1 << "\n";
  TEST_ASSERT(contains(m1, "subdomain 0: tpetraK: the CrsMatrix's row ids must be 0 .. 24"));
  auto both = local;
  for (auto& sd : both) sd.tpetraK = toTpetra(sd.K);
  const std::string m2 =
      messageOf([&] { tfeti::FetiSolver s(comm, rect.numSubdomains(), both, tight()); });
  TEST_ASSERT(contains(m2, "tpetraK and K are both given"));
  // The dry run's forecast builds the subdomains as the constructor does, after the same checks:
  // the same message for each (a load vector one entry short is the third).
  auto shortLoad = local;
  if (comm->getRank() == 0) shortLoad.front().f.pop_back();
  for (const auto* bad : {&shifted, &both, &shortLoad}) {
    const std::string run =
        messageOf([&] { tfeti::FetiSolver s(comm, rect.numSubdomains(), *bad, tight()); });
    const std::string dry = messageOf(
        [&] { tfeti::FetiSolver::forecastSetupMemory(comm, rect.numSubdomains(), *bad, tight()); });
    out << "run: " << run << "\ndry run: " << dry << "\n";
    TEST_ASSERT(!run.empty());
    TEST_EQUALITY(dry, run);
  }

  tfeti::FetiSolver solver(comm, rect.numSubdomains(), local, tight());
  solver.solve();
  const GO n = static_cast<GO>(tfeti_test::referenceSolution(rect, ph).size());
  const std::string m3 = messageOf([&] { solver.solution(cyclicMap(n, 7)); });
  out << m3 << "\n";
  TEST_ASSERT(contains(m3, "1 subdomain dof values have no entry in the map given"));
  const std::string m4 = messageOf([&] { solver.solution(cyclicMap(n, -1, n + 3)); });
  out << m4 << "\n";
  TEST_ASSERT(contains(
      m4, "entry " + std::to_string(n + 3) + " of the map given is a dof of no subdomain"));
}

}  // namespace
