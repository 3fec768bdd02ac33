#include "tfeti_Tearing.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "tfeti_DenseUtils.hpp"
#include "tfeti_Gather.hpp"

namespace tfeti {
namespace {

struct Copy {
  GO node;
  int sub;
  int localNode;
  int dirichletMask;  // bit c: component c prescribed
};

struct Row {
  int group;
  int n;
  std::array<int, 2> sub;
  std::array<int, 2> dof;
  std::array<double, 2> coef;
};

}  // namespace

namespace {

// Every rank's rows of one kind (values(row): a tuple of references to the row's numbers:
// InequalityRow: gap, the multiplier's bounds, disc and key; EqualityRow: rhs), in a canonical
// order (by their entries, then the values) so that the numbering does not depend on which rank
// contributed a row.
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr long long kKeyLimit = 1LL << 53;  // InequalityRow::key travels as a double

// A row for which glued(row) is true stays right after the row before it in its rank's list
// (the two rows of a disc, InequalityRow::disc): the pair is ordered by its first row.
template <class R, class Values, class Glued>
std::vector<R> gatherRows(const Comm& comm, const std::vector<R>& mine, Values values,
                          Glued glued) {
  constexpr std::size_t nv = std::tuple_size<decltype(values(std::declval<R&>()))>::value;
  auto get = [&](const R& r) {
    std::array<double, nv> a{};
    std::size_t i = 0;
    std::apply([&](const auto&... v) { ((a[i++] = v), ...); }, values(r));
    return a;
  };
  std::vector<double> packed;
  for (const auto& row : mine) {
    packed.push_back(static_cast<double>(row.entries.size()));
    for (double v : get(row)) packed.push_back(v);
    for (const auto& e : row.entries)
      packed.insert(packed.end(),
                    {static_cast<double>(e.subdomain), static_cast<double>(e.dof), e.coef});
  }
  const std::vector<double> all = allGather(comm, packed);
  std::vector<R> rows;
  for (std::size_t k = 0; k < all.size();) {
    R row;
    const int n = static_cast<int>(all[k]);
    std::size_t i = k + 1;
    std::apply([&](auto&... v) { ((v = all[i++]), ...); }, values(row));
    k += 1 + nv;
    for (int j = 0; j < n; ++j, k += 3)
      row.entries.push_back({static_cast<int>(all[k]), static_cast<int>(all[k + 1]), all[k + 2]});
    rows.push_back(std::move(row));
  }
  auto key = [&](const R& r) {
    std::vector<std::tuple<int, int, double>> k;
    for (const auto& e : r.entries) k.emplace_back(e.subdomain, e.dof, e.coef);
    return std::make_pair(k, get(r));
  };
  // Units: a row and the glued rows after it.
  std::vector<std::pair<std::size_t, std::size_t>> units;  // first row, count
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (glued(rows[i]) && !units.empty())
      ++units.back().second;
    else
      units.emplace_back(i, 1);
  std::stable_sort(units.begin(), units.end(), [&](const auto& a, const auto& b) {
    return key(rows[a.first]) < key(rows[b.first]);
  });
  std::vector<R> sorted;
  sorted.reserve(rows.size());
  for (const auto& [first, count] : units)
    for (std::size_t i = first; i < first + count; ++i) sorted.push_back(std::move(rows[i]));
  return sorted;
}

std::string describeRow(const std::vector<ConstraintEntry>& entries, const char* relation,
                        double value) {
  std::string s = "{";
  for (std::size_t k = 0; k < entries.size() && k < 6; ++k)
    s += (k ? ", " : "") + std::string("(subdomain ") + std::to_string(entries[k].subdomain) +
         ", dof " + std::to_string(entries[k].dof) + ", " + std::to_string(entries[k].coef) + ")";
  if (entries.size() > 6) s += ", ...";
  return s + "} " + relation + " " + std::to_string(value);
}

// A caller's row must refer to existing dofs, have a non-zero coefficient and finite values.
// Checked on the gathered rows, so every rank throws the same error.
void checkRow(const std::vector<ConstraintEntry>& entries, double value, const char* kind,
              const char* relation, const std::vector<long long>& sizes) {
  const std::string row = describeRow(entries, relation, value);
  if (entries.empty())
    throw std::invalid_argument(std::string("tearing: an ") + kind + " row has no entries");
  bool nonzero = false;
  for (const auto& e : entries) {
    if (e.subdomain < 0 || e.subdomain >= static_cast<int>(sizes.size()) || e.dof < 0 ||
        e.dof >= sizes[e.subdomain])
      throw std::invalid_argument(
          std::string("tearing: the ") + kind + " row " + row + " refers to dof " +
          std::to_string(e.dof) + " of subdomain " + std::to_string(e.subdomain) +
          (e.subdomain < 0 || e.subdomain >= static_cast<int>(sizes.size())
               ? ", which does not exist (" + std::to_string(sizes.size()) + " subdomains)"
               : ", which has " + std::to_string(sizes[e.subdomain]) + " dofs"));
    if (!std::isfinite(e.coef))
      throw std::invalid_argument(std::string("tearing: the ") + kind + " row " + row +
                                  " has a coefficient that is not finite");
    nonzero = nonzero || e.coef != 0.0;
  }
  if (!nonzero)
    throw std::invalid_argument(std::string("tearing: the ") + kind + " row " + row +
                                " has only zero coefficients");
  if (!std::isfinite(value))
    throw std::invalid_argument(std::string("tearing: the ") + kind + " row " + row +
                                " has a right-hand side that is not finite");
}

// Union-find over row indices.
struct Components {
  std::vector<std::size_t> parent;
  explicit Components(std::size_t n) : parent(n) {
    for (std::size_t i = 0; i < n; ++i) parent[i] = i;
  }
  std::size_t find(std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::size_t a, std::size_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// Global dof numbering: subdomain by subdomain. Returns every subdomain's number of dofs.
std::vector<long long> numberPrimalDofs(const Teuchos::RCP<const Comm>& comm, int numSubdomains,
                                        const std::vector<TearingInput>& local, Tearing& t) {
  std::vector<long long> sizes(numSubdomains, 0), allSizes(numSubdomains, 0);
  for (const auto& s : local) sizes[s.id] = s.numDofs;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, numSubdomains, sizes.data(), allSizes.data());
  t.dofOffset.assign(numSubdomains + 1, 0);
  for (int s = 0; s < numSubdomains; ++s) t.dofOffset[s + 1] = t.dofOffset[s] + allSizes[s];
  std::vector<GO> myDofs;
  for (const auto& s : local)
    for (int d = 0; d < s.numDofs; ++d) myDofs.push_back(t.dofOffset[s.id] + d);
  t.primalMap = Teuchos::rcp(new Map(static_cast<Tpetra::global_size_t>(t.dofOffset.back()),
                                     Teuchos::ArrayView<const GO>(myDofs), 0, comm));
  return allSizes;
}

// Who owns which subdomain: whatever distribution the caller chose (block rule, Zoltan2).
std::vector<int> subdomainOwners(const Comm& comm, int numSubdomains,
                                 const std::vector<TearingInput>& local) {
  std::vector<long long> owned;
  for (const auto& sd : local) owned.insert(owned.end(), {sd.id, comm.getRank()});
  const std::vector<long long> allOwned = allGather(comm, owned);
  std::vector<int> owner(numSubdomains, -1);
  for (std::size_t k = 0; k < allOwned.size(); k += 2) {
    const auto id = allOwned[k];
    if (id < 0 || id >= numSubdomains || owner[id] >= 0)
      throw std::invalid_argument(
          "tearing: subdomain " + std::to_string(id) +
          (id < 0 || id >= numSubdomains ? " is out of range" : " is held by two ranks"));
    owner[id] = static_cast<int>(allOwned[k + 1]);
  }
  for (int sd = 0; sd < numSubdomains; ++sd)
    if (owner[sd] < 0)
      throw std::invalid_argument("tearing: no rank holds subdomain " + std::to_string(sd));
  return owner;
}

// Every subdomain's boundary nodes, by untorn node, then subdomain.
std::vector<Copy> gatherBoundaryCopies(const Comm& comm, const std::vector<TearingInput>& local) {
  std::vector<long long> mine;  // (untorn node, subdomain, local node, Dirichlet)
  for (const auto& s : local)
    for (std::size_t k = 0; k < s.boundaryNodes.size(); ++k)
      mine.insert(mine.end(),
                  {s.boundaryGlobal[k], s.id, s.boundaryNodes[k], s.boundaryDirichlet[k]});
  const std::vector<long long> all = allGather(comm, mine);
  std::vector<Copy> copies(all.size() / 4);
  for (std::size_t k = 0; k < copies.size(); ++k)
    copies[k] = {all[4 * k], static_cast<int>(all[4 * k + 1]), static_cast<int>(all[4 * k + 2]),
                 static_cast<int>(all[4 * k + 3])};
  std::sort(copies.begin(), copies.end(), [](const Copy& a, const Copy& b) {
    return a.node != b.node ? a.node < b.node : a.sub < b.sub;
  });
  return copies;
}

// Every row of the tearing in its global numbering: the automatic rows (gluing and TFETI's
// Dirichlet rows), then the caller's equality rows, then the inequality rows.
struct RowSet {
  std::vector<Row> automatic;
  std::vector<int> groupOwner;  // the rank owning each automatic row's group
  std::vector<EqualityRow> user;
  std::vector<InequalityRow> ineq;

