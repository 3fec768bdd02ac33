#include "tfeti_MemoryUsage.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <sys/resource.h>

#include <fstream>
#include <sstream>

namespace tfeti {

MemorySample sampleMemory() {
  MemorySample s;
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    std::istringstream in(line);
    std::string key;
    double kib = 0.0;
    in >> key >> kib;
    if (key == "VmRSS:") s.rssMib = kib / 1024.0;
    if (key == "VmHWM:") s.peakMib = kib / 1024.0;
  }
  if (s.peakMib == 0.0) {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    s.peakMib = usage.ru_maxrss / 1024.0;  // KiB on Linux
  }
  if (s.rssMib == 0.0) s.rssMib = s.peakMib;
  return s;
}

void MemoryLog::record(const Comm& comm, const std::string& phase) {
  const MemorySample mine = sampleMemory();
  const double local[2] = {mine.rssMib, mine.peakMib};
  double mx[2] = {0.0, 0.0}, sum[2] = {0.0, 0.0};
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 2, local, mx);
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 2, local, sum);
  put({phase, {mx[0], mx[1]}, {sum[0], sum[1]}});
}

void MemoryLog::append(const MemoryLog& other) {
  for (const auto& p : other.phases_) put(p);
}

void MemoryLog::put(PhaseMemory p) {
  for (auto& q : phases_)
    if (q.phase == p.phase) {
      q = std::move(p);
      return;
    }
  phases_.push_back(std::move(p));
}

}  // namespace tfeti
