#pragma once
// Decomposition of one unstructured body (2D or 3D) into TFETI subdomains: METIS parts of the
// element dual graph, each split into its facet-connected components. A component is its own
// subdomain because the kernel of a subdomain's stiffness matrix has one set of rigid body modes
// per rigidly connected piece; pieces that touch only at a node (or, in 3D, along an edge) are not
// rigidly connected for elasticity (they can rotate about it), so connectivity is through shared
// element facets (edges in 2D, faces in 3D), never nodes or 3D edges.
#include <vector>

#include "contact_GmshMesh.hpp"

namespace contact {

// The unstructured counterpart of tfeti::SubdomainMesh: a subdomain's own copy of every node it
// touches and the untorn node id of each, from which the gluing rows are built.
struct UnstructuredSubdomain {
  int id = -1;    // subdomain id (see partitionBody's firstId)
  int part = -1;  // the METIS part it was cut from
  ElementType type = ElementType::Tri3;
  std::vector<int> elements;          // element ids within the body, increasing
  std::vector<int> connectivity;      // numNodes(type) local nodes per element, Gmsh node order
  std::vector<double> coords;         // mesh.dim values (x, y[, z]) per local node
  std::vector<long long> globalNode;  // untorn (GmshMesh) node id per local node, increasing;
                                      // long long as tfeti::GO
  int numNodes() const { return static_cast<int>(globalNode.size()); }
  int numElements() const { return static_cast<int>(elements.size()); }
  int nodesPerElement() const { return contact::numNodes(type); }
  // Local nodes on an element facet (edge in 2D, face in 3D) that no other element of the
  // subdomain has (midside and face-centre nodes included): the only nodes that can be shared
  // with another subdomain.
  std::vector<int> boundaryNodes() const;
};

// Element adjacency through shared facets (CSR): elements i and j are neighbours iff they have a
// facet with the same corner nodes (an edge in 2D, a face in 3D).
struct DualGraph {
  std::vector<int> offsets;    // numElements + 1
  std::vector<int> neighbors;  // increasing within each element
  int numElements() const { return static_cast<int>(offsets.size()) - 1; }
};
DualGraph edgeDualGraph(const GmshBody& body);

// The METIS part (0 .. numParts-1) of every element of the body: k-way partitioning of the facet
// dual graph with a fixed seed, so every rank computes the same parts, asking METIS for
// contiguous parts when the body is connected. No part is empty (METIS may leave some empty on
// tiny meshes; they get an element of the largest part). numParts == 1 does not call METIS.
// Throws std::invalid_argument unless 1 <= numParts <= number of elements.
std::vector<int> partitionElements(const GmshBody& body, int numParts);

// Recursive coordinate bisection of the elements' centroids: the body's elements are cut across
// their longest extent at the element count that gives each side its share of the parts, and
// each side again, until every part is one (numParts need not be a power of two). On a
// structured box it gives equal boxes (64^3 hexahedra into 512 parts: 8^3 each), whose regular
// interfaces FETI converges on in a quarter of the iterations of METIS's jagged ones
// (docs/benchmarks.md, step-42 on 2026-12-01). Ties go by element number, so every rank cuts
// alike. Throws std::invalid_argument unless 1 <= numParts <= number of elements.
std::vector<int> bisectCoordinates(const GmshMesh& mesh, const GmshBody& body, int numParts);

// Component of every element within its part (graph restricted to same-part edges), numbered
// 0, 1, ... per part in the order of each component's smallest element.
std::vector<int> componentsWithinParts(const DualGraph& graph, const std::vector<int>& part);

struct BodyPartition {
  std::vector<UnstructuredSubdomain> subdomains;  // ordered by part, then by smallest element
  int numParts = 0;                               // requested
  int emptyParts = 0;       // parts METIS left without elements (no subdomain)
  int splitParts = 0;       // parts that were not edge-connected
  int extraSubdomains = 0;  // subdomains added by splitting: subdomains.size() ==
                            // numParts - emptyParts + extraSubdomains
  int numSubdomains() const { return static_cast<int>(subdomains.size()); }
};

// Subdomains from a given element partition (part[e] in 0 .. numParts-1), each part split into its
// facet-connected components. Subdomain ids are firstId, firstId + 1, ... so that the subdomains of
// several bodies can be numbered consecutively.
BodyPartition splitIntoSubdomains(const GmshMesh& mesh, const GmshBody& body,
                                  const std::vector<int>& part, int numParts, int firstId = 0);

enum class Partitioner { Metis, CoordinateBisection };

// partitionElements (Metis) or bisectCoordinates followed by splitIntoSubdomains.
BodyPartition partitionBody(const GmshMesh& mesh, const GmshBody& body, int numParts,
                            int firstId = 0, Partitioner partitioner = Partitioner::Metis);

}  // namespace contact
