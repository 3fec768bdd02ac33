// Unit tests of the warm start's carry-over onto new rows (tfeti_RowCarryOver.hpp) on 1, 2 and
// 3 ranks: automatic rows keep their values, keyed inequality rows follow their key wherever the
// new canonical order puts them (and whichever rank owns them), new rows and rows whose key two
// rows share start at 0, unkeyed rows fall back to their position when their number is
// unchanged and to nothing otherwise; friction's boxes follow their keys like the others.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "tfeti_RowCarryOver.hpp"
#include "tfeti_StructuredMesh.hpp"
#include "tfeti_Tearing.hpp"

namespace {

using tfeti::GO;
using tfeti::LO;

const tfeti::StructuredRectangle kRect(0, 1, 0, 1, 2, 2, 2, 2);

// Row k: on subdomain k % 4, dof k (of 18), gap 0.1 k, key 100 + k (keyed) or none; passed by
// rank k % size, so that rows move between ranks when the set changes.
tfeti::Tearing tearWith(const std::vector<int>& ks, bool keyed,
                        const std::vector<long long>& keys = {}, bool boxes = false) {
  const auto comm = Tpetra::getDefaultComm();
  std::vector<tfeti::TearingInput> local;
  for (int s : tfeti::subdomainsOfRank(comm->getRank(), 4, comm->getSize())) {
    const tfeti::SubdomainMesh mesh = kRect.subdomain(s);
    tfeti::TearingInput in;
    in.id = mesh.id;
    in.numDofs = 2 * mesh.numNodes();
    in.boundaryNodes = mesh.boundaryNodes();
    const std::vector<int> dir = mesh.dirichletMasks(2);
    for (int n : in.boundaryNodes) {
      in.boundaryGlobal.push_back(mesh.globalNode[n]);
      in.boundaryDirichlet.push_back(dir[n]);
    }
    local.push_back(in);
  }
  std::vector<tfeti::InequalityRow> mine;
  for (std::size_t i = 0; i < ks.size(); ++i) {
    const int k = ks[i];
    if (k % comm->getSize() != comm->getRank()) continue;
    tfeti::InequalityRow r;
    r.entries = {{k % 4, k, 1.0}};
    r.gap = 0.1 * k;
    if (keyed) r.key = keys.empty() ? 100 + k : keys[i];
    if (boxes) r.lowerBound = -1.0, r.upperBound = 1.0;
    mine.push_back(r);
  }
  return tfeti::buildTearing(comm, 4, local, 2, {}, mine);
}

// The inequality row's k, from its gap.
int kOf(const tfeti::Tearing& t, GO row) {
  return static_cast<int>(std::lround(10 * t.inequalityRows[row - t.firstInequalityRow].gap));
}

// A vector on t's rows: automatic row g holds g + 0.5, inequality row k holds 1000 + k.
tfeti::Vector marked(const tfeti::Tearing& t) {
  tfeti::Vector v(t.multiplierMap);
  auto d = v.getDataNonConst();
  for (LO l = 0; l < static_cast<LO>(t.multiplierMap->getNodeNumElements()); ++l) {
    const GO g = t.multiplierMap->getGlobalElement(l);
    d[l] = g < t.firstInequalityRow ? g + 0.5 : 1000.0 + kOf(t, g);
  }
  return v;
}

}  // namespace

TEUCHOS_UNIT_TEST(RowCarryOver, KeyedRowsFollowTheirKeys) {
  // Row 2 dropped, row 9 new, row 0 moved from first to (canonically) elsewhere by its entries.
  const tfeti::Tearing before = tearWith({0, 1, 2, 3, 5, 6}, true);
  const tfeti::Tearing after = tearWith({9, 6, 5, 3, 1, 0}, true);
  const auto from = tfeti::rowIdentities(before), to = tfeti::rowIdentities(after);
  const std::vector<GO> continued = tfeti::continuedRows(from, to);
  TEST_EQUALITY(continued.size(), static_cast<std::size_t>(after.numRows));
  const auto v = tfeti::RowCarryOver(from, to).carry(marked(before));
  TEST_ASSERT(!v.is_null());
  auto d = v->getData();
  int carried = 0;
  for (LO l = 0; l < static_cast<LO>(after.multiplierMap->getNodeNumElements()); ++l) {
    const GO g = after.multiplierMap->getGlobalElement(l);
    if (g < after.firstInequalityRow) {
      TEST_EQUALITY(d[l], g + 0.5);
      continue;
    }
    const int k = kOf(after, g);
    TEST_EQUALITY(d[l], k == 9 ? 0.0 : 1000.0 + k);
    carried += k == 9 ? 0 : 1;
  }
  int all = 0;
  Teuchos::reduceAll(*Tpetra::getDefaultComm(), Teuchos::REDUCE_SUM, 1, &carried, &all);
  TEST_EQUALITY(all, 5);
}

