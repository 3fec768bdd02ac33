// Unit tests of the distribution of subdomains over ranks (tfeti::distributeSubdomains) on 1, 2
// and 3 ranks. Besides the communicator's own rank count, every test also partitions for 2 .. 8
// ranks without communication (tfeti::partitionSubdomains), so the single-rank run still
// exercises the partitioner. Checked: each subdomain owned exactly once, the weight imbalance
// below kTolerance on a grid with weights varying 1 .. 10, an edge cut no worse than the block
// rule's (and much better on a scrambled numbering), edge weights steering the cut, the same
// result on every rank and in every call, a contact zone shared by the ranks when the graph
// carries contact weights, the edge cases, and the input validation.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "tfeti_SubdomainDistribution.hpp"
#include "tfeti_SubdomainMesh.hpp"

namespace {

using tfeti::DistributionMethod;
using tfeti::SubdomainEdge;
using tfeti::SubdomainGraph;

// Largest rank weight over the mean that the graph method must stay below on the test grids.
// Scotch's default mapping strategy aims at 5 %; one subdomain of weight up to 10 among ~15 per
// rank is the granularity on top of that.
constexpr double kTolerance = 1.10;
constexpr int kMaxSerialRanks = 8;

Teuchos::RCP<const tfeti::Comm> comm() {
  return Tpetra::getDefaultComm();
}

// An nx x ny grid of subdomains as a structured mesh produces it: neighbours across an edge
// share an interface (edge weight hWeight across vertical interfaces, vWeight across horizontal
// ones). Weights vary 1 .. 10 in a pattern unrelated to the grid lines. With scramble the ids are
// permuted by s -> (a s + 3) mod n, so id blocks are scattered over the domain and the block rule
// cuts far more than a strip decomposition.
SubdomainGraph grid(int nx, int ny, bool scramble, double hWeight = 9.0, double vWeight = 5.0,
                    bool varyingWeights = true) {
  const int n = nx * ny;
  int a = 1, c = 0;
  if (scramble) {
    a = 7;
    while (std::gcd(a, n) != 1) ++a;
    c = 3;
  }
  auto id = [&](int i, int j) { return static_cast<int>((1LL * a * (j * nx + i) + c) % n); };
  std::vector<double> weights(n);
  std::vector<SubdomainEdge> edges;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      weights[id(i, j)] = varyingWeights ? 1 + (i * 7 + j * 3 + i * j) % 10 : 1.0;
      if (i + 1 < nx) edges.push_back({id(i, j), id(i + 1, j), hWeight});
      if (j + 1 < ny) edges.push_back({id(i, j), id(i, j + 1), vWeight});
    }
  return tfeti::makeSubdomainGraph(weights, edges);
}

// Each subdomain in exactly one rank's list, every list increasing.
void checkAssignment(const std::vector<int>& owners, int numSubdomains, int numRanks,
                     Teuchos::FancyOStream& out, bool& success) {
  TEST_EQUALITY(static_cast<int>(owners.size()), numSubdomains);
  std::vector<int> count(numSubdomains, 0);
  for (int r = 0; r < numRanks; ++r) {
    const std::vector<int> ids = tfeti::subdomainsOfRank(owners, r);
    TEST_ASSERT(std::is_sorted(ids.begin(), ids.end()));
    for (int s : ids) {
      TEST_ASSERT(s >= 0 && s < numSubdomains);
      if (s >= 0 && s < numSubdomains) ++count[s];
    }
  }
  for (int s = 0; s < numSubdomains; ++s) TEST_EQUALITY(count[s], 1);
}

TEUCHOS_UNIT_TEST(SubdomainDistribution, MethodNames) {
  TEST_ASSERT(tfeti::distributionMethodFromString("block") == DistributionMethod::Block);
  TEST_ASSERT(tfeti::distributionMethodFromString("graph") == DistributionMethod::Graph);
  TEST_EQUALITY(tfeti::toString(DistributionMethod::Block), "block");
  TEST_EQUALITY(tfeti::toString(DistributionMethod::Graph), "graph");
  TEST_THROW(tfeti::distributionMethodFromString("metis"), std::invalid_argument);
}

