#include "tfeti_Kernel.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "tfeti_DenseUtils.hpp"

namespace tfeti {

namespace {

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int a) {
    while (parent_[a] != a) a = parent_[a] = parent_[parent_[a]];
    return a;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<int> parent_;
};

// Whether the points span an affine subspace of dimension >= rank (0: a point, 1: a line, 2: a
// plane), distances below tol counting as zero.
bool spansAffine(int dim, const std::vector<double>& coords, const std::vector<int>& nodes,
                 int rank, double tol) {
  if (static_cast<int>(nodes.size()) < rank + 1) return false;
  if (rank == 0) return true;
  std::vector<std::vector<double>> basis;
  for (std::size_t i = 1; i < nodes.size() && static_cast<int>(basis.size()) < rank; ++i) {
    std::vector<double> v(dim);
    for (int c = 0; c < dim; ++c) v[c] = coords[dim * nodes[i] + c] - coords[dim * nodes[0] + c];
    for (const auto& b : basis) {
      double dot = 0.0;
      for (int c = 0; c < dim; ++c) dot += b[c] * v[c];
      for (int c = 0; c < dim; ++c) v[c] -= dot * b[c];
    }
    double norm = 0.0;
    for (int c = 0; c < dim; ++c) norm += v[c] * v[c];
    norm = std::sqrt(norm);
    if (norm <= tol) continue;
    for (double& x : v) x /= norm;
    basis.push_back(std::move(v));
  }
  return static_cast<int>(basis.size()) >= rank;
}

// A set of dofs moving by k modes (column-major, dofs.size() x k).
struct Piece {
  std::vector<int> dofs;
  int k = 0;
  std::vector<double> modes;
};

// Rigid modes of the nodes of one piece about their centroid (centred for conditioning):
// translations, then rotations in the planes (0,1) in 2D; (1,2), (2,0), (0,1) in 3D.
Piece rigidModes(int dim, int dofsPerNode, const std::vector<double>& coords,
                 const std::vector<int>& nodes) {
  Piece p;
  const int m = static_cast<int>(nodes.size()), rows = m * dofsPerNode;
  for (int a : nodes)
    for (int c = 0; c < dofsPerNode; ++c) p.dofs.push_back(a * dofsPerNode + c);
  p.k = rigidModesPerPiece(dim, dofsPerNode);
  p.modes.assign(static_cast<std::size_t>(rows) * p.k, 0.0);
  if (dofsPerNode == 1) {
    std::fill(p.modes.begin(), p.modes.end(), 1.0);
    return p;
  }
  std::vector<double> centre(dim, 0.0);
  for (int a : nodes)
    for (int c = 0; c < dim; ++c) centre[c] += coords[dim * a + c] / m;
  static const int planes2[1][2] = {{0, 1}};
  static const int planes3[3][2] = {{1, 2}, {2, 0}, {0, 1}};
  const int numPlanes = dim == 2 ? 1 : 3;
  for (int l = 0; l < m; ++l) {
    const int a = nodes[l];
    for (int c = 0; c < dim; ++c) p.modes[static_cast<std::size_t>(c) * rows + l * dim + c] = 1.0;
    for (int r = 0; r < numPlanes; ++r) {
      const int i = dim == 2 ? planes2[r][0] : planes3[r][0];
      const int j = dim == 2 ? planes2[r][1] : planes3[r][1];
      double* col = &p.modes[static_cast<std::size_t>(dim + r) * rows + l * dim];
      col[i] = -(coords[dim * a + j] - centre[j]);
      col[j] = coords[dim * a + i] - centre[i];
    }
  }
  return p;
}

// The null space of the constraints on the modes of a cluster of pieces (equal values on dofs
// several pieces hold, zero on fixed dofs), as full-length columns appended to R.
void appendClusterKernel(int numDofs, const std::vector<Piece>& pieces,
                         const std::vector<int>& cluster, const std::vector<int>& multiplicity,
                         const std::vector<char>& fixed, std::vector<double>& R) {
  std::vector<int> first;  // first coefficient of each piece of the cluster
  int total = 0;
  for (int p : cluster) {
    first.push_back(total);
    total += pieces[p].k;
  }
  // Constraint rows on the cluster's coefficients, accumulated into C^T C row by row.
  std::vector<double> CtC(static_cast<std::size_t>(total) * total, 0.0);
  bool anyRow = false;
  std::vector<std::pair<int, double>> row;
  auto addRow = [&]() {
    for (const auto& [p, vp] : row)
      for (const auto& [q, vq] : row) CtC[static_cast<std::size_t>(q) * total + p] += vp * vq;
    anyRow = true;
  };
  // Per dof of the cluster, the (piece in cluster, local row) that hold it.
  std::vector<std::vector<std::pair<int, int>>> holders(numDofs);
  for (std::size_t c = 0; c < cluster.size(); ++c) {
    const Piece& pc = pieces[cluster[c]];
    for (std::size_t l = 0; l < pc.dofs.size(); ++l)
      holders[pc.dofs[l]].push_back({static_cast<int>(c), static_cast<int>(l)});
  }
  auto pieceRow = [&](int c, int l, double sign) {
    const Piece& pc = pieces[cluster[c]];
    const std::size_t rows = pc.dofs.size();
    for (int q = 0; q < pc.k; ++q) row.push_back({first[c] + q, sign * pc.modes[q * rows + l]});
  };
  for (int d = 0; d < numDofs; ++d) {
    const auto& h = holders[d];
    if (h.empty()) continue;
    if (fixed[d]) {
      for (const auto& [c, l] : h) {
        row.clear();
        pieceRow(c, l, 1.0);
        addRow();
      }
    } else {
      for (std::size_t j = 1; j < h.size(); ++j) {
        row.clear();
        pieceRow(h[0].first, h[0].second, 1.0);
        pieceRow(h[j].first, h[j].second, -1.0);
        addRow();
      }
    }
  }
  // Null space: every coefficient vector without constraints, else the eigenvectors of C^T C
  // whose eigenvalues vanish relative to the largest.
  std::vector<std::vector<double>> coefficients;
  if (!anyRow) {
    for (int e = 0; e < total; ++e) {
      coefficients.emplace_back(total, 0.0);
      coefficients.back()[e] = 1.0;
    }
  } else {
    std::vector<double> w, V;
    dense::symmetricEigen(total, CtC, w, V);
    const double wmax = *std::max_element(w.begin(), w.end());
    for (int e = 0; e < total; ++e)
      if (!(w[e] > 1e-10 * wmax))
        coefficients.emplace_back(V.begin() + static_cast<std::size_t>(e) * total,
                                  V.begin() + static_cast<std::size_t>(e + 1) * total);
  }
  for (const auto& a : coefficients) {
    // A dof held by several pieces gets the mean of their (equal) values.
    std::vector<double> col(numDofs, 0.0);
    for (std::size_t c = 0; c < cluster.size(); ++c) {
      const Piece& pc = pieces[cluster[c]];
      const std::size_t rows = pc.dofs.size();
      for (int q = 0; q < pc.k; ++q)
        for (std::size_t l = 0; l < rows; ++l) {
          const int d = pc.dofs[l];
          const double v = pc.modes[q * rows + l] * a[first[c] + q];
          col[d] += multiplicity[d] == 1 ? v : v / multiplicity[d];
        }
    }
    for (int d = 0; d < numDofs; ++d)
      if (fixed[d]) col[d] = 0.0;
    R.insert(R.end(), col.begin(), col.end());
  }
}

// The kernel of pieces that must agree on shared dofs and vanish on fixed ones. Pieces that
// share no dof are independent: the null space is taken per cluster of touching pieces, so the
// dense problems stay as small as the touching allows.
int kernelOfPieces(int numDofs, std::vector<Piece> pieces, const std::vector<int>& fixedDofs,
                   std::vector<double>& R) {
  std::vector<char> fixed(numDofs, 0);
  for (int d : fixedDofs) fixed[d] = 1;
  std::vector<int> multiplicity(numDofs, 0), holder(numDofs, -1);
  UnionFind uf(static_cast<int>(pieces.size()));
  for (std::size_t p = 0; p < pieces.size(); ++p)
    for (int d : pieces[p].dofs) {
      ++multiplicity[d];
      if (holder[d] >= 0) uf.unite(holder[d], static_cast<int>(p));
      holder[d] = static_cast<int>(p);
    }
  // Several pieces: orthonormal modes per piece keep C^T C well scaled. One piece keeps its raw
  // modes (the kernel of a connected subdomain is then exactly that of earlier releases).
  if (pieces.size() > 1)
    for (Piece& p : pieces)
      p.k = dense::orthonormalizeColumns(static_cast<int>(p.dofs.size()), p.k, p.modes);
  std::vector<std::vector<int>> clusters(pieces.size());
  for (std::size_t p = 0; p < pieces.size(); ++p)
    clusters[uf.find(static_cast<int>(p))].push_back(static_cast<int>(p));
  R.clear();
  for (const auto& cluster : clusters)
    if (!cluster.empty()) appendClusterKernel(numDofs, pieces, cluster, multiplicity, fixed, R);
  const int k = numDofs > 0 ? static_cast<int>(R.size() / numDofs) : 0;
  return dense::orthonormalizeColumns(numDofs, k, R);
}

}  // namespace

