#include "tfeti_Tearing.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <array>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

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

// Every rank's inequality rows, in a canonical order (by their entries, then gap) so that the
// numbering does not depend on which rank contributed a row.
std::vector<InequalityRow> gatherInequalities(const Comm& comm,
                                              const std::vector<InequalityRow>& mine) {
  std::vector<double> packed;
  for (const auto& row : mine) {
    packed.insert(packed.end(), {static_cast<double>(row.entries.size()), row.gap});
    for (const auto& e : row.entries)
      packed.insert(packed.end(),
                    {static_cast<double>(e.subdomain), static_cast<double>(e.dof), e.coef});
  }
  const std::vector<double> all = allGather(comm, packed);
  std::vector<InequalityRow> rows;
  for (std::size_t k = 0; k < all.size();) {
    InequalityRow row;
    const int n = static_cast<int>(all[k]);
    row.gap = all[k + 1];
    k += 2;
    for (int i = 0; i < n; ++i, k += 3)
      row.entries.push_back({static_cast<int>(all[k]), static_cast<int>(all[k + 1]), all[k + 2]});
    rows.push_back(std::move(row));
  }
  auto key = [](const InequalityRow& r) {
    std::vector<std::tuple<int, int, double>> k;
    for (const auto& e : r.entries) k.emplace_back(e.subdomain, e.dof, e.coef);
    return std::make_pair(k, r.gap);
  };
  std::sort(rows.begin(), rows.end(),
            [&](const InequalityRow& a, const InequalityRow& b) { return key(a) < key(b); });
  return rows;
}

