// Explicit instantiation of the QP solvers for the package's Tpetra types, so that users
// including only the _decl headers do not compile the algorithms again.
#include <BelosTpetraAdapter.hpp>

#include "tfeti_MprgpIteration_def.hpp"
#include "tfeti_MprgpSolMgr_def.hpp"
#include "tfeti_SmalbeSolMgr_def.hpp"
#include "tfeti_Types.hpp"

namespace tfeti {

template class MprgpIteration<Scalar, MultiVector, Operator>;
template class MprgpSolMgr<Scalar, MultiVector, Operator>;
template class SmalbeSolMgr<Scalar, MultiVector, Operator>;

}  // namespace tfeti
