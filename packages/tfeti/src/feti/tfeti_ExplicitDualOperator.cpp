#include "tfeti_ExplicitDualOperator.hpp"

#include <Tpetra_Import.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <fstream>
#include <map>
#include <numeric>
#include <stdexcept>
#include <tuple>

#ifdef TFETI_HAVE_CUDA
#include "batched_dual_device.hpp"
#endif

// The system BLAS that Trilinos links (Teuchos::BLAS offers no symmetric matrix-vector product).
extern "C" {
void dspmv_(const char* uplo, const int* n, const double* alpha, const double* ap, const double* x,
            const int* incx, const double* beta, double* y, const int* incy);
void dsymv_(const char* uplo, const int* n, const double* alpha, const double* a, const int* lda,
            const double* x, const int* incx, const double* beta, double* y, const int* incy);
}

namespace tfeti {

namespace {
// Right-hand sides per multi-column solve: enough for CHOLMOD's supernodal BLAS-3 solve, small
// enough that the dense block of B_s^T and its solution (2 x n x 128 doubles) stay a few MiB.
constexpr int kColumnsPerSolve = 128;

using Entry = std::tuple<GO, int, double>;  // global row, dof, coefficient

// The subdomain's rows as a block: entries sorted by (row, dof), rows numbered locally.
ExplicitDualOperator::Block blockPattern(int id, const std::vector<RowEntry>& rows,
                                         std::vector<GO>& globalRows) {
  std::vector<Entry> e;
  e.reserve(rows.size());
  for (const auto& r : rows) e.emplace_back(r.row, r.dof, r.coef);
  std::sort(e.begin(), e.end());
  ExplicitDualOperator::Block b;
  b.subdomainId = id;
  globalRows.clear();
  for (const auto& [row, dof, coef] : e) {
    if (globalRows.empty() || globalRows.back() != row) globalRows.push_back(row);
    b.entryRow.push_back(static_cast<int>(globalRows.size()) - 1);
    b.entryDof.push_back(dof);
    b.entryCoef.push_back(coef);
  }
  return b;
}

bool samePattern(const ExplicitDualOperator::Block& a, const ExplicitDualOperator::Block& b) {
  return a.entryRow == b.entryRow && a.entryDof == b.entryDof && a.entryCoef == b.entryCoef;
}

// The previous operator's blocks by subdomain id, where its storage is the new one's (none
// otherwise: nothing is taken over across storages).
std::map<int, const ExplicitDualOperator::Block*> blocksById(const ExplicitDualOperator* previous,
                                                             DenseStorage storage) {
  std::map<int, const ExplicitDualOperator::Block*> old;
  if (previous && previous->storage() == storage)
    for (const auto& b : previous->blocks()) old[b.subdomainId] = &b;
  return old;
}

// Subdomain s's block among them where it was assembled from s's present factor: what a new
// block of s takes over (the same rows) or starts from (other rows); null where there is none.
const ExplicitDualOperator::Block* onSameFactor(
    const std::map<int, const ExplicitDualOperator::Block*>& old, const Subdomain& s) {
  const auto it = old.find(s.id());
  return it != old.end() && it->second->version == s.factorVersion() ? it->second : nullptr;
}

}  // namespace

std::size_t explicitBlockBytes(DenseStorage storage, std::size_t m) {
  return sizeof(double) * (storage == DenseStorage::Packed ? m * (m + 1) / 2 : m * m);
}

double explicitSchurTransient(double inverseBlockPeak, std::size_t k, std::size_t m,
                              std::size_t oldRows) {
  const double mm = static_cast<double>(m), mo = static_cast<double>(oldRows);
  return sizeof(double) * mm * mm +
         std::max(sizeof(double) * mo * mo,
                  sizeof(int) * static_cast<double>(k) + inverseBlockPeak);
}

double explicitSolvesTransient(std::size_t n, std::size_t m, std::size_t solved,
                               std::size_t oldRows) {
  const double mm = static_cast<double>(m), mo = static_cast<double>(oldRows);
  const double columns = static_cast<double>(n) * std::min<std::size_t>(kColumnsPerSolve, solved);
  return sizeof(double) * (mm * mm + std::max(mo * mo, 6.0 * columns));
}

int explicitSolveWidth(std::size_t solved) {
  return static_cast<int>(std::min<std::size_t>(kColumnsPerSolve, solved));
}

DenseStorage parseDenseStorage(const std::string& name) {
  if (name == "packed") return DenseStorage::Packed;
  if (name == "full") return DenseStorage::Full;
  throw std::invalid_argument("explicit dual operator storage \"" + name +
                              "\" is not one of: packed, full");
}

BlockAssembly parseBlockAssembly(const std::string& name) {
  if (name == "schur") return BlockAssembly::Schur;
  if (name == "solves") return BlockAssembly::Solves;
  throw std::invalid_argument("FETI \"Explicit assembly\" \"" + name +
                              "\" is not one of: schur, solves");
}

ExplicitDevice parseExplicitDevice(const std::string& name) {
  if (name == "host") return ExplicitDevice::Host;
  if (name == "gpu") return ExplicitDevice::Gpu;
  throw std::invalid_argument("FETI \"Explicit device\" \"" + name + "\" is not one of: host, gpu");
}

void checkExplicitDevice(const std::string& dualOperator, ExplicitDevice device) {
  if (device != ExplicitDevice::Gpu) return;
  if (dualOperator != "explicit" && dualOperator != "auto")
    throw std::invalid_argument(
        "FETI \"Explicit device\" = gpu applies the explicit F_s: it needs \"Dual operator\" = "
        "explicit or auto (this run has " +
        dualOperator + ")");
#ifdef TFETI_HAVE_CUDA
  std::string why;
  if (!batched_dual::deviceAvailable(why))
    throw std::invalid_argument("FETI \"Explicit device\" = gpu: " + why);
#else
  throw std::invalid_argument(
      "FETI \"Explicit device\" = gpu: this build has no CUDA (configure with "
      "-DTFETI_ENABLE_CUDA=ON where nvcc is found; docs/dual_operator.md)");
#endif
}

ExplicitDualOperator::ExplicitDualOperator(const Tearing& tearing,
                                           std::vector<std::shared_ptr<Subdomain>> subdomains,
                                           DenseStorage storage,
                                           const ExplicitDualOperator* previous,
                                           ExplicitDevice device, BlockAssembly assembly,
                                           bool releaseStiffness)
    : subdomains_(std::move(subdomains)),
      storage_(storage),
      multiplierMap_(tearing.multiplierMap),
      assembly_(assembly),
      device_(device) {
  // Before any assembly: a run asking for a device it cannot have stops at once.
  checkExplicitDevice("explicit", device_);
  if (tearing.subdomainRows.size() != subdomains_.size())
    throw std::logic_error("ExplicitDualOperator: " + std::to_string(subdomains_.size()) +
                           " subdomains, rows for " + std::to_string(tearing.subdomainRows.size()));
  std::vector<std::vector<GO>> rowsOf(subdomains_.size());
  std::vector<GO> all;
  for (std::size_t i = 0; i < subdomains_.size(); ++i) {
    blocks_.push_back(blockPattern(subdomains_[i]->id(), tearing.subdomainRows[i], rowsOf[i]));
    all.insert(all.end(), rowsOf[i].begin(), rowsOf[i].end());
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  overlapMap_ =
      Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                           Teuchos::ArrayView<const GO>(all), 0, multiplierMap_->getComm()));
  import_ = Teuchos::rcp(new Tpetra::Import<LO, GO, Node>(multiplierMap_, overlapMap_));
  const auto old = blocksById(previous, storage_);
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    Block& b = blocks_[i];
    for (GO row : rowsOf[i]) b.overlap.push_back(overlapMap_->getLocalElement(row));
    const Block* same = onSameFactor(old, *subdomains_[i]);
    if (same && samePattern(*same, b)) {
      b.F = same->F;
      b.version = same->version;
    } else {
      // Same factor, other rows (contact rows moved): the rows whose entries are unchanged keep
      // their part of the old block, and only the others are solved for.
      assemble(i, same);
    }
    if (releaseStiffness) subdomains_[i]->releaseStiffness();
  }
  if (device_ == ExplicitDevice::Gpu) uploadBlocks();
}

