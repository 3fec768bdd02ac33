#include "tfeti_TpetraInterface.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Export.hpp>

#include <map>
#include <sstream>
#include <stdexcept>

#include "tfeti_CollectiveError.hpp"

namespace tfeti {

CsrMatrix csrFromTpetra(const CrsMatrix& K, const std::string& what) {
  const auto rowMap = K.getRowMap();
  const GO n = static_cast<GO>(rowMap->getGlobalNumElements());
  auto fail = [&](const std::string& why) { throw std::invalid_argument(what + ": " + why); };
  if (static_cast<GO>(rowMap->getNodeNumElements()) != n)
    fail("the CrsMatrix's rows are spread over " + std::to_string(rowMap->getComm()->getSize()) +
         " ranks; a subdomain matrix must own all its rows on the rank that holds the "
         "subdomain (a serial communicator)");
  if (n > 0 && (rowMap->getMinGlobalIndex() != 0 || rowMap->getMaxGlobalIndex() != n - 1))
    fail("the CrsMatrix's row ids must be 0 .. " + std::to_string(n - 1) +
         " (the subdomain's local dofs), they are " + std::to_string(rowMap->getMinGlobalIndex()) +
         " .. " + std::to_string(rowMap->getMaxGlobalIndex()));
  const auto domain = K.getDomainMap();
  if (!domain.is_null() && static_cast<GO>(domain->getGlobalNumElements()) != n) {
    std::ostringstream msg;
    msg << "the CrsMatrix is " << n << " x " << domain->getGlobalNumElements()
        << "; a subdomain matrix is square";
    fail(msg.str());
  }
  std::vector<int> ri, ci;
  std::vector<double> v;
  std::vector<GO> cols;
  std::vector<Scalar> vals;
  for (GO i = 0; i < n; ++i) {
    const std::size_t len = K.getNumEntriesInGlobalRow(i);
    cols.resize(len);
    vals.resize(len);
    std::size_t got = 0;
    K.getGlobalRowCopy(i, Teuchos::arrayViewFromVector(cols), Teuchos::arrayViewFromVector(vals),
                       got);
    for (std::size_t k = 0; k < got; ++k) {
      if (cols[k] < 0 || cols[k] >= n)
        fail("row " + std::to_string(i) + " has column " + std::to_string(cols[k]) +
             ", outside 0 .. " + std::to_string(n - 1));
      ri.push_back(static_cast<int>(i));
      ci.push_back(static_cast<int>(cols[k]));
      v.push_back(vals[k]);
    }
  }
  return csrFromTriplets(static_cast<int>(n), static_cast<int>(n), ri, ci, v);
}

Teuchos::RCP<MultiVector> untornVector(const Teuchos::RCP<const Map>& map,
                                       const std::vector<std::vector<GO>>& globalNodes,
                                       int dofsPerNode,
                                       const std::vector<std::vector<double>>& values) {
  const auto comm = map->getComm();
  // Sum and count per untorn dof over this rank's subdomains.
  std::map<GO, std::pair<double, double>> local;
  long long entries = 0;
  for (std::size_t s = 0; s < globalNodes.size(); ++s)
    for (std::size_t node = 0; node < globalNodes[s].size(); ++node)
      for (int c = 0; c < dofsPerNode; ++c) {
        auto& e = local[globalNodes[s][node] * dofsPerNode + c];
        e.first += values[s][node * dofsPerNode + c];
        e.second += 1.0;
        ++entries;
      }
  std::vector<GO> gids;
  for (const auto& e : local) gids.push_back(e.first);
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  auto source = Teuchos::rcp(new Map(invalid, Teuchos::arrayViewFromVector(gids), 0, comm));
  MultiVector sumCount(source, 2);
  LO l = 0;
  for (const auto& e : local) {
    sumCount.replaceLocalValue(l, 0, e.second.first);
    sumCount.replaceLocalValue(l, 1, e.second.second);
    ++l;
  }
  // A subdomain dof missing from `map` would be dropped by the export: compare the counts.
  std::string error;
  MultiVector target(map, 2);
  Tpetra::Export<LO, GO, Node> exporter(source, map);
  target.doExport(sumCount, exporter, Tpetra::ADD);
  auto out = Teuchos::rcp(new MultiVector(map, 1));
  double arrived = 0.0;
  GO empty = -1;
  {
    auto t = target.get2dView();
    for (LO i = 0; i < static_cast<LO>(map->getNodeNumElements()); ++i) {
      arrived += t[1][i];
      if (t[1][i] == 0.0) {
        if (empty < 0) empty = map->getGlobalElement(i);
        continue;
      }
      out->replaceLocalValue(i, 0, t[0][i] / t[1][i]);
    }
  }
  if (empty >= 0)
    error = "untorn solution: entry " + std::to_string(empty) +
            " of the map given is a dof of no subdomain (dof = dofs per node * global node + "
            "component)";
  throwIfAnyRankFailed(*comm, error);
  double totalArrived = 0.0, totalEntries = 0.0, mine = double(entries);
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &arrived, &totalArrived);
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &mine, &totalEntries);
  if (totalArrived != totalEntries) {
    std::ostringstream msg;
    msg << "untorn solution: " << static_cast<long long>(totalEntries - totalArrived)
        << " subdomain dof values have no entry in the map given (the map must hold every dof "
           "= dofs per node * global node + component)";
    throw CollectiveError(msg.str());
  }
  return out;
}

}  // namespace tfeti
