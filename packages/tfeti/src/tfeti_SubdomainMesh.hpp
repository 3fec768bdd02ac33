#pragma once
// The piece of a torn mesh that one subdomain owns: its own copy of every node it touches
// (interface nodes are duplicated between subdomains) and the untorn global node id of each,
// which is what the gluing constraints are built from.
#include <utility>
#include <vector>

#include "tfeti_Types.hpp"

namespace tfeti {

struct SubdomainMesh {
  int id = -1;
  std::vector<double> coords;       // x0, y0, x1, y1, ... per local node
  std::vector<int> quads;           // 4 local nodes per element, counter-clockwise
  std::vector<GO> globalNode;       // untorn id of each local node
  std::vector<int> dirichletNodes;  // local nodes where every component is prescribed zero
  // Single components prescribed zero, (local node, component): symmetry conditions, e.g. the
  // normal displacement on a symmetry line.
  std::vector<std::pair<int, int>> fixedComponents;
  // Meshes other than the structured Q1 one (quads empty) list the nodes that may be shared
  // with other subdomains here; boundaryNodes() returns them.
  std::vector<int> interfaceCandidates;
  int numNodes() const { return static_cast<int>(globalNode.size()); }
  int numElements() const { return static_cast<int>(quads.size() / 4); }
  // Local nodes on the subdomain's boundary (on an element edge that no other element of the
  // subdomain shares): the only nodes that can be shared with another subdomain.
  std::vector<int> boundaryNodes() const;
  // Prescribed dofs (dofsPerNode * node + component), sorted: every component of the Dirichlet
  // nodes and the fixed components.
  std::vector<int> dirichletDofs(int dofsPerNode) const;
  // Per local node: bit c set when component c is prescribed.
  std::vector<int> dirichletMasks(int dofsPerNode) const;
};

// Subdomains are dealt to ranks in contiguous blocks of ids (ranks get equal counts up to one):
// with subdomain ids numbered row by row, each rank holds a strip of the domain, so that most
// gluing stays within the rank.
int ownerOfSubdomain(int subdomain, int numSubdomains, int numRanks);
std::vector<int> subdomainsOfRank(int rank, int numSubdomains, int numRanks);

}  // namespace tfeti
