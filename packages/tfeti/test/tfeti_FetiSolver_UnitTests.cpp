// End-to-end tests of tfeti::FetiSolver on 1, 2 and 3 ranks: Poisson and plane-strain
// elasticity on the unit square (4x4 subdomains of 4x4 elements, clamped at x = 0), TFETI and
// FETI, preconditioners none / lumped / Dirichlet, every local solver. The recovered solution
// must equal a direct solve of the undecomposed problem (computed redundantly on every rank) at
// every subdomain copy of every node, and satisfy the constraints B u = 0.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_Test3d.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

using tfeti_test::Physics;

struct Options {
  std::string formulation = "TFETI";
  std::string preconditioner = "dirichlet";
  std::string localSolver = "cholmod";
  std::string coarseSolver = "cholmod";
  std::string gluing = "nonredundant";
  bool gluingAtDirichlet = true;
  void (*constrain)(tfeti::SubdomainMesh&) = nullptr;  // other Dirichlet conditions
};

std::string describe(const Physics& ph, const Options& o) {
  return std::string(ph.name()) + ", " + o.formulation + ", " + o.preconditioner + ", " +
         o.localSolver + ", coarse " + o.coarseSolver + ", " + o.gluing +
         (o.gluingAtDirichlet ? "" : ", no gluing at Dirichlet");
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

Teuchos::ParameterList solverParameters(const Options& o) {
  Teuchos::ParameterList params;
  params.set("Formulation", o.formulation);
  params.set("Preconditioner", o.preconditioner);
  params.set("Local solver", o.localSolver);
  params.set("Coarse solver", o.coarseSolver);
  params.set("Gluing", o.gluing);
  params.set("Gluing at Dirichlet nodes", o.gluingAtDirichlet);
  auto& pcpg = params.sublist("PCPG");
  pcpg.set("Relative tolerance", kTolerance);
  pcpg.set("Maximum iterations", 200);
  pcpg.set("Verbosity", 0);
  return params;
}

std::vector<double> boxLoad(const tfeti_test::Material3d& mat, double scale) {
  return mat.dofsPerNode == 1 ? std::vector<double>{scale} : std::vector<double>{0, 0, -scale};
}

// Solves with FetiSolver and compares with the reference on every local subdomain copy.
Outcome solveAndCompare(int numSubdomains, std::vector<tfeti::SubdomainData> local, int dpn,
                        const Options& o, const std::vector<double>& reference) {
  auto comm = Tpetra::getDefaultComm();
  tfeti::FetiSolver solver(comm, numSubdomains, std::move(local), solverParameters(o));
  Outcome out;
  minMax(*comm, solver.dualDimension(), out.dualMin, out.dualMax);
  minMax(*comm, solver.primalDimension(), out.primalMin, out.primalMax);
  minMax(*comm, solver.coarseDimension(), out.coarseMin, out.coarseMax);
  out.result = solver.solve();

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

Outcome check(int numSubdomains, std::vector<tfeti::SubdomainData> local, int dpn,
              const std::string& description, const Options& o,
              const std::vector<double>& reference, Teuchos::FancyOStream& out, bool& success) {
  const Outcome r = solveAndCompare(numSubdomains, std::move(local), dpn, o, reference);
  out << description << ": " << (r.result.converged ? "converged" : "NOT converged") << " in "
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

Outcome check(const tfeti::StructuredRectangle& rect, const Physics& ph, const Options& o,
              const std::vector<double>& reference, Teuchos::FancyOStream& out, bool& success) {
  auto comm = Tpetra::getDefaultComm();
  return check(rect.numSubdomains(), tfeti_test::localSubdomains(rect, *comm, ph, o.constrain),
               ph.dofsPerNode(), describe(ph, o), o, reference, out, success);
}

// The subdomains of a 3D box on this rank, assembled with the test Tet4/Hex8 kernels; unit body
// load (1 for the Laplacian, (0, 0, -1) for elasticity) times loadScale.
std::vector<tfeti::SubdomainData> localBoxSubdomains(const tfeti_test::Box3d& box,
                                                     const tfeti_test::Material3d& mat,
                                                     double loadScale = 1.0) {
  auto comm = Tpetra::getDefaultComm();
  std::vector<tfeti::SubdomainData> local;
  for (int s : tfeti::subdomainsOfRank(comm->getRank(), box.numSubdomains(), comm->getSize())) {
    tfeti::SubdomainData d;
    d.mesh = box.subdomain(s);
    d.dofsPerNode = mat.dofsPerNode;
    tfeti_test::assemble3d(d.mesh.coords, d.mesh.elements, mat, boxLoad(mat, loadScale), d.K, d.f);
    local.push_back(std::move(d));
  }
  return local;
}

// SMALBE with both tolerances at 1e-10: the QP tests compare solutions to 1e-8.
Teuchos::ParameterList tightSmalbeParameters() {
  Teuchos::ParameterList params = solverParameters(Options());
  params.set("Dual solver", "SMALBE");
  params.sublist("SMALBE").set("Relative tolerance", 1e-10);
  params.sublist("SMALBE").set("Equality tolerance", 1e-10);
  return params;
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
        o.coarseSolver = solver;  // G G^T by the same solver (its own parameter)
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

// 3D: the box (0,4)^3 of 2x2x2 subdomains of 2x2x2 cubes (Hex8, or six Tet4 each), clamped at
// x = 0; nodes are shared by up to 8 subdomains. Scalar (1 mode per subdomain) and elasticity (6),
// TFETI and FETI, nonredundant and redundant gluing, against a direct solve of the untorn box.
TEUCHOS_UNIT_TEST(FetiSolver, ThreeDimensionalBoxes) {
  const int N = 8;
  for (bool tets : {false, true})
    for (int dpn : {1, 3}) {
      const tfeti_test::Box3d box(2, 2, 2, 2, 2, 2, tets);
      tfeti_test::Material3d mat;
      mat.dofsPerNode = dpn;
      const std::vector<double> reference =
          tfeti_test::referenceSolution3d(box, mat, boxLoad(mat, 1.0));
      TEST_COMPARE(tfeti_test::maxAbs(reference), >, 1e-2);
      for (const std::string form : {"TFETI", "FETI"})
        for (const std::string gluing : {"nonredundant", "redundant"}) {
          Options o;
          o.formulation = form;
          o.gluing = gluing;
          const std::string what = std::string(tets ? "Tet4" : "Hex8") +
                                   (dpn == 1 ? " Laplacian, " : " elasticity, ") + form + ", " +
                                   gluing;
          const Outcome r =
              check(N, localBoxSubdomains(box, mat), dpn, what, o, reference, out, success);
          // 8 x 27 node copies of 125 nodes: 91 nonredundant gluing rows per component; TFETI
          // adds 36 Dirichlet rows (4 subdomains x 9 nodes on x = 0).
          TEST_EQUALITY(r.primalMax, 8LL * 27 * dpn);
          if (gluing == "nonredundant")
            TEST_EQUALITY(r.dualMax, (form == "TFETI" ? 127LL : 91LL) * dpn);
          TEST_EQUALITY(r.coarseMax, (dpn == 1 ? 1LL : 6LL) * (form == "TFETI" ? N : N - 4));
        }
    }
}

// A subdomain error found on one rank (here a supplied kernel that K does not annihilate, in the
// last subdomain) is the same clear error on every rank: no rank is left in a collective.
TEUCHOS_UNIT_TEST(FetiSolver, SubdomainErrorIsRaisedOnEveryRank) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti_test::Box3d box(2, 2, 2, 1, 1, 1, false);
  tfeti_test::Material3d mat;
  mat.dofsPerNode = 3;
  std::vector<tfeti::SubdomainData> local = localBoxSubdomains(box, mat);
  for (auto& d : local)
    if (d.mesh.id == box.numSubdomains() - 1) {
      d.kernel.assign(d.K.rows, 0.0);
      for (int a = 0; a < d.K.rows / 3; ++a) d.kernel[3 * a] = d.mesh.coords[3 * a];  // u = (x,0,0)
    }
  std::string message;
  try {
    tfeti::FetiSolver solver(comm, box.numSubdomains(), std::move(local), Teuchos::ParameterList());
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  out << "rank " << comm->getRank() << ": " << message << "\n";
  TEST_INEQUALITY(message.find("subdomain 7"), std::string::npos);
  TEST_INEQUALITY(message.find("not in the kernel of K"), std::string::npos);
}

// A zero load gives exactly lambda = 0 and u = 0: PCPG, SMALBE and the penalty method (with
// inequality rows u_z <= 0 of zero gap on the top face, which a zero load leaves inactive).
TEUCHOS_UNIT_TEST(FetiSolver, ZeroLoadGivesTheExactZeroSolution) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti_test::Box3d box(2, 2, 2, 2, 2, 2, false);
  tfeti_test::Material3d mat;
  mat.dofsPerNode = 3;
  std::vector<tfeti::InequalityRow> rows;
  if (comm->getRank() == 0)
    for (int s = 4; s < 8; ++s) {  // top layer of subdomains: local nodes on z = 4
      const tfeti::SubdomainMesh m = box.subdomain(s);
      for (int n = 0; n < m.numNodes(); ++n)
        if (m.coords[3 * n + 2] == 4.0) rows.push_back({{{s, 3 * n + 2, 1.0}}, 0.0});
    }
  for (const std::string method : {"PCPG", "SMALBE", "penalty"}) {
    Options o;
    Teuchos::ParameterList params = solverParameters(o);
    params.set("Dual solver", method);
    tfeti::FetiSolver solver(comm, box.numSubdomains(), localBoxSubdomains(box, mat, 0.0), params,
                             method == "PCPG" ? std::vector<tfeti::InequalityRow>{} : rows);
    const tfeti::DualResult r = solver.solve();
    double maxU = 0.0;
    for (std::size_t i = 0; i < solver.data().size(); ++i)
      maxU = std::max(maxU, tfeti_test::maxAbs(solver.solution(i)));
    const double maxLambda = solver.multipliers().normInf();
    out << method << ": converged " << r.converged << ", " << r.iterations
        << " iterations, max |u| = " << maxU << ", max |lambda| = " << maxLambda << "\n";
    TEST_ASSERT(r.converged);
    TEST_EQUALITY(tfeti_test::globalMax(*comm, maxU), 0.0);
    TEST_EQUALITY(maxLambda, 0.0);
  }
}

// 3D friction's disc rows (InequalityRow::disc): a cantilever box (Dirichlet at x = 0, two
// subdomains along x) under its weight, its end face x = 4 held in y and z by disc pairs
// |(lambda_y, lambda_z)| <= g with gap 0, g small enough that the end nodes slide. The rigid
// body coefficients of the primal recovery are fitted on the rows that hold with equality:
// on the circle a pair does not hold (the node slips), although each of its multipliers is
// inside [-g, g]. Counting such a pair (as a test per row did) bends the fit towards zero slip
// and leaves the gluing rows violated (here by max |u| itself: the sliding end pulled back); the
// equality rows must hold to the solver's tolerance: SMALBE's (measured 5e-12 of max |u|), the
// penalty method's, which meets them only to about ||PFP|| / rho (6e-5).
TEUCHOS_UNIT_TEST(FetiSolver, SlidingDiscRowsStayOutOfTheRigidBodyFit) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti_test::Box3d box(2, 1, 1, 2, 2, 2, false);
  tfeti_test::Material3d mat;
  mat.dofsPerNode = 3;
  const double g = 0.02;
  std::vector<tfeti::InequalityRow> rows;
  if (comm->getRank() == 0) {
    const tfeti::SubdomainMesh m = box.subdomain(1);
    for (int n = 0; n < m.numNodes(); ++n)
      if (m.coords[3 * n] == 4.0)
        for (int c = 1; c <= 2; ++c) {
          tfeti::InequalityRow r;
          r.entries = {{1, 3 * n + c, 1.0}};
          r.lowerBound = -g;
          r.upperBound = g;
          r.disc = c;
          rows.push_back(r);
        }
  }
  for (const std::string method : {"SMALBE", "penalty"}) {
    Options o;
    Teuchos::ParameterList params = solverParameters(o);
    params.set("Dual solver", method);
    params.sublist("SMALBE").set("Relative tolerance", 1e-10);
    params.sublist("SMALBE").set("Equality tolerance", 1e-10);
    tfeti::FetiSolver solver(comm, box.numSubdomains(), localBoxSubdomains(box, mat), params, rows);
    const tfeti::DualResult r = solver.solve();
    TEST_ASSERT(r.converged);
    // B u - c on the equality rows (gluing and Dirichlet), against max |u|.
    tfeti::Vector u(solver.tearing().primalMap);
    {
      auto ud = u.getDataNonConst();
      std::size_t off = 0;
      for (std::size_t i = 0; i < solver.data().size(); ++i)
        for (double v : solver.solution(i)) ud[off++] = v;
    }
    tfeti::Vector Bu(solver.tearing().multiplierMap);
    solver.tearing().B->apply(u, Bu);
    double residual = 0.0;
    {
      auto b = Bu.getData();
      auto c = solver.tearing().rhs->getData();
      const auto& map = *solver.tearing().multiplierMap;
      for (std::size_t i = 0; i < map.getNodeNumElements(); ++i)
        if (!solver.tearing().isInequality(map.getGlobalElement(static_cast<tfeti::LO>(i))))
          residual = std::max(residual, std::abs(b[i] - c[i]));
    }
    residual = tfeti_test::globalMax(*comm, residual) / u.normInf();
    // The pairs on their circle (sliding), to the QP's tolerance.
    const std::vector<double> l = solver.inequalityMultipliers();
    int sliding = 0;
    for (std::size_t i = 0; i + 1 < l.size(); i += 2)
      if (std::hypot(l[i], l[i + 1]) >= g * (1.0 - 1e-8)) ++sliding;
    out << method << ": " << sliding << " of " << l.size() / 2
        << " disc pairs sliding, equality rows' residual " << residual << " of max |u|\n";
    TEST_COMPARE(sliding, >, 0);
    TEST_COMPARE(residual, <=, method == "SMALBE" ? 1e-8 : 1e-3);
  }
}

// Coulomb's bounds move between Newton iterations (g = mu lambda_N of the last solve): the
// cantilever above, its end held by keyed disc pairs of radius g, solved, then update()d to the
// radius 1.25 g. The pairs that slid start on their new circles in the same direction
// (FetiSolver::warmIncrement), so the warm solve keeps its face and needs fewer multiplications
// than the same rows solved cold, for the same solution.
TEUCHOS_UNIT_TEST(FetiSolver, SlidingDiscsStartOnTheirNewCircles) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti_test::Box3d box(2, 1, 1, 2, 2, 2, false);
  tfeti_test::Material3d mat;
  mat.dofsPerNode = 3;
  const auto endRows = [&](double g) {
    std::vector<tfeti::InequalityRow> rows;
    if (comm->getRank() != 0) return rows;
    const tfeti::SubdomainMesh m = box.subdomain(1);
    for (int n = 0; n < m.numNodes(); ++n)
      if (m.coords[3 * n] == 4.0)
        for (int c = 1; c <= 2; ++c) {
          tfeti::InequalityRow r;
          r.entries = {{1, 3 * n + c, 1.0}};
          r.lowerBound = -g;
          r.upperBound = g;
          r.disc = c;
          r.key = 4 * n + c;
          rows.push_back(r);
        }
    return rows;
  };
  Options o;
  Teuchos::ParameterList params = solverParameters(o);
  params.set("Dual solver", "SMALBE");
  params.sublist("SMALBE").set("Relative tolerance", 1e-10);
  params.sublist("SMALBE").set("Equality tolerance", 1e-10);
  const double g = 0.02;
  tfeti::FetiSolver cold(comm, box.numSubdomains(), localBoxSubdomains(box, mat), params,
                         endRows(1.25 * g));
  const tfeti::DualResult rc = cold.solve();
  tfeti::FetiSolver warm(comm, box.numSubdomains(), localBoxSubdomains(box, mat), params,
                         endRows(g));
  TEST_ASSERT(warm.solve().converged);
  std::vector<std::vector<double>> loads;
  for (const auto& sub : warm.subdomains()) loads.push_back(sub->load());
  warm.update(loads, endRows(1.25 * g));
  const tfeti::DualResult rw = warm.solve();
  TEST_ASSERT(rc.converged && rw.converged);
  const std::vector<double> lc = cold.inequalityMultipliers(), lw = warm.inequalityMultipliers();
  TEST_EQUALITY(lc.size(), lw.size());
  double diff = 0.0;
  int sliding = 0;
  for (std::size_t i = 0; i < lc.size(); ++i) diff = std::max(diff, std::abs(lc[i] - lw[i]));
  for (std::size_t i = 0; i + 1 < lc.size(); i += 2)
    if (std::hypot(lc[i], lc[i + 1]) >= 1.25 * g * (1.0 - 1e-8)) ++sliding;
  out << sliding << " of " << lc.size() / 2 << " pairs sliding; " << rw.qp.hessianMultiplications
      << " multiplications warm, " << rc.qp.hessianMultiplications
      << " cold; max |lambda_warm - lambda_cold| / g = " << diff / g << "\n";
  TEST_COMPARE(sliding, >, 0);
  TEST_COMPARE(diff, <, 1e-6 * g);
  TEST_COMPARE(rw.qp.hessianMultiplications, <, rc.qp.hessianMultiplications);
}

// The warm start across a contact update that changes the rows (tfeti_RowCarryOver.hpp): a
// cantilever box under its weight on a rigid floor z = 0, first with rows at x = 3 and 4 of its
// bottom, then (update()) with rows at x = 2 too. Keyed, the second solve starts from the first
// one's multipliers (the new rows at 0) and needs fewer multiplications than the same rows solved
// cold, for the same solution; unkeyed, the rows' number changed and it starts cold.
TEUCHOS_UNIT_TEST(FetiSolver, WarmStartFollowsKeyedRowsAcrossAnUpdate) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti_test::Box3d box(2, 1, 1, 2, 2, 2, false);
  tfeti_test::Material3d mat;
  mat.dofsPerNode = 3;
  const auto floorRows = [&](double xMin, bool keyed) {
    std::vector<tfeti::InequalityRow> rows;
    if (comm->getRank() != 0) return rows;
    const tfeti::SubdomainMesh m = box.subdomain(1);
    for (int n = 0; n < m.numNodes(); ++n)
      if (m.coords[3 * n + 2] == 0.0 && m.coords[3 * n] >= xMin) {
        tfeti::InequalityRow r;
        r.entries = {{1, 3 * n + 2, -1.0}};  // -u_z <= 0
        r.key = keyed ? n : -1;
        rows.push_back(r);
      }
    return rows;
  };
  Options o;
  Teuchos::ParameterList params = solverParameters(o);
  params.set("Dual solver", "SMALBE");
  params.sublist("SMALBE").set("Relative tolerance", 1e-10);
  const auto solution = [&](const tfeti::FetiSolver& s) {
    std::vector<double> u;
    for (std::size_t i = 0; i < s.data().size(); ++i)
      u.insert(u.end(), s.solution(i).begin(), s.solution(i).end());
    return u;
  };
  tfeti::FetiSolver cold(comm, box.numSubdomains(), localBoxSubdomains(box, mat), params,
                         floorRows(2.0, true));
  const tfeti::DualResult rc = cold.solve();
  const std::vector<double> uc = solution(cold);
  for (const bool keyed : {true, false}) {
    tfeti::FetiSolver s(comm, box.numSubdomains(), localBoxSubdomains(box, mat), params,
                        floorRows(3.0, keyed));
    TEST_ASSERT(s.solve().converged);
    std::vector<std::vector<double>> loads;
    for (const auto& sub : s.subdomains()) loads.push_back(sub->load());
    s.update(loads, floorRows(2.0, keyed));
    const tfeti::DualResult r = s.solve();
    const std::vector<double> u = solution(s);
    double diff = 0.0, scale = 0.0;
    for (std::size_t k = 0; k < u.size(); ++k) {
      diff = std::max(diff, std::abs(u[k] - uc[k]));
      scale = std::max(scale, std::abs(uc[k]));
    }
    diff = tfeti_test::globalMax(*comm, diff) / tfeti_test::globalMax(*comm, scale);
    out << (keyed ? "keyed" : "unkeyed") << ": " << r.qp.hessianMultiplications
        << " multiplications after the update, " << rc.qp.hessianMultiplications
        << " cold; solution difference " << diff << "\n";
    TEST_ASSERT(r.converged);
    TEST_COMPARE(diff, <, 1e-8);
    if (keyed) {
      TEST_COMPARE(r.qp.hessianMultiplications, <, rc.qp.hessianMultiplications);
    } else {
      TEST_EQUALITY(r.qp.hessianMultiplications, rc.qp.hessianMultiplications);
    }
  }
}