void ExplicitDualOperator::writeFull(const Block& b, double* out) const {
  const std::size_t m = static_cast<std::size_t>(b.rows());
  if (storage_ == DenseStorage::Full) {
    std::copy(b.F->begin(), b.F->end(), out);
    return;
  }
  for (std::size_t j = 0; j < m; ++j)
    for (std::size_t r = 0; r <= j; ++r)
      out[j * m + r] = out[r * m + j] = (*b.F)[r + j * (j + 1) / 2];
}

std::vector<double> ExplicitDualOperator::fullValues(const Block& b) const {
  std::vector<double> full(static_cast<std::size_t>(b.rows()) * b.rows());
  writeFull(b, full.data());
  return full;
}

void ExplicitDualOperator::uploadBlocks() {
#ifdef TFETI_HAVE_CUDA
  std::vector<int> rows;
  std::size_t vector = 0, count = 0;
  vecOffset_.clear();
  for (const Block& b : blocks_) {
    rows.push_back(b.rows());
    vecOffset_.push_back(vector);
    vector += static_cast<std::size_t>(b.rows());
    count += static_cast<std::size_t>(b.rows()) * b.rows();
  }
  // Every block full, one after the other, as DeviceBlocks takes them. Packed on the host is
  // the upper triangle by 32 x 32 tiles on the device (about half the bytes), full is full.
  std::vector<double> values(count);
  for (std::size_t i = 0, at = 0; i < blocks_.size(); ++i) {
    writeFull(blocks_[i], values.data() + at);
    at += static_cast<std::size_t>(blocks_[i].rows()) * blocks_[i].rows();
  }
  deviceBlocks_ = std::make_shared<batched_dual::DeviceBlocks>(
      rows, values,
      storage_ == DenseStorage::Packed ? batched_dual::Storage::SymmetricTiles
                                       : batched_dual::Storage::Full);
#endif
}

