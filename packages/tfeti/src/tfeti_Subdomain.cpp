#include "tfeti_Subdomain.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "tfeti_DenseUtils.hpp"

namespace tfeti {

namespace {
// The diagonal entry of row i (1 if it is structurally or numerically zero).
double diagonalOrOne(const CsrMatrix& A, int i) {
  const long k = A.find(i, i);
  return (k >= 0 && A.values[k] > 0.0) ? A.values[k] : 1.0;
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

Subdomain::Subdomain(int id, int dofsPerNode, const std::vector<double>& coords, CsrMatrix K,
                     std::vector<double> f, const std::vector<int>& dirichletDofs,
                     Formulation formulation, const std::string& localSolver)
    : id_(id),
      dofsPerNode_(dofsPerNode),
      formulation_(formulation),
      K_(std::move(K)),
      f_(std::move(f)) {
  if (dofsPerNode != 1 && dofsPerNode != 2)
    throw std::invalid_argument("subdomain " + std::to_string(id) +
                                ": only 1 (scalar) or 2 (2D elasticity) dofs per node");
  if (formulation_ == Formulation::FETI && !dirichletDofs.empty()) {
    dirichlet_ = dirichletDofs;
    K_ = decoupleDofs(K_, dirichletDofs);
    for (int d : dirichletDofs) f_[d] = 0.0;
  }
  computeKernel(coords, formulation_ == Formulation::FETI ? dirichletDofs : std::vector<int>{});
  chooseFixingDofs();
  factor_ = createLocalSolver(localSolver);
  try {
    factor_->factorize(fixing_.empty() ? K_ : decoupleDofs(K_, fixing_));
  } catch (const std::exception& e) {
    throw std::runtime_error("subdomain " + std::to_string(id_) + ": " + e.what());
  }
  work_.resize(K_.rows);
}

void Subdomain::setLoad(std::vector<double> f) {
  if (static_cast<int>(f.size()) != K_.rows)
    throw std::invalid_argument("subdomain " + std::to_string(id_) + ": load of size " +
                                std::to_string(f.size()) + ", expected " + std::to_string(K_.rows));
  f_ = std::move(f);
  for (int d : dirichlet_) f_[d] = 0.0;
}

void Subdomain::computeKernel(const std::vector<double>& coords,
                              const std::vector<int>& dirichletDofs) {
  const int n = K_.rows;
  const int nodes = n / dofsPerNode_;
  int k = dofsPerNode_ == 1 ? 1 : 3;
  std::vector<double> R(static_cast<std::size_t>(n) * k, 0.0);
  double xc = 0.0, yc = 0.0;
  for (int a = 0; a < nodes; ++a) {
    xc += coords[2 * a] / nodes;
    yc += coords[2 * a + 1] / nodes;
  }
  for (int a = 0; a < nodes; ++a) {
    if (dofsPerNode_ == 1) {
      R[a] = 1.0;
    } else {
      // Translations in x and y, and the rotation about the centroid (centred for conditioning).
      R[2 * a] = 1.0;
      R[n + 2 * a + 1] = 1.0;
      R[2 * n + 2 * a] = -(coords[2 * a + 1] - yc);
      R[2 * n + 2 * a + 1] = coords[2 * a] - xc;
    }
  }
  if (!dirichletDofs.empty()) {
    // Only the combinations of rigid modes that vanish on the Dirichlet dofs remain in the
    // kernel: the null space of C = R(D, :), from the eigenvectors of C^T C.
    std::vector<double> CtC(k * k, 0.0);
    for (int p = 0; p < k; ++p)
      for (int q = 0; q < k; ++q)
        for (int d : dirichletDofs) CtC[q * k + p] += R[p * n + d] * R[q * n + d];
    std::vector<double> w, V;
    dense::symmetricEigen(k, CtC, w, V);
    double wmax = *std::max_element(w.begin(), w.end());
    std::vector<double> Rn;
    for (int e = 0; e < k; ++e) {
      if (w[e] > 1e-10 * wmax) continue;
      std::vector<double> col(n, 0.0);
      for (int p = 0; p < k; ++p)
        for (int i = 0; i < n; ++i) col[i] += R[p * n + i] * V[e * k + p];
      for (int d : dirichletDofs) col[d] = 0.0;
      Rn.insert(Rn.end(), col.begin(), col.end());
    }
    R = std::move(Rn);
    k = static_cast<int>(R.size() / n);
  }
  kernelDim_ = dense::orthonormalizeColumns(n, k, R);
  R_ = std::move(R);
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
  const int n = K_.rows;
  if (fixing_.empty()) {
    factor_->solve(b, x, nrhs);
    return;
  }
  work_.resize(static_cast<std::size_t>(n) * nrhs);
  std::copy(b, b + static_cast<std::size_t>(n) * nrhs, work_.begin());
  for (int j = 0; j < nrhs; ++j)
    for (int d : fixing_) work_[static_cast<std::size_t>(j) * n + d] = 0.0;
  factor_->solve(work_.data(), x, nrhs);
  for (int j = 0; j < nrhs; ++j)
    for (int d : fixing_) x[static_cast<std::size_t>(j) * n + d] = 0.0;
}

void Subdomain::setupPreconditioner(const std::vector<int>& interfaceDofs, PreconditionerType type,
                                    const std::string& localSolver) {
  precType_ = type;
  interface_ = interfaceDofs;
  std::sort(interface_.begin(), interface_.end());
  interior_.clear();
  interiorFactor_.reset();
  if (type == PreconditionerType::None) return;
  Kbb_ = K_.submatrix(interface_, interface_);
  if (type == PreconditionerType::Lumped) return;
  std::vector<char> isB(K_.rows, 0);
  for (int d : interface_) isB[d] = 1;
  for (int i = 0; i < K_.rows; ++i)
    if (!isB[i]) interior_.push_back(i);
  if (interior_.empty()) return;
  Kbi_ = K_.submatrix(interface_, interior_);
  Kib_ = K_.submatrix(interior_, interface_);
  interiorFactor_ = createLocalSolver(localSolver);
  try {
    interiorFactor_->factorize(K_.submatrix(interior_, interior_));
  } catch (const std::exception& e) {
    throw std::runtime_error("subdomain " + std::to_string(id_) +
                             ": Dirichlet preconditioner, interior block: " + e.what());
  }
  wi_.resize(interior_.size());
  zi_.resize(interior_.size());
}

void Subdomain::applyPreconditionerBlock(const double* vb, double* yb) {
  Kbb_.multiply(vb, yb);
  if (precType_ != PreconditionerType::Dirichlet || interior_.empty()) return;
  // S v = K_bb v - K_bi K_ii^{-1} K_ib v
  Kib_.multiply(vb, wi_.data());
  interiorFactor_->solve(wi_.data(), zi_.data());
  for (int r = 0; r < Kbi_.rows; ++r) {
    double s = 0.0;
    for (int k = Kbi_.rowPtr[r]; k < Kbi_.rowPtr[r + 1]; ++k)
      s += Kbi_.values[k] * zi_[Kbi_.colInd[k]];
    yb[r] -= s;
  }
}

std::size_t Subdomain::factorBytes() const {
  return factor_ ? factor_->factorBytes() : 0;
}

std::size_t Subdomain::preconditionerFactorBytes() const {
  return interiorFactor_ ? interiorFactor_->factorBytes() : 0;
}

}  // namespace tfeti
