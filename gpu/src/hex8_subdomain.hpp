#pragma once
// A floating 3D subdomain for the assembly check (gpu/README.md, "Assembly"): a cube of ne³
// trilinear Hex8 elements of linear elasticity, as the main code tears a structured mesh into. Its
// stiffness K is singular (six rigid modes); TFETI's generalized inverse K⁺ solves with K_reg, in
// which six fixing dofs have their rows and columns replaced by their diagonal, and zeroes the
// fixing dofs' part of the solution. The dual rows are those of an interior subdomain: one row per
// dof of every surface node (8³ elements: 2187 dofs and 1158 rows, the prototype).
// Needs nothing beyond the C++ standard library.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace gpucheck {

// Compressed sparse rows, columns sorted in each row.
struct Csr {
  int n = 0;
  std::vector<int> rowPtr, col;
  std::vector<double> val;
  std::size_t nnz() const { return val.size(); }
};

// Local node a of a Hex8 sits at kCorner[a] of the unit cube: counter-clockwise in the bottom
// layer, then the top.
inline constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                      {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

// The element stiffness of a cube of edge h (24 × 24, row-major; dof 3a + c is component c of
// local node a), 2 × 2 × 2 Gauss points.
inline std::array<double, 576> hex8Stiffness(double h, double young, double poisson) {
  const double lambda = young * poisson / ((1 + poisson) * (1 - 2 * poisson));
  const double mu = young / (2 * (1 + poisson));
  const double g = 1.0 / std::sqrt(3.0), detJ = h * h * h / 8.0;
  std::array<double, 576> ke{};
  for (int gp = 0; gp < 8; ++gp) {
    const double xi[3] = {gp & 1 ? g : -g, gp & 2 ? g : -g, gp & 4 ? g : -g};
    double dN[8][3];  // dN_a/dx_c
    for (int a = 0; a < 8; ++a) {
      double s[3];
      for (int c = 0; c < 3; ++c) s[c] = kCorner[a][c] ? 1.0 : -1.0;
      for (int c = 0; c < 3; ++c) {
        double v = s[c] / 8.0;
        for (int d = 0; d < 3; ++d)
          if (d != c) v *= 1.0 + s[d] * xi[d];
        dN[a][c] = v * 2.0 / h;
      }
    }
    // B: strains (xx, yy, zz, yz, xz, xy, engineering shears) from the 24 dofs.
    double B[6][24] = {};
    for (int a = 0; a < 8; ++a) {
      const double* d = dN[a];
      B[0][3 * a] = d[0];
      B[1][3 * a + 1] = d[1];
      B[2][3 * a + 2] = d[2];
      B[3][3 * a + 1] = d[2];
      B[3][3 * a + 2] = d[1];
      B[4][3 * a] = d[2];
      B[4][3 * a + 2] = d[0];
      B[5][3 * a] = d[1];
      B[5][3 * a + 1] = d[0];
    }
    double D[6][6] = {};
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) D[r][c] = lambda;
      D[r][r] += 2 * mu;
      D[r + 3][r + 3] = mu;
    }
    for (int i = 0; i < 24; ++i) {
      double DB[6];
      for (int r = 0; r < 6; ++r) {
        DB[r] = 0;
        for (int c = 0; c < 6; ++c) DB[r] += D[r][c] * B[c][i];
      }
      for (int j = 0; j < 24; ++j) {
        double v = 0;
        for (int r = 0; r < 6; ++r) v += B[r][j] * DB[r];
        ke[24 * j + i] += v * detJ;
      }
    }
  }
  return ke;
}

struct Hex8Subdomain {
  int elements = 0;          // per edge
  int n = 0;                 // dofs: 3 (ne + 1)³
  std::vector<int> dualDof;  // the dof of each dual row, increasing
  std::array<int, 6> fixing{};
  Csr K;     // singular stiffness
  Csr Kreg;  // the fixing dofs' rows and columns replaced by their diagonal

  int nodesPerEdge() const { return elements + 1; }
  int node(int i, int j, int k) const { return i + nodesPerEdge() * (j + nodesPerEdge() * k); }
  bool isFixing(int dof) const {
    return std::find(fixing.begin(), fixing.end(), dof) != fixing.end();
  }
  int dualRows() const { return static_cast<int>(dualDof.size()); }
};

// K_reg from K: the fixing dofs' rows and columns dropped but their diagonal entries kept.
inline Csr regularized(const Csr& K, const std::array<int, 6>& fixing) {
  std::vector<char> fix(K.n, 0);
  for (int f : fixing) fix[f] = 1;
  Csr r;
  r.n = K.n;
  r.rowPtr.assign(1, 0);
  for (int i = 0; i < K.n; ++i) {
    for (int e = K.rowPtr[i]; e < K.rowPtr[i + 1]; ++e) {
      const int j = K.col[e];
      if ((fix[i] || fix[j]) && i != j) continue;
      r.col.push_back(j);
      r.val.push_back(K.val[e]);
    }
    r.rowPtr.push_back(static_cast<int>(r.col.size()));
  }
  return r;
}

// The stiffness pattern: each node couples with the nodes of the 3 × 3 × 3 box around it.
inline Csr stiffnessPattern(const Hex8Subdomain& s) {
  const int N = s.nodesPerEdge();
  Csr K;
  K.n = s.n;
  K.rowPtr.assign(1, 0);
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
        for (int c = 0; c < 3; ++c) {
          for (int kk = std::max(0, k - 1); kk <= std::min(N - 1, k + 1); ++kk)
            for (int jj = std::max(0, j - 1); jj <= std::min(N - 1, j + 1); ++jj)
              for (int ii = std::max(0, i - 1); ii <= std::min(N - 1, i + 1); ++ii)
                for (int cc = 0; cc < 3; ++cc) K.col.push_back(3 * s.node(ii, jj, kk) + cc);
          K.rowPtr.push_back(static_cast<int>(K.col.size()));
        }
  K.val.assign(K.col.size(), 0.0);
  return K;
}

