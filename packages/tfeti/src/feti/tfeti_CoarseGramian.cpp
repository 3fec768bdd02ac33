#include "tfeti_CoarseGramian.hpp"

#include <Tpetra_RowMatrixTransposer.hpp>

#include <algorithm>
#include <unordered_map>

#include "tfeti_Gather.hpp"

namespace tfeti {

namespace {

// The subdomain whose coarse ids hold `id`.
int subdomainOf(const std::vector<GO>& offset, GO id) {
  return static_cast<int>(std::upper_bound(offset.begin(), offset.end(), id) - offset.begin()) - 1;
}

// Dense blocks (s, t), s <= t, of G G^T: block (s, t) is dim(s) x dim(t), row-major, at
// values[start[key]], key = s * N + t.
class BlockSums {
 public:
  BlockSums(const std::vector<GO>& offset) : offset_(offset), N_(offset.size() - 1) {}
  double* block(int s, int t) {
    const long long key = static_cast<long long>(s) * N_ + t;
    auto [it, added] = start_.try_emplace(key, values_.size());
    if (added) {
      keys_.push_back(key);
      values_.resize(values_.size() + dim(s) * dim(t), 0.0);
    }
    return values_.data() + it->second;
  }
  int dim(int s) const { return static_cast<int>(offset_[s + 1] - offset_[s]); }
  const std::vector<long long>& keys() const { return keys_; }
  const std::vector<double>& values() const { return values_; }
  long long N() const { return N_; }

