// The elastic two-cylinder contact problem (examples/two_cylinders.geo, coarse) solved twice: by
// the unstructured pipeline (buildElasticContactProblem, TFETI, SMALBE) and, redundantly on every
// rank, by an exact active-set method on the undecomposed primal problem (a dense KKT solve per
// trial set, Hintermüller-Ito-Kunisch updates). The reference shares only the element kernels and
// the node-to-segment rows with the pipeline: no partition, tearing, coarse space, dual QP or
// primal recovery. Both solve the same discrete problem, so they must agree to the dual solver's
// accuracy, which checks everything between the Gmsh mesh and the recovered displacement.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact_ElasticContactProblem.hpp"
#include "contact_GmshMesh.hpp"
#include "contact_NodeToSegment.hpp"
#include "contact_TestUtils.hpp"
#include "plasticity_ElasticLaw.hpp"
#include "plasticity_Elements.hpp"
#include "tfeti_CsrMatrix.hpp"
#include "tfeti_FetiSolver.hpp"

namespace {

const std::string kGeometry = CONTACT_TEST_EXAMPLES_DIR "/two_cylinders.geo";

// The data of examples/two_cylinders_elastic.xml, restated here so that the reference does not
// read them through the pipeline's spec.
const double kYoung = 2.0e11, kPoisson = 0.3;
const double kLoadTraction = -2.0e7;  // y, force per unit length on "load" (l/2 on the half model)
const double kSearchRadius = 0.1;

struct Case {
  int order;
  double sizeFactor;
  int subdomainsPerBody;
};

contact::ElasticContactSpec specOf(const Case& c) {
  contact::ElasticContactSpec spec;
  spec.meshFile = kGeometry;
  spec.meshOptions.order = c.order;
  spec.meshOptions.sizeFactor = c.sizeFactor;
  const plasticity::ElasticLaw law(kYoung, kPoisson);
  spec.bodies = {{"cylinder", c.subdomainsPerBody, law}, {"block", c.subdomainsPerBody, law}};
  spec.fixed = {"fixed"};
  spec.symmetry = {{"cylinder_symmetry", 0}, {"block_symmetry", 0}};
  spec.tractions = {{"load", {0.0, kLoadTraction}}};
  contact::ContactPairSpec pair;
  pair.where = "Contact problem";
  pair.slave = "cylinder_contact";
  pair.master = "block_contact";
  pair.searchRadius = kSearchRadius;
  spec.pairs = {pair};
  return spec;
}

// ---------------------------------------------------------------------------------------------
// Reference: the whole bodies, numbered like the GmshMesh (2 dofs per node, interleaved).

// The mesh's element type is plasticity's (one catalogue); the reference takes the 2D ones.
plasticity::ElementType elementTypeOf(contact::ElementType t) {
  if (plasticity::spatialDimension(t) != 2 || !plasticity::elementInfo(t).complete)
    throw std::logic_error("not a 2D body element type");
  return t;
}

struct Reference {
  int numFree = 0;             // unknowns after eliminating the Dirichlet and symmetry dofs
  std::vector<double> u;       // 2 per GmshMesh node
  std::vector<int> slaveNode;  // per contact row
  std::vector<double> lambda;  // per contact row (0 where inactive)
  std::vector<double> slack;   // per contact row: gap - B_i u (>= 0 when feasible)
  std::vector<char> active;
  int iterations = 0;        // KKT solves until the active set repeated
  double equilibrium = 0.0;  // max |K u - f + B^T lambda| over free dofs / max |f|
  double appliedForce[2] = {0.0, 0.0};
};

// Dense LU of the KKT system [K_ff B_Af^T; B_Af 0] [u_f; lambda_A] = [f_f; g_A]. Dense on
// purpose: at a few hundred unknowns it is cheap and needs neither a regularization of the
// floating cylinder nor any factorization code the pipeline uses.
void solveKkt(int n, std::vector<double>& M, std::vector<double>& rhs) {
  Teuchos::LAPACK<int, double> lapack;
  std::vector<int> pivots(n);
  int info = 0;
  lapack.GETRF(n, n, M.data(), n, pivots.data(), &info);
  if (info != 0)
    throw std::runtime_error("reference: the KKT matrix is singular (GETRF info " +
                             std::to_string(info) + "): the active set does not hold the cylinder");
  lapack.GETRS('N', n, 1, M.data(), n, pivots.data(), rhs.data(), n, &info);
  if (info != 0) throw std::runtime_error("reference: GETRS failed");
}

Reference solveReference(const contact::GmshMesh& mesh) {
  const int numNodes = mesh.numNodes(), N = 2 * numNodes;
  const plasticity::ElasticLaw law(kYoung, kPoisson);

  // Stiffness of both bodies on the global numbering: each body's element mesh carries all
  // nodes, those of the other body simply have no element.
  std::vector<int> ri, ci;
  std::vector<double> vals;
  auto bodyMesh = [&](const std::string& name) {
    const contact::GmshBody& b = mesh.body(name);
    return plasticity::ElementMesh{elementTypeOf(b.type), mesh.coords, b.connectivity};
  };
  for (const char* name : {"cylinder", "block"}) {
    const tfeti::CsrMatrix K = plasticity::assembleStiffness(bodyMesh(name), law);
    for (int i = 0; i < K.rows; ++i)
      for (int k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k) {
        ri.push_back(i);
        ci.push_back(K.colInd[k]);
        vals.push_back(K.values[k]);
      }
  }
  const tfeti::CsrMatrix K = tfeti::csrFromTriplets(N, N, ri, ci, vals);

  Reference ref;
  const double t[2] = {0.0, kLoadTraction};
  const std::vector<double> f =
      plasticity::assembleEdgeTraction(bodyMesh("cylinder"), mesh.boundary("load").edges, t);
  for (int i = 0; i < N; ++i) ref.appliedForce[i % 2] += f[i];

  std::vector<char> constrained(N, 0);
  for (int node : mesh.boundary("fixed").edges)
    constrained[2 * node] = constrained[2 * node + 1] = 1;
  for (const char* name : {"cylinder_symmetry", "block_symmetry"})
    for (int node : mesh.boundary(name).edges) constrained[2 * node] = 1;
  std::vector<int> freeIndex(N, -1), freeDofs;
  for (int i = 0; i < N; ++i)
    if (!constrained[i]) freeIndex[i] = static_cast<int>(freeDofs.size()), freeDofs.push_back(i);
  const int nf = ref.numFree = static_cast<int>(freeDofs.size());

  // The same linearized non-penetration rows as the pipeline: same pair, orientation by the
  // master body, search radius.
  const contact::GmshBoundary& slave = mesh.boundary("cylinder_contact");
  const std::set<int> slaveSet(slave.edges.begin(), slave.edges.end());
  const contact::GmshBoundary& master = mesh.boundary("block_contact");
  contact::MasterSurface ms;
  ms.nodesPerSegment = master.nodesPerEdge;
  ms.segments = master.edges;
  const contact::GmshBody& block = mesh.body("block");
  contact::orientSegmentsByElements(ms, mesh.coords, block.type, block.connectivity);
  contact::NodeToSegmentOptions options;
  options.searchRadius = kSearchRadius;
  const contact::NodeToSegmentResult rows = contact::computeNodeToSegment(
      mesh.coords, std::vector<int>(slaveSet.begin(), slaveSet.end()), ms, options);
  const int m = static_cast<int>(rows.rows.size());
  if (m == 0) throw std::logic_error("reference: no contact rows");
  // Row i restricted to the free dofs (constrained dofs are zero and drop out).
  std::vector<std::vector<std::pair<int, double>>> B(m);
  std::vector<double> gap(m);
  double minGap = 1e300;
  for (int i = 0; i < m; ++i) {
    const auto& row = rows.rows[i];
    ref.slaveNode.push_back(row.slaveNode);
    gap[i] = row.gap;
    minGap = std::min(minGap, row.gap);
    for (const auto& e : row.entries) {
      const int j = freeIndex[2 * e.node + e.component];
      if (j >= 0 && e.coef != 0.0) B[i].push_back({j, e.coef});
    }
  }

  // HIK's complementarity function max(0, lambda + c (B u - g)) mixes forces and lengths; c of
  // the stiffness's scale makes both terms comparable.
  double c = 0.0;
  for (int j : freeDofs) c = std::max(c, K.values[K.find(j, j)]);

  // Start from the initially closed rows: the cylinder touches the block at one point.
  ref.active.assign(m, 0);
  for (int i = 0; i < m; ++i) ref.active[i] = gap[i] <= minGap + 1e-12;
  // PDAS converges locally superlinearly; on this problem it needs a handful of sets. Far more
  // means it is cycling, which would make "the" active set meaningless.
  const int maxIterations = 25;
  ref.u.assign(N, 0.0);
  ref.lambda.assign(m, 0.0);
  ref.slack.assign(m, 0.0);
  for (ref.iterations = 1;; ++ref.iterations) {
    if (ref.iterations > maxIterations)
      throw std::runtime_error("reference: the active set did not settle in " +
                               std::to_string(maxIterations) + " solves");
    std::vector<int> act;
    for (int i = 0; i < m; ++i)
      if (ref.active[i]) act.push_back(i);
    const int n = nf + static_cast<int>(act.size());
    std::vector<double> M(static_cast<std::size_t>(n) * n, 0.0), rhs(n, 0.0);
    for (int a = 0; a < nf; ++a) {
      const int i = freeDofs[a];
      rhs[a] = f[i];
      for (int k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k) {
        const int b = freeIndex[K.colInd[k]];
        if (b >= 0) M[static_cast<std::size_t>(b) * n + a] += K.values[k];
      }
    }
    for (std::size_t r = 0; r < act.size(); ++r) {
      const int row = nf + static_cast<int>(r);
      for (const auto& [j, coef] : B[act[r]]) {
        M[static_cast<std::size_t>(j) * n + row] = coef;  // B_A
        M[static_cast<std::size_t>(row) * n + j] = coef;  // B_A^T
      }
      rhs[row] = gap[act[r]];
    }
    solveKkt(n, M, rhs);
    std::fill(ref.u.begin(), ref.u.end(), 0.0);
    for (int a = 0; a < nf; ++a) ref.u[freeDofs[a]] = rhs[a];
    std::fill(ref.lambda.begin(), ref.lambda.end(), 0.0);
    for (std::size_t r = 0; r < act.size(); ++r) ref.lambda[act[r]] = rhs[nf + r];

    std::vector<char> next(m, 0);
    for (int i = 0; i < m; ++i) {
      double Bu = 0.0;
      for (const auto& [j, coef] : B[i]) Bu += coef * rhs[j];
      ref.slack[i] = gap[i] - Bu;
      next[i] = ref.lambda[i] - c * ref.slack[i] > 0.0;
    }
    if (next == ref.active) break;
    ref.active = next;
  }

  // Stationarity of the Lagrangian 1/2 u^T K u - f^T u + lambda^T (B u - g) on the free dofs.
  std::vector<double> r(N);
  K.multiply(ref.u.data(), r.data());
  for (int i = 0; i < m; ++i)
    for (const auto& [j, coef] : B[i]) r[freeDofs[j]] += coef * ref.lambda[i];
  double fMax = 0.0;
  for (int i = 0; i < N; ++i) fMax = std::max(fMax, std::abs(f[i]));
  for (int j : freeDofs) ref.equilibrium = std::max(ref.equilibrium, std::abs(r[j] - f[j]));
  ref.equilibrium /= fMax;
  return ref;
}

double maxAbs(const std::vector<double>& v) {
  double m = 0.0;
  for (double a : v) m = std::max(m, std::abs(a));
  return m;
}

// ---------------------------------------------------------------------------------------------
// FETI against the reference.

// The rows are the same discrete constraints in both solves, so the difference is the dual
// solver's error only: with SMALBE's relative tolerance 1e-9 it should be far below this.
const double kSolutionTolerance = 1e-6;    // max |u_FETI - u_ref| / max |u_ref|
const double kMultiplierTolerance = 1e-5;  // max |lambda_FETI - lambda_ref| / max lambda_ref
const double kForceTolerance = 1e-6;       // |sum lambda - applied| / applied

struct Comparison {
  bool converged = false;
  double solutionError = 0.0;
  double multiplierError = 0.0;
  int rows = 0;               // FETI's contact rows
  int rowsMatched = 0;        // of them, those whose slave node has exactly one reference row
  int activeMismatches = 0;   // rows active in one solve only
  long long activeRows = 0;   // FetiSolver's count (lambda > 0)
  double force = 0.0;         // FetiSolver's sum of the contact multipliers
  double appliedForce = 0.0;  // the pipeline's resultant of the tractions (|.|)
  double maxPenetration = 0.0, minMultiplier = 0.0;
};

Comparison solveAndCompare(const Case& cs, Reference& ref, int& referenceUnknowns) {
  auto comm = Tpetra::getDefaultComm();
  contact::ElasticContactProblem problem = contact::buildElasticContactProblem(specOf(cs), *comm);
  // The reference on the pipeline's GmshMesh: the numbering to compare on. Gmsh meshes a .geo
  // deterministically, so this is also the mesh a separate loadMesh would give.
  ref = solveReference(problem.mesh);
  referenceUnknowns = ref.numFree;

  Teuchos::ParameterList params;
  params.set("Dual solver", std::string("SMALBE"));
  auto& smalbe = params.sublist("SMALBE");
  smalbe.set("Relative tolerance", 1e-9);
  smalbe.set("Equality tolerance", 1e-11);
  tfeti::FetiSolver solver(comm, problem.numSubdomains(), problem.local, params,
                           problem.inequalities);
  const tfeti::DualResult result = solver.solve();

  Comparison c;
  c.converged = contact_test::convergedEverywhere(*comm, result.converged);

  // Every copy of a torn node must carry the reference's displacement.
  c.solutionError = contact_test::tornSolutionError(*comm, solver, ref.u, 2);

  // FETI's rows are renumbered canonically: identify each by its slave node, the one node of
  // the row on the slave boundary (master nodes belong to the other body).
  const std::set<int> slaveSet(ref.slaveNode.begin(), ref.slaveNode.end());
  std::map<int, int> refRowOf;
  for (std::size_t i = 0; i < ref.slaveNode.size(); ++i) refRowOf[ref.slaveNode[i]] = i;
  const auto& rows = solver.tearing().inequalityRows;
  const std::vector<double> lambdas = solver.inequalityMultipliers();
  c.rows = static_cast<int>(rows.size());
  std::map<int, int> seen;
  double lambdaErr = 0.0;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    std::set<int> slaves;
    for (const auto& e : rows[r].entries) {
      const int g = static_cast<int>(problem.subdomains.at(e.subdomain).globalNode.at(e.dof / 2));
      if (slaveSet.count(g)) slaves.insert(g);
    }
    if (slaves.size() != 1) continue;
    const int i = refRowOf.at(*slaves.begin());
    ++seen[i];
    lambdaErr = std::max(lambdaErr, std::abs(lambdas[r] - ref.lambda[i]));
    if ((lambdas[r] > 0.0) != static_cast<bool>(ref.active[i])) ++c.activeMismatches;
  }
  for (const auto& [i, count] : seen) c.rowsMatched += count == 1;
  c.multiplierError = lambdaErr / maxAbs(ref.lambda);

