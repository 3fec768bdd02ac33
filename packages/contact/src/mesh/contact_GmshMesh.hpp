#pragma once
// Unstructured 2D and 3D meshes from Gmsh: a .geo geometry meshed at run time or a user's .msh
// file, read through Gmsh's C++ API. Physical groups carry the problem's names: a named group of
// the mesh's dimension (surfaces in 2D, volumes in 3D) is a body, a named group of one dimension
// less (curves in 2D, surfaces in 3D) a boundary (Dirichlet or symmetry side, loaded side,
// contact surface). A file with volumes is a 3D mesh, one without a 2D mesh.
//
// Only this file's .cpp includes gmsh.h, so that users of the mesh do not inherit Gmsh's header
// or its process-wide state.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "plasticity_ElementTypes.hpp"

namespace contact {

// Element types are plasticity's catalogue (plasticity_ElementTypes.hpp), which knows every fact
// about a type: node count, corners, facets, Gmsh code. The reader takes bodies of the types the
// catalogue marks meshBody -- Tri3, Quad4, Tri6, Quad9 (2D); Tet4, Tet10, Hex8, Hex20, Hex27 (3D)
// -- and boundary elements of their facet types: Line2, Line3 (2D); Tri3, Tri6, Quad4, Quad8,
// Quad9 (3D). The functions below are the mesh code's names for the catalogue's answers.
using ElementType = plasticity::ElementType;

inline int numNodes(ElementType type) {
  return plasticity::nodesPerElement(type);
}
// Vertices: 2 (lines), 3, 4 (faces, tets), 8 (hexahedra).
inline int numCorners(ElementType type) {
  return plasticity::cornersPerElement(type);
}
inline int elementDimension(ElementType type) {  // 1, 2 or 3
  return plasticity::spatialDimension(type);
}
// Gmsh's description ("3-node triangle"), for messages.
inline const char* elementTypeName(ElementType type) {
  return plasticity::elementLongName(type);
}

// Facets are the (dimension - 1)-dimensional sides of an element: the edges of a triangle or
// quadrangle, the faces of a tetrahedron (4) or hexahedron (6). Throws for a line.
int numFacets(ElementType type);
// The type of a body element's facets: Line2/Line3 for 2D elements; Tri3 (Tet4), Tri6 (Tet10),
// Quad4 (Hex8), Quad8 (Hex20), Quad9 (Hex27). Throws std::invalid_argument for a type that is
// not a body.
ElementType facetType(ElementType type);
// Local nodes of facet `facet` (0 .. numFacets-1) of a body element, oriented outward:
// plasticity::facetNodes, which says the order. Throws std::invalid_argument for a type that is
// not a body, std::out_of_range for no such facet.
const std::vector<int>& elementFacetNodes(ElementType type, int facet);

// Local nodes of edge `edge` (0 .. numCorners-1) of a 2D element in Gmsh's node order: the edge
// runs from corner `edge` to corner `edge+1` (cyclically); second-order elements add the edge's
// midside node as third entry, so the result has the node order of a Gmsh 2- or 3-node line.
std::vector<int> elementEdgeNodes(ElementType type, int edge);

// A facet's identity (an edge in 2D, a face in 3D): its corner nodes sorted, unused slots -1, so
// that every element having the facet gives the same key.
using FacetKey = std::array<int, 4>;
FacetKey facetKey(const int* corners, int numCorners);
struct FacetKeyHash {
  std::size_t operator()(const FacetKey& k) const;
};

struct MeshOptions {
  // Generation options: they apply to .geo files only; a .msh file is used as stored.
  int order = 1;       // 1: 3-node triangles / 4-node quads, Tet4 / Hex8; 2: 6-node triangles /
                       // 9-node quads, Tet10 / Hex27 (complete Lagrange elements). Second-order
                       // nodes on curved boundaries are placed on the geometry.
  bool quads = false;  // 2D only: recombine the triangles of every surface into quadrilaterals.
                       // Gmsh's recombination may leave a triangle; the body is then of mixed
                       // type, which is an error. false keeps any Recombine command of the file
                       // (in 3D, hexahedra come from the file's Transfinite/Recombine commands).
  double sizeFactor = 1.0;  // multiplies every mesh size of the file (Mesh.MeshSizeFactor);
                            // < 1 refines. Transfinite curves ignore it.
  bool verbose = false;     // let Gmsh print its progress to the terminal

