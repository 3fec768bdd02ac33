#pragma once
// The explicit local dual operators (FETI "Dual operator" = explicit, docs/dual_operator.md):
// every local subdomain s keeps F_s = B_s K_s+ B_s^T as a dense symmetric matrix, B_s the
// columns of B on the subdomain's dofs restricted to the m_s rows that touch it. Then
//   F x = sum_s R_s^T F_s R_s x      (R_s: the rows of subdomain s)
// is applied as: import x onto the rows touching this rank's subdomains (one Tpetra Import),
// one dense symmetric matrix-vector product (BLAS-2) per subdomain, export-add back (the same
// Import in reverse). F_s is assembled from the Schur complement of K_reg onto the dofs B_s
// touches (dense LAPACK on the trailing block of a factorization with those dofs last), or with
// multi-right-hand-side solves: K_s+ applied to the dense columns of B_s^T, a block of columns
// at a time (BLAS-3 in CHOLMOD's supernodal solve); BlockAssembly below.
//
// Device (FETI "Explicit device" = gpu, a TFETI_ENABLE_CUDA build): the blocks are also held
// on a CUDA device (batched_dual::DeviceBlocks, gpu/src/; packed storage as the upper triangle
// by 32 x 32 tiles, full storage full), and every apply gathers the rank's stacked x_s once into
// pinned memory, applies all blocks by one kernel, and scatters the stacked y_s back; the Import
// and Export are unchanged. A reassembled block is copied over its old one on the device.
//
// Staleness: every block records the factorization it came from (Subdomain::factorVersion());
// apply() reassembles any block whose subdomain was refactorized since, so a K+ that changes
// under the operator cannot be applied with an old F_s. A new operator built after update() (new
// rows, same factors) takes over the blocks of the previous one whose subdomain, factorization
// and rows B_s (by their local pattern and coefficients) are unchanged; where only some rows
// changed (contact rows moving in a nonlinear loop), it keeps the old block's values for the
// unchanged rows and solves only for the others.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "tfeti_Subdomain.hpp"
#include "tfeti_Tearing.hpp"
#include "tfeti_Types.hpp"

namespace batched_dual {
class DeviceBlocks;
}

namespace tfeti {

// How a dense symmetric F_s is stored: the upper triangle packed (m(m+1)/2 values, BLAS dspmv)
// or the full column-major square (m^2 values, BLAS dsymv). docs/dual_operator.md: measured.
enum class DenseStorage { Packed, Full };

DenseStorage parseDenseStorage(const std::string& name);
// Bytes of one m x m F_s in that storage: 8 m(m+1)/2 packed, 8 m^2 full.
std::size_t explicitBlockBytes(DenseStorage storage, std::size_t m);
// What assembling one block of m rows takes beyond its stored values while it is made, as the
// memory check and the dry run count it: its dense m x m values; in a reassembly on the same
// factor, the old block's values copied full first (oldRows of them, 0 for none); then, from the
// Schur complement, the k dofs B_s touches and the inverse block's peak
// (Subdomain::predictInverseBlockMemory: the second factor and its factorization included).
double explicitSchurTransient(double inverseBlockPeak, std::size_t k, std::size_t m,
                              std::size_t oldRows);
// The same by solves with K+ on n dofs for `solved` of the m columns, kColumnsPerSolve at a
// time: their right-hand sides, solutions and the subdomain's scratch, and the local solver's
// solve vectors counted as three of those (a bound).
double explicitSolvesTransient(std::size_t n, std::size_t m, std::size_t solved,
                               std::size_t oldRows);
// The widest solve with K+ of an assembly that solves for `solved` columns: kColumnsPerSolve, or
// all of them where they are fewer (what a local solver's solve may keep: Tacho's workspace).
int explicitSolveWidth(std::size_t solved);

// How a block is assembled anew (FETI "Explicit assembly"): schur: F_s = C_s Z_s C_s^T, Z_s the
// block of K_s+ on the dofs B_s touches (C_s: B_s's columns there), the inverse of the Schur
// complement of K_reg onto them, from one factorization of K_reg with those dofs ordered last
// (Subdomain::pseudoInverseBlock); solves: K_s+ applied to the columns of B_s^T. A subdomain
// whose K was released, or whose local solver offers no inverse block (Amesos2's), takes the
// solves; so do the changed rows of a partial reassembly.
enum class BlockAssembly { Schur, Solves };
BlockAssembly parseBlockAssembly(const std::string& name);

// Where the F_s are applied: on the host by BLAS-2, or on a CUDA device (gpu).
enum class ExplicitDevice { Host, Gpu };
ExplicitDevice parseExplicitDevice(const std::string& name);
// FETI "Explicit device" against "Dual operator", this build and this machine: throws
// std::invalid_argument naming the parameter where gpu cannot be had (an implicit operator, no
// CUDA in the build, no device visible).
void checkExplicitDevice(const std::string& dualOperator, ExplicitDevice device);

class ExplicitDualOperator {
 public:
  // tearing: B's rows by local subdomain (tearing.subdomainRows) and the multiplier map;
  // subdomains: the local subdomains in the same order. previous (may be null): an operator
  // whose unchanged blocks are taken over instead of being assembled again.
  // device = Gpu: throws std::invalid_argument naming FETI "Explicit device" when this build
  // has no CUDA or no device is visible, std::runtime_error when the device cannot hold the
  // blocks. releaseStiffness: every subdomain's K is freed (Subdomain::releaseStiffness) once
  // its block is assembled or taken over, so that the Schur assembly, which needs K, does not
  // keep every K until the last block (FETI "Keep subdomain matrices" = false).
  ExplicitDualOperator(const Tearing& tearing, std::vector<std::shared_ptr<Subdomain>> subdomains,
                       DenseStorage storage, const ExplicitDualOperator* previous = nullptr,
                       ExplicitDevice device = ExplicitDevice::Host,
                       BlockAssembly assembly = BlockAssembly::Schur,
                       bool releaseStiffness = false);

