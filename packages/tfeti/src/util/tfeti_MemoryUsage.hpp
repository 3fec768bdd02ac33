#pragma once
// Where the memory of a run goes: the resident set size of the process after each phase of a
// solve, and the peak reached so far, the largest and the sum over the ranks. Phases that free
// what they built leave the peak higher than the resident size after them; the peak after a
// phase minus the one before is what the phase added to the run's high-water mark.
//
// Read from /proc/self/status (VmRSS, VmHWM) where it exists; elsewhere the peak comes from
// getrusage and the resident size is reported as the peak.
#include <string>
#include <vector>

#include "tfeti_Types.hpp"

namespace tfeti {

struct MemorySample {
  double rssMib = 0.0;   // resident now
  double peakMib = 0.0;  // high-water mark since the process started
};

// This process, now.
MemorySample sampleMemory();

struct PhaseMemory {
  std::string phase;
  MemorySample maxOverRanks, sumOverRanks;
};

class MemoryLog {
 public:
  // Collective: samples every rank after `phase`. A phase recorded again (update() of a
  // nonlinear solve) keeps its place in the order and takes the new sample.
  void record(const Comm& comm, const std::string& phase);
  // Appends another log's phases (e.g. the solver's after the driver's own).
  void append(const MemoryLog& other);
  const std::vector<PhaseMemory>& phases() const { return phases_; }

 private:
  void put(PhaseMemory p);
  std::vector<PhaseMemory> phases_;
};

}  // namespace tfeti
