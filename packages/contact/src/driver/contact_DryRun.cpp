#include "contact_DryRun.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <metis.h>

#include <algorithm>
#include <iomanip>
#include <numeric>
#include <sstream>

#include "tfeti_Gather.hpp"
#include "tfeti_NodeMemory.hpp"

namespace contact {

std::vector<int> fillReducingOrder(const tfeti::CsrMatrix& K) {
  const int n = K.rows;
  std::vector<idx_t> xadj(1, 0), adj;
  for (int i = 0; i < n; ++i) {
    for (int p = K.rowPtr[i]; p < K.rowPtr[i + 1]; ++p)
      if (K.colInd[p] != i) adj.push_back(K.colInd[p]);
    xadj.push_back(static_cast<idx_t>(adj.size()));
  }
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  if (n < 2 || adj.empty()) return order;
  idx_t nv = n;
  std::vector<idx_t> perm(n), iperm(n);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  if (METIS_NodeND(&nv, xadj.data(), adj.data(), nullptr, options, perm.data(), iperm.data()) !=
      METIS_OK)
    return order;  // the natural order: the estimate is then an upper bound
  for (int k = 0; k < n; ++k) order[k] = static_cast<int>(perm[k]);
  return order;
}

std::size_t choleskyFactorEntries(const tfeti::CsrMatrix& K, const std::vector<int>& order) {
  const int n = K.rows;
  std::vector<int> position(n);
  for (int k = 0; k < n; ++k) position[order[k]] = k;
  // Row k of L is the set of nodes reached from the entries A(k, j), j < k, by climbing the
  // elimination tree until a node already counted for row k (Liu's row subtrees).
  std::vector<int> parent(n, -1), flag(n, -1);
  std::size_t entries = 0;
  for (int k = 0; k < n; ++k) {
    flag[k] = k;
    ++entries;  // the diagonal
    const int row = order[k];
    for (int p = K.rowPtr[row]; p < K.rowPtr[row + 1]; ++p) {
      for (int i = position[K.colInd[p]]; i < k && flag[i] != k; i = parent[i]) {
        if (parent[i] < 0) parent[i] = k;
        flag[i] = k;
        ++entries;
      }
    }
  }
  return entries;
}

namespace {
// FETI "Memory check" as the full run will read it (its default where the list does not set it).
bool memoryChecked(const Teuchos::ParameterList& feti) {
  return !feti.isParameter("Memory check") || feti.get<bool>("Memory check");
}
}  // namespace

std::string explicitDualLine(const Teuchos::RCP<const tfeti::Comm>& comm, int numSubdomains,
                             const std::vector<tfeti::SubdomainData>& local,
                             const Teuchos::ParameterList& feti,
                             const std::vector<tfeti::InequalityRow>& inequalities,
                             const std::vector<tfeti::EqualityRow>& equalities) {
  const std::vector<long long> rows = tfeti::FetiSolver::dualRowsPerSubdomain(
      comm, numSubdomains, local, feti, inequalities, equalities);
  const auto param = [&](const char* name, const char* fallback) {
    return feti.isParameter(name) ? feti.get<std::string>(name) : std::string(fallback);
  };
  const bool packed = param("Explicit storage", "packed") == "packed";
  const tfeti::DenseStorage storage =
      packed ? tfeti::DenseStorage::Packed : tfeti::DenseStorage::Full;
  double mine[2] = {0.0, 0.0}, total = 0.0, maxRank = 0.0, largest = 0.0;  // bytes, largest m_s
  for (long long m : rows) {
    mine[0] += static_cast<double>(tfeti::explicitBlockBytes(storage, static_cast<std::size_t>(m)));
    mine[1] = std::max(mine[1], static_cast<double>(m));
  }
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &mine[0], &total);
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &mine[0], &maxRank);
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &mine[1], &largest);
  const double mb = 1024.0 * 1024.0;
  std::ostringstream s;
  const std::string kind = param("Dual operator", "implicit");
  s << "dual operator: " << kind << "; " << (kind == "explicit" ? "" : "explicit would take ")
    << "dense local F_s (" << (packed ? "packed" : "full") << ") " << std::fixed
    << std::setprecision(3) << total / mb << " MiB, largest rank " << maxRank / mb
    << " MiB, largest F_s " << static_cast<long long>(largest) << " rows";
  // Nothing is factorized yet: what a node has now is an upper bound of what the F_s will find.
  const tfeti::NodeMemory node = tfeti::nodeMemory(*comm, mine[0]);
  if (node.known)
    s << "; " << tfeti::describe(node) << " now, before the factorizations"
      << (node.fits || !memoryChecked(feti) ? "" : ": explicit would stop with an error");
  return s.str();
}