  GO numAuto() const { return static_cast<GO>(automatic.size()); }
  GO numEq() const { return numAuto() + static_cast<GO>(user.size()); }
  std::vector<ConstraintEntry> entriesOf(GO r) const {
    std::vector<ConstraintEntry> e;
    if (r < numAuto()) {
      const Row& row = automatic[r];
      for (int k = 0; k < row.n; ++k) e.push_back({row.sub[k], row.dof[k], row.coef[k]});
    } else if (r < numEq()) {
      e = user[r - numAuto()].entries;
    } else {
      e = ineq[r - numEq()].entries;
    }
    return e;
  }
};

// The automatic rows in canonical order: by untorn node, then component.
void addAutomaticRows(const std::vector<Copy>& copies, int dofsPerNode,
                      const TearingOptions& options, const std::vector<int>& owner, RowSet& set,
                      Tearing& t) {
  std::vector<Row>& rows = set.automatic;
  std::vector<int>& groupOwner = set.groupOwner;
  for (std::size_t first = 0; first < copies.size();) {
    std::size_t last = first;
    int mask = 0;
    while (last < copies.size() && copies[last].node == copies[first].node)
      mask |= copies[last++].dirichletMask;
    const int m = static_cast<int>(last - first);
    for (int c = 0; c < dofsPerNode; ++c) {
      // Dirichlet and symmetry conditions hold component by component.
      const bool dirichlet = (mask >> c) & 1;
      const bool tfetiDirichlet = dirichlet && options.formulation == Formulation::TFETI;
      const bool glue =
          m > 1 && options.gluing != Gluing::None && (!dirichlet || options.gluingAtDirichletNodes);
      const int group = static_cast<int>(groupOwner.size());
      const std::size_t before = rows.size();
      auto dofOf = [&](std::size_t k) { return copies[k].localNode * dofsPerNode + c; };
      if (tfetiDirichlet)
        for (std::size_t k = first; k < last; ++k)
          rows.push_back({group, 1, {copies[k].sub, 0}, {dofOf(k), 0}, {1.0, 0.0}});
      if (glue) {
        for (std::size_t a = first; a + 1 < last; ++a) {
          const std::size_t bEnd = options.gluing == Gluing::Redundant ? last : a + 2;
          for (std::size_t b = a + 1; b < bEnd; ++b)
            rows.push_back(
                {group, 2, {copies[a].sub, copies[b].sub}, {dofOf(a), dofOf(b)}, {1.0, -1.0}});
        }
        t.numGluingRows +=
            static_cast<GO>(rows.size() - before) - (tfetiDirichlet ? static_cast<GO>(m) : 0);
      }
      if (tfetiDirichlet) t.numDirichletRows += m;
      if (rows.size() > before) groupOwner.push_back(owner[copies[first].sub]);
    }
    first = last;
  }
}

// Each first row of a disc (InequalityRow::disc = 1) followed by its second (disc = 2), both with
// the bounds [-g, g] of one g. Throws std::invalid_argument naming the row.
void checkDiscRows(const std::vector<InequalityRow>& rows) {
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const InequalityRow& r = rows[i];
    auto fail = [&](const std::string& why) {
      throw std::invalid_argument("inequality row " + describeRow(r.entries, "<=", r.gap) + ": " +
                                  why);
    };
    if (r.disc < 0 || r.disc > 2) fail("disc must be 0, 1 or 2, got " + std::to_string(r.disc));
    if (r.disc == 2) fail("the second row of a disc (disc = 2) does not follow a first (disc = 1)");
    if (r.disc != 1) continue;
    if (i + 1 == rows.size() || rows[i + 1].disc != 2)
      fail(
          "the first row of a disc (disc = 1) is not followed by its second (disc = 2) in the "
          "rows passed");
    const InequalityRow& second = rows[++i];
    if (!(r.lowerBound == -r.upperBound) || second.lowerBound != r.lowerBound ||
        second.upperBound != r.upperBound)
      fail("the two rows of a disc need the bounds [-g, g] with one g");
  }
}

// The caller's rows, gathered from every rank in canonical order and checked.
void addCallerRows(const Comm& comm, const std::vector<EqualityRow>& equalities,
                   const std::vector<InequalityRow>& inequalities,
                   const std::vector<long long>& allSizes, RowSet& set) {
  set.user = gatherRows(
      comm, equalities, [](auto& r) { return std::tie(r.rhs); },
      [](const EqualityRow&) { return false; });
  set.ineq = gatherRows(
      comm, inequalities,
      [](auto& r) { return std::tie(r.gap, r.lowerBound, r.upperBound, r.disc, r.key); },
      [](const InequalityRow& r) { return r.disc == 2; });
  checkDiscRows(set.ineq);
  for (const auto& row : set.user) checkRow(row.entries, row.rhs, "equality", "=", allSizes);
  for (const auto& row : set.ineq) {
    checkRow(row.entries, row.gap, "inequality", "<=", allSizes);
    // NaN fails both comparisons.
    if (!(row.lowerBound <= row.upperBound) || !(row.lowerBound < kInf) ||
        !(row.upperBound > -kInf))
      throw std::invalid_argument("inequality row " + describeRow(row.entries, "<=", row.gap) +
                                  ": its multiplier's bounds [" + std::to_string(row.lowerBound) +
                                  ", " + std::to_string(row.upperBound) +
                                  "] are empty or not finite on the closed side");
    // Gathered as doubles: exact below 2^53.
    if (row.key < -1 || row.key >= kKeyLimit)
      throw std::invalid_argument("inequality row " + describeRow(row.entries, "<=", row.gap) +
                                  ": its key " + std::to_string(row.key) +
                                  " is neither -1 (none) nor in [0, 2^53)");
  }
}

// The scaling group of every row and the lowest subdomain of each group (its owner's).
struct Grouping {
  std::vector<int> groupOf;
  std::vector<GO> groupLowest;
};

// Scaling groups: the automatic groups, joined through the dofs the caller's rows share with
// them or with each other (the inequality rows too, unless they are scaled separately).
Grouping scalingGroups(const RowSet& set, const TearingOptions& options, Tearing& t) {
  const GO numAuto = set.numAuto();
  const GO numJoined = options.inequalityScaling == TearingOptions::InequalityScaling::Joined
                           ? t.numRows
                           : set.numEq();
  Grouping grouping;
  std::vector<int>& groupOf = grouping.groupOf;
  std::vector<GO>& groupLowest = grouping.groupLowest;
  groupOf.resize(t.numRows);
  Components comp(static_cast<std::size_t>(t.numRows));
  std::vector<GO> firstOfGroup(set.groupOwner.size(), -1);
  for (GO r = 0; r < numAuto; ++r) {
    GO& first = firstOfGroup[set.automatic[r].group];
    if (first < 0) first = r;
    comp.join(first, r);
  }
  if (numJoined > numAuto) {
    std::map<std::pair<int, int>, GO> rowOfDof;
    for (GO r = 0; r < numJoined; ++r)
      for (const auto& e : set.entriesOf(r)) {
        auto [it, added] = rowOfDof.insert({{e.subdomain, e.dof}, r});
        if (!added) comp.join(it->second, r);
      }
  }
  // The two rows of a disc (consecutive) in one group: one owner, so one rank holds both, next
  // to each other.
  for (GO r = set.numEq() + 1; r < t.numRows; ++r)
    if (set.ineq[static_cast<std::size_t>(r - set.numEq())].disc == 2) comp.join(r - 1, r);
  std::map<std::size_t, int> groupOfRoot;
  std::vector<GO> groupSize;
  for (GO r = 0; r < t.numRows; ++r) {
    auto [it, added] = groupOfRoot.insert({comp.find(r), static_cast<int>(groupLowest.size())});
    if (added) {
      groupLowest.push_back(std::numeric_limits<GO>::max());
      groupSize.push_back(0);
    }
    groupOf[r] = it->second;
    ++groupSize[it->second];
    for (const auto& e : set.entriesOf(r))
      groupLowest[it->second] = std::min<GO>(groupLowest[it->second], e.subdomain);
  }
  t.numScalingGroups = static_cast<GO>(groupSize.size());
  for (GO size : groupSize) {
    t.largestScalingGroup = std::max(t.largestScalingGroup, size);
    if (size > kMaxDenseScalingGroup) ++t.numSparseScalingGroups;
  }
  return grouping;
}

// The multiplier map: rows of groups owned here. Returns those rows.
std::vector<GO> buildMultiplierMap(const Teuchos::RCP<const Comm>& comm,
                                   const std::vector<int>& owner, const Grouping& grouping,
                                   Tearing& t) {
  const int me = comm->getRank();
  std::vector<GO> myRows;
  for (GO r = 0; r < t.numRows; ++r)
    if (owner[grouping.groupLowest[grouping.groupOf[r]]] == me) myRows.push_back(r);
  t.multiplierMap = Teuchos::rcp(new Map(static_cast<Tpetra::global_size_t>(t.numRows),
                                         Teuchos::ArrayView<const GO>(myRows), 0, comm));
  return myRows;
}

// c on the rows owned here: zero on the numAuto automatic rows, then the caller's right-hand
// sides and gaps.
void fillRightHandSide(GO numAuto, const std::vector<EqualityRow>& user,
                       const std::vector<InequalityRow>& ineq, Tearing& t) {
  const GO numEq = numAuto + static_cast<GO>(user.size());
  auto c = t.rhs->getDataNonConst();
  const Map& map = *t.multiplierMap;
  for (std::size_t l = 0; l < map.getNodeNumElements(); ++l) {
    const GO r = map.getGlobalElement(static_cast<LO>(l));
    c[l] = r >= numEq     ? ineq[static_cast<std::size_t>(r - numEq)].gap
           : r >= numAuto ? user[static_cast<std::size_t>(r - numAuto)].rhs
                          : 0.0;
  }
}

// B and c on the rows owned here.
void assembleConstraintMatrix(const RowSet& set, const std::vector<GO>& myRows, Tearing& t) {
  const std::vector<Row>& rows = set.automatic;
  const GO numAuto = set.numAuto(), numEq = set.numEq();
  std::size_t maxEntries = 2;
  for (const auto& row : set.user) maxEntries = std::max(maxEntries, row.entries.size());
  for (const auto& row : set.ineq) maxEntries = std::max(maxEntries, row.entries.size());
  t.B = Teuchos::rcp(new CrsMatrix(t.multiplierMap, maxEntries, Tpetra::StaticProfile));
  t.rhs = Teuchos::rcp(new Vector(t.multiplierMap));
  std::vector<GO> cols(maxEntries);
  std::vector<double> vals(maxEntries);
  for (std::size_t l = 0; l < myRows.size(); ++l) {
    const GO r = myRows[l];
    int n = 0;
    if (r < numAuto) {
      const Row& row = rows[r];
      for (n = 0; n < row.n; ++n) {
        cols[n] = t.dofOffset[row.sub[n]] + row.dof[n];
        vals[n] = row.coef[n];
      }
    } else {
      // Entries on the same dof are summed: Tpetra would sum them at fillComplete anyway.
      const auto& entries = r < numEq ? set.user[r - numAuto].entries : set.ineq[r - numEq].entries;
      for (const auto& e : entries) {
        cols[n] = t.dofOffset[e.subdomain] + e.dof;
        vals[n++] = e.coef;
      }
    }
    t.B->insertGlobalValues(r, Teuchos::ArrayView<const GO>(cols.data(), n),
                            Teuchos::ArrayView<const double>(vals.data(), n));
  }
  t.B->fillComplete(t.primalMap, t.multiplierMap);
  fillRightHandSide(numAuto, set.user, set.ineq, t);
}

// The rows touching each local subdomain.
void findSubdomainRows(const RowSet& set, const std::vector<TearingInput>& local, Tearing& t) {
  const std::vector<Row>& rows = set.automatic;
  const GO numAuto = set.numAuto(), numEq = set.numEq();
  std::map<int, std::size_t> localIndex;
  for (std::size_t k = 0; k < local.size(); ++k) localIndex[local[k].id] = k;
  t.subdomainRows.assign(local.size(), {});
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (int k = 0; k < rows[r].n; ++k) {
      auto it = localIndex.find(rows[r].sub[k]);
      if (it != localIndex.end())
        t.subdomainRows[it->second].push_back(
            {static_cast<GO>(r), rows[r].dof[k], rows[r].coef[k]});
    }
  for (std::size_t r = 0; r < set.user.size(); ++r)
    for (const auto& e : set.user[r].entries) {
      auto it = localIndex.find(e.subdomain);
      if (it != localIndex.end())
        t.subdomainRows[it->second].push_back({numAuto + static_cast<GO>(r), e.dof, e.coef});
    }
  for (std::size_t r = 0; r < set.ineq.size(); ++r)
    for (const auto& e : set.ineq[r].entries) {
      auto it = localIndex.find(e.subdomain);
      if (it != localIndex.end())
        t.subdomainRows[it->second].push_back({numEq + static_cast<GO>(r), e.dof, e.coef});
    }
}

// Owned groups and the pseudo-inverse of their block of B B^T (entries on one dof add up).
void buildScaling(const RowSet& set, const Grouping& grouping, const std::vector<GO>& myRows,
                  Tearing& t) {
  std::map<int, std::vector<LO>> groupLids;  // owned group -> local rows, ascending
  for (std::size_t l = 0; l < myRows.size(); ++l)
    groupLids[grouping.groupOf[myRows[l]]].push_back(static_cast<LO>(l));
  for (auto& [group, lids] : groupLids) {
    const int m = static_cast<int>(lids.size());
    std::vector<std::map<std::pair<int, int>, double>> coefs(m);
    for (int i = 0; i < m; ++i)
      for (const auto& e : set.entriesOf(myRows[lids[i]]))
        coefs[i][std::make_pair(e.subdomain, e.dof)] += e.coef;
    if (m <= kMaxDenseScalingGroup) {
      std::vector<double> BBt(m * m, 0.0);
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j)
          for (const auto& [dof, v] : coefs[i]) {
            auto it = coefs[j].find(dof);
            if (it != coefs[j].end()) BBt[j * m + i] += v * it->second;
          }
      t.scaling.dense.push_back(dense::pseudoInverseSpd(m, BBt));
      t.scaling.sparse.push_back(nullptr);
    } else {
      // B B^T of the group through the rows on each dof.
      std::map<std::pair<int, int>, std::vector<std::pair<int, double>>> rowsOnDof;
      for (int i = 0; i < m; ++i)
        for (const auto& [dof, v] : coefs[i]) rowsOnDof[dof].emplace_back(i, v);
      std::vector<int> ri, ci;
      std::vector<double> vals;
      for (const auto& [dof, on] : rowsOnDof)
        for (const auto& [i, vi] : on)
          for (const auto& [j, vj] : on) {
            ri.push_back(i);
            ci.push_back(j);
            vals.push_back(vi * vj);
          }
      t.scaling.dense.emplace_back();
      t.scaling.sparse.push_back(
          std::make_shared<SparsePseudoInverse>(csrFromTriplets(m, m, ri, ci, vals)));
    }
    t.scaling.rows.push_back(std::move(lids));
  }
}

}  // namespace

