#include "tfeti_SubdomainDistribution.hpp"

#include <metis.h>
#include <mpi.h>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Tpetra_CrsGraph.hpp>
#include <Zoltan2_PartitioningProblem.hpp>
#include <Zoltan2_XpetraCrsGraphAdapter.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <utility>

#include "tfeti_SubdomainMesh.hpp"

namespace tfeti {

namespace {

// Debian's Trilinos 13.2 has Scotch (PT-Scotch) but neither ParMETIS nor METIS in Zoltan2; Zoltan's
// own hypergraph partitioner (PHG) is always built and serves where Scotch is missing.
#ifdef HAVE_ZOLTAN2_SCOTCH
const char* const kGraphAlgorithm = "scotch";
#else
const char* const kGraphAlgorithm = "zoltan";
#endif

std::string where(int s) {
  return "subdomain " + std::to_string(s);
}

[[noreturn]] void invalid(const std::string& what) {
  throw std::invalid_argument("tfeti::SubdomainGraph: " + what);
}

bool positiveFinite(double w) {
  return std::isfinite(w) && w > 0.0;
}

// The weight of edge (s, t), or a negative value if the edge is absent. Rows are short (a
// subdomain has a handful of neighbours), so a linear scan beats building an index.
double edgeWeight(const SubdomainGraph& g, int s, int t) {
  for (int k = g.offsets[s]; k < g.offsets[s + 1]; ++k)
    if (g.adjacency[k] == t) return g.edgeWeights[k];
  return -1.0;
}

// A fingerprint of the whole graph, to check that every rank was given the same one: the result
// is computed on rank 0 only, so a rank with a different graph would silently get a wrong answer.
std::uint64_t fingerprint(const SubdomainGraph& g) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a
  auto mix = [&h](const void* data, std::size_t bytes) {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  const std::size_t sizes[5] = {g.weights.size(), g.offsets.size(), g.adjacency.size(),
                                g.edgeWeights.size(), g.contactWeights.size()};
  mix(sizes, sizeof(sizes));
  mix(g.contactWeights.data(), g.contactWeights.size() * sizeof(double));
  mix(g.weights.data(), g.weights.size() * sizeof(double));
  mix(g.offsets.data(), g.offsets.size() * sizeof(int));
  mix(g.adjacency.data(), g.adjacency.size() * sizeof(int));
  mix(g.edgeWeights.data(), g.edgeWeights.size() * sizeof(double));
  return h;
}

// Gives every rank the message of the first rank (lowest id) that failed, so that all ranks
// throw together instead of the healthy ones waiting forever in the next collective.
void throwIfAnyFailed(const Comm& comm, const std::string& localError) {
  const int size = comm.getSize();
  const int mine = localError.empty() ? size : comm.getRank();
  int first = size;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MIN, mine, Teuchos::outArg(first));
  if (first == size) return;
  int length = static_cast<int>(localError.size());
  Teuchos::broadcast(comm, first, Teuchos::outArg(length));
  std::string message(length, ' ');
  if (comm.getRank() == first) message = localError;
  if (length > 0) Teuchos::broadcast(comm, first, length, &message[0]);
  throw std::runtime_error("tfeti::distributeSubdomains failed on rank " + std::to_string(first) +
                           ": " + message);
}

// Sets an environment variable for the lifetime of the object and then restores it.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) {
      hadValue_ = true;
      old_ = old;
    }
    setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (hadValue_)
      setenv(name_.c_str(), old_.c_str(), 1);
    else
      unsetenv(name_.c_str());
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  std::string name_, old_;
  bool hadValue_ = false;
};

}  // namespace

