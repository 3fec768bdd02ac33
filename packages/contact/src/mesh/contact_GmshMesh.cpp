#include "contact_GmshMesh.hpp"

#include "contact_MeshIntegrity.hpp"

#include <gmsh.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace contact {

int numFacets(ElementType type) {
  if (elementDimension(type) < 2)
    throw std::invalid_argument(std::string("numFacets: a ") + elementTypeName(type) +
                                " is not a 2D or 3D element");
  return plasticity::facesPerElement(type);
}

namespace {
void requireBody(const char* who, ElementType type) {
  if (!plasticity::elementInfo(type).meshBody)
    throw std::invalid_argument(std::string(who) + ": a " + elementTypeName(type) +
                                " is not a body element");
}
}  // namespace

ElementType facetType(ElementType type) {
  requireBody("facetType", type);
  return plasticity::faceType(type);
}

const std::vector<int>& elementFacetNodes(ElementType type, int facet) {
  requireBody("elementFacetNodes", type);
  if (facet < 0 || facet >= numFacets(type))
    throw std::out_of_range("elementFacetNodes: no such facet");
  return plasticity::facetNodes(type, facet);
}

std::vector<int> elementEdgeNodes(ElementType type, int edge) {
  if (elementDimension(type) != 2)
    throw std::invalid_argument(std::string("elementEdgeNodes: a ") + elementTypeName(type) +
                                " is not a 2D element");
  if (edge < 0 || edge >= numCorners(type))
    throw std::out_of_range("elementEdgeNodes: no such edge");
  return plasticity::facetNodes(type, edge);
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

const char* bodyWhat(int dim) {
  return dim == 3 ? "body (3D physical group)" : "body (2D physical group)";
}
const char* boundaryWhat(int dim) {
  return dim == 3 ? "boundary (2D physical group)" : "boundary (1D physical group)";
}

}  // namespace

int GmshMesh::bodyIndex(const std::string& name) const {
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (bodies[b].name == name) return static_cast<int>(b);
  unknownGroup(source, bodyWhat(dim), name, namesOf(bodies));
}

const GmshBoundary& GmshMesh::boundary(const std::string& name) const {
  for (const GmshBoundary& g : boundaries)
    if (g.name == name) return g;
  unknownGroup(source, boundaryWhat(dim), name, namesOf(boundaries));
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
  if (options.dimension != 0 && options.dimension != 2 && options.dimension != 3)
    throw std::invalid_argument(path + ": mesh option dimension = " +
                                std::to_string(options.dimension) + " is not 0, 2 or 3");
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
  int gmshType = -1;  // Gmsh's code of `type`, -1 before the first element
  ElementType type = ElementType::Tri3;
  std::vector<std::size_t> tags;
  std::vector<std::size_t> nodes;
};

// The element types the reader takes: bodies of the mesh's dimension, or (boundary) their facet
// types, in the catalogue's order.
std::vector<ElementType> supportedTypes(int meshDim, bool boundary) {
  std::vector<ElementType> types;
  for (ElementType t : plasticity::allElementTypes()) {
    const plasticity::ElementInfo info = plasticity::elementInfo(t);
    if (!info.meshBody || info.dim != meshDim) continue;
    const ElementType s = boundary ? info.face : t;
    if (std::find(types.begin(), types.end(), s) == types.end()) types.push_back(s);
  }
  return types;
}

// "3-node triangle (2), 4-node quadrangle (3)": names and Gmsh codes, for messages.
std::string typeList(const std::vector<ElementType>& types) {
  std::string s;
  for (ElementType t : types)
    s += std::string(s.empty() ? "" : ", ") + elementTypeName(t) + " (" +
         std::to_string(plasticity::gmshType(t)) + ")";
  return s;
}