Tearing buildTearing(const Teuchos::RCP<const Comm>& comm, int numSubdomains,
                     const std::vector<TearingInput>& local, int dofsPerNode,
                     const TearingOptions& options, const std::vector<InequalityRow>& inequalities,
                     const std::vector<EqualityRow>& equalities) {
  Tearing t;
  const std::vector<long long> allSizes = numberPrimalDofs(comm, numSubdomains, local, t);
  const std::vector<int> owner = subdomainOwners(*comm, numSubdomains, local);
  RowSet set;
  addAutomaticRows(gatherBoundaryCopies(*comm, local), dofsPerNode, options, owner, set, t);
  addCallerRows(*comm, equalities, inequalities, allSizes, set);
  t.firstUserEqualityRow = set.numAuto();
  t.numUserEqualityRows = static_cast<GO>(set.user.size());
  t.firstInequalityRow = set.numEq();
  t.numInequalityRows = static_cast<GO>(set.ineq.size());
  t.numRows = set.numEq() + t.numInequalityRows;
  const Grouping grouping = scalingGroups(set, options, t);
  const std::vector<GO> myRows = buildMultiplierMap(comm, owner, grouping, t);
  assembleConstraintMatrix(set, myRows, t);
  findSubdomainRows(set, local, t);
  buildScaling(set, grouping, myRows, t);
  t.userEqualityRows = set.user;
  t.inequalityRows = set.ineq;
  return t;
}