void printDryRunReport(const tfeti::Comm& comm, const std::vector<std::string>& lines,
                       const std::vector<tfeti::SubdomainData>& local, long long contactRows,
                       const Teuchos::ParameterList& feti, std::ostream& out) {
  // Per subdomain of this rank: id, unknowns, bytes of K (CSR) and of its factor (values and
  // row indices, as CHOLMOD's simplicial factor stores them).
  std::vector<double> mine;
  for (const auto& s : local) {
    const double kBytes = static_cast<double>(s.K.bytes());
    const double lBytes = static_cast<double>(choleskyFactorEntries(s.K, fillReducingOrder(s.K))) *
                          (sizeof(double) + sizeof(int));
    mine.insert(mine.end(), {static_cast<double>(comm.getRank()), static_cast<double>(s.mesh.id),
                             static_cast<double>(s.K.rows), kBytes, lBytes});
  }
  const std::vector<double> all = tfeti::allGather(comm, mine);
  double factors = 0.0;
  for (std::size_t k = 4; k < mine.size(); k += 5) factors += mine[k];
  const tfeti::NodeMemory node = tfeti::nodeMemory(comm, factors);
  if (comm.getRank() != 0) return;
  const int P = comm.getSize();
  std::vector<std::vector<int>> ids(P);
  std::vector<double> rankBytes(P, 0.0);
  double unknowns = 0.0, kTotal = 0.0, lTotal = 0.0;
  for (std::size_t k = 0; k + 4 < all.size(); k += 5) {
    const int r = static_cast<int>(all[k]);
    ids[r].push_back(static_cast<int>(all[k + 1]));
    unknowns += all[k + 2];
    kTotal += all[k + 3];
    lTotal += all[k + 4];
    rankBytes[r] += all[k + 3] + all[k + 4];
  }
  for (const auto& l : lines) out << l << "\n";
  out << "subdomains per rank:";
  for (int r = 0; r < P; ++r) {
    std::sort(ids[r].begin(), ids[r].end());
    out << (r ? "," : "") << " rank " << r << ": " << ids[r].size();
    if (!ids[r].empty() && ids[r].size() <= 12) {
      out << " {";
      for (std::size_t i = 0; i < ids[r].size(); ++i) out << (i ? " " : "") << ids[r][i];
      out << "}";
    }
  }
  out << "\nunknowns: " << static_cast<long long>(unknowns)
      << " (primal, every subdomain's copy of an interface node counted)";
  if (contactRows >= 0) out << "; contact rows: " << contactRows;
  const double mb = 1024.0 * 1024.0;
  out << "\nestimated memory: subdomain matrices " << std::fixed << std::setprecision(1)
      << kTotal / mb << " MiB + Cholesky factors " << lTotal / mb
      << " MiB (METIS order, symbolic count), largest rank "
      << *std::max_element(rankBytes.begin(), rankBytes.end()) / mb << " MiB" << std::defaultfloat;
  // Nothing is factorized yet: what a node has now is what the factorizations will find.
  if (node.known)
    out << "; for the factors " << tfeti::describe(node) << " now"
        << (node.fits || !memoryChecked(feti) ? ""
                                              : ": the factorizations would stop with an error");
  out << "\n";
}

}  // namespace contact