void ExplicitDualOperator::applyOnDevice(const MultiVector& xo, MultiVector& yo) const {
#ifdef TFETI_HAVE_CUDA
  batched_dual::DeviceBlocks& dev = *deviceBlocks_;
  for (std::size_t j = 0; j < xo.getNumVectors(); ++j) {
    auto x = xo.getData(j);
    auto y = yo.getDataNonConst(j);
    double* hx = dev.hostX();
    for (std::size_t s = 0; s < blocks_.size(); ++s)
      for (int r = 0; r < blocks_[s].rows(); ++r) hx[vecOffset_[s] + r] = x[blocks_[s].overlap[r]];
    dev.apply();
    const double* hy = dev.hostY();
    for (std::size_t s = 0; s < blocks_.size(); ++s)
      for (int r = 0; r < blocks_[s].rows(); ++r) y[blocks_[s].overlap[r]] += hy[vecOffset_[s] + r];
  }
#endif
}

ExplicitDualOperator::DeviceWork ExplicitDualOperator::deviceWork() const {
  DeviceWork w;
#ifdef TFETI_HAVE_CUDA
  if (deviceBlocks_) {
    w.applies = deviceBlocks_->applies();
    w.kernelSeconds = deviceBlocks_->kernelSeconds();
    w.applySeconds = deviceBlocks_->applySeconds();
    w.kernelBytes = deviceBlocks_->kernelBytes();
    w.transferBytes = deviceBlocks_->transferBytes();
  }
#endif
  return w;
}

