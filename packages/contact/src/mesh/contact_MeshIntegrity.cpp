#include "contact_MeshIntegrity.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace contact {

namespace {

// Remembers where each tag was first defined; the second definition is the error.
class TagRegister {
 public:
  TagRegister(const std::string& path, const char* what) : path_(path), what_(what) {}
  void add(std::size_t tag, long line) {
    auto [it, inserted] = first_.emplace(tag, line);
    if (!inserted)
      throw std::runtime_error(path_ + ": " + what_ + " tag " + std::to_string(tag) +
                               " is defined twice (lines " + std::to_string(it->second) + " and " +
                               std::to_string(line) +
                               "); Gmsh would keep one of them without a word");
  }

 private:
  const std::string& path_;
  const char* what_;
  std::unordered_map<std::size_t, long> first_;
};

// Reads lines with their numbers; stops quietly at the end of the file (a truncated file is
// Gmsh's reader's to report).
class LineReader {
 public:
  explicit LineReader(const std::string& path) : in_(path) {}
  bool next(std::string& line) {
    if (!std::getline(in_, line)) return false;
    ++number_;
    return true;
  }
  long number() const { return number_; }

 private:
  std::ifstream in_;
  long number_ = 0;
};

bool firstTag(const std::string& line, std::size_t& tag) {
  std::istringstream s(line);
  return static_cast<bool>(s >> tag);
}

// Format 2.x: one entity per line, the tag first.
void scanFlatSection(LineReader& in, const std::string& end, TagRegister& tags) {
  std::string line;
  if (!in.next(line)) return;  // the count
  while (in.next(line) && line.rfind(end, 0) != 0) {
    std::size_t tag = 0;
    if (firstTag(line, tag)) tags.add(tag, in.number());
  }
}

// Format 4.x: blocks "entityDim entityTag x count"; nodes list `count` tags and then `count`
// coordinate lines, elements list `count` lines that start with the tag.
void scanBlockSection(LineReader& in, const std::string& end, TagRegister& tags, bool nodes) {
  std::string line;
  if (!in.next(line)) return;
  std::istringstream header(line);
  long blocks = 0;
  if (!(header >> blocks)) return;
  for (long b = 0; b < blocks; ++b) {
    if (!in.next(line) || line.rfind(end, 0) == 0) return;
    std::istringstream s(line);
    long entityDim = 0, entityTag = 0, kind = 0, count = 0;
    if (!(s >> entityDim >> entityTag >> kind >> count) || count < 0) return;
    for (long k = 0; k < count; ++k) {
      if (!in.next(line) || line.rfind(end, 0) == 0) return;
      std::size_t tag = 0;
      if (firstTag(line, tag)) tags.add(tag, in.number());
    }
    if (nodes) {
      // Parametric nodes carry extra values on the same lines: one line per node either way.
      for (long k = 0; k < count; ++k)
        if (!in.next(line) || line.rfind(end, 0) == 0) return;
    }
  }
}

}  // namespace

void checkUniqueMshTags(const std::string& path) {
  LineReader in(path);
  std::string line;
  double version = 0.0;
  TagRegister nodeTags(path, "node"), elementTags(path, "element");
  while (in.next(line)) {
    if (line.rfind("$MeshFormat", 0) == 0) {
      if (!in.next(line)) return;
      std::istringstream s(line);
      int fileType = 0;
      s >> version >> fileType;
      if (fileType != 0) return;  // binary
    } else if (line.rfind("$Nodes", 0) == 0) {
      if (version >= 4.0)
        scanBlockSection(in, "$EndNodes", nodeTags, true);
      else
        scanFlatSection(in, "$EndNodes", nodeTags);
    } else if (line.rfind("$Elements", 0) == 0) {
      if (version >= 4.0)
        scanBlockSection(in, "$EndElements", elementTags, false);
      else
        scanFlatSection(in, "$EndElements", elementTags);
    }
  }
}

void checkNoCoincidentNodes(const std::string& path, const std::string& body, int dim,
                            const std::vector<double>& coords, const std::vector<int>& nodes,
                            const std::vector<std::size_t>& tags) {
  double extent = 0.0;
  for (double c : coords) extent = std::max(extent, std::abs(c));
  const double tol = 1e-12 * std::max(extent, 1e-300);
  std::vector<std::size_t> order(nodes.size());
  std::iota(order.begin(), order.end(), 0);
  auto at = [&](std::size_t i, int c) { return coords[dim * nodes[i] + c]; };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    for (int c = 0; c < dim; ++c)
      if (at(a, c) != at(b, c)) return at(a, c) < at(b, c);
    return false;
  });
  // Lexicographic neighbours catch exact and near-exact copies, the cases a mesh tool or a
  // hand edit produces; two nodes closer than tol but separated in the order are not looked for.
  for (std::size_t k = 1; k < order.size(); ++k) {
    const std::size_t a = order[k - 1], b = order[k];
    double d = 0.0;
    for (int c = 0; c < dim; ++c) d = std::max(d, std::abs(at(a, c) - at(b, c)));
    if (d <= tol && nodes[a] != nodes[b]) {
      std::ostringstream s;
      s << path << ": body \"" << body << "\": nodes " << tags[a] << " and " << tags[b]
        << " (Gmsh node tags) lie at the same point (";
      for (int c = 0; c < dim; ++c) s << (c ? ", " : "") << at(a, c);
      s << "); the elements on either side are not connected (a crack). Merge the nodes, or "
           "make the two sides separate bodies";
      throw std::runtime_error(s.str());
    }
  }
}

}  // namespace contact