GroupElements groupElements(const std::string& path, int dim, const NamedGroup& group,
                            const std::vector<ElementType>& supported) {
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
      ElementType type = ElementType::Tri3;
      if (!plasticity::elementTypeOfGmsh(types[t], type) ||
          std::find(supported.begin(), supported.end(), type) == supported.end())
        throw std::runtime_error(path + ": physical group \"" + group.name + "\" has elements of " +
                                 "Gmsh type " + std::to_string(types[t]) + " (" + typeName +
                                 "), which is not supported; supported: " + typeList(supported));
      if (out.gmshType >= 0 && out.gmshType != types[t]) {
        std::string firstName;
        int d, o, n, c;
        gmsh::model::mesh::getElementProperties(out.gmshType, firstName, d, o, n, refCoords, c);
        throw std::runtime_error(path + ": physical group \"" + group.name +
                                 "\" mixes element types " + firstName + " and " + typeName +
                                 "; one type per group is required (recombined next to " +
                                 "unrecombined surfaces, or triangles left by recombination)");
      }
      out.gmshType = types[t];
      out.type = type;
      out.tags.insert(out.tags.end(), tags[t].begin(), tags[t].end());
      out.nodes.insert(out.nodes.end(), nodes[t].begin(), nodes[t].end());
    }
  }
  if (out.tags.empty())
    throw std::runtime_error(path + ": physical group \"" + group.name + "\" has no " +
                             std::to_string(dim) + "D elements (is the file meshed?)");
  return out;
}