// The 4 x 2 x 1 elastic box of 3^3-element subdomains on a rigid floor with zero gaps (a row for
// each node of its bottom at x >= 6), and a solver's solution in one vector of its local dofs.
struct FloorBox {
  tfeti_test::Box3d box{4, 2, 1, 3, 3, 3, false};
  tfeti_test::Material3d mat;
  FloorBox() { mat.dofsPerNode = 3; }
  std::vector<tfeti::InequalityRow> rows() const {
    return floorRows(
        box, [](double) { return 0.0; }, 6.0, false);
  }
};

std::vector<double> flatSolution(const tfeti::FetiSolver& s) {
  std::vector<double> u;
  for (std::size_t i = 0; i < s.data().size(); ++i)
    u.insert(u.end(), s.solution(i).begin(), s.solution(i).end());
  return u;
}

// max |u - reference| / max |reference| over every rank.
double relativeMaxDifference(const tfeti::Comm& comm, const std::vector<double>& u,
                             const std::vector<double>& reference) {
  double e = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < u.size(); ++k) {
    e = std::max(e, std::abs(u[k] - reference[k]));
    scale = std::max(scale, std::abs(reference[k]));
  }
  return tfeti_test::globalMax(comm, e) / tfeti_test::globalMax(comm, scale);
}

