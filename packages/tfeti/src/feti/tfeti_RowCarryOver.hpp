#pragma once
// A dual vector of one tearing carried onto the rows of the next (FetiSolver::update and
// updateStiffness: new contact rows, or a new stiffness with new rows), so that the Newton
// loop's next QP starts from the previous solution even when a contact update added, dropped or
// reordered rows.
//
// A row of the new tearing continues a row of the old one when
//   - both are automatic rows (gluing, TFETI's Dirichlet rows): the same subdomains give the
//     same rows in the same order;
//   - both are the caller's equality rows at the same position, their number unchanged;
//   - both are inequality rows with the same InequalityRow::key (every row of both tearings
//     keyed; a key two rows share matches neither), or, without keys, at the same position in
//     an unchanged number of rows (the rule before keys).
// Friction's rows are keyed like the others: Coulomb's bounds move between two tearings, and
// FetiSolver::warmIncrement moves the slipping ones onto their new bounds. Rows that continue
// none start at 0. The values move by one Tpetra Import from the old multiplier map to the old
// ids of the new rows each rank owns (RowCarryOver).
#include <Teuchos_RCP.hpp>
#include <Tpetra_Import.hpp>

#include <vector>

#include "tfeti_Tearing.hpp"
#include "tfeti_Types.hpp"

namespace tfeti {

// What identifies a tearing's rows: its multiplier map, where its row kinds begin, the
// inequality rows' keys.
struct RowIdentities {
  Teuchos::RCP<const Map> map;
  GO firstUserEqualityRow = 0, firstInequalityRow = 0, numRows = 0;
  std::vector<long long> keys;  // by inequality row
};

RowIdentities rowIdentities(const Tearing& t);

// The old row (global id in `from`) that each new row continues, -1 for none; the whole vector
// is empty when no row of `to` can be matched by the rules above (the rows differ in number and
// are not keyed). Row ids are those of `to`, all of them (every rank computes the same).
std::vector<GO> continuedRows(const RowIdentities& from, const RowIdentities& to);

// Dual vectors of `from` moved onto the rows of `to`: each row takes the value of the row it
// continues, 0 otherwise. The Import is built once (collective) and serves every vector.
class RowCarryOver {
 public:
  RowCarryOver(const RowIdentities& from, const RowIdentities& to);
  // v on from's map, on to's map; null when no row can be matched (continuedRows is empty).
  // Collective.
  Teuchos::RCP<Vector> carry(const Vector& v) const;

 private:
  Teuchos::RCP<const Map> to_, target_;  // target_: the old ids of the continued owned rows
  Teuchos::RCP<const Tpetra::Import<LO, GO, Node>> importer_;
  std::vector<LO> at_;  // where each of target_'s values goes on to_
};

}  // namespace tfeti
