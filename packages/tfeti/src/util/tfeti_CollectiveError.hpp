#pragma once
// Errors found on some ranks raised on every rank. A rank that throws alone leaves the others
// waiting in the next collective call (and mpirun hanging): every input check that one rank can
// fail alone ends in throwIfAnyRankFailed, which all ranks reach.
#include <stdexcept>
#include <string>

#include "tfeti_Types.hpp"

namespace tfeti {

// The same error on every rank of the communicator.
class CollectiveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Collective. When localError is non-empty on some rank, every rank throws CollectiveError with
// the message of the lowest such rank (followed by how many other ranks failed).
void throwIfAnyRankFailed(const Comm& comm, const std::string& localError);

// Collective. Runs `work`, which must not communicate; an exception on any rank is rethrown on
// every rank as CollectiveError.
template <class Work>
void collectively(const Comm& comm, Work&& work) {
  std::string error;
  try {
    work();
  } catch (const std::exception& e) {
    error = e.what();
    if (error.empty()) error = "unnamed error";
  }
  throwIfAnyRankFailed(comm, error);
}

}  // namespace tfeti