  // How an operator constructed with these arguments would come by a local subdomain's block:
  // taken over from previous as it is (the same factor and the same rows of B, in the same
  // storage), sharing its values; or assembled into new values while previous still holds the
  // old ones (the memory check of FetiSolver counts them): anew (oldRows < 0, every row
  // solved), or in part from previous's block of oldRows rows on the same factor, the unchanged
  // rows' values kept and the `solved` others solved for.
  struct PlannedBlock {
    bool takenOver = false;
    int rows = 0, oldRows = -1, solved = 0;
  };
  static std::vector<PlannedBlock> plannedBlocks(
      const Tearing& tearing, const std::vector<std::shared_ptr<Subdomain>>& subdomains,
      DenseStorage storage, const ExplicitDualOperator* previous);

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
  // Columns of F_s computed by solves in those assemblies: m_s for a block assembled anew; for a
  // block whose factor was kept and only some rows changed (contact rows after update()), the
  // changed rows alone: the kept rows' part of the previous block is reused.
  long long assembledColumns() const { return assembledColumns_; }
  // The rows of those blocks: the columns that assembling each of them anew would have solved.
  long long assembledRows() const { return assembledRows_; }
  // Of those blocks, the ones assembled from the Schur complement (BlockAssembly::Schur); their
  // m_s columns count in assembledColumns() too.
  long long schurAssemblies() const { return schurAssemblies_; }
  double assemblySeconds() const { return assemblySeconds_; }
  // Writes this rank's blocks to `file`: "TFETIF01", int64 block count, then per block int64 m
  // and m*m doubles (full, column-major), all little-endian as the machine writes them
  // (gpu/README.md reads it). Throws std::runtime_error naming the file when it cannot write.
  void exportBlocks(const std::string& file) const;

  // The device's work on this rank (all 0 on the host): applies (one per vector), the kernels'
  // seconds and the applies' seconds with the host gather/scatter and transfers; per apply the
  // bytes the kernel streams (every F_s once, x and y) and those crossing to and from the device.
  struct DeviceWork {
    long long applies = 0;
    double kernelSeconds = 0.0, applySeconds = 0.0, kernelBytes = 0.0, transferBytes = 0.0;
    // Another operator's work after this one's: counts and seconds add up, the bytes per apply
    // are the latest operator's that applied.
    void add(const DeviceWork& w) {
      applies += w.applies;
      kernelSeconds += w.kernelSeconds;
      applySeconds += w.applySeconds;
      if (w.applies > 0) {
        kernelBytes = w.kernelBytes;
        transferBytes = w.transferBytes;
      }
    }
  };
  DeviceWork deviceWork() const;

 private:
  // Block i from its subdomain's factor; with `old` (the previous operator's block of the same
  // subdomain and factorization), only the rows not among old's are solved for.
  void assemble(std::size_t i, const Block* old = nullptr) const;
  void refreshStale() const;
  // Block b full and column-major into out (m^2 values), from either storage.
  void writeFull(const Block& b, double* out) const;
  std::vector<double> fullValues(const Block& b) const;
  void uploadBlocks();
  // yo += blockdiag(F_s) xo on the overlap map: BLAS-2 per block, or the device's batch.
  void applyOnHost(const MultiVector& xo, MultiVector& yo) const;
  void applyOnDevice(const MultiVector& xo, MultiVector& yo) const;
  std::vector<std::shared_ptr<Subdomain>> subdomains_;
  DenseStorage storage_;
  Teuchos::RCP<const Map> multiplierMap_, overlapMap_;
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> import_;
  mutable std::vector<Block> blocks_;
  BlockAssembly assembly_;
  mutable long long assemblies_ = 0, assembledColumns_ = 0, assembledRows_ = 0,
                    schurAssemblies_ = 0;
  mutable double assemblySeconds_ = 0.0;
  mutable Teuchos::RCP<MultiVector> xo_, yo_, sum_;
  mutable std::vector<double> xb_, yb_;
  ExplicitDevice device_ = ExplicitDevice::Host;
  std::shared_ptr<batched_dual::DeviceBlocks> deviceBlocks_;  // Gpu only
  std::vector<std::size_t> vecOffset_;                        // block s's x_s in the stacked x
};

}  // namespace tfeti
