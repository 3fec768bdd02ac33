#pragma once
// A rectangle meshed by Q1 elements and torn into a grid of rectangular subdomains: the
// decomposition the reference paper's scalability study uses (H the subdomain size, h the
// element size). Dirichlet nodes are those on the side x = x0.
#include <utility>

#include "tfeti_SubdomainMesh.hpp"

namespace tfeti {

class StructuredRectangle {
 public:
  // (x0, x1) x (y0, y1) split into sx x sy subdomains of ex x ey elements each.
  StructuredRectangle(double x0, double x1, double y0, double y1, int sx, int sy, int ex, int ey);

  int numSubdomains() const { return sx_ * sy_; }
  int elementsX() const { return sx_ * ex_; }
  int elementsY() const { return sy_ * ey_; }
  GO numGlobalNodes() const { return static_cast<GO>(elementsX() + 1) * (elementsY() + 1); }
  // Subdomain s (row-major in the subdomain grid) with its own node copies.
  SubdomainMesh subdomain(int s) const;
  // The untorn mesh as one "subdomain" (id -1): for reference solves of the whole problem.
  SubdomainMesh wholeMesh() const;
  // Without Dirichlet nodes the whole rectangle floats (a body held only by contact).
  void setDirichletAtX0(bool on) { dirichletAtX0_ = on; }
  // One copy of the untorn node (gi, gj) (0 <= gi <= elementsX()): the subdomain with the lowest
  // id that holds it, and its local node there.
  std::pair<int, int> copyOfNode(int gi, int gj) const;

 private:
  SubdomainMesh block(int i0, int j0, int nx, int ny) const;
  double x0_, x1_, y0_, y1_;
  int sx_, sy_, ex_, ey_;
  bool dirichletAtX0_ = true;
};

}  // namespace tfeti
