#include "tfeti_SubdomainMesh.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace tfeti {

std::vector<int> SubdomainMesh::boundaryNodes() const {
  if (quads.empty()) {
    std::vector<int> nodes = interfaceCandidates;
    if (nodes.empty())
      for (int n = 0; n < numNodes(); ++n) nodes.push_back(n);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    return nodes;
  }
  std::map<std::pair<int, int>, int> edgeCount;
  for (int e = 0; e < numElements(); ++e)
    for (int a = 0; a < 4; ++a) {
      int p = quads[4 * e + a], q = quads[4 * e + (a + 1) % 4];
      edgeCount[{std::min(p, q), std::max(p, q)}]++;
    }
  std::vector<char> onBoundary(numNodes(), 0);
  for (const auto& [edge, count] : edgeCount)
    if (count == 1) onBoundary[edge.first] = onBoundary[edge.second] = 1;
  std::vector<int> nodes;
  for (int n = 0; n < numNodes(); ++n)
    if (onBoundary[n]) nodes.push_back(n);
  return nodes;
}

ElementConnectivity SubdomainMesh::connectivity() const {
  ElementConnectivity c;
  for (int e = 0; e < numElements(); ++e)
    c.add({quads[4 * e], quads[4 * e + 1], quads[4 * e + 2], quads[4 * e + 3]});
  c.nodes.insert(c.nodes.end(), elements.nodes.begin(), elements.nodes.end());
  for (int e = 0; e < elements.size(); ++e)
    c.offsets.push_back(c.offsets.back() + elements.offsets[e + 1] - elements.offsets[e]);
  return c;
}

std::vector<int> SubdomainMesh::dirichletMasks(int dofsPerNode) const {
  std::vector<int> mask(numNodes(), 0);
  for (int n : dirichletNodes) mask[n] = (1 << dofsPerNode) - 1;
  for (const auto& [n, c] : fixedComponents) {
    if (n < 0 || n >= numNodes() || c < 0 || c >= dofsPerNode)
      throw std::invalid_argument("subdomain " + std::to_string(id) + ": fixed component (" +
                                  std::to_string(n) + ", " + std::to_string(c) +
                                  ") is not a node/component of the subdomain");
    mask[n] |= 1 << c;
  }
  return mask;
}

std::vector<int> SubdomainMesh::dirichletDofs(int dofsPerNode) const {
  const std::vector<int> mask = dirichletMasks(dofsPerNode);
  std::vector<int> dofs;
  for (int n = 0; n < numNodes(); ++n)
    for (int c = 0; c < dofsPerNode; ++c)
      if (mask[n] & (1 << c)) dofs.push_back(n * dofsPerNode + c);
  return dofs;
}

int ownerOfSubdomain(int subdomain, int numSubdomains, int numRanks) {
  // Inverse of subdomainsOfRank: rank r holds [r*N/P, (r+1)*N/P).
  int r = static_cast<int>((static_cast<long long>(subdomain) * numRanks) / numSubdomains);
  while (r + 1 < numRanks && static_cast<long long>(r + 1) * numSubdomains / numRanks <= subdomain)
    ++r;
  while (r > 0 && static_cast<long long>(r) * numSubdomains / numRanks > subdomain) --r;
  return r;
}

std::vector<int> subdomainsOfRank(int rank, int numSubdomains, int numRanks) {
  const long long first = static_cast<long long>(rank) * numSubdomains / numRanks;
  const long long last = static_cast<long long>(rank + 1) * numSubdomains / numRanks;
  std::vector<int> ids;
  for (long long s = first; s < last; ++s) ids.push_back(static_cast<int>(s));
  return ids;
}

}  // namespace tfeti