// Each invalid input throws std::invalid_argument whose message names the problem.
TEUCHOS_UNIT_TEST(SubdomainDistribution, RejectsInvalidGraphs) {
  auto expectError = [&](const SubdomainGraph& g, const std::string& fragment) {
    bool threw = false;
    try {
      tfeti::validateSubdomainGraph(g);
    } catch (const std::invalid_argument& e) {
      threw = true;
      const std::string what = e.what();
      out << "  " << what << "\n";
      TEST_ASSERT(what.find(fragment) != std::string::npos);
    }
    TEST_ASSERT(threw);
  };
  const SubdomainGraph good = grid(3, 2, false);
  tfeti::validateSubdomainGraph(good);

  SubdomainGraph g = good;
  g.weights[4] = 0.0;
  expectError(g, "subdomain 4: weight must be positive");
  g = good;
  g.weights[1] = -2.0;
  expectError(g, "subdomain 1: weight must be positive");
  g = good;
  g.adjacency[0] = 6;  // 6 subdomains
  expectError(g, "out of range");
  g = good;
  g.adjacency[0] = -1;
  expectError(g, "out of range");
  g = good;
  g.adjacency[0] = 0;  // row 0
  expectError(g, "self-loop");
  g = good;
  g.edgeWeights[2] = 0.0;
  expectError(g, "edge weight must be positive");
  g = good;
  g.edgeWeights[0] *= 2.0;
  expectError(g, "not symmetric");
  g = good;
  g.offsets.pop_back();
  expectError(g, "offsets has");
  g = good;
  g.edgeWeights.pop_back();
  expectError(g, "edgeWeights has");

  // An edge 0 - 1 stored only in row 0: (1, 0) missing.
  SubdomainGraph oneWay;
  oneWay.weights = {1.0, 1.0};
  oneWay.offsets = {0, 1, 1};
  oneWay.adjacency = {1};
  oneWay.edgeWeights = {1.0};
  expectError(oneWay, "(1, 0) missing");

  TEST_THROW(tfeti::makeSubdomainGraph({1.0, 1.0}, {{0, 2, 1.0}}), std::invalid_argument);
  TEST_THROW(tfeti::makeSubdomainGraph({1.0, 1.0}, {{1, 1, 1.0}}), std::invalid_argument);
  TEST_THROW(tfeti::makeSubdomainGraph({1.0, 1.0}, {{0, 1, 1.0}, {1, 0, 1.0}}),
             std::invalid_argument);
  TEST_THROW(tfeti::makeSubdomainGraph({1.0, 1.0}, {{0, 1, -1.0}}), std::invalid_argument);
  TEST_THROW(tfeti::partitionSubdomains(good, 0), std::invalid_argument);

  g = good;
  g.contactWeights = {1.0, 0.0};
  expectError(g, "contactWeights has 2 entries, expected none or 6");
  g.contactWeights = {0.0, 0.0, 0.0, -1.0, 0.0, 0.0};
  expectError(g, "subdomain 3: contact weight must be finite and >= 0");
}

// An invalid graph, or (on more than one rank) a graph that differs between ranks, makes every
// rank throw instead of leaving some waiting in a collective.
TEUCHOS_UNIT_TEST(SubdomainDistribution, CollectiveErrors) {
  const auto c = comm();
  auto threwEverywhere = [&](const SubdomainGraph& g) {
    int threw = 0;
    try {
      tfeti::distributeSubdomains(*c, g);
    } catch (const std::exception& e) {
      out << "  rank " << c->getRank() << ": " << e.what() << "\n";
      threw = 1;
    }
    int all = 0;
    Teuchos::reduceAll(*c, Teuchos::REDUCE_MIN, threw, Teuchos::outArg(all));
    return all == 1;
  };
  SubdomainGraph bad = grid(4, 3, false);
  bad.weights[5] = 0.0;
  TEST_ASSERT(threwEverywhere(bad));
  if (c->getSize() > 1) {
    SubdomainGraph differs = grid(4, 3, false);
    if (c->getRank() == c->getSize() - 1) differs.weights[2] += 1.0;
    TEST_ASSERT(threwEverywhere(differs));
  }
  // Still usable afterwards: nothing left pending.
  TEST_EQUALITY(tfeti::distributeSubdomains(*c, grid(4, 3, false)).size(), 12u);
}