bool updateTearingValues(const Teuchos::RCP<const Comm>& comm, Tearing& t,
                         const std::vector<InequalityRow>& inequalities,
                         const std::vector<EqualityRow>& equalities) {
  const std::size_t numSubdomains = t.dofOffset.empty() ? 0 : t.dofOffset.size() - 1;
  std::vector<long long> allSizes(numSubdomains);
  for (std::size_t s = 0; s < numSubdomains; ++s) allSizes[s] = t.dofOffset[s + 1] - t.dofOffset[s];
  RowSet set;
  addCallerRows(*comm, equalities, inequalities, allSizes, set);
  // B, its maps and the scaling groups follow from the entries alone (and the pairing of disc
  // rows, which the canonical order keeps together); every rank gathered the same rows.
  const auto sameEntries = [](const auto& a, const auto& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].entries.size() != b[i].entries.size()) return false;
      for (std::size_t k = 0; k < a[i].entries.size(); ++k) {
        const ConstraintEntry &x = a[i].entries[k], &y = b[i].entries[k];
        if (x.subdomain != y.subdomain || x.dof != y.dof || x.coef != y.coef) return false;
      }
    }
    return true;
  };
  if (!sameEntries(set.user, t.userEqualityRows) || !sameEntries(set.ineq, t.inequalityRows))
    return false;
  for (std::size_t i = 0; i < set.ineq.size(); ++i)
    if (set.ineq[i].disc != t.inequalityRows[i].disc) return false;
  // The automatic rows' zeros too: a caller may have shifted them since (an increment's origin).
  fillRightHandSide(t.firstUserEqualityRow, set.user, set.ineq, t);
  t.userEqualityRows = std::move(set.user);
  t.inequalityRows = std::move(set.ineq);
  return true;
}