// A surface whose normal is -z (a clockwise curve loop) gives clockwise elements, which the
// element kernels reject as inverted: renumber them counter-clockwise (corners reversed, the
// edge midpoints and the centre following their edges) and count them for the log. An element
// with a corner angle of 0 or 180 degrees (zero area, repeated or collinear corners) or a
// non-convex quadrilateral is an error naming the file and its Gmsh tag.
int orientCounterClockwise(GmshBody& body, const std::vector<double>& coords,
                           const std::string& path) {
  const ElementType type = body.type;
  const std::vector<int>& perm = plasticity::reversedNodes(type);
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

// The largest corner-to-corner distance of an element: the length scale of its Jacobian.
double cornerDiameter(const std::vector<double>& coords, int dim, const int* el, int corners) {
  double d2 = 0.0;
  for (int a = 0; a < corners; ++a)
    for (int b = a + 1; b < corners; ++b) {
      double s = 0.0;
      for (int i = 0; i < dim; ++i) {
        const double t = coords[dim * el[a] + i] - coords[dim * el[b] + i];
        s += t * t;
      }
      d2 = std::max(d2, s);
    }
  return std::sqrt(d2);
}

[[noreturn]] void badElement(const std::string& path, const std::string& group, std::size_t tag,
                             ElementType type, const std::string& what) {
  throw std::runtime_error(path + ": element " + std::to_string(tag) + " (" +
                           elementTypeName(type) + ") of body \"" + group + "\" is " + what);
}

// Relative to the element's size: a determinant below this fraction of diameter^dim is zero.
constexpr double kDegenerate = 1e-10;

// 3D: Gmsh's Jacobian determinants at every node of every element of the group (the reference
// element's nodes: corners and, for quadratic elements, the midside and face points where a
// curved element folds first). All negative: inverted; sign change: folded; all ~0: flat.
void checkSolidElements(const std::string& path, const GmshBody& body, const NamedGroup& group,
                        const std::vector<double>& coords) {
  std::string name;
  int d = 0, o = 0, n = 0, c = 0;
  std::vector<double> ref;
  gmsh::model::mesh::getElementProperties(plasticity::gmshType(body.type), name, d, o, n, ref, c);
  std::unordered_map<std::size_t, int> indexOf;
  for (int e = 0; e < body.numElements(); ++e) indexOf[body.gmshTags[e]] = e;
  std::vector<int> entities;
  gmsh::model::getEntitiesForPhysicalGroup(3, group.tag, entities);
  const int npe = body.nodesPerElement();
  for (int entity : entities) {
    std::vector<std::size_t> tags, nodeTags;
    gmsh::model::mesh::getElementsByType(plasticity::gmshType(body.type), tags, nodeTags, entity);
    if (tags.empty()) continue;
    std::vector<double> jac, det, xyz;
    gmsh::model::mesh::getJacobians(plasticity::gmshType(body.type), ref, jac, det, xyz, entity);
    if (det.size() != tags.size() * static_cast<std::size_t>(n))
      throw std::runtime_error(path + ": Gmsh returned " + std::to_string(det.size()) +
                               " Jacobians for " + std::to_string(tags.size()) + " elements");
    for (std::size_t t = 0; t < tags.size(); ++t) {
      const int e = indexOf.at(tags[t]);
      const int* el = &body.connectivity[static_cast<std::size_t>(e) * npe];
      const double h = cornerDiameter(coords, 3, el, numCorners(body.type));
      const double* dt = &det[t * n];
      const double lo = *std::min_element(dt, dt + n), hi = *std::max_element(dt, dt + n);
      const double zero = kDegenerate * h * h * h;
      if (std::max(std::abs(lo), std::abs(hi)) <= zero)
        badElement(path, body.name, tags[t], body.type, "degenerate (zero volume)");
      if (hi < 0.0)
        badElement(path, body.name, tags[t], body.type,
                   "inverted (negative Jacobian; its nodes are numbered against Gmsh's "
                   "orientation)");
      if (lo <= zero)
        badElement(path, body.name, tags[t], body.type,
                   "distorted (its Jacobian vanishes or changes sign inside the element)");
    }
  }
}

// Relates every boundary edge (face) to the body element having it as a facet; where two bodies
// share a facet, the first body's element, and within a body the first element. Only the
// boundaries' facets are indexed, and every element facet is looked up among them: indexing every
// element facet instead (6 per hexahedron) took 2.4 % of a 1M step-42 run on each rank.
void relateFacetsToElements(GmshMesh& mesh) {
  struct Side {
    int body = -1, element = -1, facet = -1;
  };
  std::unordered_map<FacetKey, Side, FacetKeyHash> sides;
  for (const GmshBoundary& g : mesh.boundaries) {
    const int n = static_cast<int>(g.edges.size()) / g.nodesPerEdge;
    const int fc = numCorners(g.type);
    for (int i = 0; i < n; ++i)
      sides.emplace(facetKey(&g.edges[static_cast<std::size_t>(i) * g.nodesPerEdge], fc), Side{});
  }
  for (int b = 0; b < static_cast<int>(mesh.bodies.size()) && !sides.empty(); ++b) {
    const GmshBody& body = mesh.bodies[b];
    const int npe = body.nodesPerElement(), nf = numFacets(body.type);
    const int fc = numCorners(facetType(body.type));
    for (int e = 0; e < body.numElements(); ++e) {
      const int* el = &body.connectivity[static_cast<std::size_t>(e) * npe];
      for (int f = 0; f < nf; ++f) {
        const std::vector<int>& local = elementFacetNodes(body.type, f);
        int corners[4];
        for (int k = 0; k < fc; ++k) corners[k] = el[local[k]];
        auto it = sides.find(facetKey(corners, fc));
        if (it != sides.end() && it->second.body < 0) it->second = Side{b, e, f};
      }
    }
  }
  for (GmshBoundary& g : mesh.boundaries) {
    const int n = static_cast<int>(g.edges.size()) / g.nodesPerEdge;
    const int fc = numCorners(g.type);
    g.edgeBody.assign(n, -1);
    g.edgeElement.assign(n, -1);
    g.edgeLocalEdge.assign(n, -1);
    for (int i = 0; i < n; ++i) {
      const Side& side =
          sides.at(facetKey(&g.edges[static_cast<std::size_t>(i) * g.nodesPerEdge], fc));
      g.edgeBody[i] = side.body;
      g.edgeElement[i] = side.element;
      g.edgeLocalEdge[i] = side.facet;
    }
  }
}

// The dimension of the mesh in the model: 3 when it has a named physical volume.
int meshDimension(const std::string& path) {
  return namedGroups(path, 3).empty() ? 2 : 3;
}

[[noreturn]] void wrongDimension(const std::string& path, int found, int asked) {
  throw std::invalid_argument(
      path + ": the mesh is " + std::to_string(found) + "D (" +
      (found == 3 ? "it defines volumes" : "it defines no named physical volume") + ") but a " +
      std::to_string(asked) + "D problem is asked");
}

GmshMesh extract(const std::string& path, const MeshOptions& options, int dim) {
  const auto bodyGroups = selectGroups(path, namedGroups(path, dim), options.bodies, bodyWhat(dim));
  const auto boundaryGroups =
      selectGroups(path, namedGroups(path, dim - 1), options.boundaries, boundaryWhat(dim));
  if (bodyGroups.empty())
    throw std::runtime_error(path + ": no named " + std::to_string(dim) +
                             "D physical group (body); a body must be a Physical " +
                             (dim == 3 ? "Volume" : "Surface") + " with a name");

  std::vector<GroupElements> bodyElements, boundaryElements;
  for (const NamedGroup& g : bodyGroups)
    bodyElements.push_back(groupElements(path, dim, g, supportedTypes(dim, false)));
  for (const NamedGroup& g : boundaryGroups)
    boundaryElements.push_back(groupElements(path, dim - 1, g, supportedTypes(dim, true)));

  // Compact numbering by increasing Gmsh tag: independent of the order groups are visited in.
  GmshMesh mesh;
  mesh.source = path;
  mesh.dim = dim;
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
  mesh.coords.assign(static_cast<std::size_t>(dim) * mesh.gmshNodes.size(), 0.0);
  std::vector<char> found(mesh.gmshNodes.size(), 0);
  double extent = 0.0;
  for (double c : xyz) extent = std::max(extent, std::abs(c));
  // Relative to the model's size: geometry kernels may leave rounding noise in z.
  const double zTol = 1e-12 * std::max(1.0, extent);
  for (std::size_t i = 0; i < allTags.size(); ++i) {
    auto it = compact.find(allTags[i]);
    if (it == compact.end()) continue;
    const double z = xyz[3 * i + 2];
    if (dim == 2 && std::abs(z) > zTol) {
      std::ostringstream s;
      s << path << ": node " << allTags[i] << " has z = " << z
        << "; a 2D mesh must lie in the plane z = 0";
      throw std::runtime_error(s.str());
    }
    for (int c = 0; c < dim; ++c) mesh.coords[dim * it->second + c] = xyz[3 * i + c];
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
    body.type = bodyElements[g].type;
    body.connectivity = toCompact(bodyElements[g].nodes);
    body.gmshTags = std::move(bodyElements[g].tags);
    if (dim == 2)
      body.reoriented = orientCounterClockwise(body, mesh.coords, path);
    else
      checkSolidElements(path, body, bodyGroups[g], mesh.coords);
    std::vector<int> used(body.connectivity);
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    std::vector<std::size_t> usedTags(used.size());
    for (std::size_t i = 0; i < used.size(); ++i) usedTags[i] = mesh.gmshNodes[used[i]];
    checkNoCoincidentNodes(path, body.name, dim, mesh.coords, used, usedTags);
    mesh.bodies.push_back(std::move(body));
  }
  for (std::size_t g = 0; g < boundaryGroups.size(); ++g) {
    GmshBoundary boundary;
    boundary.name = boundaryGroups[g].name;
    boundary.physicalTag = boundaryGroups[g].tag;
    boundary.type = boundaryElements[g].type;
    boundary.nodesPerEdge = numNodes(boundary.type);
    boundary.edges = toCompact(boundaryElements[g].nodes);
    mesh.boundaries.push_back(std::move(boundary));
  }
  relateFacetsToElements(mesh);
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

  if (ext == ".msh") checkUniqueMshTags(path);

  GmshSession session(options.verbose);
  gmshCall(path, "reading the file", [&] { gmsh::open(path); });
  int dim = 2;
  if (ext == ".geo") {
    gmsh::vectorpair volumes;
    gmsh::model::getEntities(volumes, 3);
    dim = volumes.empty() ? 2 : 3;
  } else {
    dim = meshDimension(path);
  }
  if (options.dimension != 0 && options.dimension != dim)
    wrongDimension(path, dim, options.dimension);
  if (dim == 3 && options.quads)
    throw std::invalid_argument(path +
                                ": mesh option quads (recombination into quadrilaterals) is 2D "
                                "only; hexahedra come from the file's Transfinite Volume and "
                                "Recombine commands");
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
      // Complete (Lagrange) second-order elements: 9-node quads and 27-node hexahedra, not the
      // serendipity ones.
      gmsh::option::setNumber("Mesh.SecondOrderIncomplete", 0);
      gmsh::model::mesh::generate(dim);
      gmsh::model::mesh::setOrder(options.order);
    });
  }
  try {
    return extract(path, options, dim);
  } catch (const std::string& s) {
    // Only Gmsh's own errors: the ones extract raises already name the file.
    throw std::runtime_error(path + ": reading the mesh failed: Gmsh: " + s);
  }
}

FacetKey facetKey(const int* corners, int numCorners) {
  FacetKey k{-1, -1, -1, -1};
  for (int i = 0; i < numCorners; ++i) {  // insertion sort of at most 4 values
    int j = i;
    for (; j > 0 && k[j - 1] > corners[i]; --j) k[j] = k[j - 1];
    k[j] = corners[i];
  }
  return k;
}

std::size_t FacetKeyHash::operator()(const FacetKey& k) const {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the four ids
  for (int v : k) h = (h ^ static_cast<std::uint32_t>(v)) * 1099511628211ull;
  return static_cast<std::size_t>(h);
}

}  // namespace contact