// "block" is exactly the structured meshes' contiguous rule, whatever the weights and graph.
TEUCHOS_UNIT_TEST(SubdomainDistribution, BlockMethodIsTheContiguousRule) {
  for (int n : {1, 5, 12, 48})
    for (int p = 1; p <= kMaxSerialRanks; ++p) {
      std::vector<double> w(n);
      for (int s = 0; s < n; ++s) w[s] = 1.0 + s % 3;
      const SubdomainGraph g = tfeti::makeSubdomainGraph(w, {});
      const std::vector<int> owners = tfeti::partitionSubdomains(g, p, DistributionMethod::Block);
      for (int s = 0; s < n; ++s) TEST_EQUALITY(owners[s], tfeti::ownerOfSubdomain(s, n, p));
      for (int r = 0; r < p; ++r)
        TEST_COMPARE_ARRAYS(tfeti::subdomainsOfRank(owners, r), tfeti::subdomainsOfRank(r, n, p));
    }
  const auto c = comm();
  const SubdomainGraph g = grid(6, 4, true);
  const std::vector<int> owners = tfeti::distributeSubdomains(*c, g, DistributionMethod::Block);
  TEST_COMPARE_ARRAYS(tfeti::subdomainsOfRank(owners, c->getRank()),
                      tfeti::subdomainsOfRank(c->getRank(), 24, c->getSize()));
}

TEUCHOS_UNIT_TEST(SubdomainDistribution, EverySubdomainAssignedOnce) {
  const auto c = comm();
  for (bool scramble : {false, true}) {
    const SubdomainGraph g = grid(8, 6, scramble);
    const std::vector<int> owners = tfeti::distributeSubdomains(*c, g);
    checkAssignment(owners, 48, c->getSize(), out, success);
    for (int p = 1; p <= kMaxSerialRanks; ++p)
      checkAssignment(tfeti::partitionSubdomains(g, p), 48, p, out, success);
  }
}

// Largest rank weight / mean below kTolerance, and no idle rank.
TEUCHOS_UNIT_TEST(SubdomainDistribution, BalancesVaryingWeights) {
  const auto c = comm();
  const SubdomainGraph g = grid(12, 10, true);
  auto check = [&](const std::vector<int>& owners, int p, const char* how) {
    const double imbalance = tfeti::weightImbalance(g, owners, p);
    out << "  " << how << " P = " << p << ": imbalance " << imbalance << " (block rule "
        << tfeti::weightImbalance(g, tfeti::partitionSubdomains(g, p, DistributionMethod::Block), p)
        << "), cut " << tfeti::edgeCut(g, owners) << "\n";
    TEST_COMPARE(imbalance, <, kTolerance);
    for (int r = 0; r < p; ++r) TEST_ASSERT(!tfeti::subdomainsOfRank(owners, r).empty());
  };
  check(tfeti::distributeSubdomains(*c, g), c->getSize(), "distributed");
  for (int p = 2; p <= kMaxSerialRanks; ++p) check(tfeti::partitionSubdomains(g, p), p, "serial");
}

// On a scrambled numbering the block rule scatters each rank's subdomains over the domain; a
// partitioner that uses the graph cuts far less. (On the row-major numbering the block rule's
// strips have a near-minimal cut and the partitioner may cut a little more to balance better, so
// no comparison there.)
TEUCHOS_UNIT_TEST(SubdomainDistribution, CutNotWorseThanBlockOnScrambledGrid) {
  const auto c = comm();
  const SubdomainGraph g = grid(8, 6, true);
  auto check = [&](const std::vector<int>& owners, int p) {
    const std::vector<int> block = tfeti::partitionSubdomains(g, p, DistributionMethod::Block);
    const double cut = tfeti::edgeCut(g, owners);
    const double blockCut = tfeti::edgeCut(g, block);
    out << "  P = " << p << ": cut " << cut << ", imbalance "
        << tfeti::weightImbalance(g, owners, p) << "; block rule cut " << blockCut << ", imbalance "
        << tfeti::weightImbalance(g, block, p) << "\n";
    TEST_COMPARE(cut, <=, blockCut);
    if (p > 1) TEST_COMPARE(cut, <, 0.5 * blockCut);
  };
  check(tfeti::distributeSubdomains(*c, g), c->getSize());
  for (int p = 2; p <= kMaxSerialRanks; ++p) check(tfeti::partitionSubdomains(g, p), p);
}

