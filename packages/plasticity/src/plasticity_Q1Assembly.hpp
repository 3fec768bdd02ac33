#pragma once
// Kokkos element kernels for bilinear quadrilaterals (Q1, 2x2 Gauss quadrature) and the
// assembly of a (sub)domain's stiffness matrix and load vector from them. Two fields share
// the machinery: the scalar Laplacian (1 dof per node) and plane-strain elasticity (2 dofs per
// node, interleaved: dof 2*node + component).
#include <vector>

#include "plasticity_ElasticLaw.hpp"
#include "tfeti_CsrMatrix.hpp"

namespace plasticity {

enum class Field { Scalar, Elasticity };

inline int dofsPerNode(Field f) {
  return f == Field::Scalar ? 1 : 2;
}

// A mesh of Q1 elements: node coordinates (x0, y0, x1, y1, ...) and 4 nodes per element in
// counter-clockwise order.
struct QuadMesh {
  std::vector<double> coords;
  std::vector<int> quads;
  int numNodes() const { return static_cast<int>(coords.size() / 2); }
  int numElements() const { return static_cast<int>(quads.size() / 4); }
};

// Stiffness matrix of the mesh. For the Laplacian the law is ignored (unit conductivity).
// Throws naming the element when an element is degenerate or inverted (non-positive Jacobian).
tfeti::CsrMatrix assembleStiffness(const QuadMesh& mesh, Field field, const ElasticLaw& law);

// Consistent load vector of a uniform volume source: f (scalar) or the body force (bx, by).
std::vector<double> assembleBodyLoad(const QuadMesh& mesh, Field field, const double* source);
// The same with a source constant on each element: elementSource holds dofs-per-node values per
// element (piecewise loads such as the two-membrane benchmark's).
std::vector<double> assembleBodyLoad(const QuadMesh& mesh, Field field,
                                     const std::vector<double>& elementSource);

}  // namespace plasticity
