#include "contact_ElasticContactProblem.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "contact_SurfaceWeights.hpp"
#include "contact_TangentialRows.hpp"
#include "tfeti_SubdomainDistribution.hpp"
#include "tfeti_SubdomainMesh.hpp"

namespace contact {

plasticity::ElementType checkedBodyType(ElementType type) {
  if (plasticity::elementInfo(type).meshBody && plasticity::elementInfo(type).complete) return type;
  // The assembled body types, from the catalogue: "Tri3, Quad4, ... or Hex27".
  std::vector<std::string> names;
  for (ElementType t : plasticity::allElementTypes())
    if (plasticity::elementInfo(t).meshBody && plasticity::elementInfo(t).complete)
      names.push_back(plasticity::elementTypeName(t));
  std::string list;
  for (std::size_t k = 0; k < names.size(); ++k)
    list += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  throw std::invalid_argument(std::string("elastic contact: ") + elementTypeName(type) +
                              " bodies are not supported (" + list + ")");
}

namespace {

const GmshBoundary& boundaryNamed(const GmshMesh& mesh, const std::string& name,
                                  const std::string& role) {
  try {
    return mesh.boundary(name);
  } catch (const std::exception& e) {
    throw std::invalid_argument(role + ": " + e.what());
  }
}

std::set<int> nodesOf(const GmshBoundary& b) {
  return std::set<int>(b.edges.begin(), b.edges.end());
}

int localIndex(const UnstructuredSubdomain& s, int globalNode) {
  auto it = std::lower_bound(s.globalNode.begin(), s.globalNode.end(), globalNode);
  return it != s.globalNode.end() && *it == globalNode ? static_cast<int>(it - s.globalNode.begin())
                                                       : -1;
}

// A load given per boundary or body must have one value per component of the mesh's dimension.
void checkComponents(const std::vector<std::pair<std::string, std::vector<double>>>& loads,
                     const std::string& what, const std::string& owner, const GmshMesh& mesh) {
  for (const auto& [name, v] : loads)
    if (static_cast<int>(v.size()) != mesh.dim)
      throw std::invalid_argument(
          what + ": " + std::to_string(v.size()) + " values for " + owner + " \"" + name +
          "\"; the mesh " + mesh.source + " is " + std::to_string(mesh.dim) + "D and needs " +
          std::to_string(mesh.dim) + " (" + (mesh.dim == 3 ? "x, y, z" : "x, y") + ")");
}

// A body touching neither a Dirichlet boundary (fixed or symmetry) nor the contact pair floats
// freely: its stiffness is singular with nothing to hold it, which the solver would only report
// as a singular coarse problem. Name it before any solve.
void requireEveryBodyHeld(const GmshMesh& mesh, const ElasticContactSpec& spec,
                          const std::set<int>& fixedNodes,
                          const std::set<std::pair<int, int>>& fixedComponents,
                          const PrescribedValues& prescribed) {
  std::set<int> held(fixedNodes);
  for (const auto& nc : fixedComponents) held.insert(nc.first);
  for (const auto& [nc, value] : prescribed) held.insert(static_cast<int>(nc.first));
  for (const GmshBoundary& b : mesh.boundaries)  // a missing name is reported later
    for (const ContactPairSpec& pair : spec.pairs)
      if (b.name == pair.slave || b.name == pair.master) {
        const auto nodes = nodesOf(b);
        held.insert(nodes.begin(), nodes.end());
      }
  for (const auto& body : spec.bodies) {
    const auto& c = mesh.body(body.name).connectivity;
    if (std::none_of(c.begin(), c.end(), [&](int n) { return held.count(n) > 0; }))
      throw std::invalid_argument(
          "Bodies: body \"" + body.name +
          "\" has no Dirichlet condition (Fixed boundaries, Symmetry boundaries, Prescribed "
          "boundaries) and is not on "
          "the contact pair (Slave, Master): nothing holds it");
  }
}

// The body (index into spec.bodies) that most of a boundary's edges (faces) lie on, or -1.
int bodyOfBoundary(const GmshMesh& mesh, const ElasticContactSpec& spec, const GmshBoundary& b) {
  std::map<int, int> count;
  for (int e = 0; e < b.numEdges(); ++e)
    if (b.edgeBody[e] >= 0) ++count[b.edgeBody[e]];
  int best = -1, most = 0;
  for (const auto& [meshBody, n] : count)
    if (n > most) best = meshBody, most = n;
  if (best < 0) return -1;
  for (std::size_t k = 0; k < spec.bodies.size(); ++k)
    if (spec.bodies[k].name == mesh.bodies[best].name) return static_cast<int>(k);
  return -1;
}

}  // namespace

std::vector<plasticity::ElasticLaw> contactBodyLaws(const ElasticContactSpec& spec,
                                                    const ElasticContactProblem& p) {
  std::vector<plasticity::ElasticLaw> laws;
  for (int b : {p.pairs.front().slaveBody, p.pairs.front().masterBody})
    if (b >= 0) laws.push_back(spec.bodies[b].law);
  return laws;
}

std::vector<int> boundaryNodeIds(const GmshMesh& mesh, const std::string& name) {
  const auto nodes = nodesOf(boundaryNamed(mesh, name, "boundary"));
  return std::vector<int>(nodes.begin(), nodes.end());
}

namespace {

// The steps of buildElasticContactProblem, in the order it runs them.

// Says which bodies were reoriented (clockwise in the file) and checks the loads' component
// counts and the contact zone against the mesh's dimension.
void checkSpecAgainstMesh(const ElasticContactSpec& spec, const GmshMesh& mesh,
                          const tfeti::Comm& comm) {
  for (const GmshBody& b : mesh.bodies)  // clockwise in the file: reoriented, said once
    if (b.reoriented > 0 && comm.getRank() == 0)
      std::cout << mesh.source << ": body \"" << b.name << "\": " << b.reoriented << " of "
                << b.numElements() << " elements were clockwise and are reoriented\n";
  checkComponents(spec.tractions, "Tractions", "traction boundary", mesh);
  checkComponents(spec.bodyLoads, "Body loads", "body", mesh);
  if (spec.contactZone == "point" && mesh.dim == 2)
    throw std::invalid_argument("Contact problem: \"Contact zone\" = point needs a 3D mesh; " +
                                mesh.source + " is 2D (a 2D contact is a line contact)");
}

// Subdomains, body by body, numbered consecutively.
void partitionBodies(const ElasticContactSpec& spec, ElasticContactProblem& p) {
  const GmshMesh& mesh = p.mesh;
  for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
    const auto& body = spec.bodies[b];
    if (body.subdomains < 1)
      throw std::invalid_argument("body \"" + body.name + "\": the subdomain count must be >= 1");
    const GmshBody* gb = nullptr;
    try {
      gb = &mesh.body(body.name);
    } catch (const std::exception& e) {
      throw std::invalid_argument(std::string("Bodies: ") + e.what());
    }
    // A body cannot have more parts than elements; name the parameter that asks for them
    // (and the size factor when it is what made the mesh so coarse).
    std::ostringstream factor;
    if (spec.meshOptions.sizeFactor != 1.0)
      factor << " at \"Mesh size factor\" " << spec.meshOptions.sizeFactor;
    if (body.subdomains > gb->numElements())
      throw std::invalid_argument("Contact problem: \"Subdomains per body\" asks for " +
                                  std::to_string(body.subdomains) + " subdomains of body \"" +
                                  body.name + "\", which has " + std::to_string(gb->numElements()) +
                                  " elements" + factor.str());
    BodyPartition part;
    try {
      part = partitionBody(mesh, *gb, body.subdomains, p.numSubdomains(), spec.partitioner);
    } catch (const std::exception& e) {
      throw std::invalid_argument(std::string("Subdomains per body: ") + e.what());
    }
    for (auto& s : part.subdomains) {
      p.subdomains.push_back(std::move(s));
      p.bodyOfSubdomain.push_back(static_cast<int>(b));
    }
  }
}

// Every untorn node's first copy (lowest subdomain id): where a contact row acts on it.
void findFirstCopies(ElasticContactProblem& p) {
  p.copyOf.assign(p.mesh.numNodes(), {-1, -1});
  for (const auto& s : p.subdomains)
    for (int n = 0; n < s.numNodes(); ++n)
      if (p.copyOf[s.globalNode[n]].first < 0) p.copyOf[s.globalNode[n]] = {s.id, n};
}

// The Dirichlet conditions by mesh node: fixed nodes and (node, component) symmetry pairs.
struct Supports {
  std::set<int> fixedNodes;
  std::set<std::pair<int, int>> fixedComponents;
};

// The fixed and symmetry boundaries' nodes and p.prescribed; every body must be held.
Supports dirichletConditions(const ElasticContactSpec& spec, ElasticContactProblem& p) {
  const GmshMesh& mesh = p.mesh;
  const int dim = mesh.dim;
  Supports h;
  for (const auto& name : spec.fixed) {
    const auto nodes = nodesOf(boundaryNamed(mesh, name, "Fixed boundaries"));
    h.fixedNodes.insert(nodes.begin(), nodes.end());
  }
  for (const auto& [name, c] : spec.symmetry) {
    if (c < 0 || c >= dim)
      throw std::invalid_argument("Symmetry components: " + std::to_string(c) + " for boundary \"" +
                                  name + "\" is not " +
                                  (dim == 3 ? "0 (x), 1 (y) or 2 (z)" : "0 (x) or 1 (y)") + " (a " +
                                  std::to_string(dim) + "D mesh)");
    for (int n : nodesOf(boundaryNamed(mesh, name, "Symmetry boundaries"))) {
      h.fixedComponents.insert({n, c});
      p.mirroredComponents.insert({n, c});
    }
  }
  p.prescribed = prescribedValues(
      spec.prescribed, dim,
      [&](const std::string& name) {
        const auto nodes = nodesOf(boundaryNamed(mesh, name, "Prescribed boundaries"));
        return std::vector<long long>(nodes.begin(), nodes.end());
      },
      spec.fixed, spec.symmetry);
  requireEveryBodyHeld(mesh, spec, h.fixedNodes, h.fixedComponents, p.prescribed);
  p.heldComponents = h.fixedComponents;
  for (int n : h.fixedNodes)
    for (int c = 0; c < dim; ++c) p.heldComponents.insert({n, c});
  for (const auto& [nc, value] : p.prescribed)
    p.heldComponents.insert({static_cast<int>(nc.first), nc.second});
  return h;
}

// The kinematic couplings' rows (rank 0 keeps them).
void addCouplings(const ElasticContactSpec& spec, const Supports& h, const tfeti::Comm& comm,
                  ElasticContactProblem& p) {
  const GmshMesh& mesh = p.mesh;
  CouplingContext context;
  context.dim = mesh.dim;
  context.nodesOf = [&](const std::string& name) {
    const auto nodes = nodesOf(boundaryNamed(mesh, name, "Coupled boundaries"));
    return std::vector<long long>(nodes.begin(), nodes.end());
  };
  context.firstCopy = [&](long long n) { return p.copyOf[n]; };
  context.heldBy = [&](long long n, int c) -> std::string {
    const int node = static_cast<int>(n);
    if (h.fixedNodes.count(node)) return "fixed boundaries (Fixed boundaries)";
    if (h.fixedComponents.count({node, c})) return "symmetry boundaries (Symmetry boundaries)";
    if (p.prescribed.count({n, c})) return "prescribed displacements (Prescribed boundaries)";
    return "";
  };
  p.couplingRows = kinematicCouplingRows(spec.couplings, context);
  p.couplingRowCount = static_cast<long long>(p.couplingRows.size());
  if (comm.getRank() != 0) p.couplingRows.clear();  // each row is passed by one rank
}

// Per subdomain, the initial contact rows that touch its nodes. Those subdomains carry the
// contact zone's work: their preconditioners are rebuilt whenever the rows move, and in
// plasticity their tangents change and are refactorized while the rest keep theirs.
std::vector<double> contactWeights(const ElasticContactProblem& p,
                                   const std::vector<std::vector<int>>& holders) {
  std::vector<double> w(p.subdomains.size(), 0.0);
  std::vector<int> touched;
  for (const ContactRow& row : p.contact.rows) {
    touched.clear();
    for (const NodeEntry& e : row.entries)
      touched.insert(touched.end(), holders[e.node].begin(), holders[e.node].end());
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (int s : touched) w[s] += 1.0;
  }
  return w;
}

// The subdomain graph: edges join subdomains sharing interface nodes, weighted by their number;
// the weights are the dofs, the contact weights the initial contact rows.
tfeti::SubdomainGraph subdomainGraph(const ElasticContactProblem& p) {
  std::vector<std::vector<int>> holders(p.mesh.numNodes());
  for (const auto& s : p.subdomains)
    for (long long g : s.globalNode) holders[g].push_back(s.id);
  std::map<std::pair<int, int>, double> shared;
  for (const auto& h : holders)
    for (std::size_t i = 0; i < h.size(); ++i)
      for (std::size_t j = i + 1; j < h.size(); ++j)
        shared[{std::min(h[i], h[j]), std::max(h[i], h[j])}] += 1.0;
  std::vector<tfeti::SubdomainEdge> edges;
  for (const auto& [ab, w] : shared) edges.push_back({ab.first, ab.second, w});
  std::vector<double> weights;
  for (const auto& s : p.subdomains) weights.push_back(static_cast<double>(p.dim()) * s.numNodes());
  tfeti::SubdomainGraph graph = tfeti::makeSubdomainGraph(weights, edges);
  graph.contactWeights = contactWeights(p, holders);
  return graph;
}

// Subdomains to ranks: balance the dofs and the contact rows and keep neighbours together; the
// balance reached is reported.
void distributeToRanks(const ElasticContactSpec& spec, const tfeti::Comm& comm,
                       ElasticContactProblem& p) {
  const tfeti::SubdomainGraph graph = subdomainGraph(p);
  p.ownerOfSubdomain = tfeti::distributeSubdomains(
      comm, graph, tfeti::distributionMethodFromString(spec.distribution),
      &p.distribution.partitioner);
  p.distribution.dofImbalance = tfeti::weightImbalance(graph, p.ownerOfSubdomain, comm.getSize());
  p.distribution.contactImbalance =
      tfeti::contactImbalance(graph, p.ownerOfSubdomain, comm.getSize());
  p.distribution.edgeCut = tfeti::edgeCut(graph, p.ownerOfSubdomain);
}

// The areas of the bodies with a body load (every rank meshes all of them: no reduction).
std::map<std::string, double> bodyLoadAreas(const ElasticContactSpec& spec, const GmshMesh& mesh) {
  std::map<std::string, double> bodyArea;
  for (const auto& [name, total] : spec.bodyLoads) {
    const auto it = std::find_if(spec.bodies.begin(), spec.bodies.end(),
                                 [&](const ElasticContactSpec::Body& b) { return b.name == name; });
    if (it == spec.bodies.end())
      throw std::invalid_argument("Body load bodies: \"" + name + "\" is not one of \"Bodies\"");
    const GmshBody& gb = mesh.body(name);
    const plasticity::ElementMesh whole{checkedBodyType(gb.type), mesh.coords, gb.connectivity};
    const double unit[3] = {1.0, 0.0, 0.0};
    const auto fe = plasticity::assembleBodyForce(whole, unit);
    double area = 0.0;  // the volume in 3D
    for (std::size_t i = 0; i < fe.size(); i += mesh.dim) area += fe[i];
    bodyArea[name] = area;
  }
  return bodyArea;
}

// Tractions with a ramp other than {0, 1}: their loads apart (one part per such traction).
struct LoadParts {
  std::vector<ElasticContactProblem::RampedLoad> ramped;
  std::vector<int> rampOf;            // per traction: its index in `ramped`, or -1
  double force[3] = {0.0, 0.0, 0.0};  // this rank's resultant of every load
};

LoadParts rampedTractionParts(const ElasticContactSpec& spec) {
  LoadParts parts;
  parts.rampOf.assign(spec.tractions.size(), -1);
  for (std::size_t k = 0; k < spec.tractionRamps.size(); ++k)
    if (!spec.tractionRamps[k].isDefault()) {
      parts.rampOf[k] = static_cast<int>(parts.ramped.size());
      parts.ramped.push_back({spec.tractionRamps[k], {}, {0.0, 0.0, 0.0}});
    }
  return parts;
}

// The tearing mesh of subdomain s: elements, coordinates, interface candidates and its
// Dirichlet nodes and components.
tfeti::SubdomainData subdomainData(const UnstructuredSubdomain& s, int dim, const Supports& h) {
  tfeti::SubdomainData sd;
  sd.dofsPerNode = dim;
  sd.mesh.id = s.id;
  sd.mesh.dim = dim;
  const int npe = s.nodesPerElement();
  for (int e = 0; e < s.numElements(); ++e)
    sd.mesh.elements.add(
        std::vector<int>(s.connectivity.begin() + e * npe, s.connectivity.begin() + (e + 1) * npe));
  sd.mesh.coords = s.coords;
  sd.mesh.globalNode.assign(s.globalNode.begin(), s.globalNode.end());
  sd.mesh.interfaceCandidates = s.boundaryNodes();
  for (int n = 0; n < s.numNodes(); ++n) {
    if (h.fixedNodes.count(static_cast<int>(s.globalNode[n]))) sd.mesh.dirichletNodes.push_back(n);
    for (int c = 0; c < dim; ++c)
      if (h.fixedComponents.count({static_cast<int>(s.globalNode[n]), c}))
        sd.mesh.fixedComponents.push_back({n, c});
  }
  return sd;
}

// The tractions on subdomain s's faces (edges) and the body loads of its body, added to sd.f,
// to `proportional` or their ramped part, and to the resultants.
void addLoads(const ElasticContactSpec& spec, const ElasticContactProblem& p,
              const UnstructuredSubdomain& s, int b, const plasticity::ElementMesh& em,
              const std::map<std::string, double>& bodyArea, tfeti::SubdomainData& sd,
              std::vector<double>& proportional, LoadParts& parts) {
  const GmshMesh& mesh = p.mesh;
  const int dim = mesh.dim;
  auto& ramped = parts.ramped;
  const int bodyIndex = mesh.bodyIndex(spec.bodies[b].name);
  for (std::size_t k = 0; k < spec.tractions.size(); ++k) {
    const auto& [name, t] = spec.tractions[k];
    const GmshBoundary& gb = boundaryNamed(mesh, name, "Traction boundaries");
    std::vector<int> edges;
    for (int e = 0; e < gb.numEdges(); ++e) {
      if (gb.edgeBody[e] != bodyIndex ||
          !std::binary_search(s.elements.begin(), s.elements.end(), gb.edgeElement[e]))
        continue;
      for (int k = 0; k < gb.nodesPerEdge; ++k)
        edges.push_back(localIndex(s, gb.edges[e * gb.nodesPerEdge + k]));
    }
    if (edges.empty()) continue;
    const auto fe = plasticity::assembleSurfaceTraction(em, edges, t.data());
    for (std::size_t i = 0; i < fe.size(); ++i) {
      sd.f[i] += fe[i];
      parts.force[i % dim] += fe[i];
    }
    auto& part = ramped.empty() || parts.rampOf[k] < 0 ? proportional
                                                       : ramped[parts.rampOf[k]].f[p.local.size()];
    for (std::size_t i = 0; i < fe.size(); ++i) part[i] += fe[i];
    if (!ramped.empty() && parts.rampOf[k] >= 0)
      for (std::size_t i = 0; i < fe.size(); ++i) ramped[parts.rampOf[k]].force[i % dim] += fe[i];
  }
  for (const auto& [name, total] : spec.bodyLoads) {
    if (name != spec.bodies[b].name) continue;
    const double unit[3] = {1.0, 1.0, 1.0};
    const auto fe = plasticity::assembleBodyForce(em, unit);
    for (std::size_t i = 0; i < fe.size(); ++i) {
      const double density = total[i % dim] / bodyArea.at(name);
      sd.f[i] += density * fe[i];
      parts.force[i % dim] += density * fe[i];
      proportional[i] += density * fe[i];
    }
  }
}

// This rank's subdomains: meshes for the tearing, stiffness and loads; then the loads'
// resultants over all ranks and the equality rows at full load.
void assembleLocalSubdomains(const ElasticContactSpec& spec, const Supports& h,
                             const tfeti::Comm& comm, ElasticContactProblem& p) {
  const int dim = p.dim();
  const std::map<std::string, double> bodyArea = bodyLoadAreas(spec, p.mesh);
  LoadParts parts = rampedTractionParts(spec);
  const std::vector<int> mine = tfeti::subdomainsOfRank(p.ownerOfSubdomain, comm.getRank());
  // SubdomainData's move may throw (Teuchos::RCP's is not noexcept), so a growing vector would
  // copy every K assembled so far.
  p.local.reserve(p.local.size() + mine.size());
  p.localElements.reserve(p.localElements.size() + mine.size());
  for (int sid : mine) {
    const UnstructuredSubdomain& s = p.subdomains[sid];
    for (auto& r : parts.ramped)
      r.f.emplace_back(static_cast<std::size_t>(dim) * s.numNodes(), 0.0);
    const int b = p.bodyOfSubdomain[sid];
    plasticity::ElementMesh em{checkedBodyType(s.type), s.coords, s.connectivity};
    tfeti::SubdomainData sd = subdomainData(s, dim, h);
    sd.K = plasticity::assembleStiffness(em, spec.bodies[b].law);
    sd.f.assign(static_cast<std::size_t>(dim) * s.numNodes(), 0.0);
    std::vector<double> proportional(sd.f.size(), 0.0);
    addLoads(spec, p, s, b, em, bodyArea, sd, proportional, parts);
    if (!parts.ramped.empty()) p.proportionalLoad.push_back(std::move(proportional));
    p.local.push_back(std::move(sd));
    p.localElements.push_back(std::move(em));
    p.localBody.push_back(b);
  }
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 3, parts.force, p.appliedForce);
  for (auto& r : parts.ramped) {
    double total[3] = {0.0, 0.0, 0.0};
    Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 3, r.force, total);
    std::copy(total, total + 3, r.force);
  }
  p.rampedLoads = std::move(parts.ramped);
  p.equalities = equalityRowsAt(p, 1.0, {});
}

