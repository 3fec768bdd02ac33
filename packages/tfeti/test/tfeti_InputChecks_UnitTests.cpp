// What an application may hand to FetiSolver and the QP solvers by mistake, on 1, 2 and 3 ranks
// (issue 17): each case ends in the right answer or in the same clear error on every rank, and
// the ranks can go on communicating afterwards (no rank is left in a collective).
//  - subdomains whose elements fall into pieces: disconnected (a strip) or touching at the tip of
//    a slit, elasticity and Poisson, with and without their elements: the solution of the
//    untorn (slit) mesh, and the kernel dimension the pieces have;
//  - a load vector one entry short, coordinates one node short, K of the wrong size, K not
//    symmetric, broken CSR arrays, other dofs per node, a subdomain given twice: an error naming
//    the subdomain in the caller's terms;
//  - an error on one rank only, or on several (the lowest rank's message);
//  - an MPRGP / SMALBE bound vector on a shorter map than the operator.
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_MprgpSolMgr_def.hpp"
#include "tfeti_SmalbeSolMgr_def.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

using tfeti_test::contains;
using tfeti_test::Physics;

// A Q1 mesh of (0, nx h) x (0, ny h) with element sets for the subdomains, and optionally a slit:
// the nodes on y = slitY with x < slitEnd are doubled, the elements above the slit using the
// copies (the node at x = slitEnd, the slit's tip, stays single).
struct TornMesh {
  int nx = 0, ny = 0;
  double h = 0.25;
  std::vector<double> coords;             // global nodes (the copies last)
  std::vector<std::array<int, 4>> quads;  // counter-clockwise, global nodes
  std::vector<int> subdomainOf;           // per element

  TornMesh(int nx_, int ny_, int slitRow, int slitEnd, const std::function<int(int, int)>& owner)
      : nx(nx_), ny(ny_) {
    auto id = [&](int i, int j) { return j * (nx + 1) + i; };
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) coords.insert(coords.end(), {i * h, j * h});
    std::map<int, int> copy;  // slit node -> its copy above the slit
    if (slitRow > 0)
      for (int i = 0; i < slitEnd; ++i) {
        copy[id(i, slitRow)] = static_cast<int>(coords.size() / 2);
        coords.insert(coords.end(), {i * h, slitRow * h});
      }
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        std::array<int, 4> q{id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
        if (j == slitRow)  // the row just above the slit uses the copies of its lower nodes
          for (int a : {0, 1})
            if (copy.count(q[a])) q[a] = copy[q[a]];
        quads.push_back(q);
        subdomainOf.push_back(owner(i, j));
      }
  }
  int numNodes() const { return static_cast<int>(coords.size() / 2); }
  // u = 0 on the lower half of x = 0 (below the slit): the upper piece of a slit body is then
  // held only through the slit's tip, and even the Poisson solution depends on the slit.
  bool clamped(int n) const { return coords[2 * n] == 0.0 && coords[2 * n + 1] < 0.5; }
  int numSubdomains() const {
    return *std::max_element(subdomainOf.begin(), subdomainOf.end()) + 1;
  }

  // Subdomain s with local nodes in increasing global order.
  tfeti::SubdomainMesh subdomain(int s, bool withElements) const {
    tfeti::SubdomainMesh m;
    m.id = s;
    std::map<int, int> local;
    for (std::size_t e = 0; e < quads.size(); ++e)
      if (subdomainOf[e] == s)
        for (int a : quads[e]) local[a] = 0;
    for (auto& [g, l] : local) {
      l = m.numNodes();
      m.globalNode.push_back(g);
      m.coords.insert(m.coords.end(), {coords[2 * g], coords[2 * g + 1]});
      if (clamped(g)) m.dirichletNodes.push_back(l);
    }
    for (std::size_t e = 0; e < quads.size(); ++e)
      if (subdomainOf[e] == s) {
        std::vector<int> q;
        for (int a : quads[e]) q.push_back(local.at(a));
        if (withElements) m.elements.add(q);
        m.interfaceCandidates.insert(m.interfaceCandidates.end(), q.begin(), q.end());
      }
    return m;
  }

  plasticity::Q1Mesh q1(const std::vector<int>& elementsOf) const {
    plasticity::Q1Mesh m;
    m.coords = coords;
    for (int e : elementsOf) m.cells.insert(m.cells.end(), quads[e].begin(), quads[e].end());
    return m;
  }
};

