// Prescribed displacements on the structured box, on 1, 2 and 3 ranks: patch tests in 2D and 3D
// (symmetry conditions on the faces x0, y0 (, z0) and u_x = delta on x1, no load: a uniform
// uniaxial stress field), whose displacements are exact at every node copy to the solver's
// tolerance and whose reaction is E' A delta / L (E' = E / (1 - nu^2) in plane strain, E in 3D);
// Poisson with u = 1 on x1 and u = 0 on x0 (u = x / L); the direct solve with the values lifted;
// the rows of a load factor and a current displacement; conflicting and invalid conditions.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "contact_PrescribedDisplacement.hpp"
#include "contact_StructuredProblem.hpp"
#include "tfeti_FetiSolver.hpp"

namespace {

using contact::StructuredProblem;

const double kDelta = 1e-3, kE = 2e11, kNu = 0.3;

StructuredProblem patch(int dim) {
  StructuredProblem p;
  p.field = "elasticity";
  p.lo.assign(dim, 0.0);
  p.hi = dim == 2 ? std::vector<double>{2.0, 1.0} : std::vector<double>{2.0, 1.0, 0.5};
  p.subdomains = dim == 2 ? std::vector<int>{3, 2} : std::vector<int>{3, 2, 2};
  p.elements = dim == 2 ? std::vector<int>{3, 4} : std::vector<int>{2, 3, 2};
  p.law = plasticity::ElasticLaw(kE, kNu);
  p.bodyForce.assign(dim, 0.0);
  p.fixed.clear();
  const char* faces[3] = {"x0", "y0", "z0"};
  for (int c = 0; c < dim; ++c) p.symmetry.push_back({faces[c], c});
  p.prescribed = {{"x1", 0, kDelta, {}}};
  return p;
}

Teuchos::ParameterList parameters(const std::string& dual = "PCPG") {
  Teuchos::ParameterList feti;
  feti.set("Dual solver", dual);
  feti.sublist("PCPG").set("Relative tolerance", 1e-12);
  feti.sublist("SMALBE").set("Relative tolerance", 1e-10);
  feti.sublist("SMALBE").set("Equality tolerance", 1e-10);
  return feti;
}

double globalMax(const tfeti::Comm& comm, double v) {
  double g = v;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &v, &g);
  return g;
}

void patchTest(int dim, const std::string& dual, Teuchos::FancyOStream& out, bool& success) {
  auto comm = Tpetra::getDefaultComm();
  const StructuredProblem p = patch(dim);
  auto local = contact::buildLocalSubdomains(p, *comm);
  const auto rows = contact::prescribedDisplacementRows(local, p.prescribedValues(), 1.0);
  tfeti::FetiSolver solver(comm, p.numSubdomains(), std::move(local), parameters(dual), {}, rows);
  const tfeti::DualResult r = solver.solve();
  // Uniaxial stress: strain delta / L along x; the lateral strains of plane strain (sigma_yy = 0,
  // eps_zz = 0) or of 3D (sigma_yy = sigma_zz = 0).
  const double L = p.hi[0] - p.lo[0], eps = kDelta / L;
  const double lateral = dim == 2 ? -kNu / (1.0 - kNu) * eps : -kNu * eps;
  double err = 0.0;
  for (std::size_t i = 0; i < solver.data().size(); ++i) {
    const auto& mesh = solver.data()[i].mesh;
    for (int n = 0; n < mesh.numNodes(); ++n)
      for (int c = 0; c < dim; ++c) {
        const double exact = (c == 0 ? eps : lateral) * mesh.coords[dim * n + c];
        err = std::max(err, std::abs(solver.solution(i)[dim * n + c] - exact));
      }
  }
  err = globalMax(*comm, err) / kDelta;
  double area = 1.0;
  for (int c = 1; c < dim; ++c) area *= p.hi[c] - p.lo[c];
  const double modulus = dim == 2 ? kE / (1.0 - kNu * kNu) : kE;
  const double expected = modulus * area * eps;
  const std::vector<double> reaction = contact::prescribedReactions(
      solver, p.prescribed, [&](const std::string& f) { return p.faceNodes(f); });
  const double direct = contact::relativeErrorAgainstDirectSolve(p, solver);
  out << dim << "D patch test, " << dual << ": " << (r.converged ? "converged" : "NOT converged")
      << ", " << solver.userEqualityRows() << " prescribed rows, max |u - u_exact| / delta " << err
      << ", reaction " << reaction[0] << " (E' A eps = " << expected
      << "), against the direct solve " << direct << ", max |B_E u - c_E| "
      << solver.constraintReport().equalityResidual << "\n";
  TEST_ASSERT(r.converged);
  TEST_COMPARE(err, <, 1e-8);
  TEST_COMPARE(std::abs(reaction[0] - expected) / expected, <, 1e-8);
  TEST_COMPARE(direct, <, 1e-8);
  TEST_COMPARE(solver.constraintReport().equalityResidual, <, 1e-10 * kDelta);
  // One row per subdomain copy of every node of x1: (elements + 1) nodes per other axis, and the
  // subdomain interfaces' nodes once more per extra copy.
  long long copies = 1;
  for (int c = 1; c < dim; ++c) copies *= p.subdomains[c] * (p.elements[c] + 1);
  TEST_EQUALITY(static_cast<long long>(solver.userEqualityRows()), copies);

  // The rows of load factor t from the solved u: c_E(t) - B_E u = (t - 1) delta on every row.
  std::vector<std::vector<double>> current;
  for (std::size_t i = 0; i < solver.data().size(); ++i) current.push_back(solver.solution(i));
  double rowErr = 0.0;
  for (const auto& row :
       contact::prescribedDisplacementRows(solver.data(), p.prescribedValues(), 0.25, current))
    rowErr = std::max(rowErr, std::abs(row.rhs - (0.25 - 1.0) * kDelta));
  TEST_COMPARE(globalMax(*comm, rowErr), <, 1e-10 * kDelta);
}

