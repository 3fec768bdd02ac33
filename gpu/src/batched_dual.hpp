#pragma once
// The batched apply of the explicit local dual operators, y_s = F_s x_s for every subdomain s,
// without Trilinos, MPI or CHOLMOD: the blocks (synthetic or read from the main code's export),
// the CPU reference and the byte count. Shared by the CPU-only check and the CUDA one.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "batched_dual_tiles.hpp"
#include "check_options.hpp"

namespace gpucheck {

// All blocks, column-major and full, one after the other: block s has rows[s] rows and starts at
// offset[s] (values) and vecOffset[s] (its part of the stacked dual vector).
struct Blocks {
  std::vector<int> rows;
  std::vector<std::int64_t> offset, vecOffset;
  std::vector<double> values;
  std::int64_t vecSize = 0;
  int maxRows = 0;
  bool uniform() const {
    return std::all_of(rows.begin(), rows.end(), [&](int m) { return m == rows.front(); });
  }
  void add(int m) {
    rows.push_back(m);
    offset.push_back(static_cast<std::int64_t>(values.size()));
    vecOffset.push_back(vecSize);
    values.resize(values.size() + static_cast<std::size_t>(m) * m);
    vecSize += m;
    maxRows = std::max(maxRows, m);
  }
};

// A reproducible value in [-1, 1) from three integers (splitmix64).
inline double hashValue(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  std::uint64_t z = a * 0x9E3779B97F4A7C15ull ^
                    (b + 0x632BE59BD9B4E019ull) * 0xBF58476D1CE4E5B9ull ^
                    (c + 0x85EBCA77C2B2AE63ull) * 0x94D049BB133111EBull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

// The rows of synthetic block s of `count`: m each, or with `varying` spread over [m/2, m] (as
// the subdomains of a real tearing differ: corners, contact and Dirichlet rows) with a block of
// one row and one of m - 1 among them, so that the offsets, the sizes that are no multiple of a
// warp or of a tile, and the kernels' per-block bounds are all exercised in one batch.
inline int syntheticRows(int s, int count, int m, bool varying) {
  if (!varying || m < 2) return m;
  if (count >= 3 && s == 1) return 1;
  if (count >= 3 && s == count - 1) return m - 1;
  const int low = m / 2;
  return low + static_cast<int>((static_cast<std::uint64_t>(s) * 7919u) %
                                static_cast<std::uint64_t>(m - low + 1));
}

// count blocks: symmetric, entries in [-1, 1), diagonal m_s + 1 (diagonally dominant, so
// symmetric positive definite, like a local dual operator). Filled on every core of the host:
// the default shape's 5.5 GB took about 15 s on one, time a device session pays for.
inline Blocks synthetic(int count, int rows, bool varying) {
  Blocks b;
  for (int s = 0; s < count; ++s) b.add(syntheticRows(s, count, rows, varying));
  const auto fill = [&b](int s) {
    const int m = b.rows[s];
    double* a = b.values.data() + b.offset[s];
    for (int j = 0; j < m; ++j)
      for (int i = 0; i <= j; ++i)
        a[i + static_cast<std::size_t>(j) * m] = a[j + static_cast<std::size_t>(i) * m] =
            i == j ? m + 1.0 : hashValue(s, i, j);
  };
  const int threads = std::max(1u, std::min(std::thread::hardware_concurrency(), 64u));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (int s = t; s < count; s += threads) fill(s);
    });
  for (auto& th : pool) th.join();
  return b;
}

// The main code's export (FETI "Explicit export file", one file per rank): "TFETIF01", int64
// block count, then per block int64 m and m*m doubles (full, column-major).
inline void readExport(const std::string& file, Blocks& b) {
  std::ifstream in(file, std::ios::binary);
  char magic[8];
  std::int64_t count = 0;
  if (!in.read(magic, 8) || std::string(magic, 8) != "TFETIF01" ||
      !in.read(reinterpret_cast<char*>(&count), sizeof(count)))
    throw std::runtime_error(file + ": not a TFETIF01 file of explicit dual blocks");
  for (std::int64_t s = 0; s < count; ++s) {
    std::int64_t m = 0;
    if (!in.read(reinterpret_cast<char*>(&m), sizeof(m)) || m < 0 || m > (1 << 20))
      throw std::runtime_error(file + ": block " + std::to_string(s) + " has no valid size");
    b.add(static_cast<int>(m));
    if (!in.read(reinterpret_cast<char*>(b.values.data() + b.offset.back()),
                 static_cast<std::streamsize>(m * m * sizeof(double))))
      throw std::runtime_error(file + ": block " + std::to_string(s) + " is cut short");
  }
}