// An inexact Newton QP (setToleranceFactor > 1) stops its face CG at "Inexact face relative
// tolerance" times its loosened tolerance, not two digits beyond it: the box on a rigid floor
// (a row for each node of its bottom at x >= 6, on the first subdomain that holds it), its load
// doubled after a first solve (the warm start gives the face solve its first face), solved at a
// factor of 1e4 with the old rule (0.01) and with 0.5. Both stay within the loosened tolerance
// of the exact solution; the looser face CG takes fewer multiplications. An exact QP (factor 1)
// does not read the parameter.
TEUCHOS_UNIT_TEST(FetiSolver, InexactQpStopsTheFaceCgAtItsOwnTolerance) {
  auto comm = Tpetra::getDefaultComm();
  const FloorBox fb;
  const tfeti_test::Box3d& box = fb.box;
  const tfeti_test::Material3d& mat = fb.mat;
  const auto floor = [&] { return fb.rows(); };
  const auto solve = [&](double factor, double inexactFace, std::vector<double>& u) {
    Teuchos::ParameterList params = tightSmalbeParameters();
    params.set("Inexact face relative tolerance", inexactFace);
    tfeti::FetiSolver s(comm, box.numSubdomains(), localBoxSubdomains(box, mat), params, floor());
    TEST_ASSERT(s.solve().converged);
    // The Newton loop's situation: a warm start (its face first) for a changed load.
    std::vector<std::vector<double>> loads;
    for (const auto& d : localBoxSubdomains(box, mat, 2.0)) loads.push_back(d.f);
    s.update(loads, floor());
    s.setToleranceFactor(factor);
    const tfeti::DualResult r = s.solve();
    u = flatSolution(s);
    TEST_ASSERT(r.converged);
    return r.qp.hessianMultiplications;
  };
  std::vector<double> exact, u;
  const int exactOld = solve(1.0, 0.01, exact);
  const int exactNew = solve(1.0, 0.5, u);
  TEST_EQUALITY(exactOld, exactNew);
  const auto error = [&](const std::vector<double>& v) {
    return relativeMaxDifference(*comm, v, exact);
  };
  const int inexactOld = solve(1e4, 0.01, u);
  const double errorOld = error(u);
  const int inexactNew = solve(1e4, 0.5, u);
  const double errorNew = error(u);
  out << "exact: " << exactOld << " multiplications; factor 1e4: " << inexactOld
      << " (face CG to 0.01 of the tolerance, error " << errorOld << "), " << inexactNew
      << " (0.5, error " << errorNew << ")\n";
  TEST_COMPARE(inexactNew, <, inexactOld);
  TEST_COMPARE(errorNew, <, 1e-5);
  TEST_COMPARE(errorOld, <, 1e-5);
  // Values outside (0, 1]: an error that names the parameter.
  for (const double value : {0.0, 1.5, -0.1}) {
    Teuchos::ParameterList bad;
    bad.set("Inexact face relative tolerance", value);
    std::string message;
    try {
      tfeti::FetiSolver(comm, box.numSubdomains(), localBoxSubdomains(box, mat), bad);
    } catch (const std::exception& e) {
      message = e.what();
    }
    out << value << ": " << message.substr(0, 200) << "\n";
    TEST_ASSERT(message.find("Inexact face relative tolerance") != std::string::npos);
  }
}