// The subdomain's K and f assembled on its local elements.
tfeti::SubdomainData assembleSubdomain(const TornMesh& torn, int s, const Physics& ph,
                                       bool withElements) {
  tfeti::SubdomainData d;
  d.mesh = torn.subdomain(s, withElements);
  d.dofsPerNode = ph.dofsPerNode();
  plasticity::Q1Mesh q;
  q.coords = d.mesh.coords;
  std::map<int, int> local;
  for (int l = 0; l < d.mesh.numNodes(); ++l) local[static_cast<int>(d.mesh.globalNode[l])] = l;
  for (std::size_t e = 0; e < torn.quads.size(); ++e)
    if (torn.subdomainOf[e] == s)
      for (int a : torn.quads[e]) q.cells.push_back(local.at(a));
  d.K = plasticity::assembleStiffness(q, ph.field, ph.law);
  d.f = plasticity::assembleBodyLoad(q, ph.field, ph.source);
  return d;
}

std::vector<tfeti::SubdomainData> localData(const TornMesh& torn, const tfeti::Comm& comm,
                                            const Physics& ph, bool withElements) {
  std::vector<tfeti::SubdomainData> local;
  for (int s : tfeti::subdomainsOfRank(comm.getRank(), torn.numSubdomains(), comm.getSize()))
    local.push_back(assembleSubdomain(torn, s, ph, withElements));
  return local;
}

// Direct solve of the whole (slit) mesh.
std::vector<double> reference(const TornMesh& torn, const Physics& ph) {
  std::vector<int> all(torn.quads.size());
  for (std::size_t e = 0; e < all.size(); ++e) all[e] = static_cast<int>(e);
  const plasticity::Q1Mesh q = torn.q1(all);
  const int dpn = ph.dofsPerNode();
  std::vector<int> fixed;
  for (int n = 0; n < torn.numNodes(); ++n)
    if (torn.clamped(n))
      for (int c = 0; c < dpn; ++c) fixed.push_back(dpn * n + c);
  return tfeti_test::solveWithDirichlet(plasticity::assembleStiffness(q, ph.field, ph.law),
                                        plasticity::assembleBodyLoad(q, ph.field, ph.source),
                                        fixed);
}

Teuchos::ParameterList quietParameters() {
  Teuchos::ParameterList p;
  p.sublist("PCPG").set("Relative tolerance", 1e-10);
  p.sublist("PCPG").set("Verbosity", 0);
  return p;
}

// Solves and returns max |u - u_ref| / max |u_ref| over every local copy of every node (the
// same on every rank); kernelDims receives the kernel dimension of every subdomain.
double solveAgainstReference(const TornMesh& torn, const Physics& ph, bool withElements,
                             std::vector<long long>& kernelDims, Teuchos::FancyOStream& out,
                             bool& success) {
  auto comm = Tpetra::getDefaultComm();
  const std::vector<double> ref = reference(torn, ph);
  tfeti::FetiSolver solver(comm, torn.numSubdomains(), localData(torn, *comm, ph, withElements),
                           quietParameters());
  const tfeti::DualResult r = solver.solve();
  TEST_ASSERT(r.converged);
  const int dpn = ph.dofsPerNode();
  double err = 0.0;
  std::vector<long long> dims(torn.numSubdomains(), 0);
  for (std::size_t i = 0; i < solver.data().size(); ++i) {
    const auto& mesh = solver.data()[i].mesh;
    dims[mesh.id] = solver.subdomains()[i]->kernelDim();
    for (int n = 0; n < mesh.numNodes(); ++n)
      for (int c = 0; c < dpn; ++c)
        err = std::max(
            err, std::abs(solver.solution(i)[dpn * n + c] - ref[dpn * mesh.globalNode[n] + c]));
  }
  kernelDims.assign(dims.size(), 0);
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, static_cast<int>(dims.size()), dims.data(),
                     kernelDims.data());
  const double relative = tfeti_test::globalMax(*comm, err) / tfeti_test::maxAbs(ref);
  out << ph.name() << (withElements ? ", elements given" : ", graph of K") << ": " << r.iterations
      << " iterations, error " << relative << ", kernels";
  for (long long k : kernelDims) out << " " << k;
  out << "\n";
  return relative;
}

