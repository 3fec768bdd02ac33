// End-to-end tests of tfeti::FetiSolver on 1, 2 and 3 ranks: Poisson and plane-strain
// elasticity on the unit square (4x4 subdomains of 4x4 elements, clamped at x = 0), TFETI and
// FETI, preconditioners none / lumped / Dirichlet, every local solver. The recovered solution
// must equal a direct solve of the undecomposed problem (computed redundantly on every rank) at
// every subdomain copy of every node, and satisfy the constraints B u = 0.
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

using tfeti_test::Physics;

struct Options {
  std::string formulation = "TFETI";
  std::string preconditioner = "dirichlet";
  std::string localSolver = "cholmod";
  std::string gluing = "nonredundant";
  bool gluingAtDirichlet = true;
  void (*constrain)(tfeti::SubdomainMesh&) = nullptr;  // other Dirichlet conditions
};

std::string describe(const Physics& ph, const Options& o) {
  return std::string(ph.name()) + ", " + o.formulation + ", " + o.preconditioner + ", " +
         o.localSolver + ", " + o.gluing + (o.gluingAtDirichlet ? "" : ", no gluing at Dirichlet");
}

struct Outcome {
  tfeti::PcpgResult result;
  double solutionError = 0.0;  // max over copies |u - u_ref| / max |u_ref|
  double constraint = 0.0;     // ||B u|| / ||u||
  double dirichlet = 0.0;      // max |u| on Dirichlet copies / max |u_ref|
  // Dimensions as every rank reports them: min and max over ranks must agree.
  long long dualMin = 0, dualMax = 0, coarseMin = 0, coarseMax = 0, primalMin = 0, primalMax = 0;
};

void minMax(const tfeti::Comm& comm, long long v, long long& lo, long long& hi) {
  hi = static_cast<long long>(tfeti_test::globalMax(comm, static_cast<double>(v)));
  lo = -static_cast<long long>(tfeti_test::globalMax(comm, -static_cast<double>(v)));
}

const double kTolerance = 1e-10;

// Solves with FetiSolver and compares with the reference on every local subdomain copy.
Outcome solveAndCompare(const tfeti::StructuredRectangle& rect, const Physics& ph, const Options& o,
                        const std::vector<double>& reference) {
  auto comm = Tpetra::getDefaultComm();
  Teuchos::ParameterList params;
  params.set("Formulation", o.formulation);
  params.set("Preconditioner", o.preconditioner);
  params.set("Local solver", o.localSolver);
  params.set("Gluing", o.gluing);
  params.set("Gluing at Dirichlet nodes", o.gluingAtDirichlet);
  auto& pcpg = params.sublist("PCPG");
  pcpg.set("Relative tolerance", kTolerance);
  pcpg.set("Maximum iterations", 200);
  pcpg.set("Verbosity", 0);
  tfeti::FetiSolver solver(comm, rect.numSubdomains(),
                           tfeti_test::localSubdomains(rect, *comm, ph, o.constrain), params);
  Outcome out;
  minMax(*comm, solver.dualDimension(), out.dualMin, out.dualMax);
  minMax(*comm, solver.primalDimension(), out.primalMin, out.primalMax);
  minMax(*comm, solver.coarseDimension(), out.coarseMin, out.coarseMax);
  out.result = solver.solve();

  const int dpn = ph.dofsPerNode();
  const double scale = tfeti_test::maxAbs(reference);
  double err = 0.0, dir = 0.0;
  tfeti::Vector u(solver.tearing().primalMap);
  auto ud = u.getDataNonConst();
  std::size_t off = 0;
  for (std::size_t i = 0; i < solver.data().size(); ++i) {
    const tfeti::SubdomainMesh& mesh = solver.data()[i].mesh;
    const std::vector<double>& us = solver.solution(i);
    for (int n = 0; n < mesh.numNodes(); ++n)
      for (int c = 0; c < dpn; ++c) {
        const double ref = reference[mesh.globalNode[n] * dpn + c];
        err = std::max(err, std::abs(us[n * dpn + c] - ref));
        ud[off++] = us[n * dpn + c];
      }
    for (int d : mesh.dirichletDofs(dpn)) dir = std::max(dir, std::abs(us[d]));
  }
  ud = Teuchos::null;
  out.solutionError = tfeti_test::globalMax(*comm, err) / scale;
  out.dirichlet = tfeti_test::globalMax(*comm, dir) / scale;
  tfeti::Vector Bu(solver.tearing().multiplierMap);
  solver.tearing().B->apply(u, Bu);
  out.constraint = Bu.norm2() / u.norm2();
  return out;
}