inline std::vector<double> vectorFor(const Blocks& b) {
  std::vector<double> x(static_cast<std::size_t>(b.vecSize));
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = hashValue(7, k, 11);
  return x;
}

// y_s = F_s x_s for the blocks [first, last), in long double: the reference.
inline void referenceRange(const Blocks& b, const std::vector<double>& x, std::vector<double>& y,
                           int first, int last) {
  for (int s = first; s < last; ++s) {
    const int m = b.rows[s];
    const double* a = b.values.data() + b.offset[s];
    const double* xs = x.data() + b.vecOffset[s];
    double* ys = y.data() + b.vecOffset[s];
    std::vector<long double> acc(m, 0.0L);
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        acc[i] += static_cast<long double>(a[i + static_cast<std::size_t>(j) * m]) * xs[j];
    for (int i = 0; i < m; ++i) ys[i] = static_cast<double>(acc[i]);
  }
}

// The reference on every core of the host.
inline std::vector<double> reference(const Blocks& b, const std::vector<double>& x) {
  std::vector<double> y(x.size());
  const int n = static_cast<int>(b.rows.size());
  const int threads = std::max(1u, std::min(std::thread::hardware_concurrency(), 64u));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] { referenceRange(b, x, y, n * t / threads, n * (t + 1) / threads); });
  for (auto& th : pool) th.join();
  return y;
}

// A plain double-precision batched apply on the host (column-oriented, as BLAS dgemv 'N'), on
// `threads` threads: the CPU figure to compare the device with.
template <class T>
void hostApply(const Blocks& b, const std::vector<T>& values, const std::vector<T>& x,
               std::vector<T>& y, int threads) {
  const int n = static_cast<int>(b.rows.size());
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (int s = n * t / threads; s < n * (t + 1) / threads; ++s) {
        const int m = b.rows[s];
        const T* a = values.data() + b.offset[s];
        const T* xs = x.data() + b.vecOffset[s];
        T* ys = y.data() + b.vecOffset[s];
        std::fill(ys, ys + m, T(0));
        for (int j = 0; j < m; ++j) {
          const T xj = xs[j];
          const T* col = a + static_cast<std::size_t>(j) * m;
          for (int i = 0; i < m; ++i) ys[i] += col[i] * xj;
        }
      }
    });
  for (auto& th : pool) th.join();
}

// max |y - ref| / max |ref|.
template <class T>
double relativeError(const std::vector<T>& y, const std::vector<double>& ref) {
  double d = 0.0, s = 0.0;
  for (std::size_t k = 0; k < ref.size(); ++k) {
    const double diff = std::abs(static_cast<double>(y[k]) - ref[k]);
    if (std::isnan(diff)) return std::numeric_limits<double>::infinity();
    d = std::max(d, diff);
    s = std::max(s, std::abs(ref[k]));
  }
  return s > 0.0 ? d / s : d;
}

// Bytes one apply streams: every block once, x read and y written once.
inline double bytesMoved(const Blocks& b, std::size_t scalar) {
  return static_cast<double>(b.values.size() + 2 * b.vecSize) * static_cast<double>(scalar);
}

// Mean seconds of f() over `repeats` calls after one warm-up call.
template <class F>
double timeIt(F&& f, int repeats) {
  f();
  const auto t0 = std::chrono::steady_clock::now();
  for (int r = 0; r < repeats; ++r) f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / repeats;
}