// A tolerance factor below 1 solves tighter than configured (a Newton loop whose test stalls at
// the QPs' accuracy asks for it: contact::LoadStepIteration::tightenQps): the box on the rigid
// floor by SMALBE and by the penalty method configured at 1e-5, solved at factors 1 and 0.01,
// against the same problem solved at 1e-11. The factor 0.01 takes more multiplications and
// lands closer. A factor that is not positive and finite is an error naming the call.
TEUCHOS_UNIT_TEST(FetiSolver, ToleranceFactorBelowOneSolvesTighter) {
  auto comm = Tpetra::getDefaultComm();
  const FloorBox fb;
  const tfeti_test::Box3d& box = fb.box;
  const tfeti_test::Material3d& mat = fb.mat;
  const auto floor = [&] { return fb.rows(); };
  for (const std::string method : {"SMALBE", "penalty"}) {
    const auto solve = [&](double tolerance, double factor, std::vector<double>& u) {
      Teuchos::ParameterList params = solverParameters(Options());
      params.set("Dual solver", method);
      params.sublist(method == "SMALBE" ? "SMALBE" : "MPRGP").set("Relative tolerance", tolerance);
      if (method == "SMALBE") params.sublist("SMALBE").set("Equality tolerance", tolerance);
      tfeti::FetiSolver s(comm, box.numSubdomains(), localBoxSubdomains(box, mat), params, floor());
      s.setToleranceFactor(factor);
      const tfeti::DualResult r = s.solve();
      TEST_ASSERT(r.converged);
      u = flatSolution(s);
      return r.qp.hessianMultiplications;
    };
    std::vector<double> reference, u;
    solve(1e-11, 1.0, reference);
    const auto error = [&] { return relativeMaxDifference(*comm, u, reference); };
    const int configured = solve(1e-5, 1.0, u);
    const double configuredError = error();
    const int tighter = solve(1e-5, 0.01, u);
    const double tighterError = error();
    out << method << ": factor 1 " << configured << " multiplications, error " << configuredError
        << "; factor 0.01 " << tighter << ", error " << tighterError << "\n";
    TEST_COMPARE(tighter, >, configured);
    TEST_COMPARE(tighterError, <, 0.1 * configuredError);
  }
  Teuchos::ParameterList params = tightSmalbeParameters();
  tfeti::FetiSolver s(comm, box.numSubdomains(), localBoxSubdomains(box, mat), params, floor());
  for (const double bad : {0.0, -0.01, std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN()}) {
    std::string message;
    try {
      s.setToleranceFactor(bad);
    } catch (const std::invalid_argument& e) {
      message = e.what();
    }
    out << bad << ": " << message << "\n";
    TEST_ASSERT(message.find("setToleranceFactor") != std::string::npos);
  }
}

