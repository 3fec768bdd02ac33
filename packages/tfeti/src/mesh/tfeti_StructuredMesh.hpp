#pragma once
// A box (a rectangle in 2D, a cuboid in 3D) meshed by Q1 elements (bilinear quadrilaterals,
// trilinear hexahedra) and torn into a grid of box-shaped subdomains: the decomposition the
// reference paper's scalability study uses (H the subdomain size, h the element size).
// Dirichlet nodes are those on the face x = x0 (the side x = x0 in 2D).
//
// Numbering, in every dimension: subdomains, nodes and elements are numbered lexicographically
// with x fastest, then y, then z. The nodes of an element follow VTK's order (counter-clockwise
// in the plane z = const, the bottom face before the top one in 3D).
#include <array>
#include <utility>
#include <vector>

#include "tfeti_SubdomainMesh.hpp"

namespace tfeti {

class StructuredMesh {
 public:
  // lo, hi: the box's corners; subdomains: the grid of subdomains; elements: elements per
  // subdomain along each axis. All four have dim() = 2 or 3 entries.
  StructuredMesh(const std::vector<double>& lo, const std::vector<double>& hi,
                 const std::vector<int>& subdomains, const std::vector<int>& elements);

  int dim() const { return dim_; }
  int numSubdomains() const;
  // Elements of the whole mesh along an axis.
  int elementsAlong(int axis) const { return sub_[axis] * elem_[axis]; }
  GO numGlobalNodes() const;
  GO numGlobalElements() const;
  // Subdomain s with its own node copies and dim: its elements are the quadrilaterals or
  // hexahedra (as subdomainCells()), its interfaceCandidates the nodes on the block's sides
  // (faces in 3D).
  SubdomainMesh subdomain(int s) const;
  // The untorn mesh as one "subdomain" (id -1): for reference solves of the whole problem.
  SubdomainMesh wholeMesh() const;
  // Q1 cells (2^dim local nodes each) of subdomain(s) (the same for every s) and of wholeMesh().
  std::vector<int> subdomainCells() const { return cells(elem_); }
  std::vector<int> wholeCells() const;
  // Without Dirichlet nodes the whole box floats (a body held only by contact).
  void setDirichletAtX0(bool on) { dirichletAtX0_ = on; }
  // One copy of the untorn node with grid indices g (0 <= g[axis] <= elementsAlong(axis); g[2]
  // ignored in 2D): the subdomain with the lowest id that holds it, and its local node there.
  std::pair<int, int> copyOfNode(const std::array<int, 3>& g) const;

  // The cells of a block of n[0] x ... x n[dim-1] elements in lexicographic node numbering.
  static std::vector<int> cells(const std::vector<int>& n);

 private:
  SubdomainMesh block(const std::vector<int>& first, const std::vector<int>& n) const;
  int dim_;
  std::vector<double> lo_, hi_;
  std::vector<int> sub_, elem_;
  bool dirichletAtX0_ = true;
};

// The 2D case with the arguments of the reference paper's rectangles.
class StructuredRectangle : public StructuredMesh {
 public:
  // (x0, x1) x (y0, y1) split into sx x sy subdomains of ex x ey elements each.
  StructuredRectangle(double x0, double x1, double y0, double y1, int sx, int sy, int ex, int ey)
      : StructuredMesh({x0, y0}, {x1, y1}, {sx, sy}, {ex, ey}) {}
  int elementsX() const { return elementsAlong(0); }
  int elementsY() const { return elementsAlong(1); }
  std::pair<int, int> copyOfNode(int gi, int gj) const {
    return StructuredMesh::copyOfNode({gi, gj, 0});
  }
};

}  // namespace tfeti