// 8 x 2 elements in 3 subdomains: subdomain 0 holds columns 0-1 and 4-5, two pieces that share
// no node, each glued to subdomain 1 (columns 2-3) and the right one also to subdomain 2 (6-7).
TornMesh strip() {
  return TornMesh(8, 2, 0, 0, [](int i, int) {
    return i < 2 || (i >= 4 && i < 6) ? 0 : i < 4 ? 1 : 2;
  });
}

// 8 x 4 elements in 2 subdomains (x < 1, x > 1) with a slit along y = 0.5 from x = 0 to the
// interface x = 1: subdomain 0 falls into two pieces that touch only at the slit's tip.
TornMesh slit() {
  return TornMesh(8, 4, 2, 4, [](int i, int) { return i < 4 ? 0 : 1; });
}

// An error every rank must raise identically: returns the message (empty if nothing was thrown)
// after checking that all ranks caught a CollectiveError with a message of the same length and
// that they can still communicate.
std::string collectiveError(const std::function<void()>& f, Teuchos::FancyOStream& out,
                            bool& success) {
  auto comm = Tpetra::getDefaultComm();
  std::string message;
  bool collective = false;
  try {
    f();
  } catch (const tfeti::CollectiveError& e) {
    message = e.what();
    collective = true;
  } catch (const std::exception& e) {
    message = e.what();
  }
  out << "rank " << comm->getRank() << ": " << message << "\n";
  TEST_ASSERT(collective);
  const double len = static_cast<double>(message.size());
  TEST_EQUALITY(tfeti_test::globalMax(*comm, len), -tfeti_test::globalMax(*comm, -len));
  TEST_EQUALITY(tfeti_test::globalSum(*comm, 1LL), static_cast<long long>(comm->getSize()));
  return message;
}

// The square (0,1)^2 in 2 x 2 subdomains of 4 x 4 elements; `spoil` edits the data of subdomain
// `victim` (on whichever rank holds it) before the solver sees it.
std::string spoiledSquare(const Physics& ph, int victim,
                          const std::function<void(tfeti::SubdomainData&)>& spoil,
                          Teuchos::FancyOStream& out, bool& success) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti::StructuredRectangle rect(0, 1, 0, 1, 2, 2, 4, 4);
  return collectiveError(
      [&] {
        auto local = tfeti_test::localSubdomains(rect, *comm, ph);
        for (auto& d : local)
          if (d.mesh.id == victim) spoil(d);
        tfeti::FetiSolver solver(comm, rect.numSubdomains(), std::move(local), quietParameters());
        solver.solve();
      },
      out, success);
}

// Drops the last row and column of K.
tfeti::CsrMatrix dropLast(const tfeti::CsrMatrix& K) {
  std::vector<int> keep(K.rows - 1);
  for (int i = 0; i < K.rows - 1; ++i) keep[i] = i;
  return K.submatrix(keep, keep);
}

}  // namespace

TEUCHOS_UNIT_TEST(InputChecks, DisconnectedSubdomainGivesTheUntornSolution) {
  for (const Physics& ph : {tfeti_test::elasticity(), tfeti_test::poisson()})
    for (bool withElements : {true, false}) {
      std::vector<long long> dims;
      const double err = solveAgainstReference(strip(), ph, withElements, dims, out, success);
      TEST_COMPARE(err, <, 1e-6);
      const long long k = ph.dofsPerNode() == 1 ? 1 : 3;
      TEST_EQUALITY(dims[0], 2 * k);  // two pieces
      TEST_EQUALITY(dims[1], k);
      TEST_EQUALITY(dims[2], k);
    }
}