// The search options of a pair: its radius, or a tenth of the mesh's extent.
ContactSearchOptions searchOptions(const ContactPairSpec& spec, const GmshMesh& mesh) {
  const int dim = mesh.dim;
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (int n = 0; n < mesh.numNodes(); ++n)
    for (int c = 0; c < dim; ++c) {
      lo[c] = std::min(lo[c], mesh.coords[dim * n + c]);
      hi[c] = std::max(hi[c], mesh.coords[dim * n + c]);
    }
  double extent = 0.0;
  for (int c = 0; c < dim; ++c) extent = std::max(extent, hi[c] - lo[c]);
  ContactSearchOptions options;
  // A slave node on a symmetry line opposite the master's end (the contact point of a half
  // model) moves off that line by the solver's rounding once the contact is re-evaluated on the
  // deformed geometry; a relative tolerance far above rounding keeps its row.
  options.endTolerance = 1e-4;
  options.searchRadius = spec.searchRadius > 0.0 ? spec.searchRadius : 0.1 * extent;
  return options;
}

// A pair's master: a rigid obstacle, or the Master boundary's segments (faces) oriented by the
// master body's elements so that the normals point out of it (makePairMaster).
void makeMaster(const ElasticContactSpec& spec, const ContactSearchOptions& options,
                const std::set<int>& slaveSet, const GmshMesh& mesh,
                ElasticContactProblem::Pair& pair) {
  const ContactPairSpec& ps = pair.spec;
  const int dim = mesh.dim;
  // Messages name the old keys' parameters as they always have; a pair of Contact pairs adds
  // its path.
  const std::string at = ps.name.empty() ? "" : ps.where + "/";
  if (ps.obstacle) {
    if (!ps.master.empty())
      throw std::invalid_argument(at + "Master: \"" + ps.master +
                                  "\" is given together with a Rigid obstacle; the obstacle is "
                                  "the master (leave Master empty)");
    const RigidObstacle& obstacle = *ps.obstacle;
    if (obstacle.dim != dim)
      throw std::invalid_argument(ps.where + "/Rigid obstacle: a " + std::to_string(obstacle.dim) +
                                  "D obstacle (" +
                                  (obstacle.dim == 3 ? "plane or sphere" : "line or circle") +
                                  ") for the " + std::to_string(dim) + "D mesh " + mesh.source);
    pair.master = makePairMaster(mesh, ps, options);
    return;
  }
  const GmshBoundary& master = boundaryNamed(mesh, ps.master, at + "Master");
  bool onBody = false;
  for (int e = 0; e < master.numEdges(); ++e) onBody = onBody || master.edgeBody[e] >= 0;
  if (!onBody)
    throw std::invalid_argument(at + "Master: boundary \"" + ps.master + "\" is on no body");
  pair.master = makePairMaster(mesh, ps, options);
  pair.masterBody = bodyOfBoundary(mesh, spec, master);
  // A node on both surfaces joins the bodies there: it is glued, not in contact (a .geo that
  // extrudes touching bodies merges their coincident points unless told otherwise).
  for (int n : pair.master->masterNodes())
    if (slaveSet.count(n)) {
      std::ostringstream where;
      for (int c = 0; c < dim; ++c) where << (c ? ", " : "") << mesh.coords[dim * n + c];
      throw std::invalid_argument(
          mesh.source + ": " + (ps.name.empty() ? "" : pairLabel(ps) + ": ") + "the Slave \"" +
          ps.slave + "\" and the Master \"" + ps.master + "\" share the node at (" + where.str() +
          "): the bodies are joined there; each body needs its own "
          "nodes on the contact surfaces");
    }
}

