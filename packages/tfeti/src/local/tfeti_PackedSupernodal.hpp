#pragma once
// A CHOLMOD supernodal factor's values repacked, in place, into the order in which one
// right-hand side's forward and backward solves read them.
//
// Why: every Hessian multiplication of a FETI solve streams each subdomain's factor once
// forward and once backward, and the forward pass comes from memory (the factors of a rank do
// not fit in any cache; the backward pass that follows finds the same factor still in the
// last-level cache). CHOLMOD keeps a supernode as a dense column-major block with its upper
// triangle as padding, and solves one vector by BLAS-2 calls per supernode that walk four or
// more columns at once: on 8^3-element Hex8 subdomains its forward pass drew 11 GB/s, half of
// what one core streams. Packed, a supernode is a sequence of panels of kPanel columns, each
// stored row by row (the small triangle first, then every row below it with its kPanel values
// side by side), so a solve reads the factor as one sequential stream and skips the padding (20 %
// of the values on those subdomains). docs/benchmarks.md, "Packed supernodal solves".
//
// Packing keeps CHOLMOD's own arrays: the values are rearranged inside L->x (the packed form is
// never longer), the symbolic structure is untouched, and unpackSupernodal restores the layout
// CHOLMOD's own routines read (its multi-vector solve). A numerical factorization overwrites the
// values whatever their layout.
#include <cholmod.h>

#include <cstddef>
#include <vector>

namespace tfeti {

// The panels' width: four columns per panel row keep four independent products per row in
// flight, which is what one core needs to keep up with its memory stream.
constexpr int kPanel = 4;

// Where each supernode's packed values start in L->x (nsuper + 1 offsets; the last is the packed
// length) and the largest supernode's row count (the solves' workspace). Depends only on the
// symbolic structure: one layout serves every factor of an analysis.
struct PackedLayout {
  std::vector<std::size_t> offsets;
  int maxRows = 0;
};
PackedLayout packedLayout(const cholmod_factor& L);

// CHOLMOD's column-major supernodes to the packed order and back, in place. scratch holds one
// supernode at a time.
void packSupernodal(cholmod_factor& L, const PackedLayout& layout, std::vector<double>& scratch);
void unpackSupernodal(cholmod_factor& L, const PackedLayout& layout, std::vector<double>& scratch);

// y := L^{-1} y and y := L^{-T} y on the permuted right-hand side (CHOLMOD's L, whose
// permutation the caller applies); w is a workspace of layout.maxRows values.
void packedForwardSolve(const cholmod_factor& L, const PackedLayout& layout, double* y, double* w);
void packedBackwardSolve(const cholmod_factor& L, const PackedLayout& layout, double* y, double* w);

}  // namespace tfeti