// update() with contact rows whose entries are unchanged and only their gaps moved (a Newton
// iteration against a height-function obstacle in small strain) keeps the tearing and the coarse
// space, and solves as a solver that builds them anew: the box on a rigid floor, the floor moved,
// the load doubled, from an increment's origin with jumps between the subdomains (whose gluing
// rows it shifts, so that a kept tearing must start from unshifted rows each time). Rows with
// other entries are built anew.
TEUCHOS_UNIT_TEST(FetiSolver, UpdateWithTheSameRowEntriesKeepsTheTearing) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti_test::Box3d box(4, 2, 1, 3, 3, 3, false);
  const int N = box.numSubdomains();
  tfeti_test::Material3d mat;
  mat.dofsPerNode = 3;
  Teuchos::ParameterList params = tightSmalbeParameters();
  const auto solution = [&](const tfeti::FetiSolver& s) {
    std::vector<std::vector<double>> u;
    for (std::size_t i = 0; i < s.data().size(); ++i) u.push_back(s.solution(i));
    return u;
  };
  const auto difference = [&](const auto& a, const auto& b) {
    double diff = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
      for (std::size_t k = 0; k < a[i].size(); ++k) {
        diff = std::max(diff, std::abs(a[i][k] - b[i][k]));
        scale = std::max(scale, std::abs(b[i][k]));
      }
    return tfeti_test::globalMax(*comm, diff) / tfeti_test::globalMax(*comm, scale);
  };
  const auto flat = [](double) { return 0.0; };
  tfeti::FetiSolver s(comm, N, localBoxSubdomains(box, mat), params,
                      floorRows(box, flat, 6.0, true));
  TEST_ASSERT(s.solve().converged);
  TEST_EQUALITY(s.timings().tearings, 1LL);
  TEST_EQUALITY(s.timings().tearingsReused, 0LL);
  // The origin: the first solution with every subdomain moved by its own amount (jumps); the
  // floor curved, so that the doubled load closes some rows and not others.
  std::vector<std::vector<double>> origin = solution(s);
  double uMax = 0.0;
  for (const auto& v : origin)
    for (double x : v) uMax = std::max(uMax, std::abs(x));
  uMax = tfeti_test::globalMax(*comm, uMax);
  for (std::size_t i = 0; i < origin.size(); ++i)
    for (std::size_t k = 2; k < origin[i].size(); k += 3)
      origin[i][k] += 0.01 * uMax * (s.data()[i].mesh.id % 3);
  std::vector<std::vector<double>> loads;
  for (const auto& d : localBoxSubdomains(box, mat, 2.0)) loads.push_back(d.f);
  const auto curved = [&](double x) { return uMax * (0.2 + 2.0 * (x - 9.0) * (x - 9.0) / 9.0); };
  const std::vector<tfeti::InequalityRow> moved = floorRows(box, curved, 6.0, true);

  // The reference builds its tearing for these rows: it was built without any.
  tfeti::FetiSolver ref(comm, N, localBoxSubdomains(box, mat), params);
  ref.setIncrementOrigin(origin);
  ref.update(loads, moved);
  const tfeti::DualResult rr = ref.solve();
  TEST_ASSERT(rr.converged);
  TEST_EQUALITY(ref.timings().tearings, 2LL);
  TEST_EQUALITY(ref.timings().tearingsReused, 0LL);
  const tfeti::GO refActive = ref.constraintReport().activeRows;
  TEST_COMPARE(refActive, >, 0);
  TEST_COMPARE(refActive, <, ref.constraintReport().inequalityRows);
  const auto uRef = solution(ref);
  for (int pass = 1; pass <= 2; ++pass) {
    s.setIncrementOrigin(origin);
    s.update(loads, moved);
    const tfeti::DualResult r = s.solve();
    const double diff = difference(solution(s), uRef);
    const tfeti::GO active = s.constraintReport().activeRows;
    out << "pass " << pass << ": " << r.qp.hessianMultiplications << " multiplications ("
        << rr.qp.hessianMultiplications << " for the reference), " << active << " active rows of "
        << ref.constraintReport().inequalityRows << ", solution difference " << diff << "\n";
    TEST_ASSERT(r.converged);
    TEST_EQUALITY(active, refActive);
    TEST_COMPARE(diff, <, 1e-8);
    TEST_EQUALITY(s.timings().tearings, 1LL);
    TEST_EQUALITY(s.timings().tearingsReused, static_cast<long long>(pass));
  }
  // Fewer rows: a new tearing, and again the solution of a solver built with them.
  const std::vector<tfeti::InequalityRow> fewer = floorRows(box, curved, 7.0, true);
  s.setIncrementOrigin(origin);
  s.update(loads, fewer);
  TEST_ASSERT(s.solve().converged);
  TEST_EQUALITY(s.timings().tearings, 2LL);
  TEST_EQUALITY(s.timings().tearingsReused, 2LL);
  tfeti::FetiSolver refFewer(comm, N, localBoxSubdomains(box, mat), params);
  refFewer.setIncrementOrigin(origin);
  refFewer.update(loads, fewer);
  TEST_ASSERT(refFewer.solve().converged);
  TEST_COMPARE(difference(solution(s), solution(refFewer)), <, 1e-8);
}

