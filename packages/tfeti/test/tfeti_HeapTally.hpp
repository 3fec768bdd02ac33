#pragma once
// The bytes this process holds on the heap, counted at every allocation: C++'s (operator new and
// delete, replaced in tfeti_HeapTally.cpp) and SuiteSparse's (CHOLMOD allocates through
// SuiteSparse_config's functions, which it points at counting ones before main), with the peak
// of their sum. A test linking it compares a memory prediction with what the call it predicts
// allocated, to the byte: the call's peak beyond the bytes in use before it.
#include <cstddef>

namespace tfeti_test {

struct HeapTally {
  // The bytes allocated and not yet freed.
  static std::size_t inUse();
  // The largest inUse() since the last reset; reset() restarts it from now.
  static std::size_t peak();
  static void reset();
};

}  // namespace tfeti_test
