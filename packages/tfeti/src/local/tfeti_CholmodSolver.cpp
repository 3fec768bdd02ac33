// CHOLMOD (SuiteSparse) sparse Cholesky behind the LocalSolver interface.
#include "tfeti_CholmodSolver.hpp"

#include <cholmod.h>
#include <dlfcn.h>
#include <Teuchos_LAPACK.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <memory>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

#include "tfeti_CholmodView.hpp"
#include "tfeti_LocalSolver.hpp"
#include "tfeti_PackedSupernodal.hpp"

namespace tfeti {
namespace {

// CHOLMOD's supernodal kernels open OpenMP parallel regions with a fixed num_threads clause (4 in
// this build; CHOLMOD 3.0 has no Common->nthreads_max). Every MPI rank here is one core, so those
// threads only compete with the other ranks: on 2 cores running 2 ranks they spent 15 % of the
// samples spinning (docs/benchmarks.md, "3D setup profile"). A max-active-levels of 0 makes every
// parallel region run on its encountering thread alone, whatever its num_threads clause.
// The OpenMP runtime is looked up rather than linked: it is present only when CHOLMOD was built
// with OpenMP. An explicit OMP_THREAD_LIMIT in the environment (e.g. one rank per node) is
// respected instead.
void keepCholmodSerial() {
  if (std::getenv("OMP_THREAD_LIMIT")) return;
  using SetLevels = void (*)(int);
  if (auto set = reinterpret_cast<SetLevels>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels")))
    set(0);
}

// One CHOLMOD workspace per process: subdomains are factorized and solved one after the other
// (Kokkos is Serial here), and a common per subdomain would multiply its workspace. The same
// holds for the dense vectors of a solve (the solution and CHOLMOD's own workspace, five vectors
// of the matrix's size): kept per factor they took 70 bytes per unknown of a 2D TFETI run, a
// third of what its subdomain matrices take (docs/benchmarks.md, "Size").
struct CholmodCommon {
  cholmod_common c;
  cholmod_dense* X = nullptr;
  cholmod_dense* Y = nullptr;
  cholmod_dense* E = nullptr;
  // The packed solves' permuted vector and workspace, and one supernode while (un)packing.
  std::vector<double> y, w, scratch;
  CholmodCommon() {
    keepCholmodSerial();
    cholmod_start(&c);
    c.print = 0;
    c.error_handler = nullptr;
    // Keep L L^T even for simplicial factors: an L D L^T factorization would accept an
    // indefinite matrix, and a subdomain matrix that is not positive definite is a bug to report.
    c.final_ll = 1;
    // Both fill-reducing orderings are computed and the one with the smaller factor kept, for
    // every factor made here (subdomains, Dirichlet interiors, the coarse G G^T). CHOLMOD's own
    // default tries METIS only when AMD's factor is large; on 3D subdomains of 8^3 Hex8
    // elements (2187 dofs) it keeps AMD, whose supernodal values are 35 % larger, with 1.6x the
    // flops and twice the factorization time of METIS's (docs/benchmarks.md, "Subdomain
    // orderings"). The second analysis is paid once per sparsity pattern.
    c.nmethods = 2;
    c.method[0].ordering = CHOLMOD_AMD;
    c.method[1].ordering = CHOLMOD_METIS;
  }
  ~CholmodCommon() {
    cholmod_free_dense(&X, &c);
    cholmod_free_dense(&Y, &c);
    cholmod_free_dense(&E, &c);
    cholmod_finish(&c);
  }
};

CholmodCommon& shared() {
  static CholmodCommon instance;
  return instance;
}

cholmod_common* common() {
  return &shared().c;
}

// CHOLMOD's factorization kind: its own choice (supernodal when flops / nnz(L) >= 40), or forced.
// The supernodal kernels call the BLAS per supernode; the simplicial ones call none. For the
// thousands of small 3D subdomain matrices of a TFETI setup the simplicial kernels took less CPU
// time with this machine's reference BLAS (docs/benchmarks.md, "3D setup profile").
enum class CholmodKind { Auto, Simplicial, Supernodal };

// One sparsity pattern's symbolic analysis (the fill-reducing ordering and the symbolic factor),
// shared by every live factor of that pattern and kind. Subdomains cut from a structured mesh
// repeat a few patterns: step-42's 64^3 cube gives 526 factorizations per rank (subdomains and
// Dirichlet interiors) of 42 patterns, and with both orderings tried the analyses took 2.8-3.0 s
// of a 40 s run (docs/benchmarks.md, "Symbolic analyses shared"). The pattern is kept here once
// instead of once per factor.
struct SymbolicAnalysis {
  CholmodKind kind;
  int n;
  std::vector<int> rowPtr, colInd;
  cholmod_factor* symbolic = nullptr;  // as cholmod_analyze returned it: no numerical values
  PackedLayout packed;                 // supernodal analyses: where the packed values go
  std::size_t numericBytes = 0;        // what a numerical factor of this analysis holds
  std::size_t transientBytes = 0;      // what its factorization allocates beyond, at the peak
  // predictInverseBlockMemory's counts by the set of dofs moved last (sorted): they depend on
  // nothing but the pattern, this analysis's order and that set, so subdomains cut alike from a
  // structured mesh, and a memory check made again at each reassembly, analyse each set once.
  // The last kTrailingSets sets asked for are kept (a set is k integers; the sets change with
  // the contact rows over a long run, the analysis may live through all of it), the oldest
  // dropped first; gone with the analysis.
  struct TrailingCounts {
    std::size_t analysisPeak, numeric, factorization;
  };
  static constexpr std::size_t kTrailingSets = 8;
  mutable std::deque<std::pair<std::vector<int>, TrailingCounts>> trailing;
  SymbolicAnalysis(CholmodKind k, const CsrMatrix& A)
      : kind(k), n(A.rows), rowPtr(A.rowPtr), colInd(A.colInd) {}
  ~SymbolicAnalysis() {
    if (symbolic) cholmod_free_factor(&symbolic, common());
  }
  SymbolicAnalysis(const SymbolicAnalysis&) = delete;
  SymbolicAnalysis& operator=(const SymbolicAnalysis&) = delete;
  bool matches(CholmodKind k, const CsrMatrix& A) const {
    return kind == k && n == A.rows && rowPtr == A.rowPtr && colInd == A.colInd;
  }
};

// FNV-1a over the pattern: the key of the analyses' table (equal patterns are then compared).
std::uint64_t patternHash(CholmodKind kind, const CsrMatrix& A) {
  std::uint64_t h = 1469598103934665603ull ^ static_cast<std::uint64_t>(kind);
  auto mix = [&h](const std::vector<int>& v) {
    for (int x : v) h = (h ^ static_cast<std::uint32_t>(x)) * 1099511628211ull;
  };
  mix(A.rowPtr);
  mix(A.colInd);
  return h;
}

// The analyses of the live factors, by pattern. It holds them weakly: an analysis lives as long
// as a factor uses it, so a process that solves one problem after another keeps none of the
// earlier ones.
class SymbolicAnalyses {
 public:
  std::shared_ptr<const SymbolicAnalysis> get(CholmodKind kind, const CsrMatrix& A) {
    const std::uint64_t key = patternHash(kind, A);
    auto range = table_.equal_range(key);
    for (auto it = range.first; it != range.second;) {
      if (auto live = it->second.lock()) {
        if (live->matches(kind, A)) {
          ++counts_.shared;
          return live;
        }
        ++it;
      } else {
        it = table_.erase(it);
      }
    }
    auto made = std::make_shared<SymbolicAnalysis>(kind, A);
    made->symbolic = analyze(kind, A);
    if (made->symbolic->is_super) made->packed = packedLayout(*made->symbolic);
    made->numericBytes = numericFactorBytes(*made->symbolic);
    made->transientBytes = factorizationTransientBytes(A, *made->symbolic, made->numericBytes);
    ++counts_.made;
    table_.emplace(key, made);
    return made;
  }
  LocalAnalysisCounts counts() const { return counts_; }

 private:
  static cholmod_factor* analyze(CholmodKind kind, const CsrMatrix& A) {
    cholmod_sparse S;
    cholmodUpperView(A, S);
    cholmod_common* c = common();
    // The workspace is shared by every factor: set the kind for this analysis only.
    const int defaultKind = c->supernodal;
    if (kind == CholmodKind::Simplicial) c->supernodal = CHOLMOD_SIMPLICIAL;
    if (kind == CholmodKind::Supernodal) c->supernodal = CHOLMOD_SUPERNODAL;
    cholmod_factor* L = cholmod_analyze(&S, c);
    c->supernodal = defaultKind;
    if (!L) throw std::runtime_error("cholmod: symbolic analysis failed");
    return L;
  }

 public:
  // The bytes CHOLMOD allocates for a numerical factor copied from this symbolic one and
  // factorized (its own count, Common->memory_inuse, agrees to the byte: CholmodPredictsItsFactor):
  // the copy's integer arrays, then the values. Supernodal: Perm and ColCount, super, pi and px,
  // the row indices s, and xsize values (the packed layout stays inside them). Simplicial L L^T:
  // Perm and ColCount, then p, i, x (nzmax = the column counts' sum), nz, next and prev.
  static std::size_t numericFactorBytes(const cholmod_factor& S) {
    const std::size_t n = S.n, header = sizeof(cholmod_factor), i = sizeof(int), d = sizeof(double);
    if (S.is_super) return header + i * (2 * n + 3 * (S.nsuper + 1) + S.ssize) + d * S.xsize;
    std::size_t nnz = 0;
    for (std::size_t j = 0; j < n; ++j) nnz += static_cast<const int*>(S.ColCount)[j];
    return header + i * (2 * n + (n + 1) + n + 2 * (n + 2)) + (i + d) * nnz;
  }
  // The bytes cholmod_factorize allocates, at its peak, beyond the factor it fills (its own
  // count agrees to the byte: CholmodPredictsItsFactor), all freed before it returns. A is
  // given as its upper triangle (stype 1) of a full symmetric pattern, and CHOLMOD first
  // permutes it into a copy A1 allocated for all of A's entries (header, p, i and x, packed).
  // Supernodal: A1 and the dense update matrix C (maxcsize values) while the values are computed.
  // Simplicial: A2, the transpose of A1 sized to the triangle, then A1 is freed and the values
  // are allocated; the peak is the larger of A1 and A2 together and A2 with the values. The
  // workspace CHOLMOD keeps between factorizations (Flag, Head, Iwork, Xwork: a few integers per
  // row of the largest matrix so far) is not counted.
  static std::size_t factorizationTransientBytes(const CsrMatrix& A, const cholmod_factor& S,
                                                 std::size_t numericBytes) {
    std::size_t upper = 0;
    for (int i = 0; i < A.rows; ++i)
      for (int k = A.rowPtr[i]; k < A.rowPtr[i + 1]; ++k) upper += A.colInd[k] <= i ? 1 : 0;
    const auto copy = [&A](std::size_t entries) {
      return sizeof(cholmod_sparse) + sizeof(int) * (A.rows + 1) +
             (sizeof(int) + sizeof(double)) * entries;
    };
    const std::size_t a1 = copy(A.nnz()), a2 = copy(upper);
    if (S.is_super) return a1 + sizeof(cholmod_dense) + sizeof(double) * S.maxcsize;
    // What the factorization adds to the copied symbolic factor (header, Perm, ColCount).
    const std::size_t values = numericBytes - sizeof(cholmod_factor) - 2 * sizeof(int) * S.n;
    return std::max(a1 + a2, a2 + values) - values;
  }

 private:
  std::unordered_multimap<std::uint64_t, std::weak_ptr<SymbolicAnalysis>> table_;
  LocalAnalysisCounts counts_;
};

SymbolicAnalyses& analyses() {
  static SymbolicAnalyses instance;
  return instance;
}

class CholmodSolver final : public LocalSolver {
 public:
  explicit CholmodSolver(CholmodKind kind) : kind_(kind) {}
  ~CholmodSolver() override { release(); }

  void factorize(const CsrMatrix& A) override {
    cholmod_sparse S;
    cholmodUpperView(A, S);
    cholmod_common* c = common();
    // A new matrix with the pattern of the last one (a Newton method's next tangent): the
    // ordering and the symbolic factor are kept, only the numbers are factorized again.
    // The factorization overwrites every value, packed or not.
    if (L_ && analysis_->matches(kind_, A)) {
      pending_.reset();
      packed_ = false;
      if (!cholmod_factorize(&S, L_, c) || c->status != CHOLMOD_OK) {
        const long minor = static_cast<long>(L_->minor);
        release();
        throw std::runtime_error("cholmod: the subdomain matrix is not positive definite (column " +
                                 std::to_string(minor) + " of " + std::to_string(A.rows) + ")");
      }
      pack();
      return;
    }
    release();
    // The analysis that predictFactorMemory(A) made, or one made (or shared) now.
    analysis_ = pending_ && pending_->matches(kind_, A) ? pending_ : analyses().get(kind_, A);
    pending_.reset();
    // The numerical factorization fills a copy of the shared symbolic factor.
    L_ = cholmod_copy_factor(analysis_->symbolic, c);
    if (!L_) throw std::runtime_error("cholmod: out of memory copying a symbolic factor");
    if (!cholmod_factorize(&S, L_, c) || c->status != CHOLMOD_OK)
      throw std::runtime_error("cholmod: the subdomain matrix is not positive definite (column " +
                               std::to_string(L_->minor) + " of " + std::to_string(A.rows) + ")");
    pack();
  }

  void solve(const double* b, double* x, int nrhs) override {
    if (packed_ && nrhs <= kPackedMaxRhs) return solvePacked(b, x, nrhs);
    CholmodCommon& w = shared();
    // Many right-hand sides (the explicit dual operator's assembly, block coarse solves): CHOLMOD's
    // BLAS-3 solve on its own layout, the factor packed again afterwards.
    const bool repack = packed_;
    if (repack) {
      unpackSupernodal(*L_, analysis_->packed, w.scratch);
      packed_ = false;
    }
    cholmod_dense B;
    std::memset(&B, 0, sizeof(B));
    B.nrow = static_cast<size_t>(L_->n);
    B.ncol = static_cast<size_t>(nrhs);
    B.nzmax = B.nrow * B.ncol;
    B.d = B.nrow;
    B.x = const_cast<double*>(b);
    B.xtype = CHOLMOD_REAL;
    B.dtype = CHOLMOD_DOUBLE;
    // CHOLMOD reallocates the shared vectors when the size changes (one matrix size to the next).
    if (!cholmod_solve2(CHOLMOD_A, L_, &B, nullptr, &w.X, nullptr, &w.Y, &w.E, &w.c))
      throw std::runtime_error("cholmod: solve failed");
    std::memcpy(x, w.X->x, sizeof(double) * B.nzmax);
    if (repack) pack();
  }

  bool inverseBlock(const CsrMatrix& A, const std::vector<int>& dofs,
                    std::vector<double>& inv) override {
    if (!L_ || !analysis_->matches(kind_, A)) return false;
    const std::vector<int> at = placesIn(dofs, A.rows);
    const std::size_t k = dofs.size();
    if (k == 0) {
      inv.clear();
      return true;
    }
    cholmod_factor* F = trailingFactor(A, at, k);
    if (!F) return false;
    std::vector<double> Lkk = trailingTriangle(*F, k);
    // The factor's order of the dofs: Lkk's rows and columns.
    const std::vector<int> order(static_cast<const int*>(F->Perm) + (A.rows - k),
                                 static_cast<const int*>(F->Perm) + A.rows);
    cholmod_free_factor(&F, common());
    int info = 0;
    Teuchos::LAPACK<int, double>().POTRI('L', static_cast<int>(k), Lkk.data(), static_cast<int>(k),
                                         &info);
    if (info != 0)
      throw std::runtime_error("cholmod: inverseBlock: LAPACK potri failed (info " +
                               std::to_string(info) + ")");
    // Made only now, with the second factor gone: the k x k arrays are the largest of it.
    inv.assign(k * k, 0.0);
    for (std::size_t j = 0; j < k; ++j)
      for (std::size_t i = j; i < k; ++i) {
        const std::size_t r = at[order[i]], c = at[order[j]];
        inv[r + c * k] = inv[c + r * k] = Lkk[i + j * k];
      }
    return true;
  }

  std::ptrdiff_t predictInverseBlockMemory(const CsrMatrix& A,
                                           const std::vector<int>& dofs) override {
    // The fill-reducing order the dofs are moved behind: the factor's, or the analysis that
    // predictFactorMemory(A) made for it.
    std::shared_ptr<const SymbolicAnalysis> a;
    if (L_ && analysis_->matches(kind_, A)) {
      a = analysis_;
    } else {
      if (!pending_ || !pending_->matches(kind_, A)) pending_ = analyses().get(kind_, A);
      a = pending_;
    }
    const std::vector<int> at = placesIn(dofs, A.rows);
    const std::size_t n = A.rows, k = dofs.size(), i = sizeof(int), d = sizeof(double);
    if (k == 0) return static_cast<std::ptrdiff_t>(n * i);
    const SymbolicAnalysis::TrailingCounts t = trailingCounts(A, *a, at, dofs);
    // inverseBlock's own: the places (n); while CHOLMOD works, the order (n); then the factor
    // with the trailing triangle (k x k) and the dofs' order (k); then, the factor freed, the
    // triangle with inv (k x k).
    return static_cast<std::ptrdiff_t>(
        n * i + std::max({n * i + std::max(t.analysisPeak, t.factorization),
                          t.numeric + k * k * d + k * i, 2 * k * k * d + k * i}));
  }

  std::size_t factorBytes() const override {
    if (!L_) return 0;
    if (L_->is_super)
      return analysis_->packed.offsets.back() * sizeof(double) + L_->ssize * sizeof(int) +
             L_->nsuper * 4 * sizeof(int);
    return L_->nzmax * (sizeof(double) + sizeof(int)) + 2 * (L_->n + 1) * sizeof(int);
  }

  std::size_t factorMemory() const override { return L_ ? analysis_->numericBytes : 0; }

  std::ptrdiff_t predictFactorMemory(const CsrMatrix& A) override {
    if (L_ && analysis_->matches(kind_, A)) return 0;  // refactorized in place
    if (!pending_ || !pending_->matches(kind_, A)) pending_ = analyses().get(kind_, A);
    return static_cast<std::ptrdiff_t>(pending_->numericBytes);
  }

  std::ptrdiff_t predictFactorTransient(const CsrMatrix& A) override {
    if (L_ && analysis_->matches(kind_, A)) return -1;  // a refactorization in place: not told
    if (!pending_ || !pending_->matches(kind_, A)) pending_ = analyses().get(kind_, A);
    return static_cast<std::ptrdiff_t>(pending_->transientBytes);
  }

  std::string name() const override {
    return kind_ == CholmodKind::Auto         ? "cholmod"
           : kind_ == CholmodKind::Simplicial ? "cholmod-simplicial"
                                              : "cholmod-supernodal";
  }

 private:
  // One right-hand side (or a few, one after the other) takes the packed solves
  // (tfeti_PackedSupernodal.hpp); more take CHOLMOD's BLAS-3 solve.
  static constexpr int kPackedMaxRhs = 8;

  // x = A^{-1} b column by column with the packed factor: b permuted, L^{-1}, L^{-T}, permuted
  // back.
  void solvePacked(const double* b, double* x, int nrhs) {
    CholmodCommon& w = shared();
    const std::size_t n = L_->n;
    const int* perm = static_cast<const int*>(L_->Perm);
    w.y.resize(n);
    w.w.resize(static_cast<std::size_t>(analysis_->packed.maxRows));
    for (int j = 0; j < nrhs; ++j) {
      const double* bj = b + j * n;
      double* xj = x + j * n;
      for (std::size_t i = 0; i < n; ++i) w.y[i] = bj[perm[i]];
      packedForwardSolve(*L_, analysis_->packed, w.y.data(), w.w.data());
      packedBackwardSolve(*L_, analysis_->packed, w.y.data(), w.w.data());
      for (std::size_t i = 0; i < n; ++i) xj[perm[i]] = w.y[i];
    }
  }

  // For each of the n dofs its place in dofs, -1 where it is not among them. Throws
  // std::logic_error for a dof out of range or given twice.
  static std::vector<int> placesIn(const std::vector<int>& dofs, int n) {
    std::vector<int> at(n, -1);
    for (std::size_t i = 0; i < dofs.size(); ++i) {
      if (dofs[i] < 0 || dofs[i] >= n || at[dofs[i]] >= 0)
        throw std::logic_error("cholmod: inverseBlock: dof " + std::to_string(dofs[i]) +
                               " is out of range or given twice");
      at[dofs[i]] = static_cast<int>(i);
    }
    return at;
  }

  // The counts of the analysis of A in a's order with the dofs where at[] >= 0 last: made here
  // as inverseBlock will make it, its peak read off CHOLMOD's count, the factorization's bytes
  // following from it as for any factor; or a's memo of them for that set of dofs.
  static SymbolicAnalysis::TrailingCounts trailingCounts(const CsrMatrix& A,
                                                         const SymbolicAnalysis& a,
                                                         const std::vector<int>& at,
                                                         const std::vector<int>& dofs) {
    std::vector<int> sorted = dofs;
    std::sort(sorted.begin(), sorted.end());
    for (const auto& [set, known] : a.trailing)
      if (set == sorted) return known;
    cholmod_common* c = common();
    const std::size_t before = c->memory_inuse, outerPeak = c->memory_usage;
    c->memory_usage = before;
    cholmod_factor* F = analyzeTrailing(A, trailingOrder(*a.symbolic, at));
    SymbolicAnalysis::TrailingCounts t;
    t.analysisPeak = c->memory_usage - before;
    t.numeric = SymbolicAnalyses::numericFactorBytes(*F);
    t.factorization = t.numeric + SymbolicAnalyses::factorizationTransientBytes(A, *F, t.numeric);
    cholmod_free_factor(&F, c);
    c->memory_usage = std::max(outerPeak, before + t.analysisPeak);
    // A safeguard: CHOLMOD's workspace grown by this analysis would be in this peak but not in
    // the next one's, so such counts are not kept. (The pattern's own analysis, made first,
    // grows it for A's size; none has been seen to grow here.)
    if (c->memory_inuse == before) {
      if (a.trailing.size() == SymbolicAnalysis::kTrailingSets) a.trailing.pop_front();
      a.trailing.emplace_back(std::move(sorted), t);
    }
    return t;
  }

  // The trailing k x k triangle of the supernodal factor F, dense (column-major, the upper part
  // zero): with the dofs last, the Schur complement's Cholesky factor.
  static std::vector<double> trailingTriangle(const cholmod_factor& F, std::size_t k) {
    std::vector<double> Lkk(k * k, 0.0);
    const std::size_t first = F.n - k;
    const int* super = static_cast<const int*>(F.super);
    const int* pi = static_cast<const int*>(F.pi);
    const int* px = static_cast<const int*>(F.px);
    const int* rows = static_cast<const int*>(F.s);
    const double* x = static_cast<const double*>(F.x);
    for (std::size_t sn = 0; sn < F.nsuper; ++sn) {
      const std::size_t k1 = super[sn], k2 = super[sn + 1];
      if (k2 <= first) continue;
      const std::size_t nsrow = pi[sn + 1] - pi[sn];
      for (std::size_t j = std::max(k1, first); j < k2; ++j)
        for (std::size_t ii = j - k1; ii < nsrow; ++ii)
          Lkk[(rows[pi[sn] + ii] - first) + (j - first) * k] = x[px[sn] + ii + (j - k1) * nsrow];
    }
    return Lkk;
  }

  // The fill-reducing order of the analysis S with the dofs where at[] >= 0 moved to the end:
  // the other dofs keep their order.
  static std::vector<int> trailingOrder(const cholmod_factor& S, const std::vector<int>& at) {
    const int n = static_cast<int>(S.n);
    const int* perm = static_cast<const int*>(S.Perm);
    std::vector<int> order;
    order.reserve(n);
    for (int i = 0; i < n; ++i)
      if (at[perm[i]] < 0) order.push_back(perm[i]);
    for (int i = 0; i < n; ++i)
      if (at[perm[i]] >= 0) order.push_back(perm[i]);
    return order;
  }

  // The supernodal symbolic analysis of A in exactly that order.
  static cholmod_factor* analyzeTrailing(const CsrMatrix& A, const std::vector<int>& order) {
    cholmod_sparse S;
    cholmodUpperView(A, S);
    cholmod_common* c = common();
    const int nmethods = c->nmethods, ordering = c->method[0].ordering, postorder = c->postorder,
              supernodal = c->supernodal;
    // The given order exactly (a postorder could move interior columns behind the dofs), and
    // supernodal: the trailing block is dense, BLAS-3's work.
    c->nmethods = 1;
    c->method[0].ordering = CHOLMOD_GIVEN;
    c->postorder = 0;
    c->supernodal = CHOLMOD_SUPERNODAL;
    cholmod_factor* F = cholmod_analyze_p(&S, const_cast<int*>(order.data()), nullptr, 0, c);
    c->nmethods = nmethods;
    c->method[0].ordering = ordering;
    c->postorder = postorder;
    c->supernodal = supernodal;
    if (!F) throw std::runtime_error("cholmod: symbolic analysis with the dofs last failed");
    return F;
  }

  // A supernodal factorization of A (not kept) in the order of L_ with the k dofs where at[] >= 0
  // moved to the end. Null where CHOLMOD did not keep that order (the trailing columns would not
  // be the dofs).
  cholmod_factor* trailingFactor(const CsrMatrix& A, const std::vector<int>& at, std::size_t k) {
    const std::size_t n = A.rows;
    const std::vector<int> order = trailingOrder(*analysis_->symbolic, at);
    cholmod_factor* F = analyzeTrailing(A, order);
    cholmod_sparse S;
    cholmodUpperView(A, S);
    cholmod_common* c = common();
    if (!cholmod_factorize(&S, F, c) || c->status != CHOLMOD_OK) {
      const long minor = static_cast<long>(F->minor);
      cholmod_free_factor(&F, c);
      throw std::runtime_error("cholmod: the subdomain matrix is not positive definite (column " +
                               std::to_string(minor) + " of " + std::to_string(n) +
                               ", ordered with the dual rows' dofs last)");
    }
    const int* fp = static_cast<const int*>(F->Perm);
    bool trailing = F->is_super;
    for (std::size_t i = n - k; trailing && i < n; ++i) trailing = at[fp[i]] >= 0;
    if (!trailing) cholmod_free_factor(&F, c);
    return F;
  }

  // Supernodal factors are kept packed between solves.
  void pack() {
    if (!L_->is_super) return;
    packSupernodal(*L_, analysis_->packed, shared().scratch);
    packed_ = true;
  }
  void release() {
    cholmod_common* c = common();
    if (L_) cholmod_free_factor(&L_, c);
    analysis_.reset();
    packed_ = false;
  }
  bool packed_ = false;  // L_'s values are in the packed order
  CholmodKind kind_;
  std::shared_ptr<const SymbolicAnalysis> analysis_;  // the pattern L_ was analysed for
  std::shared_ptr<const SymbolicAnalysis> pending_;   // predictFactorMemory's, for factorize
  cholmod_factor* L_ = nullptr;
};

}  // namespace

std::unique_ptr<LocalSolver> createCholmodSolver(const std::string& kind) {
  const CholmodKind k = kind == "simplicial"   ? CholmodKind::Simplicial
                        : kind == "supernodal" ? CholmodKind::Supernodal
                                               : CholmodKind::Auto;
  return std::make_unique<CholmodSolver>(k);
}

LocalAnalysisCounts cholmodAnalysisCounts() {
  return analyses().counts();
}

std::size_t cholmodMemoryInUse() {
  return common()->memory_inuse;
}

std::size_t cholmodMemoryPeak(bool reset) {
  cholmod_common* c = common();
  if (reset) c->memory_usage = c->memory_inuse;
  return c->memory_usage;
}

}  // namespace tfeti
