#include "tfeti_InputChecks.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <exception>

#include "tfeti_Gather.hpp"
#include "tfeti_TpetraInterface.hpp"

namespace tfeti {

namespace {
std::string plural(long long n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// "the mesh has 81 nodes x 2 dofs = 162"
std::string meshCount(int nodes, int perNode, const std::string& one, const std::string& many) {
  return "the mesh has " + plural(nodes, "node", "nodes") + " x " + plural(perNode, one, many) +
         " = " + std::to_string(static_cast<long long>(nodes) * perNode);
}

bool allFinite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

// The first entry of `nodes` outside [0, numNodes), as text naming the list; empty if none.
std::string nodeRangeError(const std::vector<int>& nodes, int numNodes, const std::string& list) {
  for (std::size_t k = 0; k < nodes.size(); ++k)
    if (nodes[k] < 0 || nodes[k] >= numNodes)
      return list + " has local node " + std::to_string(nodes[k]) + " (entry " + std::to_string(k) +
             "), but the mesh has " + plural(numNodes, "node", "nodes") + " (globalNode)";
  return "";
}
}  // namespace

std::string subdomainDataError(const SubdomainData& sd, int numSubdomains) {
  if (sd.tpetraK.is_null())
    return subdomainDataError(sd.mesh, sd.mesh.coords, sd.dofsPerNode, sd.K, sd.f, sd.kernel,
                              numSubdomains);
  // K given as a Tpetra matrix: checked as the CSR arrays FetiSolver makes of it (where the
  // constructor has not made them yet: the dry run's forecast), with the constructor's words.
  const std::string what = "subdomain " + std::to_string(sd.mesh.id) + ": tpetraK";
  if (sd.K.rows != 0 || !sd.K.rowPtr.empty()) return what + " and K are both given; give one";
  try {
    return subdomainDataError(sd.mesh, sd.mesh.coords, sd.dofsPerNode,
                              csrFromTpetra(*sd.tpetraK, what), sd.f, sd.kernel, numSubdomains);
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::string subdomainDataError(const SubdomainMesh& m, const std::vector<double>& coords,
                               int dofsPerNode, const CsrMatrix& K, const std::vector<double>& f,
                               const std::vector<double>& kernel, int numSubdomains) {
  const std::string name = "subdomain " + std::to_string(m.id);
  if (m.id < 0 || m.id >= numSubdomains)
    return name + ": the id is not in 0 .. " + std::to_string(numSubdomains - 1) +
           " (the number of subdomains given to FetiSolver is " + std::to_string(numSubdomains) +
           ")";
  const int n = m.numNodes(), dpn = dofsPerNode;
  if (dpn < 1) return name + ": " + std::to_string(dpn) + " dofs per node";
  if (m.dim < 1 || m.dim > 3) return name + ": mesh dimension " + std::to_string(m.dim);
  for (GO g : m.globalNode)
    if (g < 0) return name + ": globalNode has the negative id " + std::to_string(g);
  if (coords.size() != static_cast<std::size_t>(n) * m.dim)
    return name + ": the coordinates have " + std::to_string(coords.size()) + " values, " +
           meshCount(n, m.dim, "coordinate", "coordinates") + " (globalNode gives the nodes)";
  if (!allFinite(coords)) return name + ": a coordinate is NaN or infinite";
  if (std::string e = csrError(K, "K"); !e.empty()) return name + ": " + e;
  const long long dofs = static_cast<long long>(n) * dpn;
  if (K.rows != dofs || K.cols != dofs)
    return name + ": K is " + std::to_string(K.rows) + " x " + std::to_string(K.cols) + ", " +
           meshCount(n, dpn, "dof", "dofs");
  if (static_cast<long long>(f.size()) != dofs)
    return name + ": the load vector f has " + std::to_string(f.size()) + " entries, " +
           meshCount(n, dpn, "dof", "dofs");
  if (!allFinite(f)) return name + ": the load vector f has a NaN or infinite entry";
  if (!kernel.empty() && (dofs == 0 || kernel.size() % dofs != 0))
    return name + ": the kernel has " + std::to_string(kernel.size()) +
           " values, not whole columns of " + std::to_string(dofs) + " dofs";
  const auto& off = m.elements.offsets;
  if (off.empty() || off.front() != 0 || off.back() != static_cast<int>(m.elements.nodes.size()) ||
      !std::is_sorted(off.begin(), off.end()))
    return name + ": elements.offsets must rise from 0 to the " +
           std::to_string(m.elements.nodes.size()) + " entries of elements.nodes";
  if (std::string e = nodeRangeError(m.elements.nodes, n, "elements"); !e.empty())
    return name + ": " + e;
  if (std::string e = nodeRangeError(m.dirichletNodes, n, "dirichletNodes"); !e.empty())
    return name + ": " + e;
  if (std::string e = nodeRangeError(m.interfaceCandidates, n, "interfaceCandidates"); !e.empty())
    return name + ": " + e;
  for (const auto& [node, c] : m.fixedComponents)
    if (node < 0 || node >= n || c < 0 || c >= dpn)
      return name + ": fixed component (node " + std::to_string(node) + ", component " +
             std::to_string(c) + ") is not one of its " + plural(n, "node", "nodes") + " x " +
             plural(dpn, "component", "components");
  return "";
}

void checkSubdomainInput(const Comm& comm, int numSubdomains,
                         const std::vector<SubdomainData>& local) {
  if (numSubdomains < 1)
    throw CollectiveError("FetiSolver: " + std::to_string(numSubdomains) + " subdomains");
  std::string error;
  for (const auto& sd : local)
    if (error.empty()) error = subdomainDataError(sd, numSubdomains);
  throwIfAnyRankFailed(comm, error);

  // The same dofs per node everywhere (a rank without subdomains has no say).
  int lo = 1 << 30, hi = 0;
  for (const auto& sd : local) {
    lo = std::min(lo, sd.dofsPerNode);
    hi = std::max(hi, sd.dofsPerNode);
  }
  int gLo = lo, gHi = hi;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MIN, 1, &lo, &gLo);
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &hi, &gHi);
  if (gLo != gHi)
    for (const auto& sd : local)
      if (error.empty() && sd.dofsPerNode != gHi)
        error = "subdomain " + std::to_string(sd.mesh.id) + " has " +
                plural(sd.dofsPerNode, "dof", "dofs") + " per node, another subdomain has " +
                std::to_string(gHi) + " (all subdomains must have the same)";
  throwIfAnyRankFailed(comm, error);

  // Every subdomain held once (ids are in range: checked above).
  std::vector<long long> ids;
  for (const auto& sd : local) ids.push_back(sd.mesh.id);
  const std::vector<long long> all = allGather(comm, ids);
  std::vector<int> count(numSubdomains, 0);
  for (long long id : all) ++count[id];
  for (int s = 0; s < numSubdomains; ++s)
    if (count[s] != 1)
      throw CollectiveError("subdomain " + std::to_string(s) +
                            (count[s] == 0 ? " is given by no rank"
                                           : " is given " + std::to_string(count[s]) + " times") +
                            " (FetiSolver was told of " + std::to_string(numSubdomains) +
                            " subdomains, ids 0 .. " + std::to_string(numSubdomains - 1) + ")");
}

}  // namespace tfeti