TEUCHOS_UNIT_TEST(PrescribedDisplacement, PatchTest2D) {
  patchTest(2, "PCPG", out, success);
  patchTest(2, "SMALBE", out, success);
}

TEUCHOS_UNIT_TEST(PrescribedDisplacement, PatchTest3D) {
  patchTest(3, "PCPG", out, success);
}

TEUCHOS_UNIT_TEST(PrescribedDisplacement, PoissonLinearSolution) {
  auto comm = Tpetra::getDefaultComm();
  StructuredProblem p;
  p.lo = {0.0, 0.0};
  p.hi = {2.0, 1.0};
  p.subdomains = {3, 2};
  p.elements = {3, 3};
  p.source = 0.0;
  p.prescribed = {{"x1", 0, 1.0, {}}};  // with u = 0 on x0 (the default Fixed boundaries)
  auto local = contact::buildLocalSubdomains(p, *comm);
  const auto rows = contact::prescribedDisplacementRows(local, p.prescribedValues(), 1.0);
  tfeti::FetiSolver solver(comm, p.numSubdomains(), std::move(local), parameters(), {}, rows);
  TEST_ASSERT(solver.solve().converged);
  double err = 0.0;
  for (std::size_t i = 0; i < solver.data().size(); ++i) {
    const auto& mesh = solver.data()[i].mesh;
    for (int n = 0; n < mesh.numNodes(); ++n)
      err = std::max(err, std::abs(solver.solution(i)[n] - mesh.coords[2 * n] / 2.0));
  }
  err = globalMax(*comm, err);
  out << "Poisson u = x / 2: max error " << err << "\n";
  TEST_COMPARE(err, <, 1e-9);
}

TEUCHOS_UNIT_TEST(PrescribedDisplacement, ConflictingAndInvalidConditions) {
  auto message = [](const StructuredProblem& p) {
    try {
      p.prescribedValues();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  StructuredProblem p = patch(2);
  p.symmetry = {{"y0", 1}};
  p.prescribed.push_back({"y1", 0, 2 * kDelta, {}});  // meets x1 at the corner (2, 1)
  const std::string twoValues = message(p);
  p = patch(2);
  p.prescribed = {{"x0", 0, kDelta, {}}};  // x0 is a symmetry face for u_x
  const std::string onSymmetry = message(p);
  p = patch(2);
  // Another component, zero, on x1: allowed (at the corner with y0 the symmetry holds it).
  p.prescribed.push_back({"x1", 1, 0.0, {}});
  const std::string otherComponent = message(p);
  p = patch(2);
  p.prescribed = {{"x0", 1, kDelta, {}}};  // u_y = delta meets u_y = 0 of y0 at the origin
  const std::string corner = message(p);
  p = patch(2);
  p.prescribed = {{"x1", 2, kDelta, {}}};
  const std::string component = message(p);
  p = patch(2);
  p.prescribed = {{"z1", 0, kDelta, {}}};
  const std::string face = message(p);
  for (const auto& m : {twoValues, onSymmetry, corner, component, face}) out << m << "\n";
  TEST_ASSERT(twoValues.find("different values of the same component") != std::string::npos);
  TEST_ASSERT(onSymmetry.find("symmetry boundary \"x0\"") != std::string::npos);
  TEST_EQUALITY(otherComponent, "");
  TEST_ASSERT(corner.find("symmetry boundary \"y0\"") != std::string::npos);
  TEST_ASSERT(component.find("2 for boundary \"x1\" is not 0 (x) or 1 (y)") != std::string::npos);
  TEST_ASSERT(face.find("\"z1\" is not a face of the 2D box") != std::string::npos);
}

}  // namespace