Outcome check(const tfeti::StructuredRectangle& rect, const Physics& ph, const Options& o,
              const std::vector<double>& reference, Teuchos::FancyOStream& out, bool& success) {
  const Outcome r = solveAndCompare(rect, ph, o, reference);
  out << describe(ph, o) << ": " << (r.result.converged ? "converged" : "NOT converged") << " in "
      << r.result.iterations << " iterations, error " << r.solutionError << ", ||Bu||/||u|| "
      << r.constraint << "\n";
  TEST_EQUALITY(r.dualMin, r.dualMax);
  TEST_EQUALITY(r.primalMin, r.primalMax);
  TEST_EQUALITY(r.coarseMin, r.coarseMax);
  TEST_ASSERT(r.result.converged);
  TEST_COMPARE(r.result.relativeResidual, <=, kTolerance);
  TEST_COMPARE(r.result.iterations, >, 0);
  TEST_COMPARE(r.result.iterations, <, 100);
  TEST_EQUALITY(static_cast<int>(r.result.history.size()), r.result.iterations + 1);
  TEST_COMPARE(r.solutionError, <, 1e-6);
  TEST_COMPARE(r.constraint, <, 1e-6);
  TEST_COMPARE(r.dirichlet, <, 1e-6);
  return r;
}

tfeti::StructuredRectangle square() {
  return tfeti::StructuredRectangle(0, 1, 0, 1, 4, 4, 4, 4);
}

void runMatrix(const Physics& ph, Teuchos::FancyOStream& out, bool& success) {
  const tfeti::StructuredRectangle rect = square();
  const std::vector<double> reference = tfeti_test::referenceSolution(rect, ph);
  TEST_COMPARE(tfeti_test::maxAbs(reference), >, 1e-3);  // a nontrivial solution to compare with
  const int N = rect.numSubdomains(), k = ph.dofsPerNode() == 1 ? 1 : 3;
  for (const std::string form : {"TFETI", "FETI"}) {
    std::map<std::string, int> iterations;
    for (const std::string prec : {"none", "lumped", "dirichlet"}) {
      Options o;
      o.formulation = form;
      o.preconditioner = prec;
      const Outcome r = check(rect, ph, o, reference, out, success);
      // Paper counts scaled by the dofs per node: (1/4, 1/16) has 400 primal dofs per component
      // and 111 (FETI) or 131 (TFETI) multipliers; the coarse space has k modes per floating
      // subdomain (in FETI the 4 subdomains on x = 0 do not float).
      TEST_EQUALITY(r.primalMax, 400LL * ph.dofsPerNode());
      TEST_EQUALITY(r.dualMax, (form == "TFETI" ? 131LL : 111LL) * ph.dofsPerNode());
      TEST_EQUALITY(r.coarseMax, static_cast<long long>(k * (form == "TFETI" ? N : N - 4)));
      iterations[prec] = r.result.iterations;
    }
    // The Dirichlet preconditioner must pay off against no preconditioning.
    TEST_COMPARE(iterations["dirichlet"], <, iterations["none"]);
  }
}

}  // namespace

TEUCHOS_UNIT_TEST(FetiSolver, PoissonAllFormulationsAndPreconditioners) {
  runMatrix(tfeti_test::poisson(), out, success);
}

