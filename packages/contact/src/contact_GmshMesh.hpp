#pragma once
// Unstructured 2D meshes from Gmsh: a .geo geometry meshed at run time or a user's .msh file,
// read through Gmsh's C++ API. Physical groups carry the problem's names: a named 2D group is a
// body, a named 1D group a boundary (Dirichlet or symmetry side, loaded side, contact surface).
//
// Only this file's .cpp includes gmsh.h, so that users of the mesh do not inherit Gmsh's header
// or its process-wide state.
#include <cstddef>
#include <string>
#include <vector>

namespace contact {

// Values are Gmsh's element type codes, so that an unsupported code in a file can be reported
// as Gmsh names it.
enum class ElementType { Tri3 = 2, Quad4 = 3, Tri6 = 9, Quad9 = 10 };

int numNodes(ElementType type);    // 3, 4, 6, 9
int numCorners(ElementType type);  // 3 or 4: also the number of edges
const char* elementTypeName(ElementType type);

// Local nodes of edge `edge` (0 .. numCorners-1) of an element in Gmsh's node order: the edge runs
// from corner `edge` to corner `edge+1` (cyclically); second-order elements add the edge's
// midside node as third entry, so the result has the node order of a Gmsh 2- or 3-node line.
std::vector<int> elementEdgeNodes(ElementType type, int edge);

struct MeshOptions {
  // Generation options: they apply to .geo files only; a .msh file is used as stored.
  int order = 1;       // 1: 3-node triangles / 4-node quads; 2: 6-node triangles / 9-node quads.
                       // Second-order nodes on curved boundaries are placed on the geometry.
  bool quads = false;  // recombine the triangles of every surface into quadrilaterals. Gmsh's
                       // recombination may leave a triangle; the body is then of mixed type,
                       // which is an error. false keeps any Recombine command of the file.
  double sizeFactor = 1.0;  // multiplies every mesh size of the file (Mesh.MeshSizeFactor);
                            // < 1 refines. Transfinite curves ignore it.
  bool verbose = false;     // let Gmsh print its progress to the terminal

  // Named groups to load. Empty: every named group of that dimension. A name that the file does
  // not define is an error listing the names it does define.
  std::vector<std::string> bodies;      // 2D physical groups
  std::vector<std::string> boundaries;  // 1D physical groups
};

// A named 2D physical group: elements of a single type, node ids of GmshMesh (compacted), in
// Gmsh's node order (corners first, counter-clockwise when the surface's normal is +z).
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

// A named 1D physical group: 2-node lines (first-order meshes) or 3-node lines (ends, then
// midside node). An edge is related to the body element having that edge if any: the element of
// the first body (in GmshMesh::bodies order) that has it, so for a curve shared by two bodies
// of a conforming mesh only the first body's side is reported.
struct GmshBoundary {
  std::string name;
  int physicalTag = -1;
  int nodesPerEdge = 2;            // 2 or 3
  std::vector<int> edges;          // nodesPerEdge node ids per edge
  std::vector<int> edgeBody;       // per edge: index into GmshMesh::bodies, or -1
  std::vector<int> edgeElement;    // per edge: element of that body, or -1
  std::vector<int> edgeLocalEdge;  // per edge: which edge of that element (elementEdgeNodes)
  int numEdges() const { return static_cast<int>(edgeBody.size()); }
};

struct GmshMesh {
  std::string source;                  // the file it came from, for messages
  std::vector<double> coords;          // x, y per node (z was checked to be 0)
  std::vector<std::size_t> gmshNodes;  // Gmsh's tag of each node (ids are 0..n-1 by tag)
  std::vector<GmshBody> bodies;
  std::vector<GmshBoundary> boundaries;

  int numNodes() const { return static_cast<int>(gmshNodes.size()); }
  // Throw std::invalid_argument naming the file and listing the available names.
  const GmshBody& body(const std::string& name) const;
  const GmshBoundary& boundary(const std::string& name) const;
  int bodyIndex(const std::string& name) const;
};

// Reads `path`: a .msh file as stored, or a .geo file meshed in 2D with `options`. Only the nodes
// used by the loaded groups are kept. Physical groups without a name are ignored.
// Errors name the file: std::invalid_argument for bad options or an unknown group name,
// std::runtime_error for a missing or malformed file (with Gmsh's message), an unsupported or
// mixed element type, or a node off the plane z = 0.
// Gmsh is a process-wide singleton: this call initializes and finalizes it, so it must not run
// concurrently with itself or with other Gmsh use in the process.
GmshMesh loadMesh(const std::string& path, const MeshOptions& options = MeshOptions());

}  // namespace contact