struct Options {
  int blocks = 512, rows = 1158, repeats = 20, hostThreads = 0;
  bool requireDevice = false;      // the device check: no device is an error, not a skip
  bool varying = false;            // synthetic blocks of different sizes (syntheticRows)
  std::vector<std::string> files;  // exported blocks instead of synthetic ones
};

inline Options parse(int argc, char** argv) {
  Options o;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (intOption(a, "--blocks", 1, o.blocks) || intOption(a, "--rows", 1, o.rows) ||
        intOption(a, "--repeats", 1, o.repeats) || intOption(a, "--host-threads", 0, o.hostThreads))
      continue;
    if (a.rfind("--file=", 0) == 0 && a.size() > 7)
      o.files.push_back(a.substr(7));
    else if (a == "--require-device")
      o.requireDevice = true;
    else if (a == "--sizes=varying" || a == "--sizes=uniform")
      o.varying = a == "--sizes=varying";
    else
      throw std::invalid_argument("unknown option " + a +
                                  " (--blocks=N --rows=M --sizes=uniform|varying --repeats=R "
                                  "--host-threads=T --file=EXPORT.bin ... --require-device)");
  }
  if (o.varying && !o.files.empty())
    throw std::invalid_argument("--sizes=varying is for synthetic blocks, not with --file");
  if (o.hostThreads == 0) o.hostThreads = std::max(1u, std::thread::hardware_concurrency());
  return o;
}

inline Blocks load(const Options& o) {
  if (o.files.empty()) return synthetic(o.blocks, o.rows, o.varying);
  Blocks b;
  for (const auto& f : o.files) readExport(f, b);
  return b;
}

inline void describe(const Blocks& b) {
  std::printf("blocks: %zu, rows %d..%d (%s), %.1f MiB fp64 full storage, dual vector %lld\n",
              b.rows.size(), *std::min_element(b.rows.begin(), b.rows.end()), b.maxRows,
              b.uniform() ? "uniform" : "varying", b.values.size() * 8.0 / 1048576.0,
              static_cast<long long>(b.vecSize));
}

// The host's own batched apply (fp64 and fp32) against the reference; returns false on a
// reference mismatch. Printed as the CPU line of the check.
inline bool hostCheck(const Blocks& b, const std::vector<double>& x, const std::vector<double>& ref,
                      const Options& o) {
  std::vector<double> y(x.size());
  const double t64 = timeIt([&] { hostApply(b, b.values, x, y, o.hostThreads); }, o.repeats);
  const double e64 = relativeError(y, ref);
  std::vector<float> v32(b.values.begin(), b.values.end()), x32(x.begin(), x.end()), y32(x.size());
  const double t32 = timeIt([&] { hostApply(b, v32, x32, y32, o.hostThreads); }, o.repeats);
  const double e32 = relativeError(y32, ref);
  std::printf("host  fp64: %9.3f ms, %7.1f GB/s, error %.2e (limit 1e-12)\n", 1e3 * t64,
              bytesMoved(b, 8) / t64 / 1e9, e64);
  std::printf("host  fp32: %9.3f ms, %7.1f GB/s, error %.2e (limit 1e-5)\n", 1e3 * t32,
              bytesMoved(b, 4) / t32 / 1e9, e32);
  // The symmetric tiles (the device's tiles kernel: layout, packing and order) on the host.
  std::vector<std::int64_t> tileOffset;
  const std::vector<double> tiles =
      batched_dual::packAllTiles<double>(b.rows, b.values, tileOffset);
  for (std::size_t s = 0; s < b.rows.size(); ++s)
    batched_dual::tilesApply(tiles.data() + tileOffset[s], b.rows[s], x.data() + b.vecOffset[s],
                             y.data() + b.vecOffset[s]);
  const double eTiles = relativeError(y, ref);
  std::printf(
      "host  fp64 symmetric tiles: %.1f MiB against %.1f MiB full, error %.2e (limit "
      "1e-12)\n",
      tiles.size() * 8.0 / 1048576.0, b.values.size() * 8.0 / 1048576.0, eTiles);
  return e64 <= 1e-12 && e32 <= 1e-5 && eTiles <= 1e-12;
}

}  // namespace gpucheck
