#include "contact_StructuredProblem.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "plasticity_Q1Assembly.hpp"
#include "tfeti_LocalSolver.hpp"

namespace contact {

namespace {
tfeti::SubdomainData assemble(const StructuredProblem& p, tfeti::SubdomainMesh mesh,
                              std::vector<int> cells) {
  tfeti::SubdomainData sd;
  const plasticity::Q1Mesh q{mesh.coords, std::move(cells), p.dim()};
  const double* src = p.field == "poisson" ? &p.source : p.bodyForce.data();
  sd.K = plasticity::assembleStiffness(q, p.q1Field(), p.law);
  sd.f = plasticity::assembleBodyLoad(q, p.q1Field(), src);
  sd.dofsPerNode = p.dofsPerNode();
  sd.mesh = std::move(mesh);
  return sd;
}
}  // namespace

std::vector<tfeti::SubdomainData> buildLocalSubdomains(const StructuredProblem& problem,
                                                       const tfeti::Comm& comm) {
  const auto mesh = problem.mesh();
  std::vector<tfeti::SubdomainData> local;
  const std::vector<int> cells = mesh.subdomainCells();
  const std::vector<int> mine =
      tfeti::subdomainsOfRank(comm.getRank(), mesh.numSubdomains(), comm.getSize());
  // Reserved: a growing vector would copy every subdomain assembled so far (SubdomainData's move
  // may throw, so std::vector copies), doubling the memory of the matrices for a moment.
  local.reserve(mine.size());
  for (int s : mine) {
    tfeti::SubdomainMesh m = mesh.subdomain(s);
    problem.applyFaceConditions(m);
    local.push_back(assemble(problem, std::move(m), cells));
  }
  return local;
}

namespace {
// Grid indices of an untorn node (x fastest, then y, then z).
std::array<long long, 3> gridIndex(const tfeti::StructuredMesh& mesh, long long g) {
  std::array<long long, 3> ijk{0, 0, 0};
  for (int a = 0; a < mesh.dim(); ++a) {
    const long long n = mesh.elementsAlong(a) + 1;
    ijk[a] = g % n;
    g /= n;
  }
  return ijk;
}

// (axis, side) of a face name: "x0" -> (0, 0), "z1" -> (2, 1); (-1, -1) if not a face.
std::pair<int, int> faceOf(const std::string& name, int dim) {
  if (name.size() != 2 || (name[1] != '0' && name[1] != '1')) return {-1, -1};
  const int axis = name[0] == 'x' ? 0 : name[0] == 'y' ? 1 : name[0] == 'z' ? 2 : -1;
  if (axis < 0 || axis >= dim) return {-1, -1};
  return {axis, name[1] - '0'};
}

std::pair<int, int> requireFace(const std::string& name, int dim) {
  const auto f = faceOf(name, dim);
  if (f.first < 0)
    throw std::invalid_argument("boundary \"" + name + "\" is not a face of the " +
                                std::to_string(dim) + "D box; valid: x0, x1, y0, y1" +
                                (dim == 3 ? ", z0, z1" : "") + " (the face x = x0, ...)");
  return f;
}

bool onFace(const tfeti::StructuredMesh& mesh, long long g, std::pair<int, int> face) {
  const long long i = gridIndex(mesh, g)[face.first];
  return i == (face.second == 0 ? 0 : mesh.elementsAlong(face.first));
}
}  // namespace

std::vector<long long> StructuredProblem::faceNodes(const std::string& face) const {
  const auto f = requireFace(face, dim());
  const tfeti::StructuredMesh m = mesh();
  // Every node of the face: the grid indices of the other axes run over their ranges.
  std::vector<long long> nodes;
  const int d = dim();
  std::array<long long, 3> n{1, 1, 1};
  for (int a = 0; a < d; ++a) n[a] = m.elementsAlong(a) + 1;
  std::array<long long, 3> ijk{0, 0, 0};
  ijk[f.first] = f.second == 0 ? 0 : n[f.first] - 1;
  const int u = (f.first + 1) % d, v = d == 3 ? (f.first + 2) % 3 : -1;
  for (long long a = 0; a < n[u]; ++a)
    for (long long b = 0; b < (v >= 0 ? n[v] : 1); ++b) {
      ijk[u] = a;
      if (v >= 0) ijk[v] = b;
      nodes.push_back(ijk[0] + n[0] * (ijk[1] + n[1] * ijk[2]));
    }
  return nodes;
}

PrescribedValues StructuredProblem::prescribedValues() const {
  for (const auto& name : fixed) requireFace(name, dim());
  for (const auto& [name, c] : symmetry) {
    requireFace(name, dim());
    if (c < 0 || c >= dofsPerNode())
      throw std::invalid_argument("Symmetry components: " + std::to_string(c) + " for face \"" +
                                  name + "\" is not below the " + std::to_string(dofsPerNode()) +
                                  " component(s) of the problem");
  }
  return contact::prescribedValues(
      prescribed, dofsPerNode(), [&](const std::string& f) { return faceNodes(f); }, fixed,
      symmetry);
}

void StructuredProblem::applyFaceConditions(tfeti::SubdomainMesh& m) const {
  const tfeti::StructuredMesh grid = mesh();
  std::vector<std::pair<int, int>> fixedFaces;
  for (const auto& name : fixed) fixedFaces.push_back(requireFace(name, dim()));
  m.dirichletNodes.clear();
  m.fixedComponents.clear();
  for (int n = 0; n < m.numNodes(); ++n) {
    const long long g = m.globalNode[n];
    bool all = false;
    for (const auto& f : fixedFaces) all = all || onFace(grid, g, f);
    if (all) {
      m.dirichletNodes.push_back(n);
      continue;
    }
    for (const auto& [name, c] : symmetry)
      if (onFace(grid, g, requireFace(name, dim()))) m.fixedComponents.push_back({n, c});
  }
  std::sort(m.fixedComponents.begin(), m.fixedComponents.end());
  m.fixedComponents.erase(std::unique(m.fixedComponents.begin(), m.fixedComponents.end()),
                          m.fixedComponents.end());
}

double relativeErrorAgainstDirectSolve(const StructuredProblem& problem,
                                       const tfeti::FetiSolver& solver) {
  const tfeti::StructuredMesh mesh = problem.mesh();
  tfeti::SubdomainMesh wholeMesh = mesh.wholeMesh();
  problem.applyFaceConditions(wholeMesh);
  tfeti::SubdomainData whole = assemble(problem, std::move(wholeMesh), mesh.wholeCells());
  const int dpn = whole.dofsPerNode;
  // Dirichlet and prescribed dofs eliminated: their values g lifted into the load (f -= K g),
  // then their rows and columns become the identity with g as the load.
  std::vector<char> fixed(whole.K.rows, 0);
  std::vector<double> g(whole.K.rows, 0.0);
  for (int d : whole.mesh.dirichletDofs(dpn)) fixed[d] = 1;
  for (const auto& [nc, value] : problem.prescribedValues()) {
    fixed[nc.first * dpn + nc.second] = 1;
    g[nc.first * dpn + nc.second] = value.value;  // one solve: the full value
  }
  auto& K = whole.K;
  for (int i = 0; i < K.rows; ++i)
    for (int k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k)
      if (!fixed[i] && fixed[K.colInd[k]]) whole.f[i] -= K.values[k] * g[K.colInd[k]];
  for (int i = 0; i < K.rows; ++i)
    for (int k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k)
      if (fixed[i] || fixed[K.colInd[k]]) K.values[k] = (i == K.colInd[k]) ? 1.0 : 0.0;
  for (int i = 0; i < K.rows; ++i)
    if (fixed[i]) whole.f[i] = g[i];
  auto direct = tfeti::createLocalSolver("cholmod");
  direct->factorize(K);
  std::vector<double> u(K.rows);
  direct->solve(whole.f.data(), u.data());

  double maxErr = 0.0, maxRef = 0.0;
  for (double v : u) maxRef = std::max(maxRef, std::abs(v));
  for (std::size_t i = 0; i < solver.data().size(); ++i) {
    const auto& mesh = solver.data()[i].mesh;
    const auto& us = solver.solution(i);
    for (int n = 0; n < mesh.numNodes(); ++n)
      for (int c = 0; c < dpn; ++c)
        maxErr = std::max(maxErr, std::abs(us[n * dpn + c] - u[mesh.globalNode[n] * dpn + c]));
  }
  double globalErr = 0.0;
  Teuchos::reduceAll(*solver.comm(), Teuchos::REDUCE_MAX, 1, &maxErr, &globalErr);
  return maxRef > 0.0 ? globalErr / maxRef : globalErr;
}

void checkGridSize(const Teuchos::ParameterList& mesh) {
  const auto subs = mesh.get<Teuchos::Array<int>>("Subdomains");
  const auto elems = mesh.get<Teuchos::Array<int>>("Elements per subdomain");
  // Node numbers are ints: (elements per side + 1)^2 must stay far below 2^31, and so must the
  // dofs of all nodes of a box (up to 3 per node).
  const long long perSide = 1 << 15, nodes = 1LL << 29;
  long long total = 1;
  for (int d = 0; d < subs.size() && d < elems.size(); ++d) {
    const long long n = static_cast<long long>(subs[d]) * elems[d];
    if (n > perSide)
      throw std::invalid_argument(
          "Mesh: \"Subdomains\" x \"Elements per subdomain\" = " + std::to_string(subs[d]) + " x " +
          std::to_string(elems[d]) + " elements along " + std::string(1, "xyz"[d % 3]) +
          "; at most " + std::to_string(perSide) + " per side");
    total *= n + 1;
  }
  if (total > nodes)
    throw std::invalid_argument("Mesh: \"Subdomains\" x \"Elements per subdomain\" give " +
                                std::to_string(total) + " nodes; at most " + std::to_string(nodes));
}

}  // namespace contact
