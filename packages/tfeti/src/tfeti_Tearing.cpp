#include "tfeti_Tearing.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <array>
#include <map>

#include "tfeti_DenseUtils.hpp"
#include "tfeti_Gather.hpp"

namespace tfeti {
namespace {

struct Copy {
  GO node;
  int sub;
  int localNode;
  bool dirichlet;
};

struct Row {
  int group;
  int n;
  std::array<int, 2> sub;
  std::array<int, 2> dof;
  std::array<double, 2> coef;
};

}  // namespace

Tearing buildTearing(const Teuchos::RCP<const Comm>& comm, int numSubdomains,
                     const std::vector<TearingInput>& local, int dofsPerNode,
                     const TearingOptions& options) {
  Tearing t;
  const int P = comm->getSize();

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

  // Gather every subdomain's boundary nodes: (untorn node, subdomain, local node, Dirichlet).
  std::vector<long long> mine;
  for (const auto& s : local)
    for (std::size_t k = 0; k < s.boundaryNodes.size(); ++k)
      mine.insert(mine.end(),
                  {s.boundaryGlobal[k], s.id, s.boundaryNodes[k], s.boundaryDirichlet[k] ? 1 : 0});
  const std::vector<long long> all = allGather(*comm, mine);
  std::vector<Copy> copies(all.size() / 4);
  for (std::size_t k = 0; k < copies.size(); ++k)
    copies[k] = {all[4 * k], static_cast<int>(all[4 * k + 1]), static_cast<int>(all[4 * k + 2]),
                 all[4 * k + 3] != 0};
  std::sort(copies.begin(), copies.end(), [](const Copy& a, const Copy& b) {
    return a.node != b.node ? a.node < b.node : a.sub < b.sub;
  });

  // Rows in canonical order: by untorn node, then component.
  std::vector<Row> rows;
  std::vector<int> groupOwner;
  for (std::size_t first = 0; first < copies.size();) {
    std::size_t last = first;
    bool dirichlet = false;
    while (last < copies.size() && copies[last].node == copies[first].node)
      dirichlet |= copies[last++].dirichlet;
    const int m = static_cast<int>(last - first);
    const bool tfetiDirichlet = dirichlet && options.formulation == Formulation::TFETI;
    const bool glue = m > 1 && (!dirichlet || options.gluingAtDirichletNodes);
    for (int c = 0; c < dofsPerNode; ++c) {
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
      if (rows.size() > before)
        groupOwner.push_back(ownerOfSubdomain(copies[first].sub, numSubdomains, P));
    }
    first = last;
  }
  t.numRows = static_cast<GO>(rows.size());

  // The multiplier map: rows of groups owned here.
  const int me = comm->getRank();
  std::vector<GO> myRows;
  for (std::size_t r = 0; r < rows.size(); ++r)
    if (groupOwner[rows[r].group] == me) myRows.push_back(static_cast<GO>(r));
  t.multiplierMap = Teuchos::rcp(new Map(static_cast<Tpetra::global_size_t>(t.numRows),
                                         Teuchos::ArrayView<const GO>(myRows), 0, comm));

  t.B = Teuchos::rcp(new CrsMatrix(t.multiplierMap, 2, Tpetra::StaticProfile));
  for (GO r : myRows) {
    const Row& row = rows[r];
    GO cols[2];
    for (int k = 0; k < row.n; ++k) cols[k] = t.dofOffset[row.sub[k]] + row.dof[k];
    t.B->insertGlobalValues(r, Teuchos::ArrayView<const GO>(cols, row.n),
                            Teuchos::ArrayView<const double>(row.coef.data(), row.n));
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

  // Owned groups and the pseudo-inverse of B B^T on each (rows of a group share its node's dofs).
  for (std::size_t r = 0; r < myRows.size();) {
    const int group = rows[myRows[r]].group;
    std::size_t e = r;
    while (e < myRows.size() && rows[myRows[e]].group == group) ++e;
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
  return t;
}

}  // namespace tfeti