void ScalingGroups::apply(double* x) const {
  // Most groups are a single row (a dof shared by two subdomains) and the dense ones hold at most
  // kMaxDenseScalingGroup rows: no allocation per group (this runs twice per preconditioner apply,
  // on every group of the dual vector).
  double in[kMaxDenseScalingGroup], out[kMaxDenseScalingGroup];
  std::vector<double> inSparse, outSparse;
  for (std::size_t g = 0; g < rows.size(); ++g) {
    const auto& lids = rows[g];
    const int m = static_cast<int>(lids.size());
    if (sparse[g]) {
      inSparse.resize(m);
      outSparse.assign(m, 0.0);
      for (int i = 0; i < m; ++i) inSparse[i] = x[lids[i]];
      sparse[g]->apply(inSparse.data(), outSparse.data());
      for (int i = 0; i < m; ++i) x[lids[i]] = outSparse[i];
      continue;
    }
    const double* Q = dense[g].data();
    if (m == 1) {
      x[lids[0]] *= Q[0];
      continue;
    }
    for (int i = 0; i < m; ++i) in[i] = x[lids[i]], out[i] = 0.0;
    for (int c = 0; c < m; ++c)
      for (int r = 0; r < m; ++r) out[r] += Q[c * m + r] * in[c];
    for (int i = 0; i < m; ++i) x[lids[i]] = out[i];
  }
}

std::vector<long long> subdomainRowCounts(const Tearing& t) {
  std::vector<long long> counts;
  for (const auto& entries : t.subdomainRows) {
    std::vector<GO> rows;
    for (const auto& e : entries) rows.push_back(e.row);
    std::sort(rows.begin(), rows.end());
    counts.push_back(std::unique(rows.begin(), rows.end()) - rows.begin());
  }
  return counts;
}

std::vector<int> subdomainDualDofs(const Tearing& t, std::size_t i) {
  std::vector<int> dofs;
  for (const auto& e : t.subdomainRows.at(i)) dofs.push_back(e.dof);
  std::sort(dofs.begin(), dofs.end());
  dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
  return dofs;
}

}  // namespace tfeti
