#include "contact_FrictionHistory.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <set>
#include <stdexcept>

namespace contact {

namespace {
constexpr const char* kFrictionHeader = "tfeti_contact friction restart 1";
}  // namespace

void addAccumulatedSlip(std::vector<ContactNode>& nodes,
                        const std::map<int, AccumulatedSlip>& committed) {
  for (ContactNode& n : nodes) {
    const auto it = committed.find(n.slaveNode);
    AccumulatedSlip a = it == committed.end() ? AccumulatedSlip() : it->second;
    if (n.frictionState == 1 || n.frictionState == 2) {
      a.path += std::abs(n.slip);
      a.net += n.slip;
    }
    n.accumulatedSlip = a.path;
    n.netSlip = a.net;
  }
}

void commitAccumulatedSlip(std::map<int, AccumulatedSlip>& committed,
                           const std::vector<ContactNode>& nodes) {
  for (const ContactNode& n : nodes) committed[n.slaveNode] = {n.accumulatedSlip, n.netSlip};
}

void writeFrictionRestart(const std::string& stepDir, const FrictionHistory& h) {
  const std::string path = stepDir + "/friction.txt";
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << std::setprecision(17) << kFrictionHeader << "\n";
  // One line per slave node that has either: node, slip bound (-1: none), path, net.
  std::set<int> nodes;
  for (const auto& [node, s] : h.slip) nodes.insert(node);
  for (const auto& [node, g] : h.bounds) nodes.insert(node);
  out << nodes.size() << "\n";
  for (int node : nodes) {
    const auto b = h.bounds.find(node);
    const auto s = h.slip.find(node);
    const AccumulatedSlip a = s == h.slip.end() ? AccumulatedSlip() : s->second;
    out << node << " " << (b == h.bounds.end() ? -1.0 : b->second) << " " << a.path << " " << a.net
        << "\n";
  }
  if (!out) throw std::runtime_error("cannot write " + path);
}

FrictionHistory readFrictionRestart(const std::string& stepDir) {
  const std::string path = stepDir + "/friction.txt";
  std::ifstream in(path);
  if (!in)
    throw std::runtime_error(path +
                             ": no friction state (the restart was written by a run without "
                             "friction; a frictional run continues only a frictional one)");
  std::string header;
  std::getline(in, header);
  if (header != kFrictionHeader)
    throw std::runtime_error(path + ": not a tfeti_contact friction restart file (header \"" +
                             header + "\")");
  FrictionHistory h;
  std::size_t n = 0;
  in >> n;
  for (std::size_t k = 0; k < n && in; ++k) {
    int node = -1;
    double g = 0.0;
    AccumulatedSlip a;
    in >> node >> g >> a.path >> a.net;
    if (g >= 0.0) h.bounds[node] = g;
    h.slip[node] = a;
  }
  if (!in) throw std::runtime_error(path + ": truncated or malformed friction state");
  return h;
}

}  // namespace contact