  const tfeti::ConstraintReport report = solver.constraintReport();
  c.activeRows = report.activeRows;
  c.force = report.force;
  c.maxPenetration = report.maxPenetration;
  c.minMultiplier = report.minMultiplier;
  c.appliedForce = std::hypot(problem.appliedForce[0], problem.appliedForce[1]);
  return c;
}

void checkAgainstReference(const Case& cs, Teuchos::FancyOStream& out, bool& success) {
  Reference ref;
  int unknowns = 0;
  const Comparison c = solveAndCompare(cs, ref, unknowns);
  const long long refActive = std::count(ref.active.begin(), ref.active.end(), 1);
  const double applied = std::abs(ref.appliedForce[1]);
  out << "order " << cs.order << ", size factor " << cs.sizeFactor << ", " << cs.subdomainsPerBody
      << " + " << cs.subdomainsPerBody << " subdomains, " << unknowns
      << " reference unknowns: |u - u_ref|/|u_ref| = " << c.solutionError
      << ", |lambda - lambda_ref|/|lambda_ref| = " << c.multiplierError << ", active "
      << c.activeRows << " of " << c.rows << " (reference " << refActive << " of "
      << ref.lambda.size() << "), force " << c.force << " (applied " << c.appliedForce
      << ", relative error " << std::abs(c.force - applied) / applied << ")\n";
  TEST_ASSERT(c.converged);
  TEST_EQUALITY(c.rows, static_cast<int>(ref.lambda.size()));
  TEST_EQUALITY(c.rowsMatched, static_cast<int>(ref.lambda.size()));
  TEST_COMPARE(c.solutionError, <, kSolutionTolerance);
  TEST_COMPARE(c.multiplierError, <, kMultiplierTolerance);
  TEST_EQUALITY(c.activeMismatches, 0);
  TEST_EQUALITY(c.activeRows, refActive);
  // The pipeline's load must be the reference's (both from the same traction), and the contact
  // alone carries it: the cylinder has no other vertical support.
  TEST_COMPARE(std::abs(c.appliedForce - applied), <, 1e-12 * applied);
  TEST_COMPARE(std::abs(c.force - applied), <, kForceTolerance * applied);
}

