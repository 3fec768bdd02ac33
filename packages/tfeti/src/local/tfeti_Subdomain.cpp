#include "tfeti_Subdomain.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>

#include "tfeti_DenseUtils.hpp"
#include "tfeti_Kernel.hpp"

namespace tfeti {

namespace {
std::string sci(double v) {
  std::ostringstream s;
  s << std::scientific << std::setprecision(2) << v;
  return s.str();
}

// The diagonal entry of row i (1 if it is structurally or numerically zero).
double diagonalOrOne(const CsrMatrix& A, int i) {
  const long k = A.find(i, i);
  return (k >= 0 && A.values[k] > 0.0) ? A.values[k] : 1.0;
}

// Work vectors of the solves, shared by every subdomain of the thread: one solve runs at a time,
// and vectors per subdomain (three of its size) took 20 bytes per unknown.
std::vector<double>& scratch(int which, std::size_t size) {
  thread_local std::vector<double> buffers[2];
  buffers[which].resize(size);
  return buffers[which];
}

// A new factorization's version: process-wide, never reused (see factorVersion()).
unsigned long long nextFactorVersion() {
  static std::atomic<unsigned long long> counter{0};
  return ++counter;
}

// Replaces rows and columns of the given dofs by their diagonal: decouples them while keeping
// the scale of the matrix (and its symmetry).
CsrMatrix decoupleDofs(const CsrMatrix& A, const std::vector<int>& dofs) {
  CsrMatrix B = A;
  std::vector<char> mark(A.rows, 0);
  for (int d : dofs) mark[d] = 1;
  for (int i = 0; i < A.rows; ++i)
    for (int k = A.rowPtr[i]; k < A.rowPtr[i + 1]; ++k) {
      const int j = A.colInd[k];
      if ((mark[i] || mark[j]) && i != j) B.values[k] = 0.0;
      if (mark[i] && i == j) B.values[k] = diagonalOrOne(A, i);
    }
  return B;
}
}  // namespace

MemoryPrediction predictPseudoInverseMemory(const CsrMatrix& K, bool decoupledCopy,
                                            LocalSolver& solver) {
  // The fixing dofs are decoupled by values alone (decoupleDofs keeps K's pattern), and an
  // analysis reads the pattern alone: K itself, without a copy.
  MemoryPrediction p{solver.predictFactorMemory(K), solver.predictFactorTransient(K)};
  if (!p.known()) return {-1, -1};
  if (decoupledCopy) p.transient += static_cast<std::ptrdiff_t>(K.bytes());
  return p;
}

std::ptrdiff_t predictPseudoInverseBlockMemory(const CsrMatrix& K, const std::vector<int>& dofs,
                                               const std::vector<int>& fixing,
                                               LocalSolver& solver) {
  std::vector<int> kept;
  std::vector<char> fixed(K.rows, 0);
  for (int d : fixing) fixed[d] = 1;
  for (int d : dofs)
    if (!fixed.at(d)) kept.push_back(d);
  // The copy keeps K's pattern, and the prediction reads the pattern alone.
  const std::ptrdiff_t inverse = solver.predictInverseBlockMemory(K, kept);
  if (inverse < 0) return -1;
  const std::size_t k = dofs.size(), kk = kept.size(), d = sizeof(double);
  // The fixing dofs' marks (n) and the kept dofs with their places (k each); the copy of K and
  // the solver's inverse block; then, where fixing dofs are among the dofs, that block with the
  // whole one (else the solver's block is the whole one).
  const std::size_t scatter = kk < k ? (kk * kk + k * k) * d : 0;
  const bool decoupledCopy = !fixing.empty();
  return static_cast<std::ptrdiff_t>(
      K.rows + 2 * k * sizeof(int) +
      std::max<std::size_t>((decoupledCopy ? K.bytes() : 0) + inverse, scatter));
}

std::vector<int> interiorDofs(int n, const std::vector<int>& interfaceDofs) {
  std::vector<char> onInterface(n, 0);
  for (int d : interfaceDofs) onInterface[d] = 1;
  std::vector<int> interior;
  for (int i = 0; i < n; ++i)
    if (!onInterface[i]) interior.push_back(i);
  return interior;
}

MemoryPrediction predictDirichletMemory(const CsrMatrix& K, const std::vector<int>& interfaceDofs,
                                        LocalSolver& solver) {
  std::vector<char> onInterface(K.rows, 0);
  for (int d : interfaceDofs) onInterface[d] = 1;
  // The entries of K_bb, K_bi and K_ii, as CsrMatrix::submatrix copies them.
  std::size_t bb = 0, bi = 0, ii = 0;
  for (int r = 0; r < K.rows; ++r) {
    for (int k = K.rowPtr[r]; k < K.rowPtr[r + 1]; ++k) {
      const bool rowB = onInterface[r], colB = onInterface[K.colInd[k]];
      bb += rowB && colB ? 1 : 0;
      bi += rowB && !colB ? 1 : 0;
      ii += !rowB && !colB ? 1 : 0;
    }
  }
  const std::vector<int> interior = interiorDofs(K.rows, interfaceDofs);
  const std::size_t ni = interior.size(), nb = K.rows - ni;
  const auto csr = [](std::size_t rows, std::size_t nnz) {
    return static_cast<std::ptrdiff_t>(sizeof(int) * (rows + 1) +
                                       (sizeof(int) + sizeof(double)) * nnz);
  };
  // Without interior dofs the set-up stops after K_bb.
  if (interior.empty()) return {csr(nb, bb), 0};
  const CsrMatrix pattern = K.submatrix(interior, interior, /*withValues=*/false);
  const std::ptrdiff_t held = solver.predictFactorMemory(pattern);
  const std::ptrdiff_t transient = solver.predictFactorTransient(pattern);
  if (held < 0 || transient < 0) return {-1, -1};
  return {csr(nb, bb) + csr(nb, bi) + held, csr(ni, ii) + transient};
}

Subdomain::Subdomain(int id, int dofsPerNode, const std::vector<double>& coords, CsrMatrix K,
                     std::vector<double> f, const std::vector<int>& dirichletDofs,
                     Formulation formulation, const std::string& localSolver)
    : Subdomain(id, dofsPerNode, coords, KernelOptions{}, std::move(K), std::move(f), dirichletDofs,
                formulation, localSolver) {}

Subdomain::Subdomain(int id, int dofsPerNode, const std::vector<double>& coords,
                     const KernelOptions& kernel, CsrMatrix K, std::vector<double> f,
                     const std::vector<int>& dirichletDofs, Formulation formulation,
                     const std::string& localSolver, Factorization when)
    : id_(id),
      dofsPerNode_(dofsPerNode),
      formulation_(formulation),
      K_(std::move(K)),
      f_(std::move(f)) {
  // Sizes first, in the caller's terms: everything below indexes by them.
  const auto fail = [&](const std::string& what) { throw std::invalid_argument(name() + what); };
  if (dofsPerNode < 1) fail(": " + std::to_string(dofsPerNode) + " dofs per node");
  if (const std::string e = csrError(K_, "K"); !e.empty()) fail(": " + e);
  // The factorizations read one triangle of K: an unsymmetric K would be solved as another
  // matrix without a word. Assembly rounding stays far below this tolerance.
  if (const std::string e = asymmetryError(K_, "K", 1e-10); !e.empty()) fail(": " + e);
  if (kernel.kernel.empty()) {
    try {
      rigidModesPerPiece(kernel.dim, dofsPerNode);
    } catch (const std::invalid_argument& e) {
      fail(std::string(": ") + e.what());
    }
    if (coords.size() % kernel.dim != 0 ||
        static_cast<long long>(coords.size() / kernel.dim) * dofsPerNode != K_.rows)
      fail(": K has " + std::to_string(K_.rows) + " rows, the coordinates give " +
           std::to_string(coords.size() / kernel.dim) + " nodes x " + std::to_string(dofsPerNode) +
           " dofs (" + std::to_string(coords.size()) + " values, " + std::to_string(kernel.dim) +
           " per node)");
  }
  if (K_.rows != K_.cols || K_.rows % dofsPerNode != 0)
    fail(": K is " + std::to_string(K_.rows) + " x " + std::to_string(K_.cols) +
         ", not square with whole nodes of " + std::to_string(dofsPerNode) + " dofs");
  if (static_cast<int>(f_.size()) != K_.rows)
    fail(": the load has " + std::to_string(f_.size()) + " entries, K has " +
         std::to_string(K_.rows) + " rows");
  for (int d : dirichletDofs)
    if (d < 0 || d >= K_.rows)
      fail(": Dirichlet dof " + std::to_string(d) + " is not one of its " +
           std::to_string(K_.rows) + " dofs");
  // The pieces come from K as given: eliminating Dirichlet dofs below cuts its graph there.
  std::vector<std::vector<int>> pieces;
  if (kernel.kernel.empty())
    pieces = kernel.elements.empty() ? matrixGraphPieces(K_, dofsPerNode_)
                                     : rigidPieces(kernel.dim, dofsPerNode_, coords,
                                                   kernel.elements, K_.rows / dofsPerNode_);
  if (formulation_ == Formulation::FETI && !dirichletDofs.empty()) {
    dirichlet_ = dirichletDofs;
    K_ = decoupleDofs(K_, dirichletDofs);
    for (int d : dirichletDofs) f_[d] = 0.0;
  }
  computeKernel(coords, kernel, pieces,
                formulation_ == Formulation::FETI ? dirichletDofs : std::vector<int>{});
  checkKernelResidual(kernel.residualTolerance);
  chooseFixingDofs();
  factor_ = createLocalSolver(localSolver);
  numDofs_ = K_.rows;
  if (when == Factorization::Now) factorize();
}

MemoryPrediction Subdomain::predictFactorMemory() {
  if (factorized()) return {};
  return predictPseudoInverseMemory(K_, !fixing_.empty(), *factor_);
}

void Subdomain::factorize() {
  if (factorized()) return;
  try {
    factor_->factorize(fixing_.empty() ? K_ : decoupleDofs(K_, fixing_));
    factorVersion_ = nextFactorVersion();
    factoredDigest_ = K_.digest();
  } catch (const std::exception& e) {
    throw std::runtime_error(name() + ": K with its " + std::to_string(kernelDim_) +
                             " kernel dofs fixed is not positive definite, so K has a larger "
                             "kernel than the " +
                             std::to_string(kernelDim_) + " modes found (" + e.what() + ")");
  }
  checkNoExtraKernel();
}

bool Subdomain::refactorize(CsrMatrix K, double kernelTolerance) {
  if (const std::string e = csrError(K, "K"); !e.empty())
    throw std::invalid_argument(name() + ": refactorize: " + e);
  if (K.rows != numDofs_ || K.cols != numDofs_)
    throw std::invalid_argument(name() + ": refactorize: K is " + std::to_string(K.rows) + " x " +
                                std::to_string(K.cols) + ", the subdomain has " +
                                std::to_string(numDofs_) + " dofs");
  K_ = dirichlet_.empty() ? std::move(K) : decoupleDofs(K, dirichlet_);
  // The factor (and the kernel check) of this very matrix is at hand: in a plastic body most
  // subdomains stay elastic, and their tangent is the same matrix from one iteration to the next.
  const auto digest = K_.digest();
  if (digest == factoredDigest_) return false;
  checkKernelResidual(kernelTolerance);
  factor_->factorize(fixing_.empty() ? K_ : decoupleDofs(K_, fixing_));
  factorVersion_ = nextFactorVersion();
  factoredDigest_ = digest;
  return true;
}

void Subdomain::releaseStiffness() {
  K_ = CsrMatrix{};
}

std::string Subdomain::name() const {
  return "subdomain " + std::to_string(id_);
}

void Subdomain::setLoad(std::vector<double> f) {
  if (static_cast<int>(f.size()) != numDofs_)
    throw std::invalid_argument(name() + ": the load vector f has " + std::to_string(f.size()) +
                                " entries, K has " + std::to_string(numDofs_) + " rows");
  f_ = std::move(f);
  for (int d : dirichlet_) f_[d] = 0.0;
}

void Subdomain::computeKernel(const std::vector<double>& coords, const KernelOptions& options,
                              const std::vector<std::vector<int>>& pieces,
                              const std::vector<int>& dirichletDofs) {
  if (!options.kernel.empty()) {
    if (options.kernel.size() % K_.rows != 0)
      throw std::invalid_argument(name() + ": the given kernel has " +
                                  std::to_string(options.kernel.size()) +
                                  " values, not whole columns of " + std::to_string(K_.rows));
    kernelDim_ = restrictedKernel(K_.rows, options.kernel, dirichletDofs, R_);
    return;
  }
  kernelDim_ = rigidBodyKernel(options.dim, dofsPerNode_, coords, pieces, dirichletDofs, R_);
}

void Subdomain::checkKernelResidual(double tolerance) {
  const int n = K_.rows, k = kernelDim_;
  // ||K R||: R must be in the kernel (a supplied kernel, elements that are not rigid, ...).
  const double normK = K_.frobeniusNorm();
  std::vector<double> y(n);
  double kr = 0.0;
  for (int q = 0; q < k; ++q) {
    K_.multiply(&R_[static_cast<std::size_t>(q) * n], y.data());
    for (double v : y) kr += v * v;
  }
  kernelResidual_ = normK > 0.0 ? std::sqrt(kr) / normK : 0.0;
  if (tolerance > 0.0 && kernelResidual_ > tolerance)
    throw std::runtime_error(name() + ": the " + std::to_string(k) +
                             " kernel vectors are not in the kernel of K: ||K R|| / ||K|| = " +
                             sci(kernelResidual_) + " > " + sci(tolerance));
}

void Subdomain::checkNoExtraKernel() {
  const int n = K_.rows, k = kernelDim_;
  // A kernel vector that R misses makes K with the fixing dofs decoupled singular; the
  // factorization may still succeed on rounding-level pivots. Three power iterations on K+ from
  // a fixed pseudo-random start expose it: such a direction is amplified by ~1e15 per step,
  // against at most the condition number of K for the others.
  double maxDiag = 0.0;
  for (int i = 0; i < n; ++i) {
    const long p = K_.find(i, i);
    if (p >= 0) maxDiag = std::max(maxDiag, std::abs(K_.values[p]));
  }
  if (n == k || maxDiag == 0.0) {
    lambdaMinRelative_ = 1.0;
    return;
  }
  std::vector<double> x(n), z(n);
  unsigned long long state = 88172645463325252ull;
  for (double& v : x) {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    v = static_cast<double>(state % 2000003) / 1000001.5 - 1.0;
  }
  double growth = 0.0;
  for (int it = 0; it < 3; ++it) {
    double nx = 0.0;
    for (double v : x) nx += v * v;
    nx = std::sqrt(nx);
    for (double& v : x) v /= nx;
    applyPseudoInverse(x.data(), z.data());
    double nz = 0.0;
    for (double v : z) nz += v * v;
    growth = std::sqrt(nz);
    x.swap(z);
  }
  lambdaMinRelative_ = growth > 0.0 ? 1.0 / (growth * maxDiag) : 1.0;
  if (!(lambdaMinRelative_ > 1e-11))
    throw std::runtime_error(
        name() + ": K has a larger kernel than the " + std::to_string(k) +
        " modes found (with the kernel dofs fixed its smallest eigenvalue is ~" +
        sci(lambdaMinRelative_) +
        " of its largest diagonal entry): a part of the subdomain touches the rest at a node or "
        "an edge only (give its elements), or a kernel is missing");
}

void Subdomain::chooseFixingDofs() {
  // Pivoted Gram-Schmidt on the rows of R: each step takes the dof whose row of R is largest
  // after removing the directions already fixed, which keeps R(F, :) well conditioned.
  const int n = K_.rows, k = kernelDim_;
  std::vector<double> M = R_;
  fixing_.clear();
  for (int step = 0; step < k; ++step) {
    int best = -1;
    double bestNorm = 0.0;
    for (int i = 0; i < n; ++i) {
      double s = 0.0;
      for (int q = 0; q < k; ++q) s += M[q * n + i] * M[q * n + i];
      if (s > bestNorm * (1 + 1e-12)) {
        bestNorm = s;
        best = i;
      }
    }
    if (best < 0 || bestNorm <= 0.0)
      throw std::runtime_error("subdomain " + std::to_string(id_) +
                               ": cannot choose fixing dofs for the kernel");
    fixing_.push_back(best);
    std::vector<double> v(k);
    for (int q = 0; q < k; ++q) v[q] = M[q * n + best] / std::sqrt(bestNorm);
    for (int i = 0; i < n; ++i) {
      double dot = 0.0;
      for (int q = 0; q < k; ++q) dot += M[q * n + i] * v[q];
      for (int q = 0; q < k; ++q) M[q * n + i] -= dot * v[q];
    }
  }
  std::sort(fixing_.begin(), fixing_.end());
}

void Subdomain::applyPseudoInverse(const double* b, double* x, int nrhs) {
  if (!factorized())
    throw std::logic_error(name() + ": K+ applied before factorize() (Factorization::Deferred)");
  const int n = numDofs_;
  if (fixing_.empty()) {
    factor_->solve(b, x, nrhs);
    return;
  }
  std::vector<double>& work = scratch(0, static_cast<std::size_t>(n) * nrhs);
  std::copy(b, b + static_cast<std::size_t>(n) * nrhs, work.begin());
  for (int j = 0; j < nrhs; ++j)
    for (int d : fixing_) work[static_cast<std::size_t>(j) * n + d] = 0.0;
  factor_->solve(work.data(), x, nrhs);
  for (int j = 0; j < nrhs; ++j)
    for (int d : fixing_) x[static_cast<std::size_t>(j) * n + d] = 0.0;
}

bool Subdomain::pseudoInverseBlock(const std::vector<int>& dofs, std::vector<double>& block) {
  if (!hasStiffness()) return false;
  std::vector<char> fixed(numDofs_, 0);
  for (int d : fixing_) fixed[d] = 1;
  std::vector<int> kept, at;  // the dofs K+ is not zero on, and their places in dofs
  kept.reserve(dofs.size());
  at.reserve(dofs.size());
  for (std::size_t i = 0; i < dofs.size(); ++i)
    if (!fixed.at(dofs[i])) {
      kept.push_back(dofs[i]);
      at.push_back(static_cast<int>(i));
    }
  std::vector<double> inv;
  const bool done = fixing_.empty() ? factor_->inverseBlock(K_, kept, inv)
                                    : factor_->inverseBlock(decoupleDofs(K_, fixing_), kept, inv);
  if (!done) return false;
  const std::size_t k = dofs.size(), kk = kept.size();
  if (kk == k) {  // no fixing dof among them: the block is the solver's
    block = std::move(inv);
    return true;
  }
  block.assign(k * k, 0.0);
  for (std::size_t j = 0; j < kk; ++j)
    for (std::size_t i = 0; i < kk; ++i) block[at[i] + at[j] * k] = inv[i + j * kk];
  return true;
}

std::ptrdiff_t Subdomain::predictInverseBlockMemory(const std::vector<int>& dofs) {
  if (!hasStiffness()) return -1;
  return predictPseudoInverseBlockMemory(K_, dofs, fixing_, *factor_);
}

MemoryPrediction Subdomain::predictPreconditionerMemory(const std::vector<int>& interfaceDofs,
                                                        PreconditionerType type,
                                                        const std::string& localSolver) {
  pendingInterior_.reset();
  pendingInteriorDofs_.clear();
  if (type != PreconditionerType::Dirichlet || !hasStiffness()) return {};
  auto solver = createLocalSolver(localSolver);
  const MemoryPrediction p = predictDirichletMemory(K_, interfaceDofs, *solver);
  std::vector<int> interior = interiorDofs(K_.rows, interfaceDofs);
  if (p.known() && !interior.empty()) {
    pendingInterior_ = std::move(solver);
    pendingInteriorDofs_ = std::move(interior);
  }
  return p;
}

void Subdomain::setupPreconditioner(const std::vector<int>& interfaceDofs, PreconditionerType type,
                                    const std::string& localSolver) {
  if (type != PreconditionerType::None && !hasStiffness())
    throw std::logic_error(name() +
                           ": the preconditioner cannot be set up again: K was released after "
                           "the first set-up (FETI \"Keep subdomain matrices\" = false)");
  precType_ = type;
  interface_ = interfaceDofs;
  std::sort(interface_.begin(), interface_.end());
  interior_.clear();
  interiorFactor_.reset();
  std::unique_ptr<LocalSolver> pending = std::move(pendingInterior_);
  if (type == PreconditionerType::None) return;
  Kbb_ = K_.submatrix(interface_, interface_);
  if (type == PreconditionerType::Lumped) return;
  interior_ = interiorDofs(K_.rows, interface_);
  if (interior_.empty()) return;
  Kbi_ = K_.submatrix(interface_, interior_);
  interiorFactor_ = pending && pendingInteriorDofs_ == interior_ ? std::move(pending)
                                                                 : createLocalSolver(localSolver);
  pendingInteriorDofs_.clear();
  try {
    interiorFactor_->factorize(K_.submatrix(interior_, interior_));
  } catch (const std::exception& e) {
    throw std::runtime_error("subdomain " + std::to_string(id_) +
                             ": Dirichlet preconditioner, interior block: " + e.what());
  }
}

void Subdomain::applyPreconditionerBlock(const double* vb, double* yb, int nrhs) {
  const std::size_t nb = interface_.size(), ni = interior_.size();
  for (int j = 0; j < nrhs; ++j) Kbb_.multiply(vb + j * nb, yb + j * nb);
  if (precType_ != PreconditionerType::Dirichlet || interior_.empty()) return;
  // S v = K_bb v - K_bi K_ii^{-1} K_ib v, K_ib v = K_bi^T v: every w_i sums over the interface
  // rows in increasing order, as a row of K_ib would.
  std::vector<double>& wi = scratch(0, ni * nrhs);
  std::vector<double>& zi = scratch(1, ni * nrhs);
  std::fill(wi.begin(), wi.end(), 0.0);
  for (int j = 0; j < nrhs; ++j) {
    const double* v = vb + j * nb;
    double* w = wi.data() + j * ni;
    for (int r = 0; r < Kbi_.rows; ++r)
      for (int k = Kbi_.rowPtr[r]; k < Kbi_.rowPtr[r + 1]; ++k)
        w[Kbi_.colInd[k]] += Kbi_.values[k] * v[r];
  }
  interiorFactor_->solve(wi.data(), zi.data(), nrhs);
  for (int j = 0; j < nrhs; ++j) {
    const double* z = zi.data() + j * ni;
    double* y = yb + j * nb;
    for (int r = 0; r < Kbi_.rows; ++r) {
      double s = 0.0;
      for (int k = Kbi_.rowPtr[r]; k < Kbi_.rowPtr[r + 1]; ++k)
        s += Kbi_.values[k] * z[Kbi_.colInd[k]];
      y[r] -= s;
    }
  }
}

std::size_t Subdomain::factorBytes() const {
  return factor_ ? factor_->factorBytes() : 0;
}

std::size_t Subdomain::pseudoInverseSolveKeeps(int nrhs) const {
  return factor_ ? factor_->solveKeeps(static_cast<std::size_t>(numDofs_), nrhs) : 0;
}

std::size_t Subdomain::factorMemory() const {
  return factor_ ? factor_->factorMemory() : 0;
}

std::size_t Subdomain::preconditionerFactorBytes() const {
  return interiorFactor_ ? interiorFactor_->factorBytes() : 0;
}

std::size_t Subdomain::preconditionerFactorMemory() const {
  return interiorFactor_ ? interiorFactor_->factorMemory() : 0;
}

std::size_t Subdomain::preconditionerMemory() const {
  if (precType_ != PreconditionerType::Dirichlet) return 0;
  return Kbb_.bytes() + Kbi_.bytes() + preconditionerFactorMemory();
}

}  // namespace tfeti