int rigidModesPerPiece(int dim, int dofsPerNode) {
  if (dim != 2 && dim != 3)
    throw std::invalid_argument("kernel: spatial dimension " + std::to_string(dim) +
                                " (expected 2 or 3)");
  if (dofsPerNode == 1) return 1;
  if (dofsPerNode == dim) return dim == 2 ? 3 : 6;
  throw std::invalid_argument("kernel: " + std::to_string(dofsPerNode) + " dofs per node in " +
                              std::to_string(dim) + "D (expected 1, scalar, or " +
                              std::to_string(dim) + ", elasticity; give a kernel otherwise)");
}

std::vector<std::vector<int>> rigidPieces(int dim, int dofsPerNode,
                                          const std::vector<double>& coords,
                                          const ElementConnectivity& elements, int numNodes) {
  rigidModesPerPiece(dim, dofsPerNode);
  const int ne = elements.size();
  std::vector<int> count(numNodes + 1, 0);
  for (int e = 0; e < ne; ++e)
    for (int k = elements.offsets[e]; k < elements.offsets[e + 1]; ++k) {
      const int a = elements.nodes[k];
      if (a < 0 || a >= numNodes)
        throw std::invalid_argument("kernel: element " + std::to_string(e) + " has node " +
                                    std::to_string(a) + ", but the subdomain has " +
                                    std::to_string(numNodes) + " nodes");
      ++count[a + 1];
    }
  std::partial_sum(count.begin(), count.end(), count.begin());
  std::vector<int> byNode(count.back()), fill(count.begin(), count.end() - 1);
  for (int e = 0; e < ne; ++e)
    for (int k = elements.offsets[e]; k < elements.offsets[e + 1]; ++k)
      byNode[fill[elements.nodes[k]]++] = e;

  // Two elements move as one when their shared nodes fix the relative motion.
  double diag = 0.0;
  for (int c = 0; c < dim; ++c) {
    double lo = 0.0, hi = 0.0;
    for (int a = 0; a < numNodes; ++a) {
      const double x = coords[dim * a + c];
      lo = a == 0 ? x : std::min(lo, x);
      hi = a == 0 ? x : std::max(hi, x);
    }
    diag += (hi - lo) * (hi - lo);
  }
  const double tol = 1e-10 * std::sqrt(diag);
  const int rank = dofsPerNode == 1 ? 0 : dim - 1;
  UnionFind uf(ne);
  std::vector<std::pair<int, int>> shared;  // (other element, shared node)
  std::vector<int> nodes;
  for (int e = 0; e < ne; ++e) {
    shared.clear();
    for (int k = elements.offsets[e]; k < elements.offsets[e + 1]; ++k) {
      const int a = elements.nodes[k];
      for (int i = count[a]; i < count[a + 1]; ++i)
        if (byNode[i] > e) shared.push_back({byNode[i], a});
    }
    std::sort(shared.begin(), shared.end());
    shared.erase(std::unique(shared.begin(), shared.end()), shared.end());
    for (std::size_t s = 0; s < shared.size();) {
      std::size_t t = s;
      nodes.clear();
      while (t < shared.size() && shared[t].first == shared[s].first)
        nodes.push_back(shared[t++].second);
      const int f = shared[s].first;
      if (uf.find(e) != uf.find(f) && spansAffine(dim, coords, nodes, rank, tol)) uf.unite(e, f);
      s = t;
    }
  }
  std::vector<int> pieceOf(ne, -1);
  std::vector<std::vector<int>> pieces;
  std::vector<char> inElement(numNodes, 0);
  for (int e = 0; e < ne; ++e) {
    const int root = uf.find(e);
    if (pieceOf[root] < 0) {
      pieceOf[root] = static_cast<int>(pieces.size());
      pieces.emplace_back();
    }
    auto& p = pieces[pieceOf[root]];
    for (int k = elements.offsets[e]; k < elements.offsets[e + 1]; ++k) {
      p.push_back(elements.nodes[k]);
      inElement[elements.nodes[k]] = 1;
    }
  }
  for (auto& p : pieces) {
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
  }
  for (int a = 0; a < numNodes; ++a)
    if (!inElement[a]) pieces.push_back({a});
  return pieces;
}

