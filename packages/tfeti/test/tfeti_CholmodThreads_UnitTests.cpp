// CHOLMOD's supernodal factorization must not start OpenMP threads: every MPI rank is one core,
// and CHOLMOD's fixed num_threads(4) regions made three extra threads per rank spin against the
// other ranks (docs/benchmarks.md). Its own executable, so that no earlier test has already
// created (or avoided) an OpenMP thread pool. A user's OMP_THREAD_LIMIT is respected instead of
// overridden: with it set, the test requires that CHOLMOD stays within that limit.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "tfeti_CsrMatrix.hpp"
#include "tfeti_LocalSolver.hpp"

namespace {

// Threads of this process, from /proc/self/status.
int threadCount() {
  std::ifstream in("/proc/self/status");
  std::string key;
  while (in >> key) {
    if (key == "Threads:") {
      int n = 0;
      in >> n;
      return n;
    }
    std::getline(in, key);
  }
  return -1;
}

// 7-point Laplacian on a g^3 grid plus the identity: SPD, and with a 3D fill pattern large
// supernodes, i.e. CHOLMOD's parallel regions (they open above 32-128 columns or rows).
tfeti::CsrMatrix laplacian3d(int g) {
  std::vector<int> ri, ci;
  std::vector<double> v;
  auto id = [g](int x, int y, int z) { return (z * g + y) * g + x; };
  for (int z = 0; z < g; ++z)
    for (int y = 0; y < g; ++y)
      for (int x = 0; x < g; ++x) {
        const int i = id(x, y, z);
        ri.push_back(i);
        ci.push_back(i);
        v.push_back(7.0);
        const int nb[6][3] = {{x - 1, y, z}, {x + 1, y, z}, {x, y - 1, z},
                              {x, y + 1, z}, {x, y, z - 1}, {x, y, z + 1}};
        for (const auto& n : nb) {
          if (n[0] < 0 || n[1] < 0 || n[2] < 0 || n[0] >= g || n[1] >= g || n[2] >= g) continue;
          ri.push_back(i);
          ci.push_back(id(n[0], n[1], n[2]));
          v.push_back(-1.0);
        }
      }
  return tfeti::csrFromTriplets(g * g * g, g * g * g, ri, ci, v);
}

}  // namespace

TEUCHOS_UNIT_TEST(CholmodThreads, SupernodalFactorizationStartsNoThread) {
  const tfeti::CsrMatrix A = laplacian3d(24);
  const int before = threadCount();
  TEST_COMPARE(before, >, 0);
  auto solver = tfeti::createLocalSolver("cholmod-supernodal");
  solver->factorize(A);
  // The factorization is real: it solves A x = b to rounding.
  std::vector<double> b(A.rows, 1.0), x(A.rows, 0.0), r(A.rows);
  solver->solve(b.data(), x.data());
  A.multiply(x.data(), r.data());
  double res = 0.0;
  for (int i = 0; i < A.rows; ++i) res += (r[i] - b[i]) * (r[i] - b[i]);
  TEST_COMPARE(std::sqrt(res / A.rows), <, 1e-12);
  // OMP_THREAD_LIMIT counts the encountering thread too.
  if (const char* limit = std::getenv("OMP_THREAD_LIMIT")) {
    TEST_COMPARE(threadCount() - before, <=, std::max(0, std::atoi(limit) - 1));
  } else {
    TEST_EQUALITY(threadCount(), before);
  }
}