namespace {

using Block = ExplicitDualOperator::Block;

// Where each local row's entries start (entries are sorted by row): m + 1 offsets.
std::vector<std::size_t> rowStarts(const Block& b) {
  std::vector<std::size_t> first(b.rows() + 1, 0);
  for (int r : b.entryRow) ++first[r + 1];
  std::partial_sum(first.begin(), first.end(), first.begin());
  return first;
}

// Row r of a block: its (dof, coefficient) entries, in the block's order (by dof).
std::vector<std::pair<int, double>> rowEntries(const Block& b,
                                               const std::vector<std::size_t>& first, int r) {
  std::vector<std::pair<int, double>> e;
  for (std::size_t k = first[r]; k < first[r + 1]; ++k)
    e.emplace_back(b.entryDof[k], b.entryCoef[k]);
  return e;
}

// For each row of b, the row of `old` with exactly its entries, -1 where old has none (or no
// old block): F_s(r, q) = b_r^T K+ b_q depends on nothing else, so on the same factor the kept
// rows' part of F_s is old's.
std::vector<int> keptRows(const Block& b, const std::vector<std::size_t>& first, const Block* old) {
  std::vector<int> from(b.rows(), -1);
  if (!old) return from;
  const std::vector<std::size_t> oldFirst = rowStarts(*old);
  std::map<std::vector<std::pair<int, double>>, int> oldRows;
  for (int r = 0; r < old->rows(); ++r) oldRows.emplace(rowEntries(*old, oldFirst, r), r);
  for (int r = 0; r < b.rows(); ++r) {
    const auto it = oldRows.find(rowEntries(b, first, r));
    if (it != oldRows.end()) from[r] = it->second;
  }
  return from;
}

// full (m x m, column-major) at the kept rows and columns from old's full values (mo x mo).
void copyKept(const std::vector<int>& from, const std::vector<double>& oldFull, std::size_t mo,
              std::vector<double>& full) {
  const std::size_t m = from.size();
  for (std::size_t q = 0; q < m; ++q)
    for (std::size_t r = 0; r < m; ++r)
      if (from[q] >= 0 && from[r] >= 0) full[q * m + r] = oldFull[from[q] * mo + from[r]];
}

// The columns `solved` of F_s = B_s K+ B_s^T into full (m x m, column-major), kColumnsPerSolve
// right-hand sides per solve; where a row is not solved for, its row is filled from the columns
// (F_s symmetric), so that full is complete.
void solveColumns(const Block& b, const std::vector<std::size_t>& first,
                  const std::vector<int>& solved, Subdomain& s, std::vector<double>& full) {
  const int n = s.numDofs(), m = b.rows();
  std::vector<char> isSolved(m, 0);
  for (int c : solved) isSolved[c] = 1;
  std::vector<double> rhs, sol;
  for (std::size_t c0 = 0; c0 < solved.size(); c0 += kColumnsPerSolve) {
    const int w = static_cast<int>(std::min<std::size_t>(kColumnsPerSolve, solved.size() - c0));
    rhs.assign(static_cast<std::size_t>(n) * w, 0.0);
    sol.resize(rhs.size());
    for (int c = 0; c < w; ++c) {
      const int col = solved[c0 + c];
      for (std::size_t k = first[col]; k < first[col + 1]; ++k)
        rhs[static_cast<std::size_t>(c) * n + b.entryDof[k]] += b.entryCoef[k];
    }
    s.applyPseudoInverse(rhs.data(), sol.data(), w);
    for (int c = 0; c < w; ++c) {
      const int col = solved[c0 + c];
      const double* x = sol.data() + static_cast<std::size_t>(c) * n;
      double* f = full.data() + static_cast<std::size_t>(col) * m;
      for (std::size_t k = 0; k < b.entryRow.size(); ++k)
        f[b.entryRow[k]] += b.entryCoef[k] * x[b.entryDof[k]];
      for (int r = 0; r < m; ++r)
        if (!isSolved[r]) full[static_cast<std::size_t>(r) * m + col] = f[r];
    }
  }
}

// The distinct dofs a block's rows touch, in increasing order.
std::vector<int> touchedDofs(const Block& b) {
  std::vector<int> dofs(b.entryDof);
  std::sort(dofs.begin(), dofs.end());
  dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
  return dofs;
}

// full += C Z C^T (m x m, column-major), C the block's rows on the k dofs (E entries, each at its
// dof's place at[e] in Z's k x k, column-major). Column q is the sum over its entries l of
// c_l C Z(:, at_l), taken the cheaper way: entry by entry (E multiply-adds per entry l), or
// through w = sum of c_l Z(:, at_l) and then C w (k per entry l, E once). A gluing row has one
// entry, and its column goes the first way; a mortar contact row has tens, and its column the
// second: on a 3D tetrahedral subdomain with 37,040 entries in 2429 rows the first way alone
// made the larger part of the assembly.
void addCongruence(const Block& b, const std::vector<std::size_t>& first,
                   const std::vector<double>& Z, std::size_t k, const std::vector<std::size_t>& at,
                   std::vector<double>& full) {
  const std::size_t m = static_cast<std::size_t>(b.rows()), E = at.size();
  std::vector<double> w(k);
  for (std::size_t q = 0; q < m; ++q) {
    double* f = full.data() + q * m;
    const std::size_t Eq = first[q + 1] - first[q];
    if (Eq * E <= Eq * k + E) {
      for (std::size_t l = first[q]; l < first[q + 1]; ++l) {
        const double* z = Z.data() + at[l] * k;
        const double cl = b.entryCoef[l];
        for (std::size_t e = 0; e < E; ++e) f[b.entryRow[e]] += cl * b.entryCoef[e] * z[at[e]];
      }
    } else {
      std::fill(w.begin(), w.end(), 0.0);
      for (std::size_t l = first[q]; l < first[q + 1]; ++l) {
        const double* z = Z.data() + at[l] * k;
        const double cl = b.entryCoef[l];
        for (std::size_t i = 0; i < k; ++i) w[i] += cl * z[i];
      }
      for (std::size_t e = 0; e < E; ++e) f[b.entryRow[e]] += b.entryCoef[e] * w[at[e]];
    }
  }
}

// The whole of F_s = B_s K+ B_s^T into full (m x m, column-major, zero on entry) from the block
// Z of K+ on the dofs B_s touches: F_s = C Z C^T, C the rows of B_s on those dofs. False where
// the subdomain cannot give Z.
bool schurColumns(const Block& b, const std::vector<std::size_t>& first, Subdomain& s,
                  std::vector<double>& full) {
  const std::vector<int> dofs = touchedDofs(b);
  std::vector<double> Z;
  if (!s.pseudoInverseBlock(dofs, Z)) return false;
  std::vector<std::size_t> at(b.entryDof.size());  // entry -> its dof's place in dofs
  for (std::size_t e = 0; e < at.size(); ++e)
    at[e] = std::lower_bound(dofs.begin(), dofs.end(), b.entryDof[e]) - dofs.begin();
  addCongruence(b, first, Z, dofs.size(), at, full);
  return true;
}

// F_s in the given storage from full, symmetric to rounding: the mean of the two triangles.
std::shared_ptr<std::vector<double>> symmetricStorage(const std::vector<double>& full, int m,
                                                      DenseStorage storage) {
  auto F =
      std::make_shared<std::vector<double>>(explicitBlockBytes(storage, m) / sizeof(double), 0.0);
  for (int j = 0; j < m; ++j)
    for (int r = 0; r <= j; ++r) {
      const double v = 0.5 * (full[static_cast<std::size_t>(j) * m + r] +
                              full[static_cast<std::size_t>(r) * m + j]);
      if (storage == DenseStorage::Packed) {
        (*F)[r + static_cast<std::size_t>(j) * (j + 1) / 2] = v;
      } else {
        (*F)[static_cast<std::size_t>(j) * m + r] = v;
        (*F)[static_cast<std::size_t>(r) * m + j] = v;
      }
    }
  return F;
}

}  // namespace