TEUCHOS_UNIT_TEST(FetiSolver, ElasticityAllFormulationsAndPreconditioners) {
  runMatrix(tfeti_test::elasticity(), out, success);
}

// Rollers instead of the clamp: u_x = 0 on x = 0 and u_y = 0 on y = 0 (the symmetry conditions of
// a quarter model). They are single-component conditions: Dirichlet rows (TFETI) or eliminated
// dofs (FETI) per component, and gluing of the free component at the same nodes.
void rollers(tfeti::SubdomainMesh& mesh) {
  mesh.dirichletNodes.clear();
  for (int n = 0; n < mesh.numNodes(); ++n) {
    if (mesh.coords[2 * n] == 0.0) mesh.fixedComponents.push_back({n, 0});
    if (mesh.coords[2 * n + 1] == 0.0) mesh.fixedComponents.push_back({n, 1});
  }
}

TEUCHOS_UNIT_TEST(FetiSolver, SingleComponentDirichletConditions) {
  const auto rect = square();
  const Physics ph = tfeti_test::elasticity();
  const auto reference = tfeti_test::referenceSolution(rect, ph, rollers);
  // The rollers let the square slide: the reference differs from the clamped solution.
  const auto clamped = tfeti_test::referenceSolution(rect, ph);
  double diff = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i)
    diff = std::max(diff, std::abs(reference[i] - clamped[i]));
  TEST_COMPARE(diff, >, 0.1 * tfeti_test::maxAbs(reference));
  for (const char* formulation : {"TFETI", "FETI"})
    for (bool atDirichlet : {true, false}) {
      Options o;
      o.formulation = formulation;
      o.gluingAtDirichlet = atDirichlet;
      o.constrain = rollers;
      check(rect, ph, o, reference, out, success);
    }
}

TEUCHOS_UNIT_TEST(FetiSolver, EveryLocalSolver) {
  const tfeti::StructuredRectangle rect = square();
  for (const Physics& ph : {tfeti_test::poisson(), tfeti_test::elasticity()}) {
    const std::vector<double> reference = tfeti_test::referenceSolution(rect, ph);
    for (const auto& solver : tfeti::localSolverTypes())
      for (const std::string form : {"TFETI", "FETI"}) {
        Options o;
        o.formulation = form;
        o.localSolver = solver;
        check(rect, ph, o, reference, out, success);
      }
  }
}

TEUCHOS_UNIT_TEST(FetiSolver, GluingVariants) {
  // Redundant gluing, and TFETI without the gluing rows that duplicate Dirichlet rows.
  const tfeti::StructuredRectangle rect = square();
  for (const Physics& ph : {tfeti_test::poisson(), tfeti_test::elasticity()}) {
    const std::vector<double> reference = tfeti_test::referenceSolution(rect, ph);
    for (const std::string prec : {"lumped", "dirichlet"}) {
      Options o;
      o.preconditioner = prec;
      o.gluing = "redundant";
      check(rect, ph, o, reference, out, success);
      o.gluing = "nonredundant";
      o.gluingAtDirichlet = false;
      check(rect, ph, o, reference, out, success);
      o.formulation = "FETI";
      o.gluing = "redundant";
      check(rect, ph, o, reference, out, success);
    }
  }
}

TEUCHOS_UNIT_TEST(FetiSolver, NonSquareDecomposition) {
  // (0,2) x (0,1) in 3 x 2 subdomains of 5 x 4 elements: subdomain grid and element counts differ
  // in x and y, and 6 subdomains do not divide evenly over 4 or 5 ranks' blocks.
  const tfeti::StructuredRectangle rect(0, 2, 0, 1, 3, 2, 5, 4);
  for (const Physics& ph : {tfeti_test::poisson(), tfeti_test::elasticity()}) {
    const std::vector<double> reference = tfeti_test::referenceSolution(rect, ph);
    for (const std::string form : {"TFETI", "FETI"}) {
      Options o;
      o.formulation = form;
      check(rect, ph, o, reference, out, success);
    }
  }
}

