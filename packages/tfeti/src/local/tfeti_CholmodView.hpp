#pragma once
// A CHOLMOD view of a symmetric CsrMatrix, shared by the local factorizations and the scaling
// groups' pseudo-inverse. cholmod.h is not included here: this header is installed with the
// package, and an application that includes it need not have SuiteSparse's headers.

#include "tfeti_CsrMatrix.hpp"

struct cholmod_sparse_struct;

namespace tfeti {

// Makes S a view of A, without copying: a symmetric CSR matrix is its own CSC, and S is marked
// to be read from its upper part (stype = 1). S refers to A's arrays and must not outlive A or be
// freed by CHOLMOD.
void cholmodUpperView(const CsrMatrix& A, cholmod_sparse_struct& S);

}  // namespace tfeti