 private:
  const std::vector<GO>& offset_;
  long long N_;
  std::unordered_map<long long, std::size_t> start_;
  std::vector<long long> keys_;
  std::vector<double> values_;
};

struct Term {
  int s, k;
  double v;
};

// Adds g_s(r) g_t(r)^T for every pair s <= t of subdomains in one column r of G (terms sorted
// by subdomain, then mode).
void addOuterProducts(const std::vector<Term>& terms, BlockSums& sums) {
  for (std::size_t a = 0; a < terms.size();) {
    std::size_t aEnd = a;
    while (aEnd < terms.size() && terms[aEnd].s == terms[a].s) ++aEnd;
    for (std::size_t b = a; b < terms.size();) {
      std::size_t bEnd = b;
      while (bEnd < terms.size() && terms[bEnd].s == terms[b].s) ++bEnd;
      double* blk = sums.block(terms[a].s, terms[b].s);
      const int cols = sums.dim(terms[b].s);
      for (std::size_t i = a; i < aEnd; ++i)
        for (std::size_t j = b; j < bEnd; ++j)
          blk[terms[i].k * cols + terms[j].k] += terms[i].v * terms[j].v;
      b = bEnd;
    }
    a = aEnd;
  }
}

}  // namespace

std::vector<GO> coarseBlockOffsets(const Comm& comm, const std::vector<GO>& firstIds,
                                   GO dimension) {
  std::vector<long long> all =
      allGather(comm, std::vector<long long>(firstIds.begin(), firstIds.end()));
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  // A subdomain without coarse ids shares its first id with the next one, or is the dimension.
  while (!all.empty() && all.back() >= dimension) all.pop_back();
  all.push_back(dimension);
  return std::vector<GO>(all.begin(), all.end());
}

CsrMatrix assembleGramian(const CrsMatrix& G, const std::vector<GO>& offset) {
  // G^T distributed by the multiplier map: every column of G whole on one rank.
  Tpetra::RowMatrixTransposer<Scalar, LO, GO, Node> transposer(Teuchos::rcpFromRef(G));
  return assembleGramianFromTranspose(*transposer.createTranspose(), offset);
}

CsrMatrix assembleGramianFromTranspose(const CrsMatrix& transposed, const std::vector<GO>& offset,
                                       const double* rowMask) {
  const int N = static_cast<int>(offset.size()) - 1;
  const int nc = static_cast<int>(offset[N]);
  const CrsMatrix* Gt = &transposed;
  const auto& colMap = *Gt->getColMap();
  std::vector<Term> of(colMap.getNodeNumElements());
  for (std::size_t l = 0; l < of.size(); ++l) {
    const GO id = colMap.getGlobalElement(static_cast<LO>(l));
    const int s = subdomainOf(offset, id);
    of[l] = {s, static_cast<int>(id - offset[s]), 0.0};
  }
  BlockSums local(offset);
  std::vector<Term> terms;
  for (std::size_t r = 0; r < Gt->getNodeNumRows(); ++r) {
    if (rowMask != nullptr && rowMask[r] == 0.0) continue;
    const double m = rowMask != nullptr ? rowMask[r] : 1.0;
    Teuchos::ArrayView<const LO> cols;
    Teuchos::ArrayView<const double> v;
    Gt->getLocalRowView(static_cast<LO>(r), cols, v);
    terms.clear();
    for (LO j = 0; j < cols.size(); ++j)
      if (v[j] != 0.0) terms.push_back({of[cols[j]].s, of[cols[j]].k, m * v[j]});
    std::sort(terms.begin(), terms.end(),
              [](const Term& a, const Term& b) { return a.s != b.s ? a.s < b.s : a.k < b.k; });
    addOuterProducts(terms, local);
  }

  // Every rank's blocks on every rank, summed (a pair's rows may be owned by several ranks).
  const auto comm = Gt->getRowMap()->getComm();
  const std::vector<long long> keys = allGather(*comm, local.keys());
  const std::vector<double> values = allGather(*comm, local.values());
  BlockSums all(offset);
  std::size_t at = 0;
  for (long long key : keys) {
    const int s = static_cast<int>(key / N), t = static_cast<int>(key % N);
    double* blk = all.block(s, t);
    const int size = all.dim(s) * all.dim(t);
    for (int i = 0; i < size; ++i) blk[i] += values[at + i];
    at += size;
  }
  // Every subdomain with a coarse block has its diagonal block (zero when no row touches it:
  // the factorization then reports G G^T singular).
  for (int s = 0; s < N; ++s)
    if (all.dim(s) > 0) all.block(s, s);

  // The full symmetric CSR: row block s lists its neighbours t in increasing order.
  struct Neighbour {
    int t;
    const double* blk;
    bool transposed;  // the stored block is (t, s)
  };
  std::vector<std::vector<Neighbour>> adj(N);
  std::size_t nnz = 0;
  {
    std::vector<std::size_t> start;
    start.reserve(all.keys().size());
    std::size_t pos = 0;
    for (long long key : all.keys()) {
      start.push_back(pos);
      pos += static_cast<std::size_t>(all.dim(static_cast<int>(key / N)) *
                                      all.dim(static_cast<int>(key % N)));
    }
    for (std::size_t b = 0; b < all.keys().size(); ++b) {
      const int s = static_cast<int>(all.keys()[b] / N), t = static_cast<int>(all.keys()[b] % N);
      const double* blk = all.values().data() + start[b];
      adj[s].push_back({t, blk, false});
      nnz += static_cast<std::size_t>(all.dim(s) * all.dim(t));
      if (t != s) {
        adj[t].push_back({s, blk, true});
        nnz += static_cast<std::size_t>(all.dim(s) * all.dim(t));
      }
    }
  }
  CsrMatrix A;
  A.rows = A.cols = nc;
  A.rowPtr.assign(nc + 1, 0);
  A.colInd.reserve(nnz);
  A.values.reserve(nnz);
  for (int s = 0; s < N; ++s) {
    auto& nb = adj[s];
    std::sort(nb.begin(), nb.end(),
              [](const Neighbour& a, const Neighbour& b) { return a.t < b.t; });
    const int ds = all.dim(s);
    for (int ka = 0; ka < ds; ++ka) {
      for (const auto& n : nb) {
        const int dt = all.dim(n.t);
        for (int kb = 0; kb < dt; ++kb) {
          A.colInd.push_back(static_cast<int>(offset[n.t]) + kb);
          A.values.push_back(n.transposed ? n.blk[kb * ds + ka] : n.blk[ka * dt + kb]);
        }
      }
      const int row = static_cast<int>(offset[s]) + ka;
      A.rowPtr[row + 1] = static_cast<int>(A.colInd.size());
    }
  }
  return A;
}

}  // namespace tfeti