// Equal subdomains on an 8 x 8 grid: a bisection cuts either 8 vertical or 8 horizontal
// interfaces; the partitioner must cut the light ones.
TEUCHOS_UNIT_TEST(SubdomainDistribution, EdgeWeightsSteerTheCut) {
  for (bool heavyHorizontal : {true, false}) {
    const double h = heavyHorizontal ? 100.0 : 1.0, v = heavyHorizontal ? 1.0 : 100.0;
    const SubdomainGraph g = grid(8, 8, true, h, v, false);
    const std::vector<int> owners = tfeti::partitionSubdomains(g, 2);
    out << "  h = " << h << ", v = " << v << ": cut " << tfeti::edgeCut(g, owners) << ", imbalance "
        << tfeti::weightImbalance(g, owners, 2) << "\n";
    TEST_EQUALITY(tfeti::edgeCut(g, owners), 8.0);
    TEST_EQUALITY(tfeti::weightImbalance(g, owners, 2), 1.0);
  }
}

// A 16 x 16 grid whose contact rows lie in a patch at the top, off the centre (as an indenter's):
// with contact weights every rank gets its share of the patch as well as of the dofs, where a
// partition by the weights alone may leave the whole patch on one rank. All-zero contact weights
// change nothing.
TEUCHOS_UNIT_TEST(SubdomainDistribution, BalancesTheContactZone) {
  const auto c = comm();
  const int nx = 16;
  SubdomainGraph g = grid(nx, nx, true, 5.0, 5.0, false);
  SubdomainGraph zero = g;
  zero.contactWeights.assign(g.weights.size(), 0.0);
  for (int q = 2; q <= kMaxSerialRanks; ++q)
    TEST_COMPARE_ARRAYS(tfeti::partitionSubdomains(zero, q), tfeti::partitionSubdomains(g, q));
  // The grid's ids are scrambled as grid() does it; the patch is given in grid coordinates.
  int a = 7;
  while (std::gcd(a, nx * nx) != 1) ++a;
  g.contactWeights.assign(g.weights.size(), 0.0);
  for (int j = nx - 4; j < nx; ++j)
    for (int i = 3; i < 11; ++i)
      g.contactWeights[(1LL * a * (j * nx + i) + 3) % (nx * nx)] = 1.0 + j;
  int balanced = 0;
  auto check = [&](const std::vector<int>& owners, const std::string& partitioner, int p,
                   const char* how) {
    checkAssignment(owners, g.numSubdomains(), p, out, success);
    const std::vector<int> alone = tfeti::partitionSubdomains(zero, p);
    const double dofs = tfeti::weightImbalance(g, owners, p);
    const double contact = tfeti::contactImbalance(g, owners, p);
    out << "  " << how << " P = " << p << " (" << partitioner << "): imbalance " << dofs
        << ", contact imbalance " << contact << "; by the weights alone "
        << tfeti::weightImbalance(g, alone, p) << " and " << tfeti::contactImbalance(g, alone, p)
        << "; cut " << tfeti::edgeCut(g, owners) << "\n";
    if (p == 1) return;
    if (partitioner == "metis_two_constraints") {
      ++balanced;
      // 32 patch subdomains of weight 13 .. 16: one more or less per rank is the granularity.
      TEST_COMPARE(contact, <, 1.15);
      TEST_COMPARE(dofs, <=, std::max(1.05, 1.02 * tfeti::weightImbalance(g, alone, p)));
    } else {
      TEST_ASSERT(partitioner == "scotch" || partitioner == "zoltan");
      TEST_COMPARE_ARRAYS(owners, alone);
    }
  };
  std::string name;
  const std::vector<int> owners =
      tfeti::distributeSubdomains(*c, g, DistributionMethod::Graph, &name);
  check(owners, name, c->getSize(), "distributed");
  TEST_COMPARE_ARRAYS(tfeti::partitionSubdomains(g, c->getSize()), owners);
  balanced = 0;
  // Recursive bisection up to 8 parts, k-way beyond (12 and 16).
  for (int p : {2, 3, 4, 5, 6, 7, 8, 12, 16}) {
    const std::vector<int> serial =
        tfeti::partitionSubdomains(g, p, DistributionMethod::Graph, &name);
    check(serial, name, p, "serial");
    TEST_COMPARE_ARRAYS(tfeti::partitionSubdomains(g, p), serial);
  }
  // On this grid every rank count finds a partition that shares the patch (seen: contact
  // imbalance 1.00 - 1.14, dofs 1.00 - 1.03, where the weights alone leave 1.25 - 8).
  TEST_EQUALITY(balanced, 9);
  TEST_EQUALITY(tfeti::contactImbalance(zero, tfeti::partitionSubdomains(zero, 2), 2), 1.0);
}

