// Kinematic coupling on 1, 2 and 3 ranks: a plane-strain plate (0,2)x(0,1) in 3 x 2 subdomains
// (the face x1 is cut between subdomains, and between ranks on 2 and 3), symmetric on x0 (u_x)
// and y0 (u_y), under a uniform body force along x; u_x of x1 coupled to one common value.
// Without the coupling u_x varies along x1 (a term -nu' b y^2 / (2 E') of the exact solution);
// with it the face moves as one (spread zero to the solver's tolerance), the coupling's forces
// sum to zero on the face (it holds the face straight, it does not hold it back), the supports'
// reaction balances the load, and prescribing u_x = U on x1, U the coupled value, gives the same
// displacement at every node copy (the coupled solution is the prescribed one at its optimum).
// The rows' checks: errors naming the parameter for a held component, a wrong component, a
// boundary of one node and a component coupled by two boundaries.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "contact_KinematicCoupling.hpp"
#include "contact_StructuredProblem.hpp"
#include "tfeti_FetiSolver.hpp"

namespace {

using contact::StructuredProblem;

StructuredProblem plate() {
  StructuredProblem p;
  p.field = "elasticity";
  p.lo = {0.0, 0.0};
  p.hi = {2.0, 1.0};
  p.subdomains = {3, 3};
  p.elements = {3, 3};
  p.law = plasticity::ElasticLaw(2e11, 0.3);
  p.bodyForce = {1e9, 0.0};
  p.fixed.clear();
  p.symmetry = {{"x0", 0}, {"y0", 1}};
  return p;
}

// The coupling rows of p's faces: the first copy of a node over all subdomains of the grid.
contact::CouplingContext context(const StructuredProblem& p) {
  auto first = std::make_shared<std::map<long long, std::pair<int, int>>>();
  const tfeti::StructuredMesh mesh = p.mesh();
  for (int s = 0; s < mesh.numSubdomains(); ++s) {
    const tfeti::SubdomainMesh m = mesh.subdomain(s);
    for (int n = 0; n < m.numNodes(); ++n) first->insert({m.globalNode[n], {s, n}});
  }
  contact::CouplingContext c;
  c.dim = 2;
  c.nodesOf = [p](const std::string& face) { return p.faceNodes(face); };
  c.firstCopy = [first](long long n) { return first->at(n); };
  c.heldBy = [](long long, int) { return std::string(); };
  return c;
}

Teuchos::ParameterList parameters() {
  Teuchos::ParameterList feti;
  feti.set("Dual solver", "PCPG");
  feti.sublist("PCPG").set("Relative tolerance", 1e-12);
  return feti;
}

double globalMax(const tfeti::Comm& comm, double v) {
  double g = v;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &v, &g);
  return g;
}
double globalSum(const tfeti::Comm& comm, double v) {
  double g = v;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &v, &g);
  return g;
}

// min and max of u_x over the copies of x1's nodes.
std::pair<double, double> faceRange(const tfeti::Comm& comm, const tfeti::FetiSolver& solver,
                                    const std::vector<long long>& face) {
  double lo = 1e300, hi = -1e300;
  for (std::size_t i = 0; i < solver.data().size(); ++i) {
    const auto& m = solver.data()[i].mesh;
    for (int n = 0; n < m.numNodes(); ++n)
      if (std::find(face.begin(), face.end(), m.globalNode[n]) != face.end()) {
        lo = std::min(lo, solver.solution(i)[2 * n]);
        hi = std::max(hi, solver.solution(i)[2 * n]);
      }
  }
  return {-globalMax(comm, -lo), globalMax(comm, hi)};
}