std::vector<std::vector<int>> matrixGraphPieces(const CsrMatrix& K, int dofsPerNode) {
  const int numNodes = K.rows / dofsPerNode;
  UnionFind uf(numNodes);
  for (int i = 0; i < K.rows; ++i)
    for (int k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k)
      if (K.values[k] != 0.0) uf.unite(i / dofsPerNode, K.colInd[k] / dofsPerNode);
  std::vector<int> pieceOf(numNodes, -1);
  std::vector<std::vector<int>> pieces;
  for (int a = 0; a < numNodes; ++a) {
    const int root = uf.find(a);
    if (pieceOf[root] < 0) {
      pieceOf[root] = static_cast<int>(pieces.size());
      pieces.emplace_back();
    }
    pieces[pieceOf[root]].push_back(a);
  }
  return pieces;
}

int rigidBodyKernel(int dim, int dofsPerNode, const std::vector<double>& coords,
                    const std::vector<std::vector<int>>& pieces, const std::vector<int>& fixedDofs,
                    std::vector<double>& R) {
  std::vector<Piece> modes;
  for (const auto& nodes : pieces) modes.push_back(rigidModes(dim, dofsPerNode, coords, nodes));
  const int numNodes = static_cast<int>(coords.size()) / dim;
  return kernelOfPieces(numNodes * dofsPerNode, std::move(modes), fixedDofs, R);
}

int restrictedKernel(int numDofs, std::vector<double> userKernel, const std::vector<int>& fixedDofs,
                     std::vector<double>& R) {
  if (numDofs == 0 || userKernel.size() % numDofs != 0)
    throw std::invalid_argument("kernel: " + std::to_string(userKernel.size()) +
                                " values are not whole columns of " + std::to_string(numDofs) +
                                " dofs");
  Piece p;
  p.dofs.resize(numDofs);
  std::iota(p.dofs.begin(), p.dofs.end(), 0);
  p.k = static_cast<int>(userKernel.size() / numDofs);
  p.modes = std::move(userKernel);
  return kernelOfPieces(numDofs, {std::move(p)}, fixedDofs, R);
}

}  // namespace tfeti