TEUCHOS_UNIT_TEST(InputChecks, SlitSubdomainGivesTheSlitSolution) {
  // The slit changes the answer: the same mesh without it differs by far more than the
  // tolerance, so a solver that ignored the extra kernel could not pass.
  const TornMesh whole(8, 4, 0, 0, [](int i, int) { return i < 4 ? 0 : 1; });
  for (const Physics& ph : {tfeti_test::elasticity(), tfeti_test::poisson()}) {
    const std::vector<double> cut = reference(slit(), ph), solid = reference(whole, ph);
    double diff = 0.0;
    for (int n = 0; n < whole.numNodes() * ph.dofsPerNode(); ++n)
      diff = std::max(diff, std::abs(cut[n] - solid[n]));
    TEST_COMPARE(diff, >, 0.01 * tfeti_test::maxAbs(cut));
    std::vector<long long> dims;
    const double err = solveAgainstReference(slit(), ph, true, dims, out, success);
    TEST_COMPARE(err, <, 1e-6);
    // Elasticity: two pieces of 3 modes hinged at the tip (2 conditions); Poisson: one mode.
    TEST_EQUALITY(dims[0], ph.dofsPerNode() == 1 ? 1LL : 4LL);
  }
  // Poisson without the elements: the graph of K is connected through the tip, as the pieces
  // are: the right kernel and answer.
  std::vector<long long> dims;
  TEST_COMPARE(solveAgainstReference(slit(), tfeti_test::poisson(), false, dims, out, success), <,
               1e-6);
  // Elasticity without the elements: the hinge cannot be seen in the graph of K; the extra
  // kernel is found and reported on every rank, with what to do.
  auto comm = Tpetra::getDefaultComm();
  const std::string m = collectiveError(
      [&] {
        tfeti::FetiSolver solver(comm, 2, localData(slit(), *comm, tfeti_test::elasticity(), false),
                                 quietParameters());
      },
      out, success);
  TEST_ASSERT(contains(m, "subdomain 0: K has a larger kernel than the 3 modes found"));
  TEST_ASSERT(contains(m, "give its elements"));
}

TEUCHOS_UNIT_TEST(InputChecks, LoadVectorOneEntryShort) {
  const std::string m = spoiledSquare(
      tfeti_test::poisson(), 3, [](tfeti::SubdomainData& d) { d.f.pop_back(); }, out, success);
  TEST_ASSERT(contains(m,
                       "subdomain 3: the load vector f has 24 entries, the mesh has 25 nodes x "
                       "1 dof = 25"));
}

TEUCHOS_UNIT_TEST(InputChecks, CoordinatesOneNodeShort) {
  const std::string m = spoiledSquare(
      tfeti_test::elasticity(), 3,
      [](tfeti::SubdomainData& d) { d.mesh.coords.resize(d.mesh.coords.size() - 2); }, out,
      success);
  TEST_ASSERT(contains(m,
                       "subdomain 3: the coordinates have 48 values, the mesh has 25 nodes x 2 "
                       "coordinates = 50"));
}

TEUCHOS_UNIT_TEST(InputChecks, StiffnessOfTheWrongSize) {
  std::string m = spoiledSquare(
      tfeti_test::poisson(), 3, [](tfeti::SubdomainData& d) { d.K = dropLast(d.K); }, out, success);
  TEST_ASSERT(contains(m, "subdomain 3: K is 24 x 24, the mesh has 25 nodes x 1 dof = 25"));
  m = spoiledSquare(
      tfeti_test::elasticity(), 0,
      [](tfeti::SubdomainData& d) {
        d.K = dropLast(d.K);
        d.f.pop_back();
      },
      out, success);
  TEST_ASSERT(contains(m, "subdomain 0: K is 49 x 49, the mesh has 25 nodes x 2 dofs = 50"));
}

TEUCHOS_UNIT_TEST(InputChecks, BrokenOrUnsymmetricStiffness) {
  std::string m = spoiledSquare(
      tfeti_test::poisson(), 1, [](tfeti::SubdomainData& d) { d.K.values[d.K.find(0, 1)] *= 1.5; },
      out, success);
  TEST_ASSERT(contains(m, "subdomain 1: K is not symmetric: K(0, 1) ="));
  m = spoiledSquare(
      tfeti_test::poisson(), 1, [](tfeti::SubdomainData& d) { d.K.colInd[3] = 99; }, out, success);
  TEST_ASSERT(contains(m, "subdomain 1: K: row 0 has column 99, outside 0 .. 24"));
  m = spoiledSquare(
      tfeti_test::poisson(), 2, [](tfeti::SubdomainData& d) { d.K.rowPtr.pop_back(); }, out,
      success);
  TEST_ASSERT(contains(m, "subdomain 2: K has 25 rows but rowPtr has 25 entries"));
}

