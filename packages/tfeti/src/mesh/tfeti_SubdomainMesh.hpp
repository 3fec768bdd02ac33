#pragma once
// The piece of a torn mesh that one subdomain owns: its own copy of every node it touches
// (interface nodes are duplicated between subdomains) and the untorn global node id of each,
// which is what the gluing constraints are built from.
#include <utility>
#include <vector>

#include "tfeti_Types.hpp"

namespace tfeti {

// Elements of any type and dimension (mixed too) as lists of local nodes: element e has the
// nodes nodes[offsets[e] .. offsets[e + 1]). The order of nodes within an element does not
// matter here: the kernel detection only asks which nodes elements share.
struct ElementConnectivity {
  std::vector<int> offsets{0};
  std::vector<int> nodes;
  int size() const { return static_cast<int>(offsets.size()) - 1; }
  bool empty() const { return size() <= 0; }
  void add(const std::vector<int>& elementNodes) {
    nodes.insert(nodes.end(), elementNodes.begin(), elementNodes.end());
    offsets.push_back(static_cast<int>(nodes.size()));
  }
};

struct SubdomainMesh {
  int id = -1;
  // Spatial dimension (2 or 3): coords holds dim values per node. The dofs per node of the
  // problem are 1 (scalar) or dim (elasticity).
  int dim = 2;
  std::vector<double> coords;  // x0, y0[, z0], x1, y1[, z1], ... per local node
  // The elements (any type, 2D or 3D; the structured mesh lists its Q1 quadrilaterals or
  // hexahedra here). With elements the kernel of K is found from the rigidly connected pieces of
  // the mesh (pieces touching at a node or an edge are handled); without, from the connected
  // components of the graph of K.
  ElementConnectivity elements;
  std::vector<GO> globalNode;       // untorn id of each local node
  std::vector<int> dirichletNodes;  // local nodes where every component is prescribed zero
  // Single components prescribed zero, (local node, component): symmetry conditions, e.g. the
  // normal displacement on a symmetry line.
  std::vector<std::pair<int, int>> fixedComponents;
  // The nodes that may be shared with other subdomains; boundaryNodes() returns them (every
  // node when the list is empty: correct for any mesh, only more data for the tearing to
  // gather). The structured mesh lists the nodes on the faces of its blocks.
  std::vector<int> interfaceCandidates;
  int numNodes() const { return static_cast<int>(globalNode.size()); }
  int numElements() const { return elements.size(); }
  // The elements (the list the kernel detection reads).
  ElementConnectivity connectivity() const { return elements; }
  // Local nodes that may be shared with another subdomain: interfaceCandidates, sorted without
  // repeats (all nodes when empty).
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