TEUCHOS_UNIT_TEST(KinematicCoupling, CoupledFaceMovesAsOne) {
  auto comm = Tpetra::getDefaultComm();
  const StructuredProblem p = plate();
  const std::vector<long long> x1 = p.faceNodes("x1");

  // Free face: u_x varies along it.
  tfeti::FetiSolver free(comm, p.numSubdomains(), contact::buildLocalSubdomains(p, *comm),
                         parameters(), {}, {});
  TEST_ASSERT(free.solve().converged);
  const auto [freeLo, freeHi] = faceRange(*comm, free, x1);

  // Coupled face (rows passed by rank 0 only).
  std::vector<tfeti::EqualityRow> rows = contact::kinematicCouplingRows({{"x1", 0}}, context(p));
  TEST_EQUALITY(static_cast<long long>(rows.size()), static_cast<long long>(x1.size()) - 1);
  if (comm->getRank() != 0) rows.clear();
  tfeti::FetiSolver coupled(comm, p.numSubdomains(), contact::buildLocalSubdomains(p, *comm),
                            parameters(), {}, rows);
  const tfeti::DualResult r = coupled.solve();
  TEST_ASSERT(r.converged);
  const auto [lo, hi] = faceRange(*comm, coupled, x1);
  const double U = 0.5 * (lo + hi);

  // The coupling's forces on x1 sum to zero; the x0 symmetry reaction balances the load b A.
  const auto forces = coupled.multiplierForces();
  double onFace = 0.0, onX0 = 0.0;
  const std::vector<long long> x0 = p.faceNodes("x0");
  for (std::size_t i = 0; i < coupled.data().size(); ++i) {
    const auto& m = coupled.data()[i].mesh;
    for (int n = 0; n < m.numNodes(); ++n) {
      if (std::find(x1.begin(), x1.end(), m.globalNode[n]) != x1.end()) onFace += forces[i][2 * n];
      if (std::find(x0.begin(), x0.end(), m.globalNode[n]) != x0.end()) onX0 += forces[i][2 * n];
    }
  }
  onFace = globalSum(*comm, onFace);
  onX0 = globalSum(*comm, onX0);
  const double load = 1e9 * 2.0 * 1.0;

  // The same problem with u_x = U prescribed on x1.
  StructuredProblem q = p;
  q.prescribed = {{"x1", 0, U, {}}};
  tfeti::FetiSolver prescribed(
      comm, q.numSubdomains(), contact::buildLocalSubdomains(q, *comm), parameters(), {},
      contact::prescribedDisplacementRows(contact::buildLocalSubdomains(q, *comm),
                                          q.prescribedValues(), 1.0));
  TEST_ASSERT(prescribed.solve().converged);
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < coupled.data().size(); ++i)
    for (std::size_t k = 0; k < coupled.solution(i).size(); ++k) {
      diff = std::max(diff, std::abs(coupled.solution(i)[k] - prescribed.solution(i)[k]));
      scale = std::max(scale, std::abs(coupled.solution(i)[k]));
    }
  diff = globalMax(*comm, diff) / globalMax(*comm, scale);

  out << comm->getSize() << " rank(s): free face u_x in [" << freeLo << ", " << freeHi
      << "]; coupled: " << coupled.userEqualityRows() << " rows, U = " << U << ", spread "
      << hi - lo << ", coupling force sum " << onFace << ", x0 reaction " << onX0 << " (load "
      << load << "), max |u_coupled - u_prescribed(U)| / max |u| " << diff << ", " << r.iterations
      << " PCPG iterations\n";
  TEST_COMPARE((freeHi - freeLo) / freeHi, >, 1e-3);  // the coupling has something to do
  TEST_COMPARE((hi - lo) / std::abs(U), <, 1e-9);
  TEST_COMPARE(std::abs(onFace) / load, <, 1e-8);
  TEST_COMPARE(std::abs(std::abs(onX0) - load) / load, <, 1e-8);
  TEST_COMPARE(diff, <, 1e-8);
  TEST_COMPARE(coupled.constraintReport().equalityResidual, <, 1e-10 * std::abs(U));
}

bool throwsNaming(const std::function<void()>& f, const std::string& what,
                  Teuchos::FancyOStream& out) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    out << "error: " << e.what() << "\n";
    return std::string(e.what()).find(what) != std::string::npos;
  }
  return false;
}

TEUCHOS_UNIT_TEST(KinematicCoupling, BadInput) {
  const StructuredProblem p = plate();
  contact::CouplingContext c = context(p);
  TEST_ASSERT(throwsNaming(
      [&] {
        contact::kinematicCouplingRows({{"x1", 2}}, c);
      },
      "Coupled components: 2 for boundary \"x1\" is not 0 (x) or 1 (y)", out));
  TEST_ASSERT(throwsNaming(
      [&] {
        contact::kinematicCouplingRows({{"x1", 0}, {"y1", 0}}, c);
      },
      "\"y1\" and \"x1\" couple u_x at a common node", out));
  c.heldBy = [](long long, int comp) {
    return comp == 1 ? std::string("symmetry boundaries (Symmetry boundaries)") : std::string();
  };
  TEST_ASSERT(throwsNaming(
      [&] {
        contact::kinematicCouplingRows({{"x1", 1}}, c);
      },
      "the coupling of u_y of \"x1\" meets the symmetry boundaries", out));
  c.nodesOf = [](const std::string&) { return std::vector<long long>{7}; };
  TEST_ASSERT(throwsNaming(
      [&] {
        contact::kinematicCouplingRows({{"corner", 0}}, c);
      },
      "\"corner\" has 1 node(s)", out));
  Teuchos::ParameterList list;
  contact::addKinematicCouplingParameters(list);
  list.set("Coupled boundaries",
           Teuchos::Array<std::string>(std::vector<std::string>{"top", "top"}));
  list.set("Coupled components", Teuchos::Array<int>(std::vector<int>{1}));
  TEST_ASSERT(throwsNaming([&] { contact::kinematicCouplings(list, "Contact problem"); },
                           "Contact problem: \"Coupled boundaries\" and \"Coupled components\"",
                           out));
  list.set("Coupled components", Teuchos::Array<int>(std::vector<int>{1, 1}));
  TEST_ASSERT(throwsNaming([&] { contact::kinematicCouplings(list, "Contact problem"); },
                           "\"top\" couples u_y twice", out));
}

}  // namespace