// "Keep subdomain matrices" = false frees every K once its preconditioner is set up: the same
// iterations and the same solution, bit for bit, as with K kept (nothing after the set-up reads
// K), for every preconditioner; K is then empty, and an update() that would set a preconditioner
// up again for new interface dofs is an error on every rank that names the parameter. The memory
// log has every phase, in order, with a peak that never falls.
TEUCHOS_UNIT_TEST(FetiSolver, FreeingTheSubdomainMatricesKeepsTheSolution) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti::StructuredRectangle rect = square();
  const Physics ph = tfeti_test::elasticity();
  for (const std::string prec : {"none", "lumped", "dirichlet"}) {
    Options o;
    o.preconditioner = prec;
    Teuchos::ParameterList keep = solverParameters(o), freed = solverParameters(o);
    freed.set("Keep subdomain matrices", false);
    tfeti::FetiSolver a(comm, rect.numSubdomains(), tfeti_test::localSubdomains(rect, *comm, ph),
                        keep);
    tfeti::FetiSolver b(comm, rect.numSubdomains(), tfeti_test::localSubdomains(rect, *comm, ph),
                        freed);
    const tfeti::DualResult ra = a.solve(), rb = b.solve();
    TEST_ASSERT(ra.converged && rb.converged);
    TEST_EQUALITY(ra.iterations, rb.iterations);
    double diff = 0.0, size = 0.0;
    for (std::size_t i = 0; i < a.data().size(); ++i) {
      TEST_ASSERT(a.subdomains()[i]->hasStiffness());
      TEST_ASSERT(!b.subdomains()[i]->hasStiffness());
      TEST_EQUALITY(b.subdomains()[i]->stiffness().rows, 0);
      for (std::size_t k = 0; k < a.solution(i).size(); ++k) {
        diff = std::max(diff, std::abs(a.solution(i)[k] - b.solution(i)[k]));
        size = std::max(size, std::abs(a.solution(i)[k]));
      }
    }
    out << prec << ": " << ra.iterations << " iterations both, max |u_keep - u_free| = " << diff
        << "\n";
    TEST_EQUALITY(tfeti_test::globalMax(*comm, diff), 0.0);
    TEST_COMPARE(tfeti_test::globalMax(*comm, size), >, 1e-3);

    const std::vector<std::string> phases = {
        "factorization", "tearing", "coarse", "preconditioner", "dual_rhs", "solve", "recovery"};
    const auto& log = b.memory().phases();
    TEST_EQUALITY(log.size(), phases.size());
    double peak = 0.0;
    for (std::size_t k = 0; k < log.size() && k < phases.size(); ++k) {
      TEST_EQUALITY(log[k].phase, phases[k]);
      TEST_COMPARE(log[k].maxOverRanks.rssMib, >, 0.0);
      TEST_COMPARE(log[k].maxOverRanks.peakMib, >=, log[k].maxOverRanks.rssMib);
      TEST_COMPARE(log[k].maxOverRanks.peakMib, >=, peak);
      TEST_COMPARE(log[k].sumOverRanks.peakMib, >=, log[k].maxOverRanks.peakMib);
      peak = log[k].maxOverRanks.peakMib;
    }

    if (prec == "none") continue;
    // A contact row on a dof of subdomain 5 (an inner subdomain) that no gluing row touches (its
    // centre node): the interface of subdomain 5 changes, so its preconditioner must be set up
    // again, which K kept allows and K freed does not.
    std::vector<tfeti::InequalityRow> rows;
    if (comm->getRank() == 0) rows.push_back({{{5, 2 * 12 + 1, 1.0}}, 1.0});
    std::vector<std::vector<double>> loads;
    for (const auto& s : a.subdomains()) loads.push_back(s->load());
    a.update(loads, rows);
    TEST_ASSERT(a.solve().converged);
    std::string message;
    try {
      b.update(loads, rows);
    } catch (const std::exception& e) {
      message = e.what();
    }
    out << "update with K freed: " << message << "\n";
    TEST_INEQUALITY(message.find("Keep subdomain matrices"), std::string::npos);
  }
}

