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
const double kMiB = 1024.0 * 1024.0;

// The explicit F_s: their bytes, over all ranks and on the largest, and against each node's
// memory after the factors and the preconditioner as the run's check will find it (factors:
// what this rank's factors hold).
std::string explicitDualLine(const tfeti::Comm& comm, const tfeti::SetupMemoryForecast& f,
                             double factors, const Teuchos::ParameterList& feti) {
  double mine[2] = {f.explicitBlocks, 0.0}, total = 0.0, maxRank = 0.0, largest = 0.0;
  for (long long m : f.dualRows) mine[1] = std::max(mine[1], static_cast<double>(m));
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &mine[0], &total);
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &mine[0], &maxRank);
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &mine[1], &largest);
  const std::string kind = feti.get<std::string>("Dual operator");
  std::ostringstream s;
  s << "dual operator: " << kind << "; " << (kind == "explicit" ? "" : "explicit would take ")
    << "dense local F_s (" << feti.get<std::string>("Explicit storage") << ") " << std::fixed
    << std::setprecision(3) << total / kMiB << " MiB, largest rank " << maxRank / kMiB
    << " MiB, largest F_s " << static_cast<long long>(largest) << " rows";
  // The run checks them once the factors and the preconditioner are made: their bytes come
  // on top of what a node has now.
  const double need = factors + f.preconditionerLeaves + f.explicitNeed();
  const tfeti::NodeMemory node = tfeti::nodeMemory(comm, need);
  if (node.known) {
    s << "; after the factors and the preconditioner " << tfeti::describe(node) << " now";
    if (!node.fits && feti.get<bool>("Memory check") && kind != "implicit")
      s << (kind == "explicit" ? ": explicit would stop with an error"
                               : ": auto would fall back to implicit");
  }
  return s.str();
}

// The subdomain factors over all ranks: what they hold (the local solver's analyses, or where
// it cannot tell a METIS count, an estimate the run does not check).
std::string factorsText(const tfeti::Comm& comm, bool known, double factors,
                        const std::string& solver) {
  double all = 0.0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &factors, &all);
  std::ostringstream s;
  s << "Cholesky factors " << std::fixed << std::setprecision(1) << all / kMiB
    << (known
            ? " MiB (" + solver + "'s symbolic analyses: what the factors will hold)"
            : " MiB (METIS order, symbolic count: " + solver + " cannot tell before factorizing)");
  return s.str();
}

// Their need while they are made (the factors so far and the next factorization's transient)
// against the fullest node: nothing is factorized yet, so what a node has now is what the
// factorizations will find.
std::string factorsCheck(const tfeti::Comm& comm, const tfeti::SetupMemoryForecast& f, bool known,
                         double factors, const Teuchos::ParameterList& feti) {
  const tfeti::NodeMemory node = tfeti::nodeMemory(comm, known ? f.factorPeak : factors);
  if (!node.known) return "";
  return "; for the factors " + tfeti::describe(node) + " now" +
         (node.fits || !feti.get<bool>("Memory check") || !known
              ? ""
              : ": the factorizations would stop with an error");
}

// The Dirichlet preconditioner (its blocks and interior factors), on top of the subdomain
// factors.
std::string preconditionerLine(const tfeti::Comm& comm, const tfeti::SetupMemoryForecast& f,
                               bool known, const Teuchos::ParameterList& feti) {
  double mine[2] = {f.interiorPeak, f.preconditionerLeaves}, all[2] = {0.0, 0.0};
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 2, mine, all);
  const tfeti::NodeMemory node = tfeti::nodeMemory(comm, f.factors + f.interiorPeak);
  std::ostringstream s;
  s << "Dirichlet preconditioner: ";
  if (!known) {
    s << "interior factors unknown (" << feti.get<std::string>("Local solver")
      << " cannot tell before factorizing; unchecked)";
    return s.str();
  }
  s << "set-up peak " << std::fixed << std::setprecision(1) << all[0] / kMiB
    << " MiB beyond the subdomain factors (blocks K_bb and K_bi, interior factors, a "
       "factorization's transient; "
    << all[1] / kMiB << " MiB once all are made, less the K freed)";
  if (node.known)
    s << "; with the factors " << tfeti::describe(node) << " now"
      << (node.fits || !feti.get<bool>("Memory check")
              ? ""
              : ": the preconditioner's set-up would stop with an error");
  return s.str();
}

// Every rank's subdomains (id, unknowns, bytes of K) and every rank's factors' bytes, gathered.
struct SubdomainTable {
  std::vector<std::vector<int>> ids;  // per rank
  std::vector<double> rankBytes;      // per rank: its K and its factors
  double unknowns = 0.0, kBytes = 0.0;
};

