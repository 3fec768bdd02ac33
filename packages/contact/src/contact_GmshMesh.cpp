#include "contact_GmshMesh.hpp"

#include <gmsh.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace contact {

int numNodes(ElementType type) {
  switch (type) {
    case ElementType::Tri3:
      return 3;
    case ElementType::Quad4:
      return 4;
    case ElementType::Tri6:
      return 6;
    case ElementType::Quad9:
      return 9;
  }
  throw std::logic_error("numNodes: invalid element type");
}

int numCorners(ElementType type) {
  return (type == ElementType::Tri3 || type == ElementType::Tri6) ? 3 : 4;
}

const char* elementTypeName(ElementType type) {
  switch (type) {
    case ElementType::Tri3:
      return "3-node triangle";
    case ElementType::Quad4:
      return "4-node quadrangle";
    case ElementType::Tri6:
      return "6-node triangle";
    case ElementType::Quad9:
      return "9-node quadrangle";
  }
  return "invalid element type";
}

std::vector<int> elementEdgeNodes(ElementType type, int edge) {
  const int nc = numCorners(type);
  if (edge < 0 || edge >= nc) throw std::out_of_range("elementEdgeNodes: no such edge");
  std::vector<int> nodes{edge, (edge + 1) % nc};
  // Gmsh numbers the midside nodes after the corners, in the order of the edges.
  if (numNodes(type) > nc) nodes.push_back(nc + edge);
  return nodes;
}

const GmshBody& GmshMesh::body(const std::string& name) const {
  return bodies[bodyIndex(name)];
}

namespace {

std::string joinNames(const std::vector<std::string>& names) {
  if (names.empty()) return "(none)";
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", \"" : "\"") + names[i] + "\"";
  return s;
}

template <class Group>
std::vector<std::string> namesOf(const std::vector<Group>& groups) {
  std::vector<std::string> names;
  for (const Group& g : groups) names.push_back(g.name);
  return names;
}

[[noreturn]] void unknownGroup(const std::string& file, const char* what, const std::string& name,
                               const std::vector<std::string>& available) {
  throw std::invalid_argument(file + ": no " + what + " named \"" + name +
                              "\"; available: " + joinNames(available));
}

}  // namespace

int GmshMesh::bodyIndex(const std::string& name) const {
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (bodies[b].name == name) return static_cast<int>(b);
  unknownGroup(source, "body (2D physical group)", name, namesOf(bodies));
}

const GmshBoundary& GmshMesh::boundary(const std::string& name) const {
  for (const GmshBoundary& g : boundaries)
    if (g.name == name) return g;
  unknownGroup(source, "boundary (1D physical group)", name, namesOf(boundaries));
}

