// Counting allocators for HeapTally: every block carries its size in a header ahead of it (16
// bytes, so the caller's alignment stays that of malloc). Linked only into the test executables
// that measure allocations.
#include "tfeti_HeapTally.hpp"

#include <SuiteSparse_config.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <new>

namespace {

constexpr std::size_t kHeader = 16;
std::atomic<std::size_t> inUse{0}, peak{0};

void count(std::size_t bytes) {
  const std::size_t now = inUse.fetch_add(bytes) + bytes;
  std::size_t seen = peak.load();
  while (now > seen && !peak.compare_exchange_weak(seen, now)) {
  }
}

void* allocate(std::size_t bytes) {
  auto* p = static_cast<unsigned char*>(std::malloc(bytes + kHeader));
  if (!p) return nullptr;
  std::memcpy(p, &bytes, sizeof bytes);
  count(bytes);
  return p + kHeader;
}

std::size_t sizeOf(void* user) {
  std::size_t bytes;
  std::memcpy(&bytes, static_cast<unsigned char*>(user) - kHeader, sizeof bytes);
  return bytes;
}

void release(void* user) {
  if (!user) return;
  inUse.fetch_sub(sizeOf(user));
  std::free(static_cast<unsigned char*>(user) - kHeader);
}

void* allocateZeroed(std::size_t n, std::size_t size) {
  void* p = allocate(n * size);
  if (p) std::memset(p, 0, n * size);
  return p;
}

void* reallocate(void* user, std::size_t bytes) {
  if (!user) return allocate(bytes);
  void* p = allocate(bytes);
  if (!p) return nullptr;  // the old block stays, as realloc leaves it
  std::memcpy(p, user, std::min(bytes, sizeOf(user)));
  release(user);
  return p;
}

// Before main, before CHOLMOD allocates anything: every block it frees was then counted.
struct PointSuiteSparseHere {
  PointSuiteSparseHere() {
    SuiteSparse_config.malloc_func = allocate;
    SuiteSparse_config.calloc_func = allocateZeroed;
    SuiteSparse_config.realloc_func = reallocate;
    SuiteSparse_config.free_func = release;
  }
} pointSuiteSparseHere;

void* newOrThrow(std::size_t bytes) {
  if (void* p = allocate(bytes == 0 ? 1 : bytes)) return p;
  throw std::bad_alloc();
}

}  // namespace

namespace tfeti_test {
std::size_t HeapTally::inUse() {
  return ::inUse.load();
}
std::size_t HeapTally::peak() {
  return ::peak.load();
}
void HeapTally::reset() {
  ::peak.store(::inUse.load());
}
}  // namespace tfeti_test

void* operator new(std::size_t bytes) {
  return newOrThrow(bytes);
}
void* operator new[](std::size_t bytes) {
  return newOrThrow(bytes);
}
void* operator new(std::size_t bytes, const std::nothrow_t&) noexcept {
  return allocate(bytes == 0 ? 1 : bytes);
}
void* operator new[](std::size_t bytes, const std::nothrow_t&) noexcept {
  return allocate(bytes == 0 ? 1 : bytes);
}
void operator delete(void* p) noexcept {
  release(p);
}
void operator delete[](void* p) noexcept {
  release(p);
}
void operator delete(void* p, std::size_t) noexcept {
  release(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  release(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  release(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  release(p);
}