TEUCHOS_UNIT_TEST(InputChecks, MeshListsAndDofsPerNode) {
  std::string m = spoiledSquare(
      tfeti_test::poisson(), 2, [](tfeti::SubdomainData& d) { d.mesh.elements.nodes[5] = 25; }, out,
      success);
  TEST_ASSERT(contains(m,
                       "subdomain 2: elements has local node 25 (entry 5), but the mesh has 25 "
                       "nodes"));
  m = spoiledSquare(
      tfeti_test::poisson(), 1,
      [](tfeti::SubdomainData& d) {
        // A consistent subdomain of 2 dofs per node among scalar ones.
        d.dofsPerNode = 2;
        d.K = plasticity::assembleStiffness(tfeti_test::quadMesh(d.mesh),
                                            plasticity::Field::Elasticity,
                                            plasticity::ElasticLaw(1.0, 0.3));
        d.f.assign(50, 0.0);
      },
      out, success);
  TEST_ASSERT(contains(m, "has 1 dof per node, another subdomain has 2"));
  m = spoiledSquare(
      tfeti_test::poisson(), 3, [](tfeti::SubdomainData& d) { d.mesh.id = 0; }, out, success);
  TEST_ASSERT(contains(m, "subdomain 0 is given 2 times") ||
              contains(m, "subdomain 3 is given by no rank"));
}

// Errors on several ranks: every rank reports the lowest failing rank's message and how many
// other ranks failed; then a correct problem solves on the same communicator.
TEUCHOS_UNIT_TEST(InputChecks, ErrorsOnSomeRanksOnly) {
  auto comm = Tpetra::getDefaultComm();
  const int P = comm->getSize();
  const tfeti::StructuredRectangle rect(0, 1, 0, 1, 3, 1, 4, 4);  // one subdomain per rank on 3
  const std::string m = collectiveError(
      [&] {
        auto local = tfeti_test::localSubdomains(rect, *comm, tfeti_test::poisson());
        for (auto& d : local)
          if (d.mesh.id >= 1) d.f.push_back(0.0);  // subdomains 1 and 2
        tfeti::FetiSolver solver(comm, rect.numSubdomains(), std::move(local), quietParameters());
      },
      out, success);
  TEST_ASSERT(contains(m, "subdomain 1: the load vector f has 26 entries"));
  // Subdomains 1 and 2 are on different ranks only on 3 ranks.
  TEST_EQUALITY(contains(m, "(and errors on 1 other rank)"), P == 3);
  tfeti::FetiSolver solver(comm, rect.numSubdomains(),
                           tfeti_test::localSubdomains(rect, *comm, tfeti_test::poisson()),
                           quietParameters());
  TEST_ASSERT(solver.solve().converged);
}

// update() with a load of the wrong length on one subdomain: the same error everywhere.
TEUCHOS_UNIT_TEST(InputChecks, UpdateWithAShortLoad) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti::StructuredRectangle rect(0, 1, 0, 1, 2, 2, 4, 4);
  auto local = tfeti_test::localSubdomains(rect, *comm, tfeti_test::poisson());
  std::vector<std::vector<double>> loads;
  for (const auto& d : local) loads.push_back(d.f);
  tfeti::FetiSolver solver(comm, rect.numSubdomains(), std::move(local), quietParameters());
  for (std::size_t i = 0; i < loads.size(); ++i)
    if (solver.data()[i].mesh.id == 3) loads[i].pop_back();
  const std::string m = collectiveError([&] { solver.update(loads, {}); }, out, success);
  TEST_ASSERT(contains(m, "subdomain 3: the load vector f has 24 entries, K has 25 rows"));
}

