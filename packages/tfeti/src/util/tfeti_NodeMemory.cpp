#include "tfeti_NodeMemory.hpp"

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "tfeti_CollectiveError.hpp"
#include "tfeti_Gather.hpp"

namespace tfeti {

double availableBytesIn(const std::string& meminfoFile) {
  std::ifstream in(meminfoFile);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string key, unit;
    double value = -1.0;
    if (fields >> key >> value >> unit && key == "MemAvailable:" && unit == "kB" && value >= 0)
      return value * 1024.0;
  }
  return -1.0;
}

namespace {
std::function<double()>& availableBytesSource() {
  static std::function<double()> source;
  return source;
}
}  // namespace

void setAvailableBytesSource(std::function<double()> source) {
  availableBytesSource() = std::move(source);
}

double availableNodeBytes() {
  if (availableBytesSource()) return availableBytesSource()();
  const char* file = std::getenv("TFETI_MEMINFO");
  if (!file || !*file) return availableBytesIn("/proc/meminfo");
  const double bytes = availableBytesIn(file);
  if (bytes < 0)
    throw std::invalid_argument(std::string("TFETI_MEMINFO=") + file +
                                ": no \"MemAvailable: N kB\" line to read there");
  return bytes;
}

namespace {

// The node a rank runs on, as a 64-bit FNV-1a hash of its host name (gathered as a number).
long long hostKey() {
  char name[256] = {};
  if (gethostname(name, sizeof(name) - 1) != 0) return 0;
  std::uint64_t h = 14695981039346656037ull;
  for (const char* c = name; *c; ++c) {
    h ^= static_cast<unsigned char>(*c);
    h *= 1099511628211ull;
  }
  return static_cast<long long>(h);
}

}  // namespace

NodeMemory nodeMemory(const Comm& comm, double needBytes, double heldBytes) {
  double available = -1.0;
  std::string error;
  try {
    available = availableNodeBytes();
  } catch (const std::exception& e) {
    error = e.what();
  }
  throwIfAnyRankFailed(comm, error);
  const std::vector<long long> hosts = allGather(comm, std::vector<long long>{hostKey()});
  const std::vector<double> values =
      allGather(comm, std::vector<double>{needBytes, available, heldBytes});
  struct Node {
    int firstRank = 0, ranks = 0;
    double need = 0.0, held = 0.0, available = std::numeric_limits<double>::max();
  };
  std::map<long long, Node> nodes;
  NodeMemory result;
  result.known = true;
  for (std::size_t r = 0; r < hosts.size(); ++r) {
    auto inserted = nodes.emplace(hosts[r], Node{});
    Node& n = inserted.first->second;
    if (inserted.second) n.firstRank = static_cast<int>(r);
    ++n.ranks;
    n.need += values[3 * r];
    n.held += values[3 * r + 2];
    if (values[3 * r + 1] < 0) result.known = false;
    n.available = std::min(n.available, values[3 * r + 1]);
  }
  if (!result.known) return result;
  const Node* tightest = nullptr;
  for (const auto& kv : nodes)
    if (!tightest || kv.second.available - kv.second.need < tightest->available - tightest->need)
      tightest = &kv.second;
  result.firstRank = tightest->firstRank;
  result.ranks = tightest->ranks;
  result.needBytes = tightest->need;
  result.heldBytes = tightest->held;
  result.availableBytes = tightest->available;
  result.fits = tightest->need <= tightest->available;
  return result;
}

std::string bytesText(double bytes) {
  const double kib = 1024.0, mib = 1024.0 * kib, gib = 1024.0 * mib;
  std::ostringstream s;
  s << std::fixed;
  if (bytes < mib)
    s << std::setprecision(1) << bytes / kib << " KiB";
  else if (bytes < gib)
    s << std::setprecision(1) << bytes / mib << " MiB";
  else
    s << std::setprecision(2) << bytes / gib << " GiB";
  return s.str();
}

std::string describe(const NodeMemory& m) {
  return "the " + std::to_string(m.ranks) + (m.ranks == 1 ? " rank" : " ranks") +
         " on the node of rank " + std::to_string(m.firstRank) + " need " + bytesText(m.needBytes) +
         " and it has " + bytesText(m.availableBytes) + " available (MemAvailable)";
}

}  // namespace tfeti
