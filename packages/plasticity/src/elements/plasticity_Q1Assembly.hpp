#pragma once
// Kokkos element kernels for Q1 elements: bilinear quadrilaterals (2x2 Gauss points) in 2D and
// trilinear hexahedra (2x2x2 Gauss points) in 3D, one code path for both dimensions, and the
// assembly of a (sub)domain's stiffness matrix and load vector from them. Two fields share the
// machinery: the scalar Laplacian (1 dof per node) and isotropic linear elasticity (dim dofs per
// node, interleaved: dof dim*node + component; plane strain in 2D).
#include <vector>

#include "plasticity_ElasticLaw.hpp"
#include "tfeti_CsrMatrix.hpp"

namespace plasticity {

enum class Field { Scalar, Elasticity };

inline int dofsPerNode(Field f, int dim = 2) {
  return f == Field::Scalar ? 1 : dim;
}

// A mesh of Q1 cells: node coordinates (dim per node) and 2^dim nodes per cell in VTK's order
// (counter-clockwise quadrilaterals; hexahedra: the bottom face counter-clockwise seen from
// above, then the top face).
struct Q1Mesh {
  std::vector<double> coords;
  std::vector<int> cells;
  int dim = 2;
  int nodesPerCell() const { return 1 << dim; }
  int numNodes() const { return static_cast<int>(coords.size() / dim); }
  int numElements() const { return static_cast<int>(cells.size() / nodesPerCell()); }
};

// Stiffness matrix of the mesh. For the Laplacian the law is ignored (unit conductivity).
// Throws naming the element when an element is degenerate or inverted (non-positive Jacobian).
tfeti::CsrMatrix assembleStiffness(const Q1Mesh& mesh, Field field, const ElasticLaw& law);

// Consistent load vector of a uniform volume source: f (scalar) or the body force (dim values).
std::vector<double> assembleBodyLoad(const Q1Mesh& mesh, Field field, const double* source);
// The same with a source constant on each element: elementSource holds dofs-per-node values per
// element (piecewise loads such as the two-membrane benchmark's).
std::vector<double> assembleBodyLoad(const Q1Mesh& mesh, Field field,
                                     const std::vector<double>& elementSource);

}  // namespace plasticity
