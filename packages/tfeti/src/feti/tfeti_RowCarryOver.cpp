#include "tfeti_RowCarryOver.hpp"

#include <cmath>
#include <unordered_map>

namespace tfeti {

RowIdentities rowIdentities(const Tearing& t) {
  RowIdentities r;
  r.map = t.multiplierMap;
  r.firstUserEqualityRow = t.firstUserEqualityRow;
  r.firstInequalityRow = t.firstInequalityRow;
  r.numRows = t.numRows;
  r.keys.reserve(t.inequalityRows.size());
  for (const auto& row : t.inequalityRows) r.keys.push_back(row.key);
  return r;
}

namespace {
bool allKeyed(const std::vector<long long>& keys) {
  for (long long k : keys)
    if (k < 0) return false;
  return true;
}

// key -> inequality row index; a key held by two rows maps to -1.
std::unordered_map<long long, GO> indexByKey(const std::vector<long long>& keys) {
  std::unordered_map<long long, GO> index;
  for (std::size_t r = 0; r < keys.size(); ++r) {
    auto [it, inserted] = index.emplace(keys[r], static_cast<GO>(r));
    if (!inserted) it->second = -1;
  }
  return index;
}
}  // namespace

std::vector<GO> continuedRows(const RowIdentities& from, const RowIdentities& to) {
  const GO numIneqFrom = static_cast<GO>(from.keys.size());
  const GO numIneqTo = static_cast<GO>(to.keys.size());
  const bool sameAutomatic = from.firstUserEqualityRow == to.firstUserEqualityRow;
  const bool sameUser = sameAutomatic && from.firstInequalityRow == to.firstInequalityRow;
  const bool keyed = allKeyed(from.keys) && allKeyed(to.keys);
  const bool positional = !keyed && numIneqFrom == numIneqTo;
  if (!sameAutomatic || (!keyed && !positional)) return {};
  std::vector<GO> old(static_cast<std::size_t>(to.numRows), -1);
  for (GO g = 0; g < to.firstInequalityRow; ++g)
    if (g < to.firstUserEqualityRow || sameUser) old[g] = g;
  if (positional) {
    for (GO r = 0; r < numIneqTo; ++r) old[to.firstInequalityRow + r] = from.firstInequalityRow + r;
    return old;
  }
  const auto fromIndex = indexByKey(from.keys);
  const auto toIndex = indexByKey(to.keys);
  for (GO r = 0; r < numIneqTo; ++r) {
    const auto f = fromIndex.find(to.keys[r]);
    if (f == fromIndex.end() || f->second < 0 || toIndex.at(to.keys[r]) < 0) continue;
    old[to.firstInequalityRow + r] = from.firstInequalityRow + f->second;
  }
  return old;
}

RowCarryOver::RowCarryOver(const RowIdentities& from, const RowIdentities& to) : to_(to.map) {
  const std::vector<GO> continued = continuedRows(from, to);
  if (continued.empty()) return;  // the same on every rank
  std::vector<GO> wanted;
  const LO n = static_cast<LO>(to.map->getNodeNumElements());
  for (LO l = 0; l < n; ++l) {
    const GO o = continued[static_cast<std::size_t>(to.map->getGlobalElement(l))];
    if (o < 0) continue;
    wanted.push_back(o);
    at_.push_back(l);
  }
  const Teuchos::ArrayView<const GO> view =
      wanted.empty() ? Teuchos::ArrayView<const GO>()
                     : Teuchos::ArrayView<const GO>(wanted.data(), wanted.size());
  target_ = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(), view, 0,
                                 to.map->getComm()));
  importer_ = Teuchos::rcp(new Tpetra::Import<LO, GO, Node>(from.map, target_));
}

Teuchos::RCP<Vector> RowCarryOver::carry(const Vector& v) const {
  if (importer_.is_null()) return Teuchos::null;
  Vector gathered(target_);
  gathered.doImport(v, *importer_, Tpetra::INSERT);
  auto out = Teuchos::rcp(new Vector(to_));
  auto src = gathered.getData();
  auto dst = out->getDataNonConst();
  for (std::size_t k = 0; k < at_.size(); ++k) dst[at_[k]] = src[k];
  return out;
}

}  // namespace tfeti