namespace {

// Gmsh keeps global state (the current model, options, and in 4.8 a "busy" flag that an
// exception thrown while reading a file leaves set, so that every later open is silently
// ignored). A fresh initialize/finalize per load is what makes one failed load harmless to the
// next, and the guard makes sure finalize runs on every exit path.
class GmshSession {
 public:
  explicit GmshSession(bool verbose) {
    if (active_.exchange(true))
      throw std::logic_error(
          "contact::loadMesh: Gmsh is already in use (it is a process-wide singleton; loadMesh "
          "must not run concurrently)");
    try {
      // No configuration files: the mesh must not depend on the user's ~/.gmshrc.
      gmsh::initialize(0, nullptr, false);
      gmsh::option::setNumber("General.Terminal", verbose ? 1 : 0);
      gmsh::logger::start();
    } catch (...) {
      active_ = false;
      throw;
    }
  }
  ~GmshSession() {
    try {
      gmsh::logger::stop();
      gmsh::finalize();
    } catch (...) {
      // A destructor must not throw; finalize failing leaves nothing the caller could repair.
    }
    active_ = false;
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  // Gmsh's error messages since the session started: some errors (e.g. in .geo parsing with
  // some options) are only logged, not thrown.
  static std::vector<std::string> errors() {
    std::vector<std::string> log, errs;
    gmsh::logger::get(log);
    for (const std::string& line : log)
      if (line.rfind("Error", 0) == 0) errs.push_back(line);
    return errs;
  }

 private:
  static std::atomic<bool> active_;
};

std::atomic<bool> GmshSession::active_{false};

std::string lowerExtension(const std::string& path) {
  const auto slash = path.find_last_of("/\\");
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

void validate(const std::string& path, const MeshOptions& options) {
  if (options.order != 1 && options.order != 2)
    throw std::invalid_argument(path + ": mesh option order = " + std::to_string(options.order) +
                                " is not supported (1 or 2)");
  if (!(options.sizeFactor > 0.0) || !std::isfinite(options.sizeFactor)) {
    std::ostringstream s;
    s << path << ": mesh option sizeFactor = " << options.sizeFactor
      << " must be a positive finite number";
    throw std::invalid_argument(s.str());
  }
}

// Runs one Gmsh call, turning whatever it throws into an error naming the file. Gmsh 4.8 throws
// std::string; later versions throw std::exception types.
template <class F>
void gmshCall(const std::string& path, const char* what, F&& call) {
  std::string message;
  try {
    call();
  } catch (const std::string& s) {
    message = s;
  } catch (const std::exception& e) {
    message = e.what();
  } catch (...) {
    message = "unknown error";
  }
  if (message.empty()) {
    const std::vector<std::string> errs = GmshSession::errors();
    if (errs.empty()) return;
    for (const std::string& e : errs) message += (message.empty() ? "" : "; ") + e;
  }
  throw std::runtime_error(path + ": " + what + " failed: Gmsh: " + message);
}

struct NamedGroup {
  int tag;
  std::string name;
};

// Named physical groups of dimension `dim`, by increasing tag.
std::vector<NamedGroup> namedGroups(const std::string& path, int dim) {
  gmsh::vectorpair dimTags;
  gmsh::model::getPhysicalGroups(dimTags, dim);
  std::vector<NamedGroup> groups;
  for (const auto& [d, tag] : dimTags) {
    std::string name;
    gmsh::model::getPhysicalName(d, tag, name);
    if (name.empty()) continue;
    for (const NamedGroup& g : groups)
      if (g.name == name)
        throw std::runtime_error(path + ": two " + std::to_string(dim) +
                                 "D physical groups are named \"" + name + "\"");
    groups.push_back({tag, name});
  }
  std::sort(groups.begin(), groups.end(),
            [](const NamedGroup& a, const NamedGroup& b) { return a.tag < b.tag; });
  return groups;
}

std::vector<NamedGroup> selectGroups(const std::string& path, const std::vector<NamedGroup>& all,
                                     const std::vector<std::string>& wanted, const char* what) {
  if (wanted.empty()) return all;
  std::vector<std::string> available;
  for (const NamedGroup& g : all) available.push_back(g.name);
  std::vector<NamedGroup> chosen;
  for (const std::string& name : wanted) {
    auto it =
        std::find_if(all.begin(), all.end(), [&](const NamedGroup& g) { return g.name == name; });
    if (it == all.end()) unknownGroup(path, what, name, available);
    chosen.push_back(*it);
  }
  return chosen;
}

// The elements of a physical group: all its entities' elements, each entity in the order Gmsh
// lists them, so that the numbering is reproducible.
struct GroupElements {
  int type = -1;
  std::vector<std::size_t> tags;
  std::vector<std::size_t> nodes;
};

GroupElements groupElements(const std::string& path, int dim, const NamedGroup& group,
                            const std::vector<int>& supported, const char* supportedNames) {
  std::vector<int> entities;
  gmsh::model::getEntitiesForPhysicalGroup(dim, group.tag, entities);
  GroupElements out;
  for (int entity : entities) {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> tags, nodes;
    gmsh::model::mesh::getElements(types, tags, nodes, dim, entity);
    for (std::size_t t = 0; t < types.size(); ++t) {
      if (tags[t].empty()) continue;
      std::string typeName;
      int typeDim = 0, typeOrder = 0, typeNodes = 0, typeCorners = 0;
      std::vector<double> refCoords;
      gmsh::model::mesh::getElementProperties(types[t], typeName, typeDim, typeOrder, typeNodes,
                                              refCoords, typeCorners);
      if (std::find(supported.begin(), supported.end(), types[t]) == supported.end())
        throw std::runtime_error(path + ": physical group \"" + group.name + "\" has elements of " +
                                 "Gmsh type " + std::to_string(types[t]) + " (" + typeName +
                                 "), which is not supported; supported: " + supportedNames);
      if (out.type >= 0 && out.type != types[t]) {
        std::string firstName;
        int d, o, n, c;
        gmsh::model::mesh::getElementProperties(out.type, firstName, d, o, n, refCoords, c);
        throw std::runtime_error(path + ": physical group \"" + group.name +
                                 "\" mixes element types " + firstName + " and " + typeName +
                                 "; one type per group is required (recombined next to " +
                                 "unrecombined surfaces, or triangles left by recombination)");
      }
      out.type = types[t];
      out.tags.insert(out.tags.end(), tags[t].begin(), tags[t].end());
      out.nodes.insert(out.nodes.end(), nodes[t].begin(), nodes[t].end());
    }
  }
  if (out.tags.empty())
    throw std::runtime_error(path + ": physical group \"" + group.name + "\" has no " +
                             std::to_string(dim) + "D elements (is the file meshed?)");
  return out;
}

std::uint64_t edgeKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

// Relates every boundary edge to the body element having it (same end nodes).
// A surface whose normal is -z (a clockwise curve loop) gives clockwise elements, which the
// element kernels reject as inverted: renumber them counter-clockwise (corners reversed, the
// edge midpoints and the centre following their edges) and count them for the log. An element
// with a corner angle of 0 or 180 degrees (zero area, repeated or collinear corners) or a
// non-convex quadrilateral is an error naming the file and its Gmsh tag.
int orientCounterClockwise(GmshBody& body, const std::vector<double>& coords,
                           const std::string& path) {
  static const int tri3[] = {0, 2, 1}, tri6[] = {0, 2, 1, 5, 4, 3}, quad4[] = {0, 3, 2, 1},
                   quad9[] = {0, 3, 2, 1, 7, 6, 5, 4, 8};
  const ElementType type = body.type;
  const int* perm = type == ElementType::Tri3    ? tri3
                    : type == ElementType::Tri6  ? tri6
                    : type == ElementType::Quad4 ? quad4
                                                 : quad9;
  const int npe = numNodes(type), corners = numCorners(type);
  auto x = [&](int node, int c) { return coords[2 * node + c]; };
  std::vector<int> old(npe);
  int reversed = 0;
  for (int e = 0; e < body.numElements(); ++e) {
    int* el = &body.connectivity[static_cast<std::size_t>(e) * npe];
    double twiceArea = 0.0, longest = 0.0;  // shoelace over the corners; longest side squared
    for (int k = 0; k < corners; ++k) {
      const int a = el[k], b = el[(k + 1) % corners];
      twiceArea += x(a, 0) * x(b, 1) - x(b, 0) * x(a, 1);
      longest = std::max(longest, std::pow(x(b, 0) - x(a, 0), 2) + std::pow(x(b, 1) - x(a, 1), 2));
    }
    if (twiceArea < 0.0) {
      std::copy(el, el + npe, old.begin());
      for (int k = 0; k < npe; ++k) el[k] = old[perm[k]];
      ++reversed;
    }
    // Every corner turns left, by more than rounding relative to the element's size.
    for (int k = 0; k < corners; ++k) {
      const int a = el[(k + corners - 1) % corners], b = el[k], c = el[(k + 1) % corners];
      const double turn =
          (x(b, 0) - x(a, 0)) * (x(c, 1) - x(b, 1)) - (x(b, 1) - x(a, 1)) * (x(c, 0) - x(b, 0));
      if (!(turn > 1e-12 * longest))
        throw std::runtime_error(path + ": body \"" + body.name + "\": " + elementTypeName(type) +
                                 " element " + std::to_string(body.gmshTags[e]) +
                                 " (Gmsh element tag) is " +
                                 (corners == 4 && turn < 0.0 && longest > 0.0
                                      ? "not convex"
                                      : "degenerate (zero area or collinear corners)"));
    }
  }
  return reversed;
}

void relateEdgesToElements(GmshMesh& mesh) {
  struct Side {
    int body, element, edge;
  };
  std::unordered_map<std::uint64_t, Side> sides;
  for (int b = static_cast<int>(mesh.bodies.size()) - 1; b >= 0; --b) {
    // Later bodies first, so that the first body wins where two bodies share an edge.
    const GmshBody& body = mesh.bodies[b];
    const int npe = body.nodesPerElement(), nc = numCorners(body.type);
    for (int e = body.numElements() - 1; e >= 0; --e)
      for (int k = 0; k < nc; ++k) {
        const int* el = &body.connectivity[static_cast<std::size_t>(e) * npe];
        sides[edgeKey(el[k], el[(k + 1) % nc])] = Side{b, e, k};
      }
  }
  for (GmshBoundary& g : mesh.boundaries) {
    const int n = static_cast<int>(g.edges.size()) / g.nodesPerEdge;
    g.edgeBody.assign(n, -1);
    g.edgeElement.assign(n, -1);
    g.edgeLocalEdge.assign(n, -1);
    for (int i = 0; i < n; ++i) {
      auto it = sides.find(edgeKey(g.edges[i * g.nodesPerEdge], g.edges[i * g.nodesPerEdge + 1]));
      if (it == sides.end()) continue;
      g.edgeBody[i] = it->second.body;
      g.edgeElement[i] = it->second.element;
      g.edgeLocalEdge[i] = it->second.edge;
    }
  }
}

GmshMesh extract(const std::string& path, const MeshOptions& options) {
  const auto bodyGroups =
      selectGroups(path, namedGroups(path, 2), options.bodies, "body (2D physical group)");
  const auto boundaryGroups =
      selectGroups(path, namedGroups(path, 1), options.boundaries, "boundary (1D physical group)");
  if (bodyGroups.empty())
    throw std::runtime_error(path +
                             ": no named 2D physical group (body); a body must be a "
                             "Physical Surface with a name");

  std::vector<GroupElements> bodyElements, boundaryElements;
  for (const NamedGroup& g : bodyGroups)
    bodyElements.push_back(groupElements(path, 2, g, {2, 3, 9, 10},
                                         "3-node triangle (2), 4-node quadrangle (3), 6-node "
                                         "triangle (9), 9-node quadrangle (10)"));
  for (const NamedGroup& g : boundaryGroups)
    boundaryElements.push_back(
        groupElements(path, 1, g, {1, 8}, "2-node line (1), 3-node line (8)"));

  // Compact numbering by increasing Gmsh tag: independent of the order groups are visited in.
  GmshMesh mesh;
  mesh.source = path;
  for (const auto* list : {&bodyElements, &boundaryElements})
    for (const GroupElements& ge : *list)
      mesh.gmshNodes.insert(mesh.gmshNodes.end(), ge.nodes.begin(), ge.nodes.end());
  std::sort(mesh.gmshNodes.begin(), mesh.gmshNodes.end());
  mesh.gmshNodes.erase(std::unique(mesh.gmshNodes.begin(), mesh.gmshNodes.end()),
                       mesh.gmshNodes.end());
  std::unordered_map<std::size_t, int> compact;
  compact.reserve(mesh.gmshNodes.size());
  for (std::size_t i = 0; i < mesh.gmshNodes.size(); ++i)
    compact[mesh.gmshNodes[i]] = static_cast<int>(i);
  auto toCompact = [&](const std::vector<std::size_t>& tags) {
    std::vector<int> ids(tags.size());
    for (std::size_t i = 0; i < tags.size(); ++i) ids[i] = compact.at(tags[i]);
    return ids;
  };

  std::vector<std::size_t> allTags;
  std::vector<double> xyz, param;
  gmsh::model::mesh::getNodes(allTags, xyz, param, -1, -1, false, false);
  mesh.coords.assign(2 * mesh.gmshNodes.size(), 0.0);
  std::vector<char> found(mesh.gmshNodes.size(), 0);
  double extent = 0.0;
  for (double c : xyz) extent = std::max(extent, std::abs(c));
  // Relative to the model's size: geometry kernels may leave rounding noise in z.
  const double zTol = 1e-12 * std::max(1.0, extent);
  for (std::size_t i = 0; i < allTags.size(); ++i) {
    auto it = compact.find(allTags[i]);
    if (it == compact.end()) continue;
    const double z = xyz[3 * i + 2];
    if (std::abs(z) > zTol) {
      std::ostringstream s;
      s << path << ": node " << allTags[i] << " has z = " << z
        << "; a 2D mesh must lie in the plane z = 0";
      throw std::runtime_error(s.str());
    }
    mesh.coords[2 * it->second] = xyz[3 * i];
    mesh.coords[2 * it->second + 1] = xyz[3 * i + 1];
    found[it->second] = 1;
  }
  for (std::size_t i = 0; i < found.size(); ++i)
    if (!found[i])
      throw std::runtime_error(path + ": element node " + std::to_string(mesh.gmshNodes[i]) +
                               " has no coordinates");

  for (std::size_t g = 0; g < bodyGroups.size(); ++g) {
    GmshBody body;
    body.name = bodyGroups[g].name;
    body.physicalTag = bodyGroups[g].tag;
    body.type = static_cast<ElementType>(bodyElements[g].type);
    body.connectivity = toCompact(bodyElements[g].nodes);
    body.gmshTags = std::move(bodyElements[g].tags);
    body.reoriented = orientCounterClockwise(body, mesh.coords, path);
    mesh.bodies.push_back(std::move(body));
  }
  for (std::size_t g = 0; g < boundaryGroups.size(); ++g) {
    GmshBoundary boundary;
    boundary.name = boundaryGroups[g].name;
    boundary.physicalTag = boundaryGroups[g].tag;
    boundary.nodesPerEdge = boundaryElements[g].type == 8 ? 3 : 2;
    boundary.edges = toCompact(boundaryElements[g].nodes);
    mesh.boundaries.push_back(std::move(boundary));
  }
  relateEdgesToElements(mesh);
  return mesh;
}

}  // namespace

GmshMesh loadMesh(const std::string& path, const MeshOptions& options) {
  validate(path, options);
  const std::string ext = lowerExtension(path);
  if (ext != ".msh" && ext != ".geo")
    throw std::invalid_argument(path + ": unknown mesh file type \"" + ext +
                                "\" (.msh: a mesh, .geo: a geometry meshed at run time)");
  // Gmsh 4.8 silently opens nothing for a missing file.
  if (!std::ifstream(path).good())
    throw std::runtime_error(path + ": cannot open the mesh file (missing or unreadable)");

  GmshSession session(options.verbose);
  gmshCall(path, "reading the file", [&] { gmsh::open(path); });
  if (ext == ".geo") {
    gmshCall(path, "meshing", [&] {
      // Set after open so that they override the file's own global settings.
      gmsh::option::setNumber("Mesh.MeshSizeFactor", options.sizeFactor);
      if (options.quads) {
        // Blossom recombination from the default Frontal-Delaunay triangulation. (Gmsh 4.8.4's
        // "Frontal-Delaunay for quads" algorithm crashes on curved boundaries.)
        gmsh::option::setNumber("Mesh.RecombineAll", 1);
        gmsh::option::setNumber("Mesh.RecombinationAlgorithm", 1);
      }
      // Complete (Lagrange) second-order elements: 9-node quads, not 8-node serendipity ones.
      gmsh::option::setNumber("Mesh.SecondOrderIncomplete", 0);
      gmsh::model::mesh::generate(2);
      gmsh::model::mesh::setOrder(options.order);
    });
  }
  try {
    return extract(path, options);
  } catch (const std::string& s) {
    // Only Gmsh's own errors: the ones extract raises already name the file.
    throw std::runtime_error(path + ": reading the mesh failed: Gmsh: " + s);
  }
}

}  // namespace contact
