#pragma once
// Two 64-bit digests of a sequence of byte arrays (sizes and contents), for telling whether data
// changed without holding a copy of it: CsrMatrix::digest (a subdomain's K against the factorized
// one), plasticity's ElementMesh::checkedDigest (a mesh against the checked one). Equal sequences
// give equal digests; unequal ones collide with a probability of about 2^-128.
#include <array>
#include <cstddef>
#include <cstdint>

namespace tfeti {

class Digest {
 public:
  // header: sizes or kinds that distinguish sequences before any array is added.
  explicit Digest(std::uint64_t header);
  // Chains the bytes of one array into both digests (in the manner of xxHash64: four lanes over
  // 32-byte stripes, so a subdomain's K takes about a millisecond).
  void add(const void* data, std::size_t bytes);
  std::array<std::uint64_t, 2> value() const { return d_; }

 private:
  std::array<std::uint64_t, 2> d_;
  std::uint64_t arrays_ = 0;  // arrays added: each is hashed with its own seeds
};

}  // namespace tfeti
