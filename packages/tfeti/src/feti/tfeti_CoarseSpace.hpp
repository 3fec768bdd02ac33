#pragma once
// The natural coarse space of (T)FETI: G = R^T B^T (one row per rigid body mode of a floating
// subdomain), the coarse matrix G G^T, and the orthogonal projector onto ker G,
//   P = I - G^T (G G^T)^{-1} G  =  I - Ghat^T Ghat,   Ghat = L^{-1} G,  G G^T = L L^T,
// i.e. G orthonormalized implicitly through the Cholesky factor of G G^T. G G^T is small (the
// number of rigid body modes) and sparse; it is gathered to every rank and factorized there
// once, so each coarse solve is local after one Import.
#include <memory>
#include <utility>
#include <vector>

#include "tfeti_DualOperators.hpp"
#include "tfeti_LocalSolver.hpp"

namespace tfeti {

class CoarseSpace {
 public:
  CoarseSpace(const Tearing& tearing, const SubdomainList& subdomains,
              const std::string& localSolver);

  GO dimension() const { return dimension_; }
  Teuchos::RCP<const Map> coarseMap() const { return coarseMap_; }
  Teuchos::RCP<const CrsMatrix> G() const { return G_; }

  // alpha = (G G^T)^{-1} G x   (alpha on the coarse map)
  void leastSquaresCoefficients(const Vector& x, Vector& alpha) const;
  // alpha = (G_A G_A^T)^{-1} G_A x with G_A = G diag(rowMask), rowMask 1 on the selected rows and
  // 0 elsewhere: the rigid body coefficients of a contact solution, where only the equality
  // rows and the active inequality rows hold with equality. Factorizes G_A G_A^T (once per call).
  void leastSquaresOnRows(const Vector& x, const Vector& rowMask, Vector& alpha,
                          const std::string& localSolver) const;
  // alpha = (G G^T)^{-1} c
  void coarseSolve(const Vector& c, Vector& alpha) const;
  // a = (G G^T)^{-1} G x on every rank (dimension() values; collective).
  void coefficientsEverywhere(const Vector& x, double* a) const;
  // c = G x on every rank (dimension() values; collective).
  void applyGEverywhere(const Vector& x, double* c) const;
  // G G^T, dense and column-major (dimension()^2 values; local: every rank holds it).
  std::vector<double> denseGramian() const;
  // y += scale G^T a for coefficients a that every rank holds alike (collective).
  void addTransposeEverywhere(const double* a, double scale, Vector& y) const;
  // y = P x (y may alias x)
  void project(const Vector& x, Vector& y) const;
  // G's columns at the multiplier ids `ids`, on every rank (collective): per id its entries as
  // (coarse id, value), sorted by coarse id.
  std::vector<std::vector<std::pair<GO, double>>> columnsOfG(
      const std::vector<long long>& ids) const;
  // x = (G G^T)^{-1} b for nrhs dense coarse vectors of dimension() values each, on this rank
  // alone (the factor is replicated).
  void coarseSolveLocal(const double* b, double* x, int nrhs) const;
  // The minimum-norm solution of G lambda = e: lambda = G^T (G G^T)^{-1} e.
  void particularSolution(const Vector& e, Vector& lambda) const;
  // e = R^T f (coarse map) for the local subdomains' loads.
  void applyKernelTranspose(const MultiVector& primal, Vector& coarse) const;
  // u += R alpha on the local subdomains.
  void addKernelCombination(const Vector& alpha, MultiVector& primal) const;

  std::size_t factorBytes() const { return factor_ ? factor_->factorBytes() : 0; }

 private:
  // alpha = factor^{-1} c with c brought to every rank (the factor is replicated).
  void solveReplicated(LocalSolver& factor, const Vector& c, Vector& alpha) const;
  // keep (optional): receives the assembled G G^T.
  // G diag(rowMask) G^T (rowMask nullptr: G G^T) factorized.
  std::unique_ptr<LocalSolver> factorizeGramian(const Vector* rowMask,
                                                const std::string& localSolver,
                                                CsrMatrix* keep = nullptr) const;
  GO dimension_ = 0;
  SubdomainList subdomains_;
  std::vector<GO> coarseOffset_;  // per local subdomain: first coarse id
  Teuchos::RCP<const Map> coarseMap_, replicatedMap_;
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> replicate_;
  Teuchos::RCP<CrsMatrix> G_;
  // G^T by the multiplier map, made once for the Gramians: least squares on rows asks for one
  // per primal recovery, and Tpetra's transpose took most of their time (docs/benchmarks.md,
  // "Packed supernodal solves").
  Teuchos::RCP<const CrsMatrix> Gt_;
  std::unique_ptr<LocalSolver> factor_;
  CsrMatrix gramian_;  // G G^T as factorized, replicated
  mutable Teuchos::RCP<Vector> c_, alpha_;
  mutable Teuchos::RCP<Vector> replicated_;
  mutable std::vector<double> rhs_, sol_;
};

}  // namespace tfeti