SubdomainGraph makeSubdomainGraph(std::vector<double> weights,
                                  const std::vector<SubdomainEdge>& edges) {
  const int n = static_cast<int>(weights.size());
  std::vector<std::vector<std::pair<int, double>>> rows(n);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const SubdomainEdge& edge = edges[e];
    const std::string name = "edge " + std::to_string(e) + " (" + std::to_string(edge.a) + ", " +
                             std::to_string(edge.b) + ")";
    if (edge.a < 0 || edge.a >= n || edge.b < 0 || edge.b >= n)
      invalid(name + ": subdomain id out of range [0, " + std::to_string(n) + ")");
    if (edge.a == edge.b) invalid(name + ": self-loop");
    if (!positiveFinite(edge.weight))
      invalid(name + ": edge weight must be positive and finite, got " +
              std::to_string(edge.weight));
    rows[edge.a].push_back({edge.b, edge.weight});
    rows[edge.b].push_back({edge.a, edge.weight});
  }
  SubdomainGraph g;
  g.weights = std::move(weights);
  g.offsets.assign(1, 0);
  for (int s = 0; s < n; ++s) {
    std::sort(rows[s].begin(), rows[s].end());
    for (std::size_t k = 0; k < rows[s].size(); ++k) {
      if (k > 0 && rows[s][k].first == rows[s][k - 1].first)
        invalid("edge (" + std::to_string(s) + ", " + std::to_string(rows[s][k].first) +
                ") listed more than once");
      g.adjacency.push_back(rows[s][k].first);
      g.edgeWeights.push_back(rows[s][k].second);
    }
    g.offsets.push_back(static_cast<int>(g.adjacency.size()));
  }
  validateSubdomainGraph(g);
  return g;
}

void validateSubdomainGraph(const SubdomainGraph& g) {
  const int n = g.numSubdomains();
  for (int s = 0; s < n; ++s)
    if (!positiveFinite(g.weights[s]))
      invalid(where(s) + ": weight must be positive and finite, got " +
              std::to_string(g.weights[s]));
  if (!g.contactWeights.empty() && static_cast<int>(g.contactWeights.size()) != n)
    invalid("contactWeights has " + std::to_string(g.contactWeights.size()) +
            " entries, expected none or " + std::to_string(n) + " (one per subdomain)");
  for (std::size_t s = 0; s < g.contactWeights.size(); ++s)
    if (!std::isfinite(g.contactWeights[s]) || g.contactWeights[s] < 0.0)
      invalid(where(static_cast<int>(s)) + ": contact weight must be finite and >= 0, got " +
              std::to_string(g.contactWeights[s]));
  if (static_cast<int>(g.offsets.size()) != n + 1)
    invalid("offsets has " + std::to_string(g.offsets.size()) + " entries, expected " +
            std::to_string(n + 1) + " (number of subdomains + 1)");
  if (g.offsets[0] != 0) invalid("offsets[0] must be 0, got " + std::to_string(g.offsets[0]));
  for (int s = 0; s < n; ++s)
    if (g.offsets[s + 1] < g.offsets[s]) invalid("offsets decrease at " + where(s));
  if (static_cast<std::size_t>(g.offsets[n]) != g.adjacency.size())
    invalid("offsets end at " + std::to_string(g.offsets[n]) + " but adjacency has " +
            std::to_string(g.adjacency.size()) + " entries");
  if (g.edgeWeights.size() != g.adjacency.size())
    invalid("edgeWeights has " + std::to_string(g.edgeWeights.size()) + " entries, adjacency has " +
            std::to_string(g.adjacency.size()));
  // Every entry on its own first, so that a bad id or weight is reported as such and not as
  // the asymmetry it also causes.
  for (int s = 0; s < n; ++s) {
    std::vector<int> seen;
    for (int k = g.offsets[s]; k < g.offsets[s + 1]; ++k) {
      const int t = g.adjacency[k];
      const std::string edge = "edge (" + std::to_string(s) + ", " + std::to_string(t) + ")";
      if (t < 0 || t >= n)
        invalid(edge + ": neighbour id out of range [0, " + std::to_string(n) + ")");
      if (t == s) invalid(edge + ": self-loop");
      if (!positiveFinite(g.edgeWeights[k]))
        invalid(edge + ": edge weight must be positive and finite, got " +
                std::to_string(g.edgeWeights[k]));
      if (std::find(seen.begin(), seen.end(), t) != seen.end())
        invalid(edge + ": neighbour listed more than once");
      seen.push_back(t);
    }
  }
  for (int s = 0; s < n; ++s)
    for (int k = g.offsets[s]; k < g.offsets[s + 1]; ++k) {
      const int t = g.adjacency[k];
      const std::string edge = "edge (" + std::to_string(s) + ", " + std::to_string(t) + ")";
      const double back = edgeWeight(g, t, s);
      if (back < 0.0)
        invalid("graph is not symmetric: " + edge + " present, (" + std::to_string(t) + ", " +
                std::to_string(s) + ") missing");
      if (back != g.edgeWeights[k])
        invalid("graph is not symmetric: " + edge + " has weight " +
                std::to_string(g.edgeWeights[k]) + ", the reverse edge " + std::to_string(back));
    }
}