// ---------------------------------------------------------------------------------------------

const Case kLinear{1, 2.0, 4};
const Case kQuadratic{2, 8.0, 3};

// The reference must be a KKT point of the discrete contact problem, with margins that make "the
// same active set" a well-posed comparison.
TEUCHOS_UNIT_TEST(ElasticContact, ReferenceIsKktPoint) {
  for (const Case& cs : {kLinear, kQuadratic}) {
    contact::MeshOptions options;
    options.order = cs.order;
    options.sizeFactor = cs.sizeFactor;
    const Reference ref = solveReference(contact::loadMesh(kGeometry, options));
    double force = 0.0, minActive = 1e300, minInactiveSlack = 1e300, maxActiveSlack = 0.0;
    for (std::size_t i = 0; i < ref.lambda.size(); ++i) {
      force += ref.lambda[i];
      if (ref.active[i]) {
        minActive = std::min(minActive, ref.lambda[i]);
        maxActiveSlack = std::max(maxActiveSlack, std::abs(ref.slack[i]));
      } else {
        minInactiveSlack = std::min(minInactiveSlack, ref.slack[i]);
        TEST_EQUALITY(ref.lambda[i], 0.0);
      }
    }
    const double applied = std::abs(ref.appliedForce[1]);
    const long long numActive = std::count(ref.active.begin(), ref.active.end(), 1);
    out << "order " << cs.order << ", size factor " << cs.sizeFactor << ": " << ref.numFree
        << " unknowns, " << ref.iterations << " KKT solves, active " << numActive << " of "
        << ref.lambda.size() << ", min lambda on active " << minActive << ", min slack on inactive "
        << minInactiveSlack << ", max |slack| on active " << maxActiveSlack << ", force " << force
        << " (applied " << applied << "), equilibrium residual " << ref.equilibrium << "\n";
    TEST_COMPARE(ref.numFree, <, 4000);
    // Some rows in contact and some not: otherwise the set would not be exercised.
    TEST_COMPARE(numActive, >, 1);
    TEST_COMPARE(numActive, <, static_cast<long long>(ref.lambda.size()));
    TEST_COMPARE(minActive, >, 1e-6 * applied);
    TEST_COMPARE(minInactiveSlack, >, 1e-6 * maxAbs(ref.u));
    TEST_COMPARE(maxActiveSlack, <, 1e-12 * maxAbs(ref.u));
    TEST_COMPARE(ref.equilibrium, <, 1e-9);
    // The flat master has normal (0, 1): the multipliers' sum is the vertical contact force.
    TEST_FLOATING_EQUALITY(force, applied, 1e-9);
    TEST_FLOATING_EQUALITY(applied, 2.0e7, 1e-12);  // l/2 on the unit-length top edge
  }
}

