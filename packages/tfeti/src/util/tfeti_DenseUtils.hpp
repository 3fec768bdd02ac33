#pragma once
// Small dense linear algebra for the few places that need it: rigid-body kernels (1-6 columns
// per piece, and the constraint systems between touching pieces),
// the pseudo-inverse of one interface node's B B^T block (a handful of rows). Column-major.
#include <vector>

namespace tfeti {
namespace dense {

// Eigen-decomposition of a symmetric n x n matrix by cyclic Jacobi rotations: A = V diag(w) V^T.
void symmetricEigen(int n, std::vector<double> A, std::vector<double>& w, std::vector<double>& V);

// Moore-Penrose pseudo-inverse of a symmetric positive semi-definite n x n matrix; eigenvalues
// below relTol times the largest count as zero.
std::vector<double> pseudoInverseSpd(int n, const std::vector<double>& A, double relTol = 1e-10);

// Orthonormalizes the k columns of the n x k matrix M (modified Gram-Schmidt, run twice for
// stability). Returns the number of independent columns kept (dependent ones are dropped).
int orthonormalizeColumns(int n, int k, std::vector<double>& M, double relTol = 1e-10);

}  // namespace dense
}  // namespace tfeti