  // Named groups to load. Empty: every named group of that dimension. A name that the file does
  // not define is an error listing the names it does define.
  std::vector<std::string> bodies;      // physical surfaces (2D) or volumes (3D)
  std::vector<std::string> boundaries;  // physical curves (2D) or surfaces (3D)

  // The dimension the problem needs: 2 or 3; 0 accepts the file's. A file of the other
  // dimension is an error naming it.
  int dimension = 0;
};

// A named body group: elements of a single type, node ids of GmshMesh (compacted), in Gmsh's
// node order. 2D: corners counter-clockwise (clockwise elements, which Gmsh makes for a surface
// whose normal is -z, are renumbered). 3D: positive Jacobian (an inverted element is an error).
struct GmshBody {
  std::string name;
  int physicalTag = -1;
  ElementType type = ElementType::Tri3;
  std::vector<int> connectivity;      // numNodes(type) node ids per element
  std::vector<std::size_t> gmshTags;  // Gmsh element tag of each element, for messages
  int reoriented = 0;                 // clockwise elements of the file renumbered counter-clockwise
  int nodesPerElement() const { return numNodes(type); }
  int numElements() const { return static_cast<int>(gmshTags.size()); }
};

// A named boundary group: its boundary elements ("edges", the name of the 2D case, are faces in
// 3D): 2-node or 3-node lines (ends, then midside node) in 2D; Tri3, Tri6, Quad4, Quad8 or Quad9
// faces in 3D, in Gmsh's node order. An edge is related to the body element having it as a facet
// (same corner nodes) if any: the element of the first body (in GmshMesh::bodies order) that has
// it, so for a boundary shared by two bodies of a conforming mesh only the first body's side is
// reported. elementFacetNodes(body type, edgeLocalEdge) gives the same nodes oriented outward.
struct GmshBoundary {
  std::string name;
  int physicalTag = -1;
  ElementType type = ElementType::Line2;  // the boundary elements' type
  int nodesPerEdge = 2;                   // numNodes(type)
  std::vector<int> edges;                 // nodesPerEdge node ids per edge (face in 3D)
  std::vector<int> edgeBody;              // per edge: index into GmshMesh::bodies, or -1
  std::vector<int> edgeElement;           // per edge: element of that body, or -1
  std::vector<int> edgeLocalEdge;         // per edge: which facet of that element, or -1
  int numEdges() const { return static_cast<int>(edgeBody.size()); }
};

struct GmshMesh {
  std::string source;                  // the file it came from, for messages
  int dim = 2;                         // 2 or 3
  std::vector<double> coords;          // dim values per node (in 2D z was checked to be 0)
  std::vector<std::size_t> gmshNodes;  // Gmsh's tag of each node (ids are 0..n-1 by tag)
  std::vector<GmshBody> bodies;
  std::vector<GmshBoundary> boundaries;

  int numNodes() const { return static_cast<int>(gmshNodes.size()); }
  // Throw std::invalid_argument naming the file and listing the available names.
  const GmshBody& body(const std::string& name) const;
  const GmshBoundary& boundary(const std::string& name) const;
  int bodyIndex(const std::string& name) const;
};

// Reads `path`: a .msh file as stored, or a .geo file meshed with `options` (in 3D when the file
// defines volumes, else in 2D). A .msh file is 3D when it has a named physical volume. Only the
// nodes used by the loaded groups are kept. Physical groups without a name are ignored.
// Errors name the file: std::invalid_argument for bad options, an unknown group name or a mesh of
// the wrong dimension; std::runtime_error for a missing or malformed file (with Gmsh's message),
// an unsupported or mixed element type, a 2D node off the plane z = 0, and (naming the element's
// Gmsh tag) a degenerate element (zero area or volume) or a 3D element whose Jacobian is
// negative (inverted) or changes sign at its nodes. Inverted 3D elements are rejected, not
// reoriented: Gmsh's own volume meshes are positive, so one in a file is a broken mesh.
// Gmsh is a process-wide singleton: this call initializes and finalizes it, so it must not run
// concurrently with itself or with other Gmsh use in the process.
GmshMesh loadMesh(const std::string& path, const MeshOptions& options = MeshOptions());

}  // namespace contact
