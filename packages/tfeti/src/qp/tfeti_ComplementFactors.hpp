#pragma once
// SMALBE's projector Q onto the range of its equality rows in its factored form
//   Q = G^T (G G^T)^{-1} G,   G a matrix of few rows (FETI's G = R^T B^T, one row per rigid body
// mode), for a face projector that shares one application of Q between the two projections of
// P_F = P - P E_A^T S^{-1} E_A P (tfeti_FaceProjector.hpp): Q applied to E_A^T s needs only G's
// columns at the active rows, so P_F costs one pass over G and one over G^T instead of two each.
#include <utility>
#include <vector>

namespace tfeti {

// Faces with more rows than G work with G G^T densely (tfeti_FaceProjector.hpp, "the coarse
// side") up to this many rows of G; a source need not provide G G^T beyond it.
constexpr int kDenseGramianMaxRows = 1000;

template <class S, class MV>
class ComplementFactors {
 public:
  virtual ~ComplementFactors() = default;
  // The number of rows of G.
  virtual int rows() const = 0;
  // c = G x, on every rank (collective).
  virtual void applyG(const MV& x, std::vector<S>& c) const = 0;
  // The lower Cholesky factor L of G G^T = L L^T, dense and column-major, the same on every
  // rank, computed once (for faces with more rows than G; asked for only when rows() <=
  // kDenseGramianMaxRows).
  virtual const std::vector<S>& gramianFactor() const = 0;
  // a = (G G^T)^{-1} G x, on every rank (collective).
  virtual void coefficients(const MV& x, std::vector<S>& a) const = 0;
  // y += alpha G^T a, a the same on every rank (collective).
  virtual void addTranspose(const std::vector<S>& a, S alpha, MV& y) const = 0;
  // b = (G G^T)^{-1} b, local (every rank holds the factor).
  virtual void solve(std::vector<S>& b) const = 0;
  // G's columns at the global indices `ids` (collective): per index its entries as (row of G,
  // value), the same on every rank and rank count.
  virtual std::vector<std::vector<std::pair<int, S>>> columns(
      const std::vector<long long>& ids) const = 0;
};

}  // namespace tfeti
