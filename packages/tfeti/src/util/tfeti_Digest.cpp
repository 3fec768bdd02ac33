#include "tfeti_Digest.hpp"

#include <cstring>

namespace tfeti {
namespace {
constexpr std::uint64_t kPrime1 = 0x9e3779b185ebca87ULL, kPrime2 = 0xc2b2ae3d27d4eb4fULL,
                        kPrime3 = 0x165667b19e3779f9ULL;
// The seeds of the two digests.
constexpr std::uint64_t kSeeds[2] = {0x243f6a8885a308d3ULL, 0x13198a2e03707344ULL};

std::uint64_t rotl(std::uint64_t x, int r) {
  return (x << r) | (x >> (64 - r));
}

// SplitMix64's finalizer: every input bit moves every output bit.
std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Two 64-bit digests (seeds s0, s1) of `bytes` bytes in one pass, each in the manner of
// xxHash64: four independent lanes over 32-byte stripes (so the multiplications pipeline), the
// tail byte by byte, then a finalizer.
std::array<std::uint64_t, 2> digestBytes(const void* data, std::size_t bytes, std::uint64_t s0,
                                         std::uint64_t s1) {
  const auto* p = static_cast<const unsigned char*>(data);
  const std::uint64_t seed[2] = {s0, s1};
  std::uint64_t lane[2][4];
  for (int k = 0; k < 2; ++k) {
    lane[k][0] = seed[k] + kPrime1 + kPrime2;
    lane[k][1] = seed[k] + kPrime2;
    lane[k][2] = seed[k];
    lane[k][3] = seed[k] - kPrime1;
  }
  const auto round = [](std::uint64_t acc, std::uint64_t w) {
    return rotl(acc + w * kPrime2, 31) * kPrime1;
  };
  std::size_t at = 0;
  for (; at + 32 <= bytes; at += 32)
    for (int l = 0; l < 4; ++l) {
      std::uint64_t w;
      std::memcpy(&w, p + at + 8 * l, 8);
      lane[0][l] = round(lane[0][l], w);
      lane[1][l] = round(lane[1][l], w);
    }
  std::array<std::uint64_t, 2> d{};
  for (int k = 0; k < 2; ++k) {
    const std::uint64_t* v = lane[k];
    std::uint64_t h = rotl(v[0], 1) + rotl(v[1], 7) + rotl(v[2], 12) + rotl(v[3], 18);
    for (int l = 0; l < 4; ++l) h = (h ^ round(0, v[l])) * kPrime1 + kPrime3;
    for (std::size_t t = at; t < bytes; ++t) h = rotl(h ^ (p[t] * kPrime3), 11) * kPrime1;
    d[k] = mix64(h ^ bytes);
  }
  return d;
}
}  // namespace

Digest::Digest(std::uint64_t header) {
  for (int k = 0; k < 2; ++k) d_[k] = mix64(kSeeds[k] ^ header);
}

void Digest::add(const void* data, std::size_t bytes) {
  // Each array with its own seeds, so that moving bytes from one array to the next changes it.
  const auto h = digestBytes(data, bytes, kSeeds[0] + arrays_, kSeeds[1] + arrays_);
  for (int k = 0; k < 2; ++k) d_[k] = mix64(d_[k] ^ h[k]);
  ++arrays_;
}

}  // namespace tfeti
