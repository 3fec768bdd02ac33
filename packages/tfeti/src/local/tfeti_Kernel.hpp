#pragma once
// The kernel of a subdomain stiffness matrix, for scalar problems and elasticity in 2D and 3D.
//
// A subdomain is a set of rigid pieces: elements are joined into one piece when the nodes they
// share fix their relative motion (scalar problem: any shared node; elasticity: shared nodes
// spanning a line in 2D, a plane in 3D, i.e. a common edge or face). Each piece moves by its
// own rigid modes (1: a constant; 3 in 2D elasticity; 6 in 3D elasticity). Pieces that still
// touch (at a node, or along an edge in 3D) must move equally there, and dofs the formulation
// eliminates must not move: the kernel is the null space of that small dense constraint system
// on the pieces' mode coefficients. Without elements the pieces are the connected components of
// the graph of K, which misses pieces touching at a node: the caller verifies the result.
#include <vector>

#include "tfeti_CsrMatrix.hpp"
#include "tfeti_SubdomainMesh.hpp"

namespace tfeti {

// Number of rigid modes of one connected piece: 1 (scalar), 3 (2D elasticity), 6 (3D
// elasticity). Throws std::invalid_argument for other combinations of dim and dofsPerNode.
int rigidModesPerPiece(int dim, int dofsPerNode);

// The rigid pieces of a mesh as lists of local nodes (sorted); a node where pieces touch is in
// each of them, a node in no element is a piece of its own. Ordered by their first element.
std::vector<std::vector<int>> rigidPieces(int dim, int dofsPerNode,
                                          const std::vector<double>& coords,
                                          const ElementConnectivity& elements, int numNodes);

// The connected components of the graph of K (nodes coupled by a nonzero entry).
std::vector<std::vector<int>> matrixGraphPieces(const CsrMatrix& K, int dofsPerNode);

// Orthonormal basis (column-major, numDofs x k) of the rigid motions of the pieces that agree at
// shared nodes and vanish on fixedDofs (sorted). Returns k.
int rigidBodyKernel(int dim, int dofsPerNode, const std::vector<double>& coords,
                    const std::vector<std::vector<int>>& pieces, const std::vector<int>& fixedDofs,
                    std::vector<double>& R);

// Orthonormal basis of the vectors of span(userKernel) (column-major, numDofs x k) that vanish on
// fixedDofs. Returns its dimension.
int restrictedKernel(int numDofs, std::vector<double> userKernel, const std::vector<int>& fixedDofs,
                     std::vector<double>& R);

}  // namespace tfeti