// Contact: every pair's slave boundary's nodes against its master, the rows on the reference
// configuration, with bonded contact their tangential rows, and the slave nodes' lumping
// weights.
void setUpContact(const ElasticContactSpec& spec, const tfeti::Comm& comm,
                  ElasticContactProblem& p) {
  const GmshMesh& mesh = p.mesh;
  const int dim = mesh.dim;
  std::set<int> surface;
  p.namedPairs = spec.namedPairs;
  for (const ContactPairSpec& ps : spec.pairs) {
    ElasticContactProblem::Pair pair;
    pair.spec = ps;
    const std::string at = ps.name.empty() ? "" : ps.where + "/";
    const GmshBoundary& slave = boundaryNamed(mesh, ps.slave, at + "Slave");
    const std::set<int> slaveSet = nodesOf(slave);
    pair.slaveNodes.assign(slaveSet.begin(), slaveSet.end());
    pair.slaveBody = bodyOfBoundary(mesh, spec, slave);
    const ContactSearchOptions options = searchOptions(ps, mesh);
    pair.searchRadius = options.searchRadius;
    makeMaster(spec, options, slaveSet, mesh, pair);
    surface.insert(slaveSet.begin(), slaveSet.end());
    for (int n : pair.master->masterNodes()) surface.insert(n);
    // Lumping weights: a slave node's share of the slave boundary's length (2D) or area (3D);
    // the contact pressure is its multiplier (a nodal force; per unit thickness in 2D) divided
    // by it.
    std::map<int, double> weight = boundaryNodeWeights(mesh, slave);
    for (int n : pair.slaveNodes) pair.slaveWeights.push_back(weight[n]);
    p.pairs.push_back(std::move(pair));
  }
  p.surfaceNodes.assign(surface.begin(), surface.end());
  updateContact(p, {}, comm.getRank());
  if (spec.bonded && comm.getRank() == 0) {
    // Bonded: beside each contact row its tangential rows, B_T u = 0 (held with equality as the
    // contact rows): no relative motion of the pair along the surface either.
    auto dofOf = [&](int node, int component) {
      return std::make_pair(p.copyOf[node].first, dim * p.copyOf[node].second + component);
    };
    for (const auto& row : p.contact.rows) {
      const std::vector<ContactRow> tangents = tangentialRows(row, dim);
      for (std::size_t j = 0; j < tangents.size(); ++j) {
        p.inequalities.push_back(toInequalityRow(tangents[j], dofOf));
        p.inequalities.back().key = tangentialKey(p.inequalities.back(), j);
      }
    }
  }
}

}  // namespace

