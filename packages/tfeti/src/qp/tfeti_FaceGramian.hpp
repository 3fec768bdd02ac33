#pragma once
// The columns of E_C Q E_C^T for the bound components C of SMALBE's problem (Q the projector
// onto the range of the equality rows), computed when first needed and kept for one solve.
// Every face's Schur complement S = I - E_A Q E_A^T (A a subset of C, tfeti_FaceProjector.hpp)
// is a principal submatrix of I - E_C Q E_C^T, so the faces of one solve (the level search's
// bisection, the active-set steps) share their columns: one application of Q per component that
// is ever active, instead of one per component of every face.
//
// Collective: a missing column is computed by all ranks together, so all ranks must ask for the
// same columns in the same order (the faces are replicated, which they are).
#include <BelosMultiVecTraits.hpp>
#include <BelosOperatorTraits.hpp>
#include <Teuchos_RCP.hpp>

#include <algorithm>
#include <map>
#include <vector>

#include "tfeti_BoundTraits.hpp"

namespace tfeti {

template <class S, class MV, class OP>
class FaceGramian {
 public:
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;
  using BT = BoundTraits<S, MV>;

  // candidates: sorted global indices (every component that can be active); like: a vector on
  // Q's map.
  FaceGramian(Teuchos::RCP<const OP> Q, std::vector<long long> candidates, const MV& like)
      : Q_(std::move(Q)), c_(std::move(candidates)) {
    e_ = MVT::Clone(like, 1);
    qe_ = MVT::Clone(like, 1);
  }

  // True when every index of `rows` (sorted) is a candidate.
  bool covers(const std::vector<long long>& rows) const {
    return std::includes(c_.begin(), c_.end(), rows.begin(), rows.end());
  }
  // The place of candidate i in the candidates' order (i must be one).
  std::size_t position(long long i) const {
    return static_cast<std::size_t>(std::lower_bound(c_.begin(), c_.end(), i) - c_.begin());
  }
  // E_C Q e_j for the candidate j (collective when not computed before).
  const std::vector<S>& column(long long j) {
    auto it = columns_.find(j);
    if (it != columns_.end()) return it->second;
    MVT::MvInit(*e_, S(0));
    BT::addAt({j}, {S(1)}, S(1), *e_);
    OPT::Apply(*Q_, *e_, *qe_);
    ++qApplies_;
    return columns_.emplace(j, BT::gatherAt(*qe_, c_)).first->second;
  }
  long long projectorApplications() const { return qApplies_; }

 private:
  Teuchos::RCP<const OP> Q_;
  std::vector<long long> c_;
  std::map<long long, std::vector<S>> columns_;
  Teuchos::RCP<MV> e_, qe_;
  long long qApplies_ = 0;
};

}  // namespace tfeti