// updateStiffness() with a new K on some subdomains only (a plastic zone: the others' tangent is
// the elastic one again) refactorizes those alone, sets up their Dirichlet preconditioners
// anew, and solves as a solver built from the new matrices does. A second call with the same
// matrices factorizes nothing. 3 x 3 x 3 Hex8 elasticity, every third subdomain twice as stiff.
TEUCHOS_UNIT_TEST(FetiSolver, UpdateStiffnessRefactorizesOnlyTheChangedSubdomains) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti_test::Box3d box(3, 3, 3, 2, 2, 2, false);
  const int N = box.numSubdomains();
  tfeti_test::Material3d soft, stiff;
  soft.dofsPerNode = stiff.dofsPerNode = 3;
  stiff.E = 2.0 * soft.E;
  const auto changes = [](int id) { return id % 3 == 0; };
  std::vector<tfeti::SubdomainData> mixed = localBoxSubdomains(box, soft);
  for (auto& d : mixed)
    if (changes(d.mesh.id)) {
      tfeti::CsrMatrix K;
      std::vector<double> f;
      tfeti_test::assemble3d(d.mesh.coords, d.mesh.elements, stiff, boxLoad(stiff, 1.0), K, f);
      d.K = std::move(K);
    }
  int changed = 0;
  for (int s = 0; s < N; ++s) changed += changes(s) ? 1 : 0;

  Options o;
  tfeti::FetiSolver updated(comm, N, localBoxSubdomains(box, soft), solverParameters(o));
  TEST_ASSERT(updated.solve().converged);
  const tfeti_test::StiffnessUpdate up = tfeti_test::stiffnessUpdate(mixed);
  const std::vector<tfeti::CsrMatrix>& K = up.K;
  const std::vector<std::vector<double>>& coords = up.coords;
  const std::vector<std::vector<double>>& loads = up.loads;
  updated.updateStiffness(K, coords, loads, {});
  TEST_EQUALITY(updated.timings().factorizations, static_cast<long long>(N + changed));
  TEST_EQUALITY(updated.timings().factorizationsReused, static_cast<long long>(N - changed));
  const tfeti::DualResult ru = updated.solve();

  tfeti::FetiSolver fresh(comm, N, mixed, solverParameters(o));
  const tfeti::DualResult rf = fresh.solve();
  TEST_ASSERT(ru.converged && rf.converged);
  TEST_EQUALITY(ru.iterations, rf.iterations);
  double diff = 0.0, size = 0.0;
  for (std::size_t i = 0; i < mixed.size(); ++i)
    for (std::size_t k = 0; k < fresh.solution(i).size(); ++k) {
      diff = std::max(diff, std::abs(updated.solution(i)[k] - fresh.solution(i)[k]));
      size = std::max(size, std::abs(fresh.solution(i)[k]));
    }
  diff = tfeti_test::globalMax(*comm, diff) / tfeti_test::globalMax(*comm, size);
  out << changed << " of " << N << " subdomains changed: " << ru.iterations << " / "
      << rf.iterations << " iterations, relative solution difference " << diff << "\n";
  TEST_COMPARE(diff, <, 1e-9);

  updated.updateStiffness(K, coords, loads, {});
  TEST_EQUALITY(updated.timings().factorizations, static_cast<long long>(N + changed));
  TEST_EQUALITY(updated.timings().factorizationsReused, static_cast<long long>(2 * N - changed));
  TEST_ASSERT(updated.solve().converged);

  // An empty K keeps the subdomain's own (the caller knows it unchanged): back to the soft
  // material where it changed, nothing given elsewhere, and again the fresh solver's solution.
  std::vector<tfeti::CsrMatrix> back;
  const std::vector<tfeti::SubdomainData> softData = localBoxSubdomains(box, soft);
  for (const auto& d : softData) back.push_back(changes(d.mesh.id) ? d.K : tfeti::CsrMatrix{});
  updated.updateStiffness(back, coords, loads, {});
  TEST_EQUALITY(updated.timings().factorizations, static_cast<long long>(N + 2 * changed));
  TEST_EQUALITY(updated.timings().factorizationsReused,
                static_cast<long long>(3 * N - 2 * changed));
  const tfeti::DualResult rb = updated.solve();
  std::vector<tfeti::SubdomainData> softAgain = localBoxSubdomains(box, soft);
  for (std::size_t i = 0; i < softAgain.size(); ++i) softAgain[i].f = loads[i];
  tfeti::FetiSolver freshSoft(comm, N, softAgain, solverParameters(o));
  const tfeti::DualResult rs = freshSoft.solve();
  TEST_ASSERT(rb.converged && rs.converged);
  TEST_EQUALITY(rb.iterations, rs.iterations);
  double backDiff = 0.0;
  for (std::size_t i = 0; i < mixed.size(); ++i)
    for (std::size_t k = 0; k < freshSoft.solution(i).size(); ++k)
      backDiff = std::max(backDiff, std::abs(updated.solution(i)[k] - freshSoft.solution(i)[k]));
  TEST_COMPARE(tfeti_test::globalMax(*comm, backDiff), <,
               1e-9 * tfeti_test::globalMax(*comm, size));

  // An empty K cannot be kept where the solver rebuilds every subdomain (new kernel positions)
  // or has freed K ("Keep subdomain matrices" = false): clear errors, on every rank.
  std::vector<tfeti::CsrMatrix> none(mixed.size());
  std::vector<std::vector<double>> moved = coords;
  for (auto& c : moved)
    for (double& x : c) x += 0.5;
  const std::string rebuilt =
      tfeti_test::messageOf([&] { updated.updateStiffness(none, moved, loads, {}); });
  out << rebuilt << "\n";
  TEST_ASSERT(tfeti_test::contains(rebuilt, "an empty K keeps the current one") || mixed.empty());
  // Checked before anything changed: the solver goes on as before the call.
  updated.updateStiffness(back, coords, loads, {});
  const tfeti::DualResult after = updated.solve();
  TEST_ASSERT(after.converged);
  TEST_EQUALITY(after.iterations, rs.iterations);
  Teuchos::ParameterList freedParams = solverParameters(o);
  freedParams.set("Keep subdomain matrices", false);
  tfeti::FetiSolver freed(comm, N, localBoxSubdomains(box, soft), freedParams);
  const std::string released =
      tfeti_test::messageOf([&] { freed.updateStiffness(none, coords, loads, {}); });
  out << released << "\n";
  TEST_ASSERT(tfeti_test::contains(released, "Keep subdomain matrices") || mixed.empty());
}