std::vector<ExplicitDualOperator::PlannedBlock> ExplicitDualOperator::plannedBlocks(
    const Tearing& tearing, const std::vector<std::shared_ptr<Subdomain>>& subdomains,
    DenseStorage storage, const ExplicitDualOperator* previous) {
  std::vector<PlannedBlock> plan(subdomains.size());
  const auto old = blocksById(previous, storage);
  std::vector<GO> rows;
  for (std::size_t i = 0; i < subdomains.size() && i < tearing.subdomainRows.size(); ++i) {
    Block b = blockPattern(subdomains[i]->id(), tearing.subdomainRows[i], rows);
    b.overlap.assign(rows.size(), 0);  // its size is the block's row count
    PlannedBlock& p = plan[i];
    p.rows = p.solved = b.rows();
    // As the constructor and assemble() decide.
    const Block* same = onSameFactor(old, *subdomains[i]);
    if (!same) continue;
    p.oldRows = same->rows();
    p.takenOver = samePattern(*same, b);
    if (p.takenOver) {
      p.solved = 0;
      continue;
    }
    const std::vector<int> from = keptRows(b, rowStarts(b), same);
    p.solved = static_cast<int>(std::count(from.begin(), from.end(), -1));
  }
  return plan;
}

void ExplicitDualOperator::assemble(std::size_t i, const Block* old) const {
  const auto start = std::chrono::steady_clock::now();
  Block& b = blocks_[i];
  Subdomain& s = *subdomains_[i];
  const int m = b.rows();
  const std::vector<std::size_t> first = rowStarts(b);
  const std::vector<int> from = keptRows(b, first, old);
  std::vector<double> full(static_cast<std::size_t>(m) * m, 0.0);
  if (old) copyKept(from, fullValues(*old), static_cast<std::size_t>(old->rows()), full);
  std::vector<int> solved;
  for (int r = 0; r < m; ++r)
    if (from[r] < 0) solved.push_back(r);
  // A block assembled anew from the Schur complement; kept rows (few changed ones) by solves.
  const bool anew = m > 0 && static_cast<int>(solved.size()) == m;
  if (anew && assembly_ == BlockAssembly::Schur && schurColumns(b, first, s, full))
    ++schurAssemblies_;
  else
    solveColumns(b, first, solved, s, full);
  b.F = symmetricStorage(full, m, storage_);
  b.version = s.factorVersion();
  ++assemblies_;
  assembledColumns_ += static_cast<long long>(solved.size());
  assembledRows_ += m;
  assemblySeconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void ExplicitDualOperator::refreshStale() const {
  for (std::size_t i = 0; i < blocks_.size(); ++i)
    if (blocks_[i].version != subdomains_[i]->factorVersion()) {
      assemble(i);
#ifdef TFETI_HAVE_CUDA
      if (deviceBlocks_) deviceBlocks_->update(i, fullValues(blocks_[i]).data());
#endif
    }
}

void ExplicitDualOperator::apply(const MultiVector& X, MultiVector& Y, Scalar alpha,
                                 Scalar beta) const {
  refreshStale();
  const std::size_t nv = X.getNumVectors();
  if (xo_.is_null() || xo_->getNumVectors() != nv) {
    xo_ = Teuchos::rcp(new MultiVector(overlapMap_, nv));
    yo_ = Teuchos::rcp(new MultiVector(overlapMap_, nv));
    sum_ = Teuchos::rcp(new MultiVector(multiplierMap_, nv));
  }
  xo_->doImport(X, *import_, Tpetra::INSERT);
  yo_->putScalar(0.0);
  if (deviceBlocks_)
    applyOnDevice(*xo_, *yo_);
  else
    applyOnHost(*xo_, *yo_);
  sum_->putScalar(0.0);
  sum_->doExport(*yo_, *import_, Tpetra::ADD);
  Y.update(alpha, *sum_, beta);
}

void ExplicitDualOperator::applyOnHost(const MultiVector& xo, MultiVector& yo) const {
  const char uplo = 'U';
  const int one = 1;
  const double dOne = 1.0, dZero = 0.0;
  for (std::size_t j = 0; j < xo.getNumVectors(); ++j) {
    auto x = xo.getData(j);
    auto y = yo.getDataNonConst(j);
    for (const Block& b : blocks_) {
      const int m = b.rows();
      if (m == 0) continue;
      xb_.resize(m);
      yb_.resize(m);
      for (int r = 0; r < m; ++r) xb_[r] = x[b.overlap[r]];
      if (storage_ == DenseStorage::Packed)
        dspmv_(&uplo, &m, &dOne, b.F->data(), xb_.data(), &one, &dZero, yb_.data(), &one);
      else
        dsymv_(&uplo, &m, &dOne, b.F->data(), &m, xb_.data(), &one, &dZero, yb_.data(), &one);
      for (int r = 0; r < m; ++r) y[b.overlap[r]] += yb_[r];
    }
  }
}

std::vector<double> ExplicitDualOperator::fullBlock(std::size_t i) const {
  refreshStale();
  return fullValues(blocks_.at(i));
}

std::size_t ExplicitDualOperator::bytes() const {
  std::size_t total = 0;
  for (const auto& b : blocks_)
    if (b.F) total += b.F->size() * sizeof(double);
  return total;
}

void ExplicitDualOperator::exportBlocks(const std::string& file) const {
  std::ofstream out(file, std::ios::binary);
  const auto put = [&](const void* p, std::size_t bytes) {
    out.write(static_cast<const char*>(p), static_cast<std::streamsize>(bytes));
  };
  put("TFETIF01", 8);
  const std::int64_t count = static_cast<std::int64_t>(blocks_.size());
  put(&count, sizeof(count));
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    const std::vector<double> f = fullBlock(i);
    const std::int64_t m = blocks_[i].rows();
    put(&m, sizeof(m));
    put(f.data(), f.size() * sizeof(double));
  }
  if (!out) throw std::runtime_error("FETI: cannot write the explicit dual blocks to " + file);
}

}  // namespace tfeti