TEUCHOS_UNIT_TEST(FetiSolver, RanksWithoutSubdomains) {
  // 2 subdomains: on 3 ranks, rank 0 holds none (subdomainsOfRank(0, 2, 3) is empty) and must
  // still take part in every collective with the right number of dofs per node.
  // Dual dimension: 5 interface nodes, plus 5 Dirichlet nodes in TFETI, per component.
  const tfeti::StructuredRectangle rect(0, 2, 0, 1, 2, 1, 4, 4);
  for (const Physics& ph : {tfeti_test::poisson(), tfeti_test::elasticity()}) {
    const std::vector<double> reference = tfeti_test::referenceSolution(rect, ph);
    const int dpn = ph.dofsPerNode();
    for (const std::string form : {"TFETI", "FETI"}) {
      Options o;
      o.formulation = form;
      const Outcome r = check(rect, ph, o, reference, out, success);
      TEST_EQUALITY(r.dualMax, dpn * (form == "TFETI" ? 10LL : 5LL));
      TEST_EQUALITY(r.primalMax, dpn * 50LL);
      TEST_EQUALITY(r.coarseMax, (dpn == 1 ? 1LL : 3LL) * (form == "TFETI" ? 2 : 1));
    }
  }
}

TEUCHOS_UNIT_TEST(FetiSolver, IterationLimitIsReportedAsFailure) {
  const tfeti::StructuredRectangle rect = square();
  const Physics ph = tfeti_test::poisson();
  auto comm = Tpetra::getDefaultComm();
  Teuchos::ParameterList params;
  params.set("Preconditioner", "none");
  params.sublist("PCPG").set("Relative tolerance", 1e-12);
  params.sublist("PCPG").set("Maximum iterations", 3);
  tfeti::FetiSolver solver(comm, rect.numSubdomains(), tfeti_test::localSubdomains(rect, *comm, ph),
                           params);
  const tfeti::PcpgResult r = solver.solve();
  TEST_ASSERT(!r.converged);
  TEST_EQUALITY(r.iterations, 3);
  TEST_COMPARE(r.relativeResidual, >, 1e-12);
  TEST_EQUALITY(static_cast<int>(r.history.size()), 4);
  TEST_FLOATING_EQUALITY(r.history.back(), r.relativeResidual, 1e-14);
  TEST_COMPARE(solver.dualOperatorApplies(), >=, 3LL);
}

TEUCHOS_UNIT_TEST(FetiSolver, InvalidParametersThrow) {
  const tfeti::StructuredRectangle rect(0, 1, 0, 1, 2, 2, 2, 2);
  auto comm = Tpetra::getDefaultComm();
  const auto make = [&](const Teuchos::ParameterList& params) {
    tfeti::FetiSolver solver(comm, rect.numSubdomains(),
                             tfeti_test::localSubdomains(rect, *comm, tfeti_test::poisson()),
                             params);
  };
  for (const auto& [name, value] :
       std::vector<std::pair<std::string, std::string>>{{"Formulation", "TFETI2"},
                                                        {"Preconditioner", "jacobi"},
                                                        {"Local solver", "mumps"},
                                                        {"Gluing", "both"}}) {
    Teuchos::ParameterList params;
    params.set(name, value);
    TEST_THROW(make(params), Teuchos::Exceptions::InvalidParameter);
  }
  Teuchos::ParameterList typo;
  typo.set("Preconditoner", "lumped");
  TEST_THROW(make(typo), Teuchos::Exceptions::InvalidParameter);
  Teuchos::ParameterList pcpgTypo;
  pcpgTypo.sublist("PCPG").set("Tolerance", 1e-8);
  TEST_THROW(make(pcpgTypo), Teuchos::Exceptions::InvalidParameter);
}
