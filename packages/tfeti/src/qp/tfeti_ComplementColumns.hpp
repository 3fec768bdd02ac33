#pragma once
// E_C Q E_J^T, columns of SMALBE's projector Q onto the range of its equality rows restricted
// to the bound components, computed from Q's structure where it has one. SMALBE's face Schur
// complements need one such column per component that is ever active (tfeti_FaceGramian.hpp);
// without this source each column costs an application of Q to a unit vector, which in FETI
// (Q = G^T (G G^T)^{-1} G) streams all of G twice to use a handful of its entries.
#include <vector>

namespace tfeti {

template <class S>
class ComplementColumns {
 public:
  virtual ~ComplementColumns() = default;
  // The candidates C (sorted global indices) of the gramian that will ask (collective).
  virtual void setCandidates(const std::vector<long long>& candidates) = 0;
  // E_C Q E_J^T for J, candidates of setCandidates: |C| values per index of J, one column after
  // the other. Local: every rank computes the same values.
  virtual void columns(const std::vector<long long>& J, std::vector<S>& out) const = 0;
};

}  // namespace tfeti