DistributionMethod distributionMethodFromString(const std::string& name) {
  if (name == "block") return DistributionMethod::Block;
  if (name == "graph") return DistributionMethod::Graph;
  throw std::invalid_argument("unknown subdomain distribution \"" + name +
                              "\"; valid: \"block\", \"graph\"");
}

std::string toString(DistributionMethod method) {
  return method == DistributionMethod::Block ? "block" : "graph";
}

namespace detail {

std::vector<int> zoltan2Partition(const SubdomainGraph& g, int numParts,
                                  const std::string& algorithm) {
  using Graph = Tpetra::CrsGraph<LO, GO, Node>;
  using Adapter = Zoltan2::XpetraCrsGraphAdapter<Graph>;
  using offset_t = Adapter::offset_t;
  using gno_t = Adapter::gno_t;

  validateSubdomainGraph(g);
  if (numParts < 1)
    throw std::invalid_argument("tfeti::detail::zoltan2Partition: numParts must be >= 1, got " +
                                std::to_string(numParts));
  const int n = g.numSubdomains();
  if (n == 0) return {};
  // A one-process communicator: the partition must not depend on how many ranks run, and
  // partitioning a few thousand vertices serially costs next to nothing.
  Teuchos::RCP<const Comm> self = Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF));
  Teuchos::RCP<const Map> map = Teuchos::rcp(new Map(n, 0, self));
  Teuchos::Array<std::size_t> rowLengths(n);
  for (int s = 0; s < n; ++s) rowLengths[s] = g.offsets[s + 1] - g.offsets[s];
  Teuchos::RCP<Graph> crs = Teuchos::rcp(new Graph(map, rowLengths()));
  for (int s = 0; s < n; ++s) {
    Teuchos::Array<GO> cols(g.adjacency.begin() + g.offsets[s],
                            g.adjacency.begin() + g.offsets[s + 1]);
    if (!cols.empty()) crs->insertGlobalIndices(s, cols());
  }
  crs->fillComplete();

  Adapter adapter(Teuchos::RCP<const Graph>(crs), 1, 1);
  adapter.setVertexWeights(g.weights.data(), 1, 0);
  // fillComplete reorders each row's columns, so the edge weights are laid out in the order the
  // adapter reports the edges, not in the input's order.
  const offset_t* offsets = nullptr;
  const gno_t* adjacency = nullptr;
  adapter.getEdgesView(offsets, adjacency);
  std::vector<double> weights(offsets[n]);
  for (int s = 0; s < n; ++s)
    for (offset_t k = offsets[s]; k < offsets[s + 1]; ++k)
      weights[k] = edgeWeight(g, s, static_cast<int>(adjacency[k]));
  adapter.setEdgeWeights(weights.data(), 1, 0);

  Teuchos::ParameterList params("Zoltan2");
  params.set("algorithm", algorithm);
  params.set("num_global_parts", numParts);
  params.set("partitioning_approach", "partition");
  // Honoured by Zoltan's PHG; Zoltan2 13.2 runs Scotch with its default strategy, which aims at
  // the same 5 %.
  params.set("imbalance_tolerance", 1.05);
  if (algorithm == "zoltan") {
    Teuchos::ParameterList& z = params.sublist("zoltan_parameters");
    // Zoltan applies parameters in order: quiet first, or it announces the method.
    z.set("DEBUG_LEVEL", "0");
    z.set("LB_METHOD", "HYPERGRAPH");
    // PHG's coarsening is randomized; a fixed seed makes repeated calls agree.
    z.set("SEED", "1");
  }

