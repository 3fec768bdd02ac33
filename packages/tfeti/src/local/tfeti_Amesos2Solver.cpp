// Amesos2's KLU2 and Tacho behind the LocalSolver interface. The matrix is a Tpetra matrix on a
// serial communicator: a subdomain matrix never spans ranks, which also keeps KLU2 on its
// transposed solve path (its non-transposed solve is miscompiled by GCC 12, see the README).
#include "tfeti_Amesos2Solver.hpp"

#include <Amesos2.hpp>
#include <Teuchos_DefaultSerialComm.hpp>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "tfeti_LocalSolver.hpp"
#include "tfeti_Types.hpp"

namespace tfeti {
namespace {

class Amesos2Solver final : public LocalSolver {
 public:
  explicit Amesos2Solver(std::string type) : type_(std::move(type)) {}

  void factorize(const CsrMatrix& A) override {
    widest_ = 0;  // the next Amesos2 solver starts without a workspace, even if this one fails
    auto comm = Teuchos::rcp(new Teuchos::SerialComm<int>());
    map_ = Teuchos::rcp(new Map(A.rows, 0, comm, Tpetra::LocallyReplicated));
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

  // The multivectors are views of the caller's b and x, not copies held by the solver. Copies
  // sized by the last nrhs stayed with every subdomain's solver until its next one-column solve
  // (2 n nrhs doubles, and Amesos2 keeps one more of its own), so after an explicit dual
  // operator's assembly by 128-column solves every subdomain held about 3 n 128 doubles, more
  // than its F_s in 3D, which the memory check did not count.
  void solve(const double* b, double* x, int nrhs) override {
    solveViews(b, x, nrhs);
    widest_ = std::max(widest_, nrhs);
    if (nrhs > 1) {
      // Amesos2 keeps its arrays of a multi-column solve (its own copy, not a view of ours)
      // until a solve of another width reallocates them: a solve of one zero column (1/nrhs of
      // the solve just made) shrinks them to a column.
      std::vector<double> zero(2 * map_->getNodeNumElements(), 0.0);
      solveViews(zero.data(), zero.data() + zero.size() / 2, 1);
    }
  }

  // Tacho's workspace (Amesos2's TachoSolver::workspace_) grows to a solve's width and stays
  // with the Amesos2 solver, which only a new factorization replaces: the one-column solve above
  // does not shrink it. KLU2 keeps nothing of a solve's width.
  std::size_t solveKeeps(std::size_t n, int nrhs) const override {
    if (type_ != "tacho" || nrhs <= widest_) return 0;
    const std::size_t rows = map_.is_null() ? n : map_->getNodeNumElements();
    return sizeof(double) * rows * static_cast<std::size_t>(nrhs - widest_);
  }

  // Amesos2's Tacho adapter does not report its factor size (0 then means unknown).
  std::size_t factorBytes() const override { return nnzLU_ * (sizeof(double) + sizeof(int)); }
  std::string name() const override { return type_; }

 private:
  void solveViews(const double* b, double* x, int nrhs) {
    const std::size_t n = map_->getNodeNumElements();
    using View = MultiVector::dual_view_type::t_dev;
    const View bv(const_cast<double*>(b), n, static_cast<std::size_t>(nrhs));
    const View xv(x, n, static_cast<std::size_t>(nrhs));
    const MultiVector B(map_, MultiVector::dual_view_type(bv, bv));
    MultiVector X(map_, MultiVector::dual_view_type(xv, xv));
    solver_->solve(Teuchos::ptrFromRef(X), Teuchos::ptrFromRef(B));
  }

  std::string type_;
  Teuchos::RCP<const Map> map_;
  Teuchos::RCP<CrsMatrix> matrix_;
  Teuchos::RCP<Amesos2::Solver<CrsMatrix, MultiVector>> solver_;
  std::size_t nnzLU_ = 0;
  int widest_ = 0;  // the widest solve of this factor
};

}  // namespace

std::unique_ptr<LocalSolver> createAmesos2Solver(const std::string& type) {
  return std::make_unique<Amesos2Solver>(type);
}

}  // namespace tfeti