ElasticContactProblem buildElasticContactProblem(const ElasticContactSpec& spec,
                                                 const tfeti::Comm& comm) {
  ElasticContactProblem p;
  // The problem's dimension is the mesh's (spec.meshOptions.dimension may demand one).
  p.mesh = loadMesh(spec.meshFile, spec.meshOptions);
  checkSpecAgainstMesh(spec, p.mesh, comm);
  partitionBodies(spec, p);
  findFirstCopies(p);
  const Supports supports = dirichletConditions(spec, p);
  addCouplings(spec, supports, comm, p);
  // The contact rows first: where they lie is part of the work the distribution balances.
  setUpContact(spec, comm, p);
  distributeToRanks(spec, comm, p);
  assembleLocalSubdomains(spec, supports, comm, p);
  return p;
}

std::vector<std::vector<double>> loadAt(const ElasticContactProblem& p, double t) {
  std::vector<std::vector<double>> f(p.local.size());
  for (std::size_t i = 0; i < p.local.size(); ++i) {
    f[i].resize(p.local[i].f.size());
    if (p.rampedLoads.empty()) {  // proportional loading: exactly t f, as it has always been
      for (std::size_t k = 0; k < f[i].size(); ++k) f[i][k] = t * p.local[i].f[k];
      continue;
    }
    for (std::size_t k = 0; k < f[i].size(); ++k) f[i][k] = t * p.proportionalLoad[i][k];
    for (const auto& r : p.rampedLoads) {
      const double s = r.ramp.factor(t);
      for (std::size_t k = 0; k < f[i].size(); ++k) f[i][k] += s * r.f[i][k];
    }
  }
  return f;
}

