#pragma once
// The coarse matrix G G^T of (T)FETI, assembled block by block.
//
// Row i of G belongs to one subdomain (its i-th rigid body mode), so G G^T is made of dense
// blocks, one per pair of subdomains that share a constraint row:
//   (G G^T)_{st} = sum over rows r touching s and t of g_s(r) g_t(r)^T,
// g_s(r) the kernel-dim vector of G's entries of subdomain s in column r. Each rank sums the
// outer products of the columns of G it owns (the rows of G^T on the multiplier map), and the
// blocks are gathered to every rank, which factorizes the replicated matrix. This replaces a
// sparse matrix-matrix product whose result was then taken apart entry by entry: at thousands
// of subdomains the coarse phase was the largest of the 3D setup (docs/benchmarks.md).
#include <vector>

#include "tfeti_CsrMatrix.hpp"
#include "tfeti_Types.hpp"

namespace tfeti {

// The coarse blocks of all ranks' subdomains, as offsets: block b holds the coarse ids
// [offset[b], offset[b + 1]), the last entry is the coarse dimension. firstIds: the first coarse
// id of every local subdomain; subdomains without a coarse id (FETI's non-floating ones) leave
// no block. The same vector on every rank (collective).
std::vector<GO> coarseBlockOffsets(const Comm& comm, const std::vector<GO>& firstIds, GO dimension);

// G G^T on every rank (full symmetric pattern, columns sorted). offset: the coarse blocks (a
// subdomain's ids, consecutive), the same on every rank; G's row map holds the coarse ids of the
// local subdomains, its domain map is the multiplier map.
CsrMatrix assembleGramian(const CrsMatrix& G, const std::vector<GO>& offset);
// The same from G^T distributed by the multiplier map (Tpetra::RowMatrixTransposer's, built once
// and kept by CoarseSpace), with the columns of G weighted by rowMask: G diag(m) G^T, m the local
// values of a vector on G^T's row map (nullptr: all ones).
CsrMatrix assembleGramianFromTranspose(const CrsMatrix& Gt, const std::vector<GO>& offset,
                                       const double* rowMask = nullptr);

}  // namespace tfeti