// The preconditioners take a block of columns at once (one interior solve per subdomain with
// every column as a right-hand side: SMALBE's stiff circles ask for hundreds of columns M e_j);
// each column must be what a one-column application gives.
TEUCHOS_UNIT_TEST(FetiSolver, PreconditionerAppliesABlockOfColumnsAsOneByOne) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti::StructuredRectangle rect = square();
  for (const std::string prec : {"lumped", "dirichlet"}) {
    Options o;
    o.preconditioner = prec;
    tfeti::FetiSolver solver(comm, rect.numSubdomains(),
                             tfeti_test::localSubdomains(rect, *comm, tfeti_test::elasticity()),
                             solverParameters(o));
    const tfeti::DualPreconditioner M(solver.tearing(), solver.subdomains());
    const auto& map = solver.tearing().multiplierMap;
    tfeti::MultiVector X(map, 5), Y(map, 5);
    X.randomize();
    M.apply(X, Y);
    double worst = 0.0;
    for (std::size_t j = 0; j < X.getNumVectors(); ++j) {
      tfeti::Vector y(map);
      M.apply(*X.getVector(j), y);
      y.update(-1.0, *Y.getVector(j), 1.0);
      worst = std::max(worst, y.norm2() / Y.getVector(j)->norm2());
    }
    out << prec << ": max ||M x_j - (M X)_j|| / ||(M X)_j|| = " << worst << "\n";
    TEST_COMPARE(worst, <, 1e-14);
  }
}