// Two unconnected grids (e.g. two bodies in contact): two ranks get one body each, no cut.
TEUCHOS_UNIT_TEST(SubdomainDistribution, DisconnectedBodies) {
  const int n = 32;
  std::vector<double> w(n, 1.0);
  std::vector<SubdomainEdge> edges;
  for (int body = 0; body < 2; ++body)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        // Interleaved ids: body b's subdomain k is 2 k + b, so the block rule mixes the bodies.
        auto id = [&](int ii, int jj) { return 2 * (4 * jj + ii) + body; };
        if (i + 1 < 4) edges.push_back({id(i, j), id(i + 1, j), 3.0});
        if (j + 1 < 4) edges.push_back({id(i, j), id(i, j + 1), 3.0});
      }
  const SubdomainGraph g = tfeti::makeSubdomainGraph(w, edges);
  const std::vector<int> owners = tfeti::partitionSubdomains(g, 2);
  out << "  cut " << tfeti::edgeCut(g, owners) << ", block rule "
      << tfeti::edgeCut(g, tfeti::partitionSubdomains(g, 2, DistributionMethod::Block)) << "\n";
  TEST_EQUALITY(tfeti::edgeCut(g, owners), 0.0);
  TEST_EQUALITY(tfeti::weightImbalance(g, owners, 2), 1.0);
}

// Rank 0 partitions and broadcasts; every rank also partitions locally with its own Scotch run,
// which must give the same answer (no dependence on the process), as must repeated calls.
TEUCHOS_UNIT_TEST(SubdomainDistribution, SameOnEveryRankAndRepeatable) {
  const auto c = comm();
  const int p = c->getSize();
  const SubdomainGraph g = grid(12, 10, true);
  const std::vector<int> owners = tfeti::distributeSubdomains(*c, g);
  const int n = static_cast<int>(owners.size());
  std::vector<int> all(static_cast<std::size_t>(n) * p);
  Teuchos::gatherAll(*c, n, owners.data(), n * p, all.data());
  for (int r = 0; r < p; ++r)
    TEST_ASSERT(std::equal(owners.begin(), owners.end(), all.begin() + static_cast<long>(r) * n));
  TEST_COMPARE_ARRAYS(tfeti::distributeSubdomains(*c, g), owners);
  TEST_COMPARE_ARRAYS(tfeti::partitionSubdomains(g, p), owners);
  for (int q = 2; q <= kMaxSerialRanks; ++q)
    TEST_COMPARE_ARRAYS(tfeti::partitionSubdomains(g, q), tfeti::partitionSubdomains(g, q));
}