#ifdef HAVE_ZOLTAN2_SCOTCH
  // Scotch draws from a process-global generator that advances with every call: fix the seed and
  // rewind it, or successive calls could partition the same graph differently. (Zoltan2 includes
  // scotch.h inside its namespace.)
  Zoltan2::SCOTCH_randomProc(0);
  Zoltan2::SCOTCH_randomSeed(1);
  Zoltan2::SCOTCH_randomReset();
  // Debian's Scotch 7 is threaded and its result depends on the thread count and timing (seen:
  // two ranks of one run disagreeing); one thread makes it a function of the graph alone.
  const ScopedEnv oneThread("SCOTCH_PTHREAD_NUMBER", "1");
#endif
  Zoltan2::PartitioningProblem<Adapter> problem(&adapter, &params, self);
  problem.solve();
  const auto* parts = problem.getSolution().getPartListView();
  std::vector<int> owners(parts, parts + n);
  for (int s = 0; s < n; ++s)
    if (owners[s] < 0 || owners[s] >= numParts)
      throw std::runtime_error("Zoltan2 (" + algorithm + ") put " + where(s) + " in part " +
                               std::to_string(owners[s]) + " of " + std::to_string(numParts));
  return owners;
}

std::vector<int> metisTwoConstraintPartition(const SubdomainGraph& g, int numParts,
                                             double contactTolerance) {
  validateSubdomainGraph(g);
  const int n = g.numSubdomains();
  if (numParts < 1)
    throw std::invalid_argument(
        "tfeti::detail::metisTwoConstraintPartition: numParts must be >= 1, got " +
        std::to_string(numParts));
  if (static_cast<int>(g.contactWeights.size()) != n)
    throw std::invalid_argument(
        "tfeti::detail::metisTwoConstraintPartition: the graph has no contact weights");
  // METIS takes integers, and sums them in 32 bits: each kind is scaled so that its largest entry
  // is at least 100 (fractional weights stay apart) and its total at most 1e8.
  auto scaleOf = [](const std::vector<double>& w) {
    double max = 0.0, total = 0.0;
    for (double v : w) {
      max = std::max(max, v);
      total += v;
    }
    if (total <= 0.0) return 1.0;
    return std::min(max < 100.0 ? 100.0 / max : 1.0, 1e8 / total);
  };
  const double weightScale = scaleOf(g.weights), contactScale = scaleOf(g.contactWeights),
               edgeScale = scaleOf(g.edgeWeights);
  auto scaled = [](double w, double scale, idx_t least) {
    return std::max<idx_t>(static_cast<idx_t>(std::llround(w * scale)), least);
  };
  std::vector<idx_t> vwgt(2 * static_cast<std::size_t>(n)),
      xadj(g.offsets.begin(), g.offsets.end()), adjncy(g.adjacency.begin(), g.adjacency.end()),
      adjwgt(g.edgeWeights.size());
  for (int s = 0; s < n; ++s) {
    vwgt[2 * s] = scaled(g.weights[s], weightScale, 1);
    vwgt[2 * s + 1] = scaled(g.contactWeights[s], contactScale, 0);
  }
  for (std::size_t k = 0; k < adjwgt.size(); ++k)
    adjwgt[k] = scaled(g.edgeWeights[k], edgeScale, 1);
  idx_t nvtxs = n, ncon = 2, nparts = numParts, objval = 0;
  std::vector<idx_t> part(n, 0);
  std::vector<real_t> ubvec = {static_cast<real_t>(1.02), static_cast<real_t>(contactTolerance)};
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;
  options[METIS_OPTION_NUMBERING] = 0;
  // Recursive bisection for a few parts (METIS' advice up to 8), k-way beyond.
  const int status =
      numParts <= 8 ? METIS_PartGraphRecursive(&nvtxs, &ncon, xadj.data(), adjncy.data(),
                                               vwgt.data(), nullptr, adjwgt.data(), &nparts,
                                               nullptr, ubvec.data(), options, &objval, part.data())
                    : METIS_PartGraphKway(&nvtxs, &ncon, xadj.data(), adjncy.data(), vwgt.data(),
                                          nullptr, adjwgt.data(), &nparts, nullptr, ubvec.data(),
                                          options, &objval, part.data());
  if (status != METIS_OK)
    throw std::runtime_error("METIS (two constraints) failed with status " +
                             std::to_string(status) + " on " + std::to_string(n) +
                             " subdomains and " + std::to_string(numParts) + " parts");
  std::vector<int> owners(part.begin(), part.end());
  for (int s = 0; s < n; ++s)
    if (owners[s] < 0 || owners[s] >= numParts)
      throw std::runtime_error("METIS put " + where(s) + " in part " + std::to_string(owners[s]) +
                               " of " + std::to_string(numParts));
  return owners;
}

}  // namespace detail

