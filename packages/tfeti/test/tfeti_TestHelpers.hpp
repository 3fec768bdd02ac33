#pragma once
// Shared helpers of the tfeti unit tests: the benchmark problems (Poisson and plane-strain
// elasticity on a StructuredRectangle, assembled with the plasticity Q1 kernels), the direct
// reference solve of the undecomposed problem, and small dense utilities.
#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "plasticity_Q1Assembly.hpp"
#include "tfeti_CsrMatrix.hpp"
#include "tfeti_FetiSolver.hpp"
#include "tfeti_LocalSolver.hpp"
#include "tfeti_StructuredMesh.hpp"
#include "tfeti_SubdomainMesh.hpp"

namespace tfeti_test {

// A FETI list with this preconditioner and dual operator, and PCPG to 1e-12 (300 iterations at
// most, quiet): solves that two set-ups must reproduce to the last digits.
inline Teuchos::ParameterList tightFetiParameters(const std::string& preconditioner,
                                                  const std::string& dualOperator) {
  Teuchos::ParameterList params;
  params.set("Preconditioner", preconditioner);
  params.set("Dual operator", dualOperator);
  auto& pcpg = params.sublist("PCPG");
  pcpg.set("Relative tolerance", 1e-12);
  pcpg.set("Maximum iterations", 300);
  pcpg.set("Verbosity", 0);
  return params;
}

struct Physics {
  plasticity::Field field = plasticity::Field::Scalar;
  plasticity::ElasticLaw law;
  double source[2] = {1.0, 0.0};
  int dofsPerNode() const { return plasticity::dofsPerNode(field); }
  const char* name() const { return field == plasticity::Field::Scalar ? "Poisson" : "elasticity"; }
};

// -Laplace u = 1.
inline Physics poisson() {
  return Physics{};
}

// Plane strain, E = 1, nu = 0.3, body force (0, -1).
inline Physics elasticity() {
  Physics p;
  p.field = plasticity::Field::Elasticity;
  p.law = plasticity::ElasticLaw(1.0, 0.3);
  p.source[0] = 0.0;
  p.source[1] = -1.0;
  return p;
}

inline plasticity::Q1Mesh quadMesh(const tfeti::SubdomainMesh& m) {
  plasticity::Q1Mesh q;
  q.coords = m.coords;
  q.cells = m.elements.nodes;  // Q1: 4 (or 8) nodes per element
  return q;
}

inline tfeti::SubdomainData subdomainData(const tfeti::SubdomainMesh& mesh, const Physics& ph) {
  tfeti::SubdomainData d;
  d.mesh = mesh;
  d.dofsPerNode = ph.dofsPerNode();
  d.K = plasticity::assembleStiffness(quadMesh(mesh), ph.field, ph.law);
  d.f = plasticity::assembleBodyLoad(quadMesh(mesh), ph.field, ph.source);
  return d;
}

// The subdomains of this rank, in increasing id order.
// constrain (optional) replaces the subdomain's Dirichlet conditions (x = x0 clamped).
inline std::vector<tfeti::SubdomainData> localSubdomains(
    const tfeti::StructuredRectangle& rect, const tfeti::Comm& comm, const Physics& ph,
    void (*constrain)(tfeti::SubdomainMesh&) = nullptr) {
  std::vector<tfeti::SubdomainData> local;
  for (int s : tfeti::subdomainsOfRank(comm.getRank(), rect.numSubdomains(), comm.getSize())) {
    tfeti::SubdomainMesh mesh = rect.subdomain(s);
    if (constrain) constrain(mesh);
    local.push_back(subdomainData(mesh, ph));
  }
  return local;
}

inline std::vector<int> dirichletDofs(const tfeti::SubdomainMesh& mesh, int dpn) {
  return mesh.dirichletDofs(dpn);
}

inline std::vector<double> solveWithDirichlet(tfeti::CsrMatrix K, std::vector<double> f,
                                              const std::vector<int>& dirichlet);

// Direct solve of the undecomposed problem: the whole mesh assembled with the same kernels, the
// Dirichlet dofs (x = x0) replaced by identity rows and columns, factorized by CHOLMOD. Indexed
// by untorn dof (dofsPerNode * global node + component).
inline std::vector<double> referenceSolution(const tfeti::StructuredRectangle& rect,
                                             const Physics& ph,
                                             void (*constrain)(tfeti::SubdomainMesh&) = nullptr) {
  tfeti::SubdomainMesh whole = rect.wholeMesh();
  if (constrain) constrain(whole);
  const int dpn = ph.dofsPerNode();
  tfeti::CsrMatrix K = plasticity::assembleStiffness(quadMesh(whole), ph.field, ph.law);
  std::vector<double> f = plasticity::assembleBodyLoad(quadMesh(whole), ph.field, ph.source);
  return solveWithDirichlet(std::move(K), std::move(f), dirichletDofs(whole, dpn));
}

// K u = f with the given dofs held at zero (rows and columns replaced by identity), by CHOLMOD.
inline std::vector<double> solveWithDirichlet(tfeti::CsrMatrix K, std::vector<double> f,
                                              const std::vector<int>& dirichlet) {
  std::vector<char> fixed(K.rows, 0);
  for (int d : dirichlet) fixed[d] = 1;
  for (int i = 0; i < K.rows; ++i)
    for (int k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k) {
      const int j = K.colInd[k];
      if (fixed[i] || fixed[j]) K.values[k] = (i == j) ? 1.0 : 0.0;
    }
  for (int i = 0; i < K.rows; ++i)
    if (fixed[i]) f[i] = 0.0;
  auto solver = tfeti::createLocalSolver("cholmod");
  solver->factorize(K);
  std::vector<double> u(K.rows);
  solver->solve(f.data(), u.data());
  return u;
}

// Column-major dense copy.
inline std::vector<double> toDense(const tfeti::CsrMatrix& A) {
  std::vector<double> D(static_cast<std::size_t>(A.rows) * A.cols, 0.0);
  for (int i = 0; i < A.rows; ++i)
    for (int k = A.rowPtr[i]; k < A.rowPtr[i + 1]; ++k)
      D[static_cast<std::size_t>(A.colInd[k]) * A.rows + i] = A.values[k];
  return D;
}

inline double norm2(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

inline double maxAbs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

inline double globalMax(const tfeti::Comm& comm, double local) {
  double g = local;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &local, &g);
  return g;
}

inline double globalSum(const tfeti::Comm& comm, double local) {
  double g = local;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &local, &g);
  return g;
}

inline long long globalSum(const tfeti::Comm& comm, long long local) {
  long long g = local;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &local, &g);
  return g;
}

// The message of the exception f throws ("" if none).
inline std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

inline bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// The arguments of FetiSolver::updateStiffness from every local subdomain in data: its K,
// coordinates and load.
struct StiffnessUpdate {
  std::vector<tfeti::CsrMatrix> K;
  std::vector<std::vector<double>> coords, loads;
};
inline StiffnessUpdate stiffnessUpdate(const std::vector<tfeti::SubdomainData>& data) {
  StiffnessUpdate u;
  for (const auto& d : data) {
    u.K.push_back(d.K);
    u.coords.push_back(d.mesh.coords);
    u.loads.push_back(d.f);
  }
  return u;
}

}  // namespace tfeti_test
