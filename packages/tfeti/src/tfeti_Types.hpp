#pragma once
// Scalar, ordinal and Tpetra types shared by the whole TFETI package. Debian's Trilinos 13.2
// instantiates Tpetra for double with int local and long long global ordinals only.
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Operator.hpp>
#include <Tpetra_Vector.hpp>

namespace tfeti {

using Scalar = double;
using LO = int;
using GO = long long;
using Node = Tpetra::Map<>::node_type;
using Map = Tpetra::Map<LO, GO, Node>;
using MultiVector = Tpetra::MultiVector<Scalar, LO, GO, Node>;
using Vector = Tpetra::Vector<Scalar, LO, GO, Node>;
using Operator = Tpetra::Operator<Scalar, LO, GO, Node>;
using CrsMatrix = Tpetra::CrsMatrix<Scalar, LO, GO, Node>;
using Comm = Teuchos::Comm<int>;

}  // namespace tfeti
