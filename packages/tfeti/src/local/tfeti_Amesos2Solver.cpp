// Amesos2's KLU2 and Tacho behind the LocalSolver interface. The matrix is a Tpetra matrix on a
// serial communicator: a subdomain matrix never spans ranks, which also keeps KLU2 on its
// transposed solve path (its non-transposed solve is miscompiled by GCC 12, see the README).
#include "tfeti_Amesos2Solver.hpp"

#include <Amesos2.hpp>
#include <Teuchos_DefaultSerialComm.hpp>

#include <cstring>
#include <stdexcept>

#include "tfeti_LocalSolver.hpp"
#include "tfeti_Types.hpp"

namespace tfeti {
namespace {

class Amesos2Solver final : public LocalSolver {
 public:
  explicit Amesos2Solver(std::string type) : type_(std::move(type)) {}

  void factorize(const CsrMatrix& A) override {
    auto comm = Teuchos::rcp(new Teuchos::SerialComm<int>());
    map_ = Teuchos::rcp(new Map(A.rows, 0, comm, Tpetra::LocallyReplicated));
    X_ = B_ = Teuchos::null;  // work vectors of a previous factorization have the old size
    Teuchos::Array<size_t> rowCounts(A.rows);
    for (int i = 0; i < A.rows; ++i) rowCounts[i] = A.rowPtr[i + 1] - A.rowPtr[i];
    matrix_ = Teuchos::rcp(new CrsMatrix(map_, map_, rowCounts()));
    for (int i = 0; i < A.rows; ++i) {
      const int len = A.rowPtr[i + 1] - A.rowPtr[i];
      matrix_->insertLocalValues(i, Teuchos::ArrayView<const int>(&A.colInd[A.rowPtr[i]], len),
                                 Teuchos::ArrayView<const double>(&A.values[A.rowPtr[i]], len));
    }
    matrix_->fillComplete();
    const std::string amesosName = type_ == "klu2" ? "KLU2" : "Tacho";
    solver_ = Amesos2::create<CrsMatrix, MultiVector>(amesosName, matrix_);
    solver_->symbolicFactorization().numericFactorization();
    nnzLU_ = solver_->getStatus().getNnzLU();
  }

  void solve(const double* b, double* x, int nrhs) override {
    const std::size_t n = map_->getNodeNumElements();
    if (X_.is_null() || X_->getNumVectors() != static_cast<std::size_t>(nrhs)) {
      X_ = Teuchos::rcp(new MultiVector(map_, nrhs));
      B_ = Teuchos::rcp(new MultiVector(map_, nrhs));
    }
    for (int j = 0; j < nrhs; ++j) {
      auto col = B_->getDataNonConst(j);
      std::memcpy(col.getRawPtr(), b + j * n, sizeof(double) * n);
    }
    solver_->solve(X_.ptr(), B_.ptr());
    for (int j = 0; j < nrhs; ++j) {
      auto col = X_->getData(j);
      std::memcpy(x + j * n, col.getRawPtr(), sizeof(double) * n);
    }
  }

  // Amesos2's Tacho adapter does not report its factor size (0 then means unknown).
  std::size_t factorBytes() const override { return nnzLU_ * (sizeof(double) + sizeof(int)); }
  std::string name() const override { return type_; }

 private:
  std::string type_;
  Teuchos::RCP<const Map> map_;
  Teuchos::RCP<CrsMatrix> matrix_;
  Teuchos::RCP<Amesos2::Solver<CrsMatrix, MultiVector>> solver_;
  Teuchos::RCP<MultiVector> X_, B_;
  std::size_t nnzLU_ = 0;
};

}  // namespace

std::unique_ptr<LocalSolver> createAmesos2Solver(const std::string& type) {
  return std::make_unique<Amesos2Solver>(type);
}

}  // namespace tfeti