// K's values: every element's stiffness (unit cubes, E = 1, ν = 0.3) added into the pattern.
inline void assembleStiffness(const Hex8Subdomain& s, Csr& K) {
  const std::array<double, 576> ke = hex8Stiffness(1.0, 1.0, 0.3);
  for (int k = 0; k < s.elements; ++k)
    for (int j = 0; j < s.elements; ++j)
      for (int i = 0; i < s.elements; ++i) {
        int dof[24];
        for (int a = 0; a < 8; ++a)
          for (int c = 0; c < 3; ++c)
            dof[3 * a + c] =
                3 * s.node(i + kCorner[a][0], j + kCorner[a][1], k + kCorner[a][2]) + c;
        for (int r = 0; r < 24; ++r) {
          const auto first = K.col.begin() + K.rowPtr[dof[r]];
          const auto last = K.col.begin() + K.rowPtr[dof[r] + 1];
          for (int c = 0; c < 24; ++c)
            K.val[std::lower_bound(first, last, dof[c]) - K.col.begin()] += ke[24 * c + r];
        }
      }
}

// The dual rows of an interior subdomain: every dof of every surface node, increasing.
inline std::vector<int> surfaceDofs(const Hex8Subdomain& s) {
  const int N = s.nodesPerEdge(), ne = s.elements;
  std::vector<int> dofs;
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
        if (i == 0 || j == 0 || k == 0 || i == ne || j == ne || k == ne)
          for (int c = 0; c < 3; ++c) dofs.push_back(3 * s.node(i, j, k) + c);
  return dofs;
}

// The six fixing dofs: node A = (0,0,0) fixed in x, y, z removes the translations; B = (ne,0,0)
// in y, z the rotations about z and y; C = (0,ne,0) in z the rotation about x.
inline std::array<int, 6> fixingDofs(const Hex8Subdomain& s) {
  const int A = s.node(0, 0, 0), B = s.node(s.elements, 0, 0), C = s.node(0, s.elements, 0);
  return {3 * A, 3 * A + 1, 3 * A + 2, 3 * B + 1, 3 * B + 2, 3 * C + 2};
}

// The cube [0, ne]³ of unit elements.
inline Hex8Subdomain hex8Subdomain(int elements) {
  if (elements < 1 || elements > 64)
    throw std::invalid_argument("--elements = " + std::to_string(elements) +
                                " is not within 1..64 per edge");
  Hex8Subdomain s;
  s.elements = elements;
  s.n = 3 * s.nodesPerEdge() * s.nodesPerEdge() * s.nodesPerEdge();
  s.K = stiffnessPattern(s);
  assembleStiffness(s, s.K);
  s.dualDof = surfaceDofs(s);
  s.fixing = fixingDofs(s);
  s.Kreg = regularized(s.K, s.fixing);
  return s;
}

// The dofs renumbered: natural order, or the interior dofs first and the dual rows' dofs last, in
// the dual rows' order (then B_sᵀ touches only the trailing block of the Cholesky factor).
enum class Ordering { Natural, BoundaryLast };

inline const char* name(Ordering o) {
  return o == Ordering::Natural ? "natural" : "boundary-last";
}

// position[dof] in the given ordering.
inline std::vector<int> positions(const Hex8Subdomain& s, Ordering o) {
  std::vector<int> p(s.n);
  if (o == Ordering::Natural) {
    for (int i = 0; i < s.n; ++i) p[i] = i;
    return p;
  }
  std::vector<char> dual(s.n, 0);
  for (int d : s.dualDof) dual[d] = 1;
  int next = 0;
  for (int i = 0; i < s.n; ++i)
    if (!dual[i]) p[i] = next++;
  for (int d : s.dualDof) p[d] = next++;
  return p;
}

// P A Pᵀ for the positions p (rows and columns renumbered, columns sorted again).
inline Csr permuted(const Csr& a, const std::vector<int>& p) {
  std::vector<int> inverse(a.n);
  for (int i = 0; i < a.n; ++i) inverse[p[i]] = i;
  Csr r;
  r.n = a.n;
  r.rowPtr.assign(1, 0);
  std::vector<std::pair<int, double>> row;
  for (int ip = 0; ip < a.n; ++ip) {
    const int i = inverse[ip];
    row.clear();
    for (int e = a.rowPtr[i]; e < a.rowPtr[i + 1]; ++e) row.emplace_back(p[a.col[e]], a.val[e]);
    std::sort(row.begin(), row.end());
    for (const auto& [c, v] : row) {
      r.col.push_back(c);
      r.val.push_back(v);
    }
    r.rowPtr.push_back(static_cast<int>(r.col.size()));
  }
  return r;
}

// The position of dual row k's unit column of B_sᵀ, or -1 where its dof is a fixing dof (K⁺
// zeroes those, so the row and column of F_s are zero).
inline std::vector<int> unitPositions(const Hex8Subdomain& s, const std::vector<int>& p) {
  std::vector<int> u(s.dualDof.size());
  for (std::size_t k = 0; k < u.size(); ++k) u[k] = s.isFixing(s.dualDof[k]) ? -1 : p[s.dualDof[k]];
  return u;
}

}  // namespace gpucheck
