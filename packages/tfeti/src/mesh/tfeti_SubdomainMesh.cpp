#include "tfeti_SubdomainMesh.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace tfeti {

std::vector<int> SubdomainMesh::boundaryNodes() const {
  std::vector<int> nodes = interfaceCandidates;
  if (nodes.empty())
    for (int n = 0; n < numNodes(); ++n) nodes.push_back(n);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
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