TEUCHOS_UNIT_TEST(RowCarryOver, SharedKeysMatchNothing) {
  const tfeti::Tearing before = tearWith({1, 2, 3}, true, {7, 8, 9});
  const tfeti::Tearing after = tearWith({1, 2, 3}, true, {7, 7, 9});  // rows 1 and 2 share 7
  const auto from = tfeti::rowIdentities(before), to = tfeti::rowIdentities(after);
  const auto v = tfeti::RowCarryOver(from, to).carry(marked(before));
  auto d = v->getData();
  for (LO l = 0; l < static_cast<LO>(after.multiplierMap->getNodeNumElements()); ++l) {
    const GO g = after.multiplierMap->getGlobalElement(l);
    if (g >= after.firstInequalityRow) TEST_EQUALITY(d[l], kOf(after, g) == 3 ? 1003.0 : 0.0);
  }
}

TEUCHOS_UNIT_TEST(RowCarryOver, UnkeyedRowsKeepTheirPositionOrNothing) {
  const tfeti::Tearing before = tearWith({1, 2, 3}, false);
  // The same number of rows (one changed): by position, as before keys.
  const tfeti::Tearing same = tearWith({1, 2, 5}, false);
  auto from = tfeti::rowIdentities(before), to = tfeti::rowIdentities(same);
  std::vector<GO> continued = tfeti::continuedRows(from, to);
  TEST_EQUALITY(continued.size(), static_cast<std::size_t>(same.numRows));
  for (GO g = 0; g < same.numRows; ++g) TEST_EQUALITY(continued[g], g);
  // Another number of rows: nothing carried.
  const tfeti::Tearing more = tearWith({1, 2, 3, 5}, false);
  to = tfeti::rowIdentities(more);
  continued = tfeti::continuedRows(from, to);
  TEST_ASSERT(continued.empty());
  TEST_ASSERT(tfeti::RowCarryOver(from, to).carry(marked(before)).is_null());
  // Keyed on one side only: by position when the numbers agree.
  const tfeti::Tearing keyed = tearWith({1, 2, 3}, true);
  to = tfeti::rowIdentities(keyed);
  continued = tfeti::continuedRows(from, to);
  TEST_EQUALITY(continued.size(), static_cast<std::size_t>(keyed.numRows));
}

TEUCHOS_UNIT_TEST(RowCarryOver, BoxesFollowTheirKeys) {
  // Friction's boxes (2D tangential rows) are matched like every keyed row: by key, not by
  // position (which would put k = 9 where k = 0 was), whether or not their number changed.
  const tfeti::Tearing before = tearWith({0, 1, 2, 3, 5, 6}, true, {}, true);
  const tfeti::Tearing after = tearWith({9, 6, 5, 3, 1, 0}, true, {}, true);
  const tfeti::Tearing plainBefore = tearWith({0, 1, 2, 3, 5, 6}, true);
  const tfeti::Tearing plainAfter = tearWith({9, 6, 5, 3, 1, 0}, true);
  const std::vector<GO> boxes =
      tfeti::continuedRows(tfeti::rowIdentities(before), tfeti::rowIdentities(after));
  const std::vector<GO> plain =
      tfeti::continuedRows(tfeti::rowIdentities(plainBefore), tfeti::rowIdentities(plainAfter));
  TEST_EQUALITY(boxes.size(), static_cast<std::size_t>(after.numRows));
  TEST_ASSERT(boxes == plain);
  const tfeti::Vector moved =
      *tfeti::RowCarryOver(tfeti::rowIdentities(before), tfeti::rowIdentities(after))
           .carry(marked(before));
  auto m = moved.getData();
  for (LO l = 0; l < static_cast<LO>(after.multiplierMap->getNodeNumElements()); ++l) {
    const GO g = after.multiplierMap->getGlobalElement(l);
    if (g < after.firstInequalityRow) continue;
    const int k = kOf(after, g);
    TEST_EQUALITY(m[l], k == 9 ? 0.0 : 1000.0 + k);
  }
}

TEUCHOS_UNIT_TEST(RowCarryOver, KeysOutOfRangeAreAnError) {
  for (const long long key : {-2LL, 1LL << 53}) {
    std::string message;
    try {
      tearWith({1, 2}, true, {key, 5});
    } catch (const std::invalid_argument& e) {
      message = e.what();
    }
    out << message << "\n";
    TEST_ASSERT(message.find("its key " + std::to_string(key)) != std::string::npos);
  }
}
