// The two-membrane contact problem solved twice: by TFETI (FetiSolver, the dual contact QP by
// SMALBE or by the penalty method) and, redundantly on every rank, by a primal-dual active set
// method on the undecomposed primal problem. The two share nothing but the Q1 assembly and the
// CHOLMOD factorization, so their agreement on the nodal values, the contact multipliers, the
// active set and the total force checks the tearing, the contact rows, the dual QP and the primal
// recovery together, as a discretization-exact test (both solve the same discrete problem).
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact_TestUtils.hpp"
#include "contact_TwoMembranes.hpp"
#include "plasticity_Q1Assembly.hpp"
#include "tfeti_CsrMatrix.hpp"
#include "tfeti_FetiSolver.hpp"
#include "tfeti_Gather.hpp"
#include "tfeti_LocalSolver.hpp"
#include "tfeti_StructuredMesh.hpp"

namespace {

// ---------------------------------------------------------------------------------------------
// Reference: the undecomposed problem by the primal-dual active set method (Hintermüller, Ito,
// Kunisch). For a trial active set the contact pairs in it are merged into one unknown (u1 = u2
// there), which keeps the system SPD and holds the otherwise floating membrane 2.

// Restated from the benchmark's definition instead of taken from contact_TwoMembranes.cpp, so
// that a wrong load there shows up as a disagreement rather than being shared by both solves.
double sourceAt(int membrane, double y) {
  if (membrane == 0) return y >= 0.75 ? -3.0 : 0.0;
  return y < 0.25 ? -1.0 : 0.0;
}

struct Membrane {
  tfeti::SubdomainMesh mesh;
  tfeti::CsrMatrix K;
  std::vector<double> f;
};

// Membrane `which` (0: (0,1)x(0,1), 1: (1,2)x(0,1)) as one untorn mesh of NX x NY elements.
Membrane assembleMembrane(int which, int NX, int NY) {
  const double x0 = which;
  tfeti::StructuredRectangle rect(x0, x0 + 1.0, 0.0, 1.0, 1, 1, NX, NY);
  // Membrane 1's Dirichlet side is found from the coordinates below, not from the mesh class.
  rect.setDirichletAtX0(false);
  Membrane m;
  m.mesh = rect.wholeMesh();
  plasticity::Q1Mesh q{m.mesh.coords, m.mesh.elements.nodes, 2};
  std::vector<double> source(m.mesh.numElements());
  for (int e = 0; e < m.mesh.numElements(); ++e) {
    double yc = 0.0;
    for (int a = 0; a < 4; ++a)
      yc += 0.25 * m.mesh.coords[2 * m.mesh.elements.nodes[4 * e + a] + 1];
    source[e] = sourceAt(which, yc);
  }
  plasticity::ElasticLaw unused;
  m.K = plasticity::assembleStiffness(q, plasticity::Field::Scalar, unused);
  m.f = plasticity::assembleBodyLoad(q, plasticity::Field::Scalar, source);
  return m;
}

struct Reference {
  int NY = 0;                  // contact pairs: heights j = 0 .. NY on x = 1
  std::vector<double> u;       // by untorn node id; membrane 2's ids follow membrane 1's
  std::vector<double> lambda;  // contact force per height (0 where inactive)
  std::vector<double> gap;     // u2 - u1 per height
  std::vector<char> active;
  int iterations = 0;        // solves until the active set repeated
  double equilibrium = 0.0;  // max |K u - f - contact force| over both membranes' free dofs
};

Reference solveReference(int NX, int NY) {
  const Membrane m[2] = {assembleMembrane(0, NX, NY), assembleMembrane(1, NX, NY)};
  const int n1 = m[0].mesh.numNodes(), n = n1 + m[1].mesh.numNodes();
  auto x = [&](int g) { return g < n1 ? m[0].mesh.coords[2 * g] : m[1].mesh.coords[2 * (g - n1)]; };
  auto y = [&](int g) {
    return g < n1 ? m[0].mesh.coords[2 * g + 1] : m[1].mesh.coords[2 * (g - n1) + 1];
  };
  // Contact pairs from the geometry: the nodes of both membranes on x = 1 at the same height.
  std::vector<int> pair1(NY + 1, -1), pair2(NY + 1, -1);
  std::vector<char> dirichlet(n, 0);
  for (int g = 0; g < n; ++g) {
    if (g < n1 && std::abs(x(g)) < 1e-12) dirichlet[g] = 1;
    if (std::abs(x(g) - 1.0) < 1e-12) (g < n1 ? pair1 : pair2)[std::lround(y(g) * NY)] = g;
  }
  for (int j = 0; j <= NY; ++j)
    if (pair1[j] < 0 || pair2[j] < 0)
      throw std::logic_error("reference: no contact pair at height " + std::to_string(j));

  Reference ref;
  ref.NY = NY;
  ref.lambda.assign(NY + 1, 0.0);
  ref.gap.assign(NY + 1, 0.0);
  // All pairs in contact first: membrane 2 has no other support.
  ref.active.assign(NY + 1, 1);
  // With an M-matrix stiffness (Q1 Laplacian on squares) the method is monotone and needs at
  // most one solve per pair plus the confirming one; more means something is wrong.
  const int maxIterations = NY + 2;
  auto cholmod = tfeti::createLocalSolver("cholmod");
  for (ref.iterations = 1;; ++ref.iterations) {
    if (ref.iterations > maxIterations)
      throw std::runtime_error("reference: the active set did not settle in " +
                               std::to_string(maxIterations) + " solves");
    // Unknown of each node: none at Dirichlet nodes, membrane 1's at active membrane-2 nodes.
    std::vector<int> unknown(n, -1);
    std::vector<int> mergedInto(n, -1);
    for (int j = 0; j <= NY; ++j)
      if (ref.active[j]) mergedInto[pair2[j]] = pair1[j];
    int numUnknowns = 0;
    for (int g = 0; g < n; ++g)
      if (!dirichlet[g] && mergedInto[g] < 0) unknown[g] = numUnknowns++;
    for (int g = 0; g < n; ++g)
      if (mergedInto[g] >= 0) unknown[g] = unknown[mergedInto[g]];

    std::vector<int> ri, ci;
    std::vector<double> v, rhs(numUnknowns, 0.0);
    for (int w = 0; w < 2; ++w) {
      const tfeti::CsrMatrix& K = m[w].K;
      for (int i = 0; i < K.rows; ++i) {
        const int r = unknown[w * n1 + i];
        if (r < 0) continue;
        rhs[r] += m[w].f[i];
        for (int k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k) {
          const int c = unknown[w * n1 + K.colInd[k]];
          if (c < 0) continue;
          ri.push_back(r);
          ci.push_back(c);
          v.push_back(K.values[k]);
        }
      }
    }
    cholmod->factorize(tfeti::csrFromTriplets(numUnknowns, numUnknowns, ri, ci, v));
    std::vector<double> sol(numUnknowns);
    cholmod->solve(rhs.data(), sol.data());
    ref.u.assign(n, 0.0);
    for (int g = 0; g < n; ++g)
      if (unknown[g] >= 0) ref.u[g] = sol[unknown[g]];

    // r_w = K_w u_w - f_w: the force the contact (and, on membrane 1, the support) exerts.
    std::vector<double> r[2];
    for (int w = 0; w < 2; ++w) {
      r[w].resize(m[w].K.rows);
      m[w].K.multiply(ref.u.data() + w * n1, r[w].data());
      for (std::size_t i = 0; i < r[w].size(); ++i) r[w][i] -= m[w].f[i];
    }
    std::vector<char> next(NY + 1, 0);
    bool any = false;
    for (int j = 0; j <= NY; ++j) {
      ref.lambda[j] = ref.active[j] ? r[1][pair2[j] - n1] : 0.0;
      ref.gap[j] = ref.u[pair2[j]] - ref.u[pair1[j]];  // exactly 0 on merged pairs
      // HIK with c = 1: active where lambda + c (u1 - u2) > 0.
      next[j] = ref.lambda[j] - ref.gap[j] > 0.0;
      any = any || next[j];
    }
    if (next == ref.active) {
      // The converged set's KKT residual: membrane 1 feels -lambda, membrane 2 +lambda.
      std::vector<double> contact(n, 0.0);
      for (int j = 0; j <= NY; ++j) {
        contact[pair1[j]] = -ref.lambda[j];
        contact[pair2[j]] = ref.lambda[j];
      }
      ref.equilibrium = 0.0;
      for (int g = 0; g < n; ++g)
        if (!dirichlet[g])
          ref.equilibrium =
              std::max(ref.equilibrium, std::abs((g < n1 ? r[0][g] : r[1][g - n1]) - contact[g]));
      return ref;
    }
    if (!any)
      throw std::runtime_error("reference: the active set became empty (membrane 2 would float)");
    ref.active = next;
  }
}

double maxAbs(const std::vector<double>& v) {
  double m = 0.0;
  for (double a : v) m = std::max(m, std::abs(a));
  return m;
}

// ---------------------------------------------------------------------------------------------
// FETI against the reference.

// The contact rows are exact for the discrete problem (no gap, matching nodes), so both solves
// must agree up to the dual solvers' errors, not a discretization error.
const double kSolutionTolerance = 1e-6;    // max |u_FETI - u_ref| / max |u_ref|
const double kMultiplierTolerance = 1e-6;  // max |lambda_FETI - lambda_ref| / max lambda_ref

struct Method {
  Teuchos::ParameterList params;
  double forceTolerance;  // |sum lambda - 0.25|
};

Method smalbe() {
  Method m;
  m.params.set("Dual solver", std::string("SMALBE"));
  auto& s = m.params.sublist("SMALBE");
  s.set("Relative tolerance", 1e-9);
  s.set("Equality tolerance", 1e-9);
  m.forceTolerance = 1e-8;
  return m;
}

Method penalty() {
  Method m;
  m.params.set("Dual solver", std::string("penalty"));
  m.params.sublist("Penalty").set("Penalty", 1e6);
  m.params.sublist("MPRGP").set("Relative tolerance", 1e-9);
  // The penalty method meets G lambda = e, Ω2's force balance, only to O(1/rho), whatever the
  // MPRGP tolerance: the force error was 7.6e-9 (2x2) and 9.8e-9 (3x3) at 1e6 and ten times
  // smaller at 1e7, so 1e-8 would be no margin at all.
  m.forceTolerance = 1e-7;
  return m;
}

struct Comparison {
  bool converged = false;
  double solutionError = 0.0;    // max over all node copies, relative to max |u_ref|
  double multiplierError = 0.0;  // max over contact rows, relative to max lambda_ref
  int rowsFound = 0;             // contact rows reported, each height once
  int activeMismatches = 0;      // heights where FETI and the reference disagree on contact
  long long activeRows = 0;      // FetiSolver's own count (lambda > 0)
  double force = 0.0;            // FetiSolver's sum of contact multipliers
};

Comparison solveAndCompare(const contact::TwoMembranes& tm, const Teuchos::ParameterList& params,
                           const Reference& ref) {
  auto comm = Tpetra::getDefaultComm();
  contact::ContactProblemData data = contact::buildTwoMembranes(tm, *comm);
  tfeti::FetiSolver solver(comm, tm.numSubdomains(), std::move(data.local), params,
                           data.inequalities);
  const tfeti::DualResult result = solver.solve();
  Comparison c;
  c.converged = contact_test::convergedEverywhere(*comm, result.converged);

  c.solutionError = contact_test::tornSolutionError(*comm, solver, ref.u, 1);

  // Each contact row once, from membrane 1's side (coefficient +1), keyed by its height.
  const auto rows = solver.inequalityMultipliersOnSubdomains();
  std::vector<double> mine;
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (const auto& e : rows[i])
      if (e.coef > 0.0)
        mine.insert(mine.end(), {solver.data()[i].mesh.coords[2 * e.dof + 1], e.lambda});
  const std::vector<double> all = tfeti::allGather(*comm, mine);
  std::vector<int> seen(ref.NY + 1, 0);
  double lambdaErr = 0.0;
  for (std::size_t k = 0; k + 1 < all.size(); k += 2) {
    const long j = std::lround(all[k] * ref.NY);
    const double lambda = all[k + 1];
    ++seen.at(j);
    lambdaErr = std::max(lambdaErr, std::abs(lambda - ref.lambda[j]));
    if ((lambda > 0.0) != static_cast<bool>(ref.active[j])) ++c.activeMismatches;
  }
  c.rowsFound = static_cast<int>(std::count(seen.begin(), seen.end(), 1));
  c.multiplierError = lambdaErr / maxAbs(ref.lambda);

  const tfeti::ConstraintReport report = solver.constraintReport();
  c.activeRows = report.activeRows;
  c.force = report.force;
  return c;
}

contact::TwoMembranes membranes(int subdomains, int elements) {
  contact::TwoMembranes tm;
  tm.subdomainsX = tm.subdomainsY = subdomains;
  tm.elementsX = tm.elementsY = elements;
  return tm;
}

void checkAgainstReference(const contact::TwoMembranes& tm, const Method& method,
                           Teuchos::FancyOStream& out, bool& success) {
  const Teuchos::ParameterList& params = method.params;
  const Reference ref =
      solveReference(tm.subdomainsX * tm.elementsX, tm.subdomainsY * tm.elementsY);
  const Comparison c = solveAndCompare(tm, params, ref);
  const long long refActive = std::count(ref.active.begin(), ref.active.end(), 1);
  out << params.get<std::string>("Dual solver") << ", " << tm.subdomainsX << "x" << tm.subdomainsY
      << " subdomains of " << tm.elementsX << "x" << tm.elementsY
      << " elements per membrane: |u - u_ref|/|u_ref| = " << c.solutionError
      << ", |lambda - lambda_ref|/|lambda_ref| = " << c.multiplierError << ", active "
      << c.activeRows << " (reference " << refActive << "), force " << c.force << " (error "
      << std::abs(c.force - 0.25) << ")\n";
  TEST_ASSERT(c.converged);
  TEST_EQUALITY(c.rowsFound, ref.NY + 1);
  TEST_COMPARE(c.solutionError, <, kSolutionTolerance);
  TEST_COMPARE(c.multiplierError, <, kMultiplierTolerance);
  TEST_EQUALITY(c.activeMismatches, 0);
  TEST_EQUALITY(c.activeRows, refActive);
  TEST_COMPARE(std::abs(c.force - tm.expectedContactForce()), <, method.forceTolerance);
}

// ---------------------------------------------------------------------------------------------

// The reference must itself be a KKT point of the discrete contact problem, with a margin that
// makes "the same active set" a well-posed comparison.
TEUCHOS_UNIT_TEST(TwoMembranes, ReferenceIsKktPoint) {
  for (int N : {8, 12}) {
    const Reference ref = solveReference(N, N);
    double force = 0.0, minActive = 1e300, minInactiveGap = 1e300, maxActiveGap = 0.0;
    for (int j = 0; j <= N; ++j) {
      force += ref.lambda[j];
      if (ref.active[j]) {
        minActive = std::min(minActive, ref.lambda[j]);
        maxActiveGap = std::max(maxActiveGap, std::abs(ref.gap[j]));
      } else {
        minInactiveGap = std::min(minInactiveGap, ref.gap[j]);
        TEST_EQUALITY(ref.lambda[j], 0.0);
      }
    }
    out << N << "x" << N << " elements per membrane: " << ref.iterations
        << " active-set solves, active " << std::count(ref.active.begin(), ref.active.end(), 1)
        << " of " << N + 1 << ", min lambda on active " << minActive << ", min gap on inactive "
        << minInactiveGap << ", force " << force << ", equilibrium residual " << ref.equilibrium
        << "\n";
    // Not all nodes in contact and not none: otherwise the test would not exercise the set.
    TEST_COMPARE(minInactiveGap, <, 1e300);
    TEST_COMPARE(minActive, >, 1e-6 * force);
    TEST_COMPARE(minInactiveGap, >, 1e-6 * maxAbs(ref.u));
    TEST_EQUALITY(maxActiveGap, 0.0);
    TEST_COMPARE(ref.equilibrium, <, 1e-12);
    // Membrane 2 floats: the contact alone carries its load, 1 x 0.25.
    TEST_FLOATING_EQUALITY(force, 0.25, 1e-12);
  }
}

// 2x2 subdomains of 4x4 elements per membrane (h = 1/8).
TEUCHOS_UNIT_TEST(TwoMembranes, SmalbeMatchesReference) {
  checkAgainstReference(membranes(2, 4), smalbe(), out, success);
}

TEUCHOS_UNIT_TEST(TwoMembranes, PenaltyMatchesReference) {
  checkAgainstReference(membranes(2, 4), penalty(), out, success);
}

// 3x3 subdomains of 4x4 elements (h = 1/12): the subdomain boundaries (y = 1/3, 2/3) are not at
// the load's jumps (y = 0.25, 0.75), which cut through subdomains on element edges.
TEUCHOS_UNIT_TEST(TwoMembranes, SmalbeMatchesReferenceOffLoadJumps) {
  checkAgainstReference(membranes(3, 4), smalbe(), out, success);
}

TEUCHOS_UNIT_TEST(TwoMembranes, PenaltyMatchesReferenceOffLoadJumps) {
  checkAgainstReference(membranes(3, 4), penalty(), out, success);
}

}  // namespace
