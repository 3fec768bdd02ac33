#pragma once
// The columns of E_C Q E_C^T for the bound components C of SMALBE's problem (Q the projector
// onto the range of the equality rows), computed when first needed and kept for one solve.
// Every face's Schur complement S = I - E_A Q E_A^T (A a subset of C, tfeti_FaceProjector.hpp)
// is a principal submatrix of I - E_C Q E_C^T, so the faces of one solve (the level search's
// bisection, the active-set steps) share their columns: one application of Q per component that
// is ever active, instead of one per component of every face. Where Q has structure to exploit
// (FETI's G^T (G G^T)^{-1} G), a ComplementColumns source computes them in blocks instead.
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
#include "tfeti_ComplementColumns.hpp"

namespace tfeti {

template <class S, class MV, class OP>
class FaceGramian {
 public:
  using MVT = Belos::MultiVecTraits<S, MV>;
  using OPT = Belos::OperatorTraits<S, MV, OP>;
  using BT = BoundTraits<S, MV>;

  // candidates: sorted global indices (every component that can be active); like: a vector on
  // Q's map. structured (optional, collective): the columns from Q's structure instead of one
  // application of Q each.
  FaceGramian(Teuchos::RCP<const OP> Q, std::vector<long long> candidates, const MV& like,
              Teuchos::RCP<ComplementColumns<S>> structured = Teuchos::null)
      : Q_(std::move(Q)), c_(std::move(candidates)), structured_(std::move(structured)) {
    e_ = MVT::Clone(like, 1);
    qe_ = MVT::Clone(like, 1);
    if (!structured_.is_null()) structured_->setCandidates(c_);
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
    if (!structured_.is_null()) {
      prefetch({j});
      return columns_.find(j)->second;
    }
    MVT::MvInit(*e_, S(0));
    BT::addAt({j}, {S(1)}, S(1), *e_);
    OPT::Apply(*Q_, *e_, *qe_);
    ++qApplies_;
    return columns_.emplace(j, BT::gatherAt(*qe_, c_)).first->second;
  }
  // With a structured source, computes the missing columns among `indices` (candidates)
  // kBlock at a time, each block one coarse solve with kBlock right-hand sides; without one,
  // nothing (column() applies Q then).
  void prefetch(const std::vector<long long>& indices) {
    if (structured_.is_null()) return;
    std::vector<long long> missing;
    for (long long j : indices)
      if (columns_.find(j) == columns_.end()) missing.push_back(j);
    std::sort(missing.begin(), missing.end());
    missing.erase(std::unique(missing.begin(), missing.end()), missing.end());
    std::vector<S> values;
    for (std::size_t first = 0; first < missing.size(); first += kBlock) {
      const auto from = missing.begin() + static_cast<std::ptrdiff_t>(first);
      const std::vector<long long> block(
          from, from + static_cast<std::ptrdiff_t>(std::min(kBlock, missing.size() - first)));
      structured_->columns(block, values);
      for (std::size_t k = 0; k < block.size(); ++k) {
        const auto at = values.begin() + static_cast<std::ptrdiff_t>(k * c_.size());
        columns_.emplace(block[k], std::vector<S>(at, at + static_cast<std::ptrdiff_t>(c_.size())));
      }
    }
  }
  // Applications of Q (one per column computed without a structured source).
  long long projectorApplications() const { return qApplies_; }

 private:
  // Columns per call of the structured source: for FETI one coarse solve with 64 right-hand
  // sides (1.6 MB of them at 512 subdomains), whose supernodal solve runs in BLAS-3.
  static constexpr std::size_t kBlock = 64;
  Teuchos::RCP<const OP> Q_;
  std::vector<long long> c_;
  Teuchos::RCP<ComplementColumns<S>> structured_;
  std::map<long long, std::vector<S>> columns_;
  Teuchos::RCP<MV> e_, qe_;
  long long qApplies_ = 0;
};

}  // namespace tfeti