// Linear triangles, size factor 2: elements of 4 mm at the contact point, six rows in contact.
TEUCHOS_UNIT_TEST(ElasticContact, SmalbeMatchesReferenceLinear) {
  checkAgainstReference(kLinear, out, success);
}

// Quadratic triangles (curved slave edges, three-node master segments), size factor 8: cheap,
// and only three rows in contact, so the linear case carries the larger active set.
TEUCHOS_UNIT_TEST(ElasticContact, SmalbeMatchesReferenceQuadratic) {
  checkAgainstReference(kQuadratic, out, success);
}

// A nonlinear driver keeps K and changes loads and contact rows: update() (factorizations
// reused, warm start) and updateStiffness() (refactorized) must give what a new solver gives.
TEUCHOS_UNIT_TEST(ElasticContact, UpdateMatchesNewSolver) {
  auto comm = Tpetra::getDefaultComm();
  contact::ElasticContactProblem problem =
      contact::buildElasticContactProblem(specOf(kLinear), *comm);
  Teuchos::ParameterList params;
  params.set("Dual solver", std::string("SMALBE"));
  params.sublist("SMALBE").set("Relative tolerance", 1e-10);
  params.sublist("SMALBE").set("Equality tolerance", 1e-12);
  std::vector<std::vector<double>> half, stiffnessCoords;
  std::vector<tfeti::CsrMatrix> K;
  for (const auto& sd : problem.local) {
    half.push_back(sd.f);
    for (double& v : half.back()) v *= 0.5;
    K.push_back(sd.K);
    stiffnessCoords.push_back(sd.mesh.coords);
  }
  tfeti::FetiSolver reused(comm, problem.numSubdomains(), problem.local, params,
                           problem.inequalities);
  const auto full = reused.solve();
  TEST_ASSERT(contact_test::convergedEverywhere(*comm, full.converged));
  reused.update(half, problem.inequalities);
  const auto warm = reused.solve();
  TEST_ASSERT(contact_test::convergedEverywhere(*comm, warm.converged));

  auto data = problem.local;
  for (std::size_t i = 0; i < data.size(); ++i) data[i].f = half[i];
  tfeti::FetiSolver fresh(comm, problem.numSubdomains(), data, params, problem.inequalities);
  const auto cold = fresh.solve();
  TEST_ASSERT(contact_test::convergedEverywhere(*comm, cold.converged));
  double err = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < data.size(); ++i)
    for (std::size_t k = 0; k < fresh.solution(i).size(); ++k) {
      err = std::max(err, std::abs(reused.solution(i)[k] - fresh.solution(i)[k]));
      scale = std::max(scale, std::abs(fresh.solution(i)[k]));
    }
  double gErr = 0.0, gScale = 0.0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &err, &gErr);
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &scale, &gScale);
  out << "update: |u - u_fresh| / max|u| = " << gErr / gScale << ", Hessian multiplications "
      << warm.qp.hessianMultiplications << " (warm) vs " << cold.qp.hessianMultiplications
      << " (new solver)\n";
  TEST_COMPARE(gErr, <=, 1e-7 * gScale);

  reused.updateStiffness(K, stiffnessCoords, half, problem.inequalities);
  const auto refactorized = reused.solve();
  TEST_ASSERT(contact_test::convergedEverywhere(*comm, refactorized.converged));
  err = 0.0;
  for (std::size_t i = 0; i < data.size(); ++i)
    for (std::size_t k = 0; k < fresh.solution(i).size(); ++k)
      err = std::max(err, std::abs(reused.solution(i)[k] - fresh.solution(i)[k]));
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &err, &gErr);
  out << "updateStiffness: |u - u_fresh| / max|u| = " << gErr / gScale << "\n";
  TEST_COMPARE(gErr, <=, 1e-7 * gScale);

  // B^T lambda balances the load on every subdomain: K u = f - B^T lambda.
  const auto btl = reused.multiplierForces();
  double res = 0.0, fmax = 0.0;
  for (std::size_t i = 0; i < data.size(); ++i) {
    std::vector<double> Ku(K[i].rows, 0.0);
    K[i].multiply(reused.solution(i).data(), Ku.data());
    for (std::size_t k = 0; k < Ku.size(); ++k) {
      res = std::max(res, std::abs(Ku[k] - half[i][k] + btl[i][k]));
      fmax = std::max(fmax, std::abs(half[i][k]));
    }
  }
  double gRes = 0.0, gF = 0.0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &res, &gRes);
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &fmax, &gF);
  out << "max |K u - f + B^T lambda| / max|f| = " << gRes / gF << "\n";
  TEST_COMPARE(gRes, <=, 1e-6 * gF);
}

}  // namespace