std::vector<double> appliedForceAt(const ElasticContactProblem& p, double t) {
  std::vector<double> F(p.appliedForce, p.appliedForce + p.dim());
  if (p.rampedLoads.empty()) {
    for (double& v : F) v *= t;
    return F;
  }
  for (int c = 0; c < p.dim(); ++c) {
    double rampedPart = 0.0, now = 0.0;
    for (const auto& r : p.rampedLoads) {
      rampedPart += r.force[c];
      now += r.ramp.factor(t) * r.force[c];
    }
    F[c] = t * (p.appliedForce[c] - rampedPart) + now;
  }
  return F;
}

std::vector<tfeti::EqualityRow> equalityRowsAt(const ElasticContactProblem& p, double t,
                                               const std::vector<std::vector<double>>& current) {
  std::vector<tfeti::EqualityRow> rows =
      prescribedDisplacementRows(p.local, p.prescribed, t, current);
  // The couplings hold from the start: an increment keeps the coupled values equal.
  rows.insert(rows.end(), p.couplingRows.begin(), p.couplingRows.end());
  return rows;
}

namespace {

// The rows of one pair; throws naming the pair when it has none.
NodeToSegmentResult pairRows(const ElasticContactProblem& p,
                             const ElasticContactProblem::Pair& pair,
                             const std::vector<double>& displacement) {
  NodeToSegmentResult r = pair.master->rows(p.mesh.coords, pair.slaveNodes, displacement);
  if (!r.rows.empty()) return r;
  const ContactPairSpec& ps = pair.spec;
  const std::string what =
      ps.master.empty() ? (ps.name.empty() ? std::string("the rigid obstacle (Contact problem/"
                                                         "Rigid obstacle: its Point or Centre, "
                                                         "Normal, Radius, Gap direction)")
                                           : "the rigid obstacle (" + ps.where +
                                                 "/Rigid obstacle: its Point or Centre, Normal, "
                                                 "Radius, Gap direction; or its Search radius)")
                        : "\"" + ps.master + "\"";
  throw std::invalid_argument((ps.name.empty() ? std::string() : ps.where + ": ") +
                              "no slave node of \"" + ps.slave +
                              "\" is within the search radius of " + what);
}

}  // namespace