SubdomainTable gatherSubdomains(const tfeti::Comm& comm,
                                const std::vector<tfeti::SubdomainData>& local, double factors) {
  std::vector<double> mine;
  double kBytes = factors;
  for (const auto& s : local) {
    mine.insert(mine.end(), {static_cast<double>(comm.getRank()), static_cast<double>(s.mesh.id),
                             static_cast<double>(s.K.rows), static_cast<double>(s.K.bytes())});
    kBytes += static_cast<double>(s.K.bytes());
  }
  const std::vector<double> all = tfeti::allGather(comm, mine);
  SubdomainTable t;
  t.ids.resize(comm.getSize());
  t.rankBytes = tfeti::allGather(comm, std::vector<double>{kBytes});
  for (std::size_t k = 0; k + 3 < all.size(); k += 4) {
    t.ids[static_cast<int>(all[k])].push_back(static_cast<int>(all[k + 1]));
    t.unknowns += all[k + 2];
    t.kBytes += all[k + 3];
  }
  return t;
}

void printSubdomainsPerRank(std::vector<std::vector<int>> ids, std::ostream& out) {
  out << "subdomains per rank:";
  for (std::size_t r = 0; r < ids.size(); ++r) {
    std::sort(ids[r].begin(), ids[r].end());
    out << (r ? "," : "") << " rank " << r << ": " << ids[r].size();
    if (!ids[r].empty() && ids[r].size() <= 12) {
      out << " {";
      for (std::size_t i = 0; i < ids[r].size(); ++i) out << (i ? " " : "") << ids[r][i];
      out << "}";
    }
  }
  out << "\n";
}
}  // namespace

void printDryRunReport(const Teuchos::RCP<const tfeti::Comm>& comm, int numSubdomains,
                       const std::vector<std::string>& lines,
                       const std::vector<tfeti::SubdomainData>& local, long long contactRows,
                       const Teuchos::ParameterList& fetiAsGiven, std::ostream& out,
                       const std::vector<tfeti::InequalityRow>& inequalities,
                       const std::vector<tfeti::EqualityRow>& equalities) {
  // The settings as the run reads them, and the same analyses as the run's: what its checks
  // will count, to the byte.
  const Teuchos::ParameterList feti = tfeti::FetiSolver::validatedParameters(fetiAsGiven);
  const tfeti::SetupMemoryForecast forecast = tfeti::FetiSolver::forecastSetupMemory(
      comm, numSubdomains, local, feti, inequalities, equalities);
  int unknown[2] = {forecast.factorsKnown ? 0 : 1, forecast.interiorKnown ? 0 : 1},
      anyUnknown[2] = {0, 0};
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 2, unknown, anyUnknown);
  const bool factorsKnown = !anyUnknown[0];
  // This rank's factors: the forecast's, or where the local solver cannot tell (KLU2, Tacho)
  // the entries of L under a METIS order (values and row indices, as a simplicial factor stores
  // them).
  double factors = forecast.factors;
  if (!factorsKnown)
    for (const auto& s : local)
      factors += static_cast<double>(choleskyFactorEntries(s.K, fillReducingOrder(s.K))) *
                 (sizeof(double) + sizeof(int));
  const std::string dualLine = explicitDualLine(*comm, forecast, factors, feti);
  const std::string factorsLine =
      factorsText(*comm, factorsKnown, factors, feti.get<std::string>("Local solver"));
  const std::string factorsChecked = factorsCheck(*comm, forecast, factorsKnown, factors, feti);
  const bool dirichlet = feti.get<std::string>("Preconditioner") == "dirichlet";
  const std::string preconditioner =
      dirichlet ? preconditionerLine(*comm, forecast, !anyUnknown[1], feti) : std::string();
  const SubdomainTable table = gatherSubdomains(*comm, local, factors);
  if (comm->getRank() != 0) return;
  for (const auto& l : lines) out << l << "\n";
  out << dualLine << "\n";
  printSubdomainsPerRank(table.ids, out);
  out << "unknowns: " << static_cast<long long>(table.unknowns)
      << " (primal, every subdomain's copy of an interface node counted)";
  if (contactRows >= 0) out << "; contact rows: " << contactRows;
  out << "\nestimated memory: subdomain matrices " << std::fixed << std::setprecision(1)
      << table.kBytes / kMiB << " MiB + " << factorsLine << ", largest rank "
      << *std::max_element(table.rankBytes.begin(), table.rankBytes.end()) / kMiB << " MiB"
      << std::defaultfloat << factorsChecked << "\n";
  if (dirichlet) out << preconditioner << "\n";
}

}  // namespace contact