namespace {

// The dofs come first: a rank with more of them is slower in every F-apply, a rank with more of
// the contact rows only where they move or yield. A two-constraint partition is kept when its
// dof imbalance is below 1.05 or within 2 % of the one-constraint partition's (few subdomains per
// rank leave METIS little room for both) and it balances the contact rows better.
constexpr double kDofImbalanceAllowed = 1.05, kDofImbalanceRatio = 1.02;

// The contact rows balanced as well, by METIS, where that costs little dof balance: the best
// contact balance among its partitions for several contact targets (METIS meets the dof target
// of 1.02 only loosely once the contact one is tight) that keep the dofs acceptable and improve
// on the one-weight partition `alone`; empty when none does.
std::vector<int> bestTwoConstraintPartition(const SubdomainGraph& graph, int numRanks,
                                            const std::vector<int>& alone) {
  const double allowed =
      std::max(kDofImbalanceAllowed, kDofImbalanceRatio * weightImbalance(graph, alone, numRanks));
  std::vector<int> best;
  double bestContact = contactImbalance(graph, alone, numRanks);
  for (double tolerance : {1.05, 1.1, 1.2, 1.5}) {
    std::vector<int> both = detail::metisTwoConstraintPartition(graph, numRanks, tolerance);
    const double contact = contactImbalance(graph, both, numRanks);
    if (weightImbalance(graph, both, numRanks) <= allowed && contact < bestContact) {
      best = std::move(both);
      bestContact = contact;
    }
  }
  return best;
}

std::pair<std::string, std::vector<int>> choosePartition(const SubdomainGraph& graph, int numRanks,
                                                         DistributionMethod method) {
  const int n = graph.numSubdomains();
  std::vector<int> owners(n, 0);
  if (method == DistributionMethod::Block) {
    for (int s = 0; s < n; ++s) owners[s] = ownerOfSubdomain(s, n, numRanks);
    return {"block", owners};
  }
  // With no more subdomains than ranks one subdomain per rank is optimal for balance, and the
  // partitioners may pair subdomains up and leave ranks idle.
  if (numRanks == 1 || n <= numRanks) {
    for (int s = 0; s < n && numRanks > 1; ++s) owners[s] = s;
    return {"single", owners};
  }
  owners = detail::zoltan2Partition(graph, numRanks, kGraphAlgorithm);
  const bool contact = std::any_of(graph.contactWeights.begin(), graph.contactWeights.end(),
                                   [](double w) { return w > 0.0; });
  if (!contact) return {kGraphAlgorithm, owners};
  std::vector<int> both = bestTwoConstraintPartition(graph, numRanks, owners);
  if (both.empty()) return {kGraphAlgorithm, owners};
  return {"metis_two_constraints", both};
}

// The partitioners' names, so that rank 0 can pass its choice on as an index.
const char* const kPartitioners[] = {"block", "single", "scotch", "zoltan",
                                     "metis_two_constraints"};

}  // namespace

