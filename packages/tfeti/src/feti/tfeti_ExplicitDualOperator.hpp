#pragma once
// The explicit local dual operators (FETI "Dual operator" = explicit, docs/dual_operator.md):
// every local subdomain s keeps F_s = B_s K_s+ B_s^T as a dense symmetric matrix, B_s the
// columns of B on the subdomain's dofs restricted to the m_s rows that touch it. Then
//   F x = sum_s R_s^T F_s R_s x      (R_s: the rows of subdomain s)
// is applied as: import x onto the rows touching this rank's subdomains (one Tpetra Import),
// one dense symmetric matrix-vector product (BLAS-2) per subdomain, export-add back (the same
// Import in reverse). F_s is assembled with multi-right-hand-side solves: K_s+ applied to the
// dense columns of B_s^T, a block of columns at a time (BLAS-3 in CHOLMOD's supernodal solve).
//
// Staleness: every block records the factorization it came from (Subdomain::factorVersion());
// apply() reassembles any block whose subdomain was refactorized since, so a K+ that changes
// under the operator cannot be applied with an old F_s. A new operator built after update() (new
// rows, same factors) takes over the blocks of the previous one whose subdomain, factorization
// and rows B_s (by their local pattern and coefficients) are unchanged.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "tfeti_Subdomain.hpp"
#include "tfeti_Tearing.hpp"
#include "tfeti_Types.hpp"

namespace tfeti {

// How a dense symmetric F_s is stored: the upper triangle packed (m(m+1)/2 values, BLAS dspmv)
// or the full column-major square (m^2 values, BLAS dsymv). docs/dual_operator.md: measured.
enum class DenseStorage { Packed, Full };

DenseStorage parseDenseStorage(const std::string& name);

class ExplicitDualOperator {
 public:
  // tearing: B's rows by local subdomain (tearing.subdomainRows) and the multiplier map;
  // subdomains: the local subdomains in the same order. previous (may be null): an operator
  // whose unchanged blocks are taken over instead of being assembled again.
  ExplicitDualOperator(const Tearing& tearing, std::vector<std::shared_ptr<Subdomain>> subdomains,
                       DenseStorage storage, const ExplicitDualOperator* previous = nullptr);

  // Y = alpha F X + beta Y on the multiplier map (collective: one Import and one Export).
  void apply(const MultiVector& X, MultiVector& Y, Scalar alpha, Scalar beta) const;

  struct Block {
    int subdomainId = -1;
    unsigned long long version = 0;  // Subdomain::factorVersion() it was assembled from
    // B_s: the (local row, dof, coefficient) entries sorted by row then dof; rows are numbered
    // 0 .. m-1 in increasing global row id, overlap[] their positions in the overlap map.
    std::vector<int> entryRow, entryDof;
    std::vector<double> entryCoef;
    std::vector<LO> overlap;
    // Packed upper or full column-major, as storage(); shared with an operator taking it over.
    std::shared_ptr<const std::vector<double>> F;
    int rows() const { return static_cast<int>(overlap.size()); }
  };
  const std::vector<Block>& blocks() const { return blocks_; }
  DenseStorage storage() const { return storage_; }
  // The dense block of local subdomain i as a full column-major m x m matrix (tests, export).
  std::vector<double> fullBlock(std::size_t i) const;
  // Bytes of the F_s of this rank.
  std::size_t bytes() const;
  // Blocks assembled (not taken over) since construction, reassemblies after a refactorization
  // included; and the wall time that took on this rank.
  long long assemblies() const { return assemblies_; }
  double assemblySeconds() const { return assemblySeconds_; }
  // Writes this rank's blocks to `file`: "TFETIF01", int64 block count, then per block int64 m
  // and m*m doubles (full, column-major), all little-endian as the machine writes them
  // (gpu/README.md reads it). Throws std::runtime_error naming the file when it cannot write.
  void exportBlocks(const std::string& file) const;

 private:
  void assemble(std::size_t i) const;
  void refreshStale() const;
  std::vector<std::shared_ptr<Subdomain>> subdomains_;
  DenseStorage storage_;
  Teuchos::RCP<const Map> multiplierMap_, overlapMap_;
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> import_;
  mutable std::vector<Block> blocks_;
  mutable long long assemblies_ = 0;
  mutable double assemblySeconds_ = 0.0;
  mutable Teuchos::RCP<MultiVector> xo_, yo_, sum_;
  mutable std::vector<double> xb_, yb_;
};

}  // namespace tfeti