Tearing buildTearing(const Teuchos::RCP<const Comm>& comm, int numSubdomains,
                     const std::vector<TearingInput>& local, int dofsPerNode,
                     const TearingOptions& options,
                     const std::vector<InequalityRow>& inequalities) {
  Tearing t;

  // Global dof numbering: subdomain by subdomain.
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

  // Who owns which subdomain: whatever distribution the caller chose (block rule, Zoltan2).
  std::vector<long long> owned;
  for (const auto& sd : local) owned.insert(owned.end(), {sd.id, comm->getRank()});
  const std::vector<long long> allOwned = allGather(*comm, owned);
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

  // Gather every subdomain's boundary nodes: (untorn node, subdomain, local node, Dirichlet).
  std::vector<long long> mine;
  for (const auto& s : local)
    for (std::size_t k = 0; k < s.boundaryNodes.size(); ++k)
      mine.insert(mine.end(),
                  {s.boundaryGlobal[k], s.id, s.boundaryNodes[k], s.boundaryDirichlet[k]});
  const std::vector<long long> all = allGather(*comm, mine);
  std::vector<Copy> copies(all.size() / 4);
  for (std::size_t k = 0; k < copies.size(); ++k)
    copies[k] = {all[4 * k], static_cast<int>(all[4 * k + 1]), static_cast<int>(all[4 * k + 2]),
                 static_cast<int>(all[4 * k + 3])};
  std::sort(copies.begin(), copies.end(), [](const Copy& a, const Copy& b) {
    return a.node != b.node ? a.node < b.node : a.sub < b.sub;
  });

  // Rows in canonical order: by untorn node, then component.
  std::vector<Row> rows;
  std::vector<int> groupOwner;
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
      const bool glue = m > 1 && (!dirichlet || options.gluingAtDirichletNodes);
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
  // Inequality rows follow the equality rows, each its own group, owned with its first entry.
  const std::vector<InequalityRow> ineq = gatherInequalities(*comm, inequalities);
  const GO numEq = static_cast<GO>(rows.size());
  t.firstInequalityRow = numEq;
  t.numInequalityRows = static_cast<GO>(ineq.size());
  t.numRows = numEq + t.numInequalityRows;
  std::size_t maxEntries = 2;
  for (const auto& row : ineq) {
    for (const auto& e : row.entries)
      if (e.subdomain < 0 || e.subdomain >= numSubdomains || e.dof < 0 ||
          e.dof >= allSizes[e.subdomain])
        throw std::invalid_argument("tearing: an inequality row refers to dof " +
                                    std::to_string(e.dof) + " of subdomain " +
                                    std::to_string(e.subdomain) + ", which does not exist");
    if (row.entries.empty())
      throw std::invalid_argument("tearing: an inequality row has no entries");
    maxEntries = std::max(maxEntries, row.entries.size());
  }

  // The multiplier map: rows of groups owned here.
  const int me = comm->getRank();
  std::vector<GO> myRows;
  for (std::size_t r = 0; r < rows.size(); ++r)
    if (groupOwner[rows[r].group] == me) myRows.push_back(static_cast<GO>(r));
  for (std::size_t r = 0; r < ineq.size(); ++r)
    if (owner[ineq[r].entries.front().subdomain] == me)
      myRows.push_back(numEq + static_cast<GO>(r));
  t.multiplierMap = Teuchos::rcp(new Map(static_cast<Tpetra::global_size_t>(t.numRows),
                                         Teuchos::ArrayView<const GO>(myRows), 0, comm));

  t.B = Teuchos::rcp(new CrsMatrix(t.multiplierMap, maxEntries, Tpetra::StaticProfile));
  t.rhs = Teuchos::rcp(new Vector(t.multiplierMap));
  {
    auto c = t.rhs->getDataNonConst();
    std::vector<GO> cols(maxEntries);
    std::vector<double> vals(maxEntries);
    for (std::size_t l = 0; l < myRows.size(); ++l) {
      const GO r = myRows[l];
      int n = 0;
      if (r < numEq) {
        const Row& row = rows[r];
        for (n = 0; n < row.n; ++n) {
          cols[n] = t.dofOffset[row.sub[n]] + row.dof[n];
          vals[n] = row.coef[n];
        }
      } else {
        const InequalityRow& row = ineq[r - numEq];
        // Entries on the same dof are summed: Tpetra would sum them at fillComplete anyway.
        for (const auto& e : row.entries) {
          cols[n] = t.dofOffset[e.subdomain] + e.dof;
          vals[n++] = e.coef;
        }
        c[l] = row.gap;
      }
      t.B->insertGlobalValues(r, Teuchos::ArrayView<const GO>(cols.data(), n),
                              Teuchos::ArrayView<const double>(vals.data(), n));
    }
  }
  t.B->fillComplete(t.primalMap, t.multiplierMap);

  // Rows touching each local subdomain.
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
  for (std::size_t r = 0; r < ineq.size(); ++r)
    for (const auto& e : ineq[r].entries) {
      auto it = localIndex.find(e.subdomain);
      if (it != localIndex.end())
        t.subdomainRows[it->second].push_back({numEq + static_cast<GO>(r), e.dof, e.coef});
    }

  // Owned groups and the pseudo-inverse of B B^T on each (rows of a group share its node's dofs).
  std::size_t numMyEq = 0;
  while (numMyEq < myRows.size() && myRows[numMyEq] < numEq) ++numMyEq;
  for (std::size_t r = 0; r < numMyEq;) {
    const int group = rows[myRows[r]].group;
    std::size_t e = r;
    while (e < numMyEq && rows[myRows[e]].group == group) ++e;
    const int m = static_cast<int>(e - r);
    std::vector<double> BBt(m * m, 0.0);
    std::vector<LO> lids;
    for (int i = 0; i < m; ++i) {
      lids.push_back(static_cast<LO>(r + i));
      const Row& ri = rows[myRows[r + i]];
      for (int j = 0; j < m; ++j) {
        const Row& rj = rows[myRows[r + j]];
        for (int a = 0; a < ri.n; ++a)
          for (int b = 0; b < rj.n; ++b)
            if (ri.sub[a] == rj.sub[b] && ri.dof[a] == rj.dof[b])
              BBt[j * m + i] += ri.coef[a] * rj.coef[b];
      }
    }
    t.groupRows.push_back(std::move(lids));
    t.groupScaling.push_back(dense::pseudoInverseSpd(m, BBt));
    r = e;
  }
  for (std::size_t l = numMyEq; l < myRows.size(); ++l) {
    // Entries on one dof add up before the row norm is taken.
    std::map<std::pair<int, int>, double> coefs;
    for (const auto& e : ineq[myRows[l] - numEq].entries) coefs[{e.subdomain, e.dof}] += e.coef;
    double norm2 = 0.0;
    for (const auto& [key, v] : coefs) norm2 += v * v;
    t.groupRows.push_back({static_cast<LO>(l)});
    t.groupScaling.push_back({norm2 > 0.0 ? 1.0 / norm2 : 0.0});
  }
  t.inequalityRows = ineq;
  return t;
}

}  // namespace tfeti
