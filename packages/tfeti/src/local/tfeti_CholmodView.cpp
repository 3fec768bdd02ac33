#include "tfeti_CholmodView.hpp"

#include <cholmod.h>

#include <cstring>

namespace tfeti {

void cholmodUpperView(const CsrMatrix& A, cholmod_sparse& S) {
  std::memset(&S, 0, sizeof(S));
  S.nrow = S.ncol = static_cast<size_t>(A.rows);
  S.nzmax = A.nnz();
  S.p = const_cast<int*>(A.rowPtr.data());
  S.i = const_cast<int*>(A.colInd.data());
  S.x = const_cast<double*>(A.values.data());
  S.stype = 1;
  S.itype = CHOLMOD_INT;
  // A pattern without values (CsrMatrix::submatrix withValues = false): for an analysis only.
  S.xtype = A.values.empty() && A.nnz() > 0 ? CHOLMOD_PATTERN : CHOLMOD_REAL;
  S.dtype = CHOLMOD_DOUBLE;
  S.sorted = 1;
  S.packed = 1;
}

}  // namespace tfeti