void updateContact(ElasticContactProblem& p, const std::vector<double>& displacement, int rank) {
  const int dim = p.dim();
  if (p.pairs.size() == 1) {  // one pair: its rows as they have always been
    p.contact = pairRows(p, p.pairs.front(), displacement);
    p.rowPair.assign(p.contact.rows.size(), 0);
  } else {
    p.contact = NodeToSegmentResult();
    p.rowPair.clear();
    std::map<int, int> pairOfSlave;  // the one pair a slave node has rows in
    for (std::size_t k = 0; k < p.pairs.size(); ++k) {
      NodeToSegmentResult r = pairRows(p, p.pairs[k], displacement);
      for (const ContactRow& row : r.rows) {
        const auto [it, fresh] = pairOfSlave.emplace(row.slaveNode, static_cast<int>(k));
        if (!fresh) {
          std::ostringstream at;
          for (int c = 0; c < dim; ++c)
            at << (c ? ", " : "") << p.mesh.coords[dim * row.slaveNode + c];
          throw std::invalid_argument(
              "Contact problem/Contact pairs: the slave node at (" + at.str() + ") has rows in " +
              pairLabel(p.pairs[it->second].spec) + " and in " + pairLabel(p.pairs[k].spec) +
              "; a slave node may have rows in one pair only (their masters overlap within the "
              "Search radius: make the radii smaller or the slave surfaces disjoint)");
        }
      }
      p.contact.rows.insert(p.contact.rows.end(), r.rows.begin(), r.rows.end());
      p.rowPair.insert(p.rowPair.end(), r.rows.size(), static_cast<int>(k));
      p.contact.candidatePairs += r.candidatePairs;
      p.contact.allPairs += r.allPairs;
      p.contact.beyondRadius += r.beyondRadius;
      p.contact.beyondEnd += r.beyondEnd;
      p.contact.gridCells += r.gridCells;
      p.contact.cellSize = std::max(p.contact.cellSize, r.cellSize);
    }
  }
  setInequalitiesFromRows(p, rank);
}

void setInequalitiesFromRows(ElasticContactProblem& p, int rank) {
  const int dim = p.dim();
  auto dofOf = [&](int node, int component) {
    return std::make_pair(p.copyOf[node].first, dim * p.copyOf[node].second + component);
  };
  p.inequalities.clear();
  if (rank == 0)
    for (const auto& row : p.contact.rows) p.inequalities.push_back(toInequalityRow(row, dofOf));
}

std::vector<double> contactRowWeights(const ElasticContactProblem& p) {
  std::vector<std::map<int, double>> weight(p.pairs.size());
  for (std::size_t k = 0; k < p.pairs.size(); ++k)
    for (std::size_t i = 0; i < p.pairs[k].slaveNodes.size(); ++i)
      weight[k][p.pairs[k].slaveNodes[i]] = p.pairs[k].slaveWeights[i];
  std::vector<double> w;
  // A mortar row carries its own weight (the integral of its dual basis function).
  for (std::size_t r = 0; r < p.contact.rows.size(); ++r)
    w.push_back(p.contact.rows[r].weight > 0.0
                    ? p.contact.rows[r].weight
                    : weight[p.rowPair[r]].at(p.contact.rows[r].slaveNode));
  return w;
}

}  // namespace contact