namespace {
using Qp = tfeti::BoundConstrainedQp<double, tfeti::MultiVector, tfeti::Operator>;

// A = tridiag(-1, 2.5, -1) on n unknowns, b = 1, x = 0.
Qp smallQp(const Teuchos::RCP<const tfeti::Map>& map) {
  auto A = Teuchos::rcp(new tfeti::CrsMatrix(map, 3));
  const tfeti::GO n = static_cast<tfeti::GO>(map->getGlobalNumElements());
  for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {
    const tfeti::GO i = map->getGlobalElement(static_cast<tfeti::LO>(l));
    std::vector<tfeti::GO> cols;
    std::vector<double> vals;
    for (tfeti::GO j : {i - 1, i, i + 1})
      if (j >= 0 && j < n) {
        cols.push_back(j);
        vals.push_back(j == i ? 2.5 : -1.0);
      }
    A->insertGlobalValues(i, Teuchos::ArrayView<const tfeti::GO>(cols),
                          Teuchos::ArrayView<const double>(vals));
  }
  A->fillComplete();
  Qp qp;
  qp.A = A;
  auto b = Teuchos::rcp(new tfeti::MultiVector(map, 1));
  b->putScalar(1.0);
  qp.b = b;
  qp.x = Teuchos::rcp(new tfeti::MultiVector(map, 1));
  return qp;
}
}  // namespace

TEUCHOS_UNIT_TEST(InputChecks, BoundVectorOnAShorterMap) {
  auto comm = Tpetra::getDefaultComm();
  const auto map = Teuchos::rcp(new tfeti::Map(40, 0, comm));
  const auto shorter = Teuchos::rcp(new tfeti::Map(39, 0, comm));
  Qp qp = smallQp(map);
  auto lower = Teuchos::rcp(new tfeti::MultiVector(shorter, 1));
  lower->putScalar(0.0);
  qp.lower = lower;
  Teuchos::ParameterList params;
  const auto mprgp = [&] {
    tfeti::MprgpSolMgr<double, tfeti::MultiVector, tfeti::Operator> solver(qp, params);
    solver.solve();
  };
  std::string m = tfeti_test::messageOf(mprgp);
  out << m << "\n";
  TEST_ASSERT(contains(m, "MPRGP: the lower bound vector has 39 entries, x has 40"));
  // The same length on a differently distributed map (on more than one rank).
  if (comm->getSize() > 1) {
    std::vector<tfeti::GO> mine;
    if (comm->getRank() == 0)
      for (tfeti::GO i = 0; i < 40; ++i) mine.push_back(i);
    const auto allOnRank0 =
        Teuchos::rcp(new tfeti::Map(40, Teuchos::ArrayView<const tfeti::GO>(mine), 0, comm));
    auto lower0 = Teuchos::rcp(new tfeti::MultiVector(allOnRank0, 1));
    qp.lower = lower0;
    m = tfeti_test::messageOf(mprgp);
    out << m << "\n";
    TEST_ASSERT(
        contains(m, "MPRGP: the lower bound vector has the 40 entries of x but another map"));
  }
  // SMALBE checks its Q as well: here a projector on the shorter map.
  qp.lower = Teuchos::rcp(new tfeti::MultiVector(map, 1));
  const Qp onShorter = smallQp(shorter);
  m = tfeti_test::messageOf([&] {
    tfeti::SmalbeSolMgr<double, tfeti::MultiVector, tfeti::Operator> solver(qp, onShorter.A,
                                                                            params);
    solver.solve();
  });
  out << m << "\n";
  TEST_ASSERT(contains(m, "SMALBE: the domain of Q has 39 entries, x has 40"));
  // Right maps: the bound-constrained solution (lower = 0 is inactive for b > 0) solves A x = b.
  m = tfeti_test::messageOf(mprgp);
  TEST_EQUALITY(m, "");
  tfeti::MultiVector r(map, 1);
  qp.A->apply(*qp.x, r);
  r.update(-1.0, *qp.b, 1.0);
  Teuchos::Array<double> rn(1), bn(1);
  r.norm2(rn());
  qp.b->norm2(bn());
  TEST_COMPARE(rn[0], <=, 1e-6 * bn[0]);
}
