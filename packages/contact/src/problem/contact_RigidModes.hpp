#pragma once
// The pieces' rigid modes behind contact_RigidMotions.hpp, shared by its two sources (the free
// motions, contact_RigidMotions.cpp; the load limit, contact_LoadLimit.cpp): installed with
// every header, but not part of the API.
#include <array>
#include <map>
#include <string>
#include <vector>

#include "contact_ElasticContactProblem.hpp"

namespace contact::rigid {

// Subdomains that share a node are glued: they move as one piece. Union-find over subdomains.
struct Pieces {
  int count = 0;
  std::vector<int> ofSubdomain;
  std::vector<int> ofNode;  // -1: a node in no subdomain
  std::vector<std::array<double, 3>> centre;
  std::vector<double> length;  // the largest side of the piece's bounding box (> 0)
};

// The piece of every subdomain (numbered by first appearance) and of every mesh node (-1: in
// no subdomain).
Pieces joinSubdomains(const ElasticContactProblem& p);
// Each piece's centroid (of its nodes) and size (the largest side of its bounding box).
void measurePieces(const ElasticContactProblem& p, Pieces& pieces);

int modesPerPiece(int dim);
// Component c at x of the piece's rigid modes: the translations, then the rotations about the
// axes through its centre, scaled by its size so that all modes are of one magnitude.
void modeValues(const Pieces& pieces, int q, int dim, const double* x, int c, double* out);
// out[i] += coef * (mode i at x, component c), over the piece's modes: a dof's coefficient (a row's
// entry, a load) on them.
void addModeValues(const Pieces& pieces, int q, int dim, const double* x, int c, double coef,
                   double* out);

// The Gram matrix sum_rows (R^T b)(R^T b)^T over the pieces' modes, a row given as (piece,
// position, component, coefficient) entries.
class Gram {
 public:
  Gram(const Pieces& pieces, int dim)
      : pieces_(pieces),
        dim_(dim),
        nm_(modesPerPiece(dim)),
        n_(pieces.count * nm_),
        m_(static_cast<std::size_t>(n_) * n_, 0.0) {}

  void beginRow() { row_.clear(); }
  void add(int piece, const double* x, int component, double coef) {
    std::vector<double>& v = row_[piece];
    v.resize(nm_, 0.0);
    addModeValues(pieces_, piece, dim_, x, component, coef, v.data());
  }
  void endRow() {
    for (const auto& [a, va] : row_)
      for (const auto& [b, vb] : row_)
        for (int i = 0; i < nm_; ++i)
          for (int j = 0; j < nm_; ++j)
            m_[static_cast<std::size_t>(a * nm_ + i) +
               static_cast<std::size_t>(b * nm_ + j) * n_] += va[i] * vb[j];
  }
  int size() const { return n_; }
  std::vector<double>& matrix() { return m_; }

 private:
  const Pieces& pieces_;
  int dim_, nm_, n_;
  std::vector<double> m_;  // column-major n x n
  std::map<int, std::vector<double>> row_;
};

// The Gram matrix of every row of B but the gluing: Fixed, Symmetry and Prescribed components
// (one row per held node and component), the couplings (rank 0 holds them) and `inequalities`.
Gram gramOfRows(const ElasticContactProblem& p, const Pieces& pieces,
                const std::vector<tfeti::InequalityRow>& inequalities);
// The null space of the Gram matrix, k x n row-major in reduced row echelon form (each vector
// with its own leading mode, the translations before the rotations), tiny entries zeroed.
std::vector<std::vector<double>> nullSpace(Gram& gram);

// A motion per vector of mode coefficients, in words ("body \"box\": translation along x").
std::vector<std::string> describe(const ElasticContactSpec& spec, const ElasticContactProblem& p,
                                  const Pieces& pieces,
                                  const std::vector<std::vector<double>>& motions);
// Rank 0's lines on every rank.
std::vector<std::string> broadcastLines(const std::vector<std::string>& lines,
                                        const tfeti::Comm& comm);

}  // namespace contact::rigid
