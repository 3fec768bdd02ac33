#pragma once
// Sparse direct factorization of one subdomain matrix, on one rank. Every local solver in the
// package (CHOLMOD, Amesos2's KLU2 and Tacho) sits behind this interface so that the choice
// is a run-time parameter and can be measured rather than assumed.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "tfeti_CsrMatrix.hpp"

namespace tfeti {

class LocalSolver {
 public:
  virtual ~LocalSolver() = default;
  // Factorizes the symmetric positive definite matrix A (the full symmetric pattern is given).
  // Throws std::runtime_error naming the solver when the factorization fails.
  virtual void factorize(const CsrMatrix& A) = 0;
  // x = A^{-1} b for nrhs right-hand sides stored column by column with leading dimension n.
  virtual void solve(const double* b, double* x, int nrhs = 1) = 0;
  // The block of A^{-1} on the given distinct dofs (dense, k x k column-major, in their order)
  // into inv, for the matrix A last factorized (same values): the inverse of the Schur complement
  // of A onto those dofs, from a factorization of A with them ordered last, whose trailing
  // triangle is the Schur complement's Cholesky factor (dense LAPACK: potri). It does not touch
  // the factor of factorize(). Returns false where the solver cannot (then use solve() with the
  // unit columns); the base class cannot.
  virtual bool inverseBlock(const CsrMatrix& A, const std::vector<int>& dofs,
                            std::vector<double>& inv) {
    (void)A, (void)dofs, (void)inv;
    return false;
  }
  // The bytes inverseBlock(A, dofs, inv) will allocate at its peak, inv included, all freed but
  // inv before it returns (CHOLMOD: the analysis with the dofs last, that factor and its
  // factorization's transient, the trailing triangle), told from that analysis alone, made now
  // and not kept. A is the matrix factorize() was given or will be given (its analysis, as
  // predictFactorMemory's, is the order the dofs are moved behind). CHOLMOD's workspace, which it
  // keeps and grows only for a larger matrix than before, is not counted. Negative where the
  // solver has no inverse block.
  virtual std::ptrdiff_t predictInverseBlockMemory(const CsrMatrix& A,
                                                   const std::vector<int>& dofs) {
    (void)A, (void)dofs;
    return -1;
  }
  // The bytes a solve of nrhs columns of n rows (the factor's rows once there is one) would
  // leave with this solver beyond what it keeps now, for as long as its factor lives: Tacho's
  // workspace, kept at the widest solve of the factor (the explicit dual operator's assembly by
  // solves, 128 columns a time, leaves an n x 128 array with every subdomain's solver); 0 for the
  // others, whose solves leave nothing per solver (CHOLMOD's solve vectors are the process's, not a
  // factor's).
  virtual std::size_t solveKeeps(std::size_t n, int nrhs) const {
    (void)n, (void)nrhs;
    return 0;
  }
  // Memory held by the factor (values and indices), in bytes: what one solve streams.
  virtual std::size_t factorBytes() const = 0;
  // The bytes factorize(A) will allocate for its factor, told from A's symbolic analysis alone
  // (made now and kept for factorize(A), so nothing is analysed twice): 0 where factorize(A)
  // would refactorize the present factor in place; negative where the solver cannot tell before
  // it factorizes (Amesos2's). FetiSolver compares the subdomains' sum with the nodes' memory
  // before it factorizes any of them (tfeti_NodeMemory.hpp).
  virtual std::ptrdiff_t predictFactorMemory(const CsrMatrix& A) {
    (void)A;
    return -1;
  }
  // The bytes factorize(A) will allocate beyond its factor at its peak and free before it
  // returns (CHOLMOD: a permuted copy of A's triangle, and the supernodal update matrix), from
  // the same analysis as predictFactorMemory(A); negative where the solver cannot tell, or for a
  // refactorization in place.
  virtual std::ptrdiff_t predictFactorTransient(const CsrMatrix& A) {
    (void)A;
    return -1;
  }
  // The bytes the present factor holds, as predictFactorMemory counts them (CHOLMOD: its
  // supernodal values unpacked, the index arrays); factorBytes() where the solver cannot tell.
  virtual std::size_t factorMemory() const { return factorBytes(); }
  virtual std::string name() const = 0;
};

// What a factorization (or a set-up around one) will allocate, told before it: held, the bytes
// it keeps; transient, those it allocates beyond at its peak and frees before it returns.
// Negative where the solver cannot tell.
struct MemoryPrediction {
  std::ptrdiff_t held = 0, transient = 0;
  bool known() const { return held >= 0 && transient >= 0; }
};

// Symbolic analyses (fill-reducing orderings and symbolic factors) made by the local solvers of
// this process, and factorizations that shared the analysis of a live factor with the same
// sparsity pattern instead (CHOLMOD; Amesos2's solvers analyse every matrix and count nothing).
struct LocalAnalysisCounts {
  long long made = 0, shared = 0;
};
LocalAnalysisCounts localAnalysisCounts();

// The bytes CHOLMOD holds for this process's local solvers, by its own count (factors, symbolic
// analyses and its workspace): what predictFactorMemory is checked against.
std::size_t localSolverMemoryInUse();
// The peak of that count since the last reset (reset = true restarts it from now).
std::size_t localSolverMemoryPeak(bool reset = false);

// Local solver types this build offers: "cholmod" (CHOLMOD choosing simplicial or supernodal
// per matrix), "cholmod-simplicial", "cholmod-supernodal" (the kind forced), "klu2", "tacho".
const std::vector<std::string>& localSolverTypes();

// Creates a local solver by type name; an unknown name is an error listing the valid ones.
std::unique_ptr<LocalSolver> createLocalSolver(const std::string& type);

}  // namespace tfeti
