// The dry run's memory estimate: the symbolic count of the Cholesky factor's entries against
// closed forms (a tridiagonal matrix has no fill; an arrow matrix fills completely when its hub
// is eliminated first and not at all when it is eliminated last; a dense matrix gives
// n(n+1)/2), against a brute-force symbolic elimination on a 2D grid, and the fill-reducing order
// being a permutation that does not fill more than the natural order there.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <numeric>
#include <set>
#include <vector>

#include "contact_DryRun.hpp"

namespace {

tfeti::CsrMatrix pattern(int n, const std::vector<std::pair<int, int>>& offDiagonal) {
  std::vector<int> r, c;
  std::vector<double> v;
  for (int i = 0; i < n; ++i) r.push_back(i), c.push_back(i), v.push_back(1.0);
  for (auto [i, j] : offDiagonal) {
    r.insert(r.end(), {i, j});
    c.insert(c.end(), {j, i});
    v.insert(v.end(), {1.0, 1.0});
  }
  return tfeti::csrFromTriplets(n, n, r, c, v);
}

std::vector<int> identity(int n) {
  std::vector<int> o(n);
  std::iota(o.begin(), o.end(), 0);
  return o;
}

// Symbolic Gaussian elimination on sets: the entries of L in the given order.
std::size_t bruteForce(const tfeti::CsrMatrix& K, const std::vector<int>& order) {
  const int n = K.rows;
  std::vector<int> pos(n);
  for (int k = 0; k < n; ++k) pos[order[k]] = k;
  std::vector<std::set<int>> lower(n);  // lower[j]: rows i > j with L(i, j) != 0
  for (int i = 0; i < n; ++i)
    for (int p = K.rowPtr[i]; p < K.rowPtr[i + 1]; ++p) {
      const int a = pos[i], b = pos[K.colInd[p]];
      if (a > b) lower[b].insert(a);
    }
  std::size_t entries = 0;
  for (int j = 0; j < n; ++j) {
    entries += 1 + lower[j].size();
    for (int a : lower[j])
      for (int b : lower[j])
        if (a > b) lower[b].insert(a);
  }
  return entries;
}

TEUCHOS_UNIT_TEST(DryRun, CholeskyEntriesClosedForms) {
  const int n = 50;
  std::vector<std::pair<int, int>> chain, arrow, dense;
  for (int i = 0; i + 1 < n; ++i) chain.push_back({i, i + 1});
  for (int i = 1; i < n; ++i) arrow.push_back({0, i});
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) dense.push_back({i, j});
  TEST_EQUALITY(contact::choleskyFactorEntries(pattern(n, chain), identity(n)),
                static_cast<std::size_t>(2 * n - 1));
  TEST_EQUALITY(contact::choleskyFactorEntries(pattern(n, arrow), identity(n)),
                static_cast<std::size_t>(n * (n + 1) / 2));
  std::vector<int> hubLast = identity(n);
  std::rotate(hubLast.begin(), hubLast.begin() + 1, hubLast.end());
  TEST_EQUALITY(contact::choleskyFactorEntries(pattern(n, arrow), hubLast),
                static_cast<std::size_t>(2 * n - 1));
  TEST_EQUALITY(contact::choleskyFactorEntries(pattern(n, dense), identity(n)),
                static_cast<std::size_t>(n * (n + 1) / 2));
}

TEUCHOS_UNIT_TEST(DryRun, CholeskyEntriesOfAGridAgainstBruteForce) {
  const int m = 12, n = m * m;  // 5-point stencil on an m x m grid
  std::vector<std::pair<int, int>> edges;
  for (int y = 0; y < m; ++y)
    for (int x = 0; x < m; ++x) {
      if (x + 1 < m) edges.push_back({y * m + x, y * m + x + 1});
      if (y + 1 < m) edges.push_back({y * m + x, (y + 1) * m + x});
    }
  const tfeti::CsrMatrix K = pattern(n, edges);
  const std::vector<int> nd = contact::fillReducingOrder(K);
  std::vector<int> sorted = nd;
  std::sort(sorted.begin(), sorted.end());
  TEST_ASSERT(sorted == identity(n));
  for (const auto& order : {identity(n), nd})
    TEST_EQUALITY(contact::choleskyFactorEntries(K, order), bruteForce(K, order));
  // Banded natural order: m + 1 entries per column at most; nested dissection does better.
  TEST_ASSERT(contact::choleskyFactorEntries(K, nd) <
              contact::choleskyFactorEntries(K, identity(n)));
}

}  // namespace
