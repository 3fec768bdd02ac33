#pragma once
// Which rank owns which subdomain. Structured meshes deal subdomains in contiguous blocks of ids
// (tfeti_SubdomainMesh.hpp): with row-major ids each rank gets a strip of the domain. For
// unstructured meshes partitioned by METIS, ids carry no geometry and subdomains differ in size,
// so the subdomains are distributed by a Zoltan2 graph partitioner over the subdomain adjacency
// graph: balance the per-rank work, keep gluing between ranks (the cut) small.
#include <string>
#include <vector>

#include "tfeti_Types.hpp"

namespace tfeti {

// The same global description on every rank. Adjacency in CSR form (as METIS returns it): the
// neighbours of subdomain s are adjacency[offsets[s] .. offsets[s+1]), with edgeWeights alongside
// (e.g. the number of shared interface nodes). The graph must be symmetric with equal weights in
// both directions, without self-loops or repeated neighbours.
struct SubdomainGraph {
  std::vector<double> weights;  // work per subdomain (dofs, factorization cost estimate), > 0
  std::vector<int> offsets;     // size numSubdomains() + 1
  std::vector<int> adjacency;
  std::vector<double> edgeWeights;  // > 0, same size as adjacency
  // Optional, empty or one per subdomain, >= 0: work that sits in a few subdomains and that the
  // weights do not show, such as the contact rows a subdomain's nodes carry (every Newton
  // iteration rebuilds those subdomains' preconditioners and, in plasticity, their tangents).
  // When any is positive the graph method balances both (METIS' multi-constraint partitioning;
  // Scotch balances one weight only), so that no rank is left with all of the contact zone.
  std::vector<double> contactWeights;

  int numSubdomains() const { return static_cast<int>(weights.size()); }
};

// One undirected edge, listed once, for building a SubdomainGraph from an edge list.
struct SubdomainEdge {
  int a = -1, b = -1;
  double weight = 1.0;
};

// Builds the CSR graph from an edge list (each edge once, either orientation). Throws
// std::invalid_argument on out-of-range ids, self-loops, repeated edges or non-positive weights.
SubdomainGraph makeSubdomainGraph(std::vector<double> weights,
                                  const std::vector<SubdomainEdge>& edges);

// Throws std::invalid_argument naming the first offending subdomain or edge if the graph is not
// valid (see SubdomainGraph).
void validateSubdomainGraph(const SubdomainGraph& graph);

enum class DistributionMethod {
  Block,  // contiguous blocks of ids, ownerOfSubdomain(); ignores weights and adjacency
  Graph,  // Zoltan2 graph partitioning (Scotch) of the weighted adjacency graph
};

// "block" or "graph"; throws std::invalid_argument listing the valid names otherwise.
DistributionMethod distributionMethodFromString(const std::string& name);
std::string toString(DistributionMethod method);

// Owning rank of every subdomain for comm.getSize() ranks, identical on every rank: rank 0
// partitions and broadcasts, because a parallel partitioner's result would depend on how the
// input was spread over the ranks. Depends only on the graph and the rank count. Collective.
// partitioner, when given, receives which partition was returned (on every rank): "block",
// "single" (one rank, or no more subdomains than ranks: one each), "scotch" (or "zoltan" where
// Trilinos has no Scotch) on the weights, or "metis_two_constraints" when there are contact
// weights and a partition that balances them better costs little dof balance (the dof imbalance
// below 1.05 or within 2 % of the one-weight partition's; else the one-weight partition).
std::vector<int> distributeSubdomains(const Comm& comm, const SubdomainGraph& graph,
                                      DistributionMethod method = DistributionMethod::Graph,
                                      std::string* partitioner = nullptr);

// The same computation without communication (what rank 0 does). Needs MPI to be initialized
// for DistributionMethod::Graph (Zoltan2 runs on MPI_COMM_SELF). Scotch is run single-threaded
// for reproducibility: SCOTCH_PTHREAD_NUMBER is set to 1 during the call and then restored, so
// do not call this while another thread reads or writes the environment.
std::vector<int> partitionSubdomains(const SubdomainGraph& graph, int numRanks,
                                     DistributionMethod method = DistributionMethod::Graph,
                                     std::string* partitioner = nullptr);

// The subdomains owned by rank, in increasing id order.
std::vector<int> subdomainsOfRank(const std::vector<int>& owners, int rank);

// Quality of a distribution: the largest rank weight over the mean rank weight (1 = perfect), the
// same for the contact weights (1 when they are absent or all zero), and the total weight of edges
// whose ends are on different ranks (each undirected edge once).
double weightImbalance(const SubdomainGraph& graph, const std::vector<int>& owners, int numRanks);
double contactImbalance(const SubdomainGraph& graph, const std::vector<int>& owners, int numRanks);
double edgeCut(const SubdomainGraph& graph, const std::vector<int>& owners);

namespace detail {
// One Zoltan2 PartitioningProblem on MPI_COMM_SELF with the given "algorithm" parameter, raw
// (no special cases, no determinism guard beyond the Scotch seed reset). Exposed for the tests
// and for comparing algorithms; throws std::runtime_error if Zoltan2 fails.
std::vector<int> zoltan2Partition(const SubdomainGraph& graph, int numParts,
                                  const std::string& algorithm);
// METIS with two constraints per subdomain, its weight (to within 2 %) and its contact weight (to
// within contactTolerance), as far as the graph allows, the edge cut minimized; deterministic (a
// fixed seed).
std::vector<int> metisTwoConstraintPartition(const SubdomainGraph& graph, int numParts,
                                             double contactTolerance);
}  // namespace detail

}  // namespace tfeti