std::vector<int> partitionSubdomains(const SubdomainGraph& graph, int numRanks,
                                     DistributionMethod method, std::string* partitioner) {
  if (numRanks < 1)
    throw std::invalid_argument("tfeti::partitionSubdomains: numRanks must be >= 1, got " +
                                std::to_string(numRanks));
  validateSubdomainGraph(graph);
  auto [name, owners] = choosePartition(graph, numRanks, method);
  if (partitioner) *partitioner = name;
  return owners;
}

std::vector<int> distributeSubdomains(const Comm& comm, const SubdomainGraph& graph,
                                      DistributionMethod method, std::string* partitioner) {
  std::string error;
  try {
    validateSubdomainGraph(graph);
  } catch (const std::exception& e) {
    error = e.what();
  }
  throwIfAnyFailed(comm, error);

  std::uint64_t reference = fingerprint(graph);
  Teuchos::broadcast(comm, 0, Teuchos::outArg(reference));
  if (reference != fingerprint(graph))
    error = "the subdomain graph differs from rank 0's; every rank must pass the same graph";
  throwIfAnyFailed(comm, error);

  std::vector<int> owners(graph.numSubdomains(), 0);
  int chosen = 0;
  if (comm.getRank() == 0) {
    try {
      std::string name;
      owners = partitionSubdomains(graph, comm.getSize(), method, &name);
      const auto* end = std::end(kPartitioners);
      chosen = static_cast<int>(std::find(std::begin(kPartitioners), end, name) -
                                std::begin(kPartitioners));
      if (chosen == static_cast<int>(end - std::begin(kPartitioners)))
        error = "unknown partitioner " + name;
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  throwIfAnyFailed(comm, error);
  if (!owners.empty()) Teuchos::broadcast(comm, 0, static_cast<int>(owners.size()), owners.data());
  Teuchos::broadcast(comm, 0, Teuchos::outArg(chosen));
  if (partitioner) *partitioner = kPartitioners[chosen];
  return owners;
}

std::vector<int> subdomainsOfRank(const std::vector<int>& owners, int rank) {
  std::vector<int> ids;
  for (int s = 0; s < static_cast<int>(owners.size()); ++s)
    if (owners[s] == rank) ids.push_back(s);
  return ids;
}

namespace {

double imbalance(const char* name, const std::vector<double>& weights,
                 const std::vector<int>& owners, int numRanks) {
  if (owners.size() != weights.size())
    throw std::invalid_argument(std::string("tfeti::") + name +
                                ": owners and weights differ in size");
  std::vector<double> load(numRanks, 0.0);
  double total = 0.0;
  for (std::size_t s = 0; s < owners.size(); ++s) {
    if (owners[s] < 0 || owners[s] >= numRanks)
      throw std::invalid_argument(std::string("tfeti::") + name + ": owner of subdomain " +
                                  std::to_string(s) + " out of range");
    load[owners[s]] += weights[s];
    total += weights[s];
  }
  if (total == 0.0) return 1.0;
  return *std::max_element(load.begin(), load.end()) / (total / numRanks);
}

}  // namespace

double weightImbalance(const SubdomainGraph& graph, const std::vector<int>& owners, int numRanks) {
  return imbalance("weightImbalance", graph.weights, owners, numRanks);
}

double contactImbalance(const SubdomainGraph& graph, const std::vector<int>& owners, int numRanks) {
  if (graph.contactWeights.empty()) return 1.0;
  return imbalance("contactImbalance", graph.contactWeights, owners, numRanks);
}

double edgeCut(const SubdomainGraph& graph, const std::vector<int>& owners) {
  if (owners.size() != graph.weights.size())
    throw std::invalid_argument("tfeti::edgeCut: owners and weights differ in size");
  double cut = 0.0;
  for (int s = 0; s < graph.numSubdomains(); ++s)
    for (int k = graph.offsets[s]; k < graph.offsets[s + 1]; ++k) {
      const int t = graph.adjacency[k];
      if (s < t && owners[s] != owners[t]) cut += graph.edgeWeights[k];
    }
  return cut;
}

}  // namespace tfeti
