#pragma once
// Internal to FetiSolver's sources: the timer of its phases (FetiTimings).
#include <chrono>
#include <exception>

#include "tfeti_MemoryUsage.hpp"
#include "tfeti_Types.hpp"

namespace tfeti {

// Wall time of a phase, measured between barriers so that it is the slowest rank's time, and,
// with a log, the memory after it.
class PhaseTimer {
 public:
  PhaseTimer(const Comm& comm, double& into, MemoryLog* log = nullptr, const char* phase = "")
      : comm_(comm), into_(into), log_(log), phase_(phase) {
    comm_.barrier();
    start_ = std::chrono::steady_clock::now();
  }
  ~PhaseTimer() {
    comm_.barrier();
    into_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    // Unwinding (an error thrown on every rank): no report of a phase that did not finish.
    if (log_ && std::uncaught_exceptions() == 0) log_->record(comm_, phase_);
  }

 private:
  const Comm& comm_;
  double& into_;
  MemoryLog* log_;
  const char* phase_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace tfeti