// No more subdomains than ranks: one subdomain per rank, the rest idle.
TEUCHOS_UNIT_TEST(SubdomainDistribution, FewerSubdomainsThanRanks) {
  const SubdomainGraph g = tfeti::makeSubdomainGraph({5.0, 1.0, 2.0}, {{0, 1, 1.0}, {1, 2, 4.0}});
  for (int p = 3; p <= kMaxSerialRanks; ++p) {
    const std::vector<int> owners = tfeti::partitionSubdomains(g, p);
    checkAssignment(owners, 3, p, out, success);
    for (int r = 0; r < p; ++r) TEST_COMPARE(tfeti::subdomainsOfRank(owners, r).size(), <=, 1u);
  }
  const auto c = comm();
  const int n = std::max(1, c->getSize() - 1);
  std::vector<SubdomainEdge> chain;
  for (int s = 0; s + 1 < n; ++s) chain.push_back({s, s + 1, 2.0});
  const SubdomainGraph h = tfeti::makeSubdomainGraph(std::vector<double>(n, 1.0), chain);
  const std::vector<int> owners = tfeti::distributeSubdomains(*c, h);
  checkAssignment(owners, n, c->getSize(), out, success);
  TEST_COMPARE(tfeti::subdomainsOfRank(owners, c->getRank()).size(), <=, 1u);
}

// Barely more subdomains than ranks (a 2 x k grid of 2k = P + 1 or P + 2 equal subdomains): no
// rank idle, none with more than two subdomains.
TEUCHOS_UNIT_TEST(SubdomainDistribution, FewSubdomainsPerRank) {
  for (int p = 2; p <= kMaxSerialRanks; ++p) {
    const int k = p / 2 + 1;
    const SubdomainGraph g = grid(k, 2, true, 1.0, 1.0, false);
    const std::vector<int> owners = tfeti::partitionSubdomains(g, p);
    out << "  P = " << p << ", " << 2 * k << " subdomains: imbalance "
        << tfeti::weightImbalance(g, owners, p) << ", cut " << tfeti::edgeCut(g, owners) << "\n";
    checkAssignment(owners, 2 * k, p, out, success);
    for (int r = 0; r < p; ++r) {
      const std::size_t count = tfeti::subdomainsOfRank(owners, r).size();
      TEST_ASSERT(count >= 1 && count <= 2);
    }
  }
}

TEUCHOS_UNIT_TEST(SubdomainDistribution, OneOrNoSubdomain) {
  const auto c = comm();
  const SubdomainGraph one = tfeti::makeSubdomainGraph({3.0}, {});
  for (DistributionMethod m : {DistributionMethod::Graph, DistributionMethod::Block}) {
    const std::vector<int> owners = tfeti::distributeSubdomains(*c, one, m);
    checkAssignment(owners, 1, c->getSize(), out, success);
    for (int p = 1; p <= kMaxSerialRanks; ++p)
      checkAssignment(tfeti::partitionSubdomains(one, p, m), 1, p, out, success);
    TEST_ASSERT(tfeti::distributeSubdomains(*c, tfeti::makeSubdomainGraph({}, {}), m).empty());
  }
  TEST_EQUALITY(tfeti::distributeSubdomains(*c, one)[0], 0);
}

// The fallback for builds without Scotch, Zoltan's hypergraph partitioner (PHG), works in this
// build, is repeatable (fixed seed) and also beats the block rule on the scrambled grid.
TEUCHOS_UNIT_TEST(SubdomainDistribution, ZoltanHypergraphFallback) {
  const SubdomainGraph g = grid(8, 6, true);
  for (int p = 2; p <= 5; ++p) {
    const std::vector<int> owners = tfeti::detail::zoltan2Partition(g, p, "zoltan");
    const double cut = tfeti::edgeCut(g, owners);
    const double blockCut =
        tfeti::edgeCut(g, tfeti::partitionSubdomains(g, p, DistributionMethod::Block));
    out << "  P = " << p << ": imbalance " << tfeti::weightImbalance(g, owners, p) << ", cut "
        << cut << ", block rule " << blockCut << "\n";
    checkAssignment(owners, 48, p, out, success);
    TEST_COMPARE(tfeti::weightImbalance(g, owners, p), <, kTolerance);
    TEST_COMPARE(cut, <, blockCut);
    TEST_COMPARE_ARRAYS(tfeti::detail::zoltan2Partition(g, p, "zoltan"), owners);
  }
}

}  // namespace
