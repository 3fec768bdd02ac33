#include "contact_ContactOutput.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "contact_Friction.hpp"
#include "contact_Materials.hpp"

namespace contact {

std::vector<ContactNode> contactNodes(const ElasticContactProblem& problem,
                                      const tfeti::FetiSolver& solver,
                                      const ContactExtentRule& rule,
                                      const std::vector<double>& surfaceDisplacement,
                                      const std::vector<double>& surfaceSolution) {
  // The tearing numbers its rows canonically: match them to the node-to-segment rows by content.
  const auto lambdas = solver.inequalityMultipliers();
  using Key = std::tuple<std::vector<std::tuple<int, int, double>>, double>;
  std::map<Key, double> byRow;
  auto key = [](const tfeti::InequalityRow& r) {
    std::vector<std::tuple<int, int, double>> k;
    for (const auto& e : r.entries) k.emplace_back(e.subdomain, e.dof, e.coef);
    return Key(k, r.gap);
  };
  const auto& rows = solver.tearing().inequalityRows;
  for (std::size_t i = 0; i < rows.size(); ++i) byRow[key(rows[i])] = lambdas[i];
  const std::vector<double> weights = contactRowWeights(problem);
  const int dim = problem.dim();
  auto dofOf = [&](int n, int c) {
    return std::make_pair(problem.copyOf[n].first, dim * problem.copyOf[n].second + c);
  };
  std::vector<ContactNode> nodes;
  for (std::size_t k = 0; k < problem.contact.rows.size(); ++k) {
    const ContactRow& row = problem.contact.rows[k];
    const double lambda = byRow.at(key(toInequalityRow(row, dofOf)));
    const double w = weights[k];
    double x[3] = {0.0, 0.0, 0.0};
    for (int c = 0; c < dim; ++c) {
      x[c] = problem.mesh.coords[dim * row.slaveNode + c];
      if (!surfaceDisplacement.empty()) x[c] += surfaceDisplacement[dim * row.slaveNode + c];
    }
    const double rx = x[0] - rule.centre[0], ry = x[1] - rule.centre[1];
    const double d0 = rule.direction[0], d1 = rule.direction[1];
    // Signed angle from the direction to the node, counter-clockwise positive (towards +x for
    // the default direction (0, -1)).
    const double angle = std::atan2(d0 * ry - d1 * rx, d0 * rx + d1 * ry) * 180.0 / M_PI;
    double radius = 0.0;
    if (dim == 3) {
      const double r[3] = {rx, ry, x[2] - rule.centre[2]};
      const double along = r[0] * rule.axis[0] + r[1] * rule.axis[1] + r[2] * rule.axis[2];
      double r2 = 0.0;
      for (int c = 0; c < 3; ++c)
        r2 += (r[c] - along * rule.axis[c]) * (r[c] - along * rule.axis[c]);
      radius = std::sqrt(r2);
    }
    double gap = row.gap;  // the row is sum coef u <= gap
    if (!surfaceSolution.empty())
      for (const NodeEntry& e : row.entries)
        gap -= e.coef * surfaceSolution[dim * e.node + e.component];
    nodes.push_back({x[0],
                     x[1],
                     x[2],
                     lambda,
                     w > 0.0 ? lambda / w : 0.0,
                     angle,
                     radius,
                     {row.normal[0], row.normal[1], row.normal[2]},
                     gap});
    nodes.back().slaveNode = row.slaveNode;
    if (problem.namedPairs) nodes.back().pair = problem.rowPair[k];
  }
  std::sort(nodes.begin(), nodes.end(), [&](const ContactNode& a, const ContactNode& b) {
    if (dim == 3) return a.radius < b.radius;
    return rule.angle ? a.angle < b.angle : a.x < b.x;
  });
  return nodes;
}

double maxPressure(const std::vector<ContactNode>& nodes) {
  double p = 0.0;
  for (const auto& n : nodes) p = std::max(p, n.pressure);
  return p;
}

double resultantForce(const std::vector<ContactNode>& nodes, const double direction[], int dim) {
  double f = 0.0;
  // A node with friction rows: its whole force, so that a load friction carries (a block pushed
  // along the surface) is part of the resultant.
  for (const auto& n : nodes)
    for (int c = 0; c < dim; ++c)
      f += (n.frictionState >= 0 ? n.force[c] : n.lambda * n.normal[c]) * direction[c];
  return std::abs(f);
}

namespace {

// Between the outermost loaded node and its unloaded neighbour outwards, the nodes sorted by
// `measure` (the contact zone's distance from its centre).
template <class Measure>
double extentOfSorted(const std::vector<const ContactNode*>& nodes, Measure measure) {
  double extent = 0.0;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    if (!(nodes[k]->lambda > 0.0)) continue;
    const double here = measure(*nodes[k]);
    double next = here;
    if (k + 1 < nodes.size() && !(nodes[k + 1]->lambda > 0.0)) next = measure(*nodes[k + 1]);
    extent = std::max(extent, 0.5 * (here + next));
  }
  return extent;
}

}  // namespace

double contactExtent(const std::vector<ContactNode>& nodes, const ContactExtentRule& rule,
                     int dim) {
  if (dim == 3 && rule.line) {
    const auto planes = halfWidthPerPlane(nodes);
    double sum = 0.0;
    for (const auto& p : planes) sum += p.halfWidth;
    return planes.empty() ? 0.0 : sum / static_cast<double>(planes.size());
  }
  std::vector<const ContactNode*> sorted;
  for (const auto& n : nodes) sorted.push_back(&n);
  return extentOfSorted(sorted, [&](const ContactNode& n) {
    return dim == 3 ? n.radius : rule.angle ? std::abs(n.angle) : std::abs(n.x);
  });
}

std::vector<PlaneHalfWidth> halfWidthPerPlane(const std::vector<ContactNode>& nodes) {
  std::vector<const ContactNode*> byZ;
  for (const auto& n : nodes) byZ.push_back(&n);
  std::sort(byZ.begin(), byZ.end(),
            [](const ContactNode* a, const ContactNode* b) { return a->z < b->z; });
  std::vector<PlaneHalfWidth> planes;
  if (byZ.empty()) return planes;
  const double tol = 1e-9 * (byZ.back()->z - byZ.front()->z);
  const auto across = [](const ContactNode& n) { return std::abs(n.x); };
  for (std::size_t first = 0; first < byZ.size();) {
    std::size_t end = first + 1;
    while (end < byZ.size() && byZ[end]->z - byZ[end - 1]->z <= tol) ++end;
    std::vector<const ContactNode*> plane(byZ.begin() + first, byZ.begin() + end);
    std::sort(plane.begin(), plane.end(),
              [&](const ContactNode* a, const ContactNode* b) { return across(*a) < across(*b); });
    planes.push_back(
        {plane.front()->z, static_cast<int>(plane.size()), extentOfSorted(plane, across)});
    first = end;
  }
  return planes;
}

void writeContactCsv(const tfeti::Comm& comm, const std::string& path,
                     const std::vector<ContactNode>& nodes, int dim) {
  if (comm.getRank() != 0) return;
  std::ofstream csv(path);
  if (!csv) throw std::runtime_error("cannot write " + path);
  // Friction adds its columns; a frictionless run's file is unchanged.
  const bool friction = std::any_of(nodes.begin(), nodes.end(),
                                    [](const ContactNode& n) { return n.frictionState >= 0; });
  const bool pairs = !nodes.empty() && nodes.front().pair >= 0;
  csv << (dim == 3 ? "x,y,z,lambda,pressure,radius" : "x,y,lambda,pressure,angle")
      << (friction ? ",tangential_force,tangential_traction,slip_increment,state,accumulated_slip,"
                     "net_slip,node,force_x,force_y"
                   : "")
      << (friction && dim == 3 ? ",force_z" : "") << (pairs ? ",pair" : "")
      << ",pressure_recovered\n"
      << std::setprecision(12);
  for (const auto& n : nodes) {
    csv << n.x << "," << n.y << ",";
    if (dim == 3) csv << n.z << ",";
    csv << n.lambda << "," << n.pressure << "," << (dim == 3 ? n.radius : n.angle);
    if (friction)
      csv << "," << n.tangentialForce << "," << n.tangentialTraction << "," << n.slip << ","
          << frictionStateName(n.frictionState) << "," << n.accumulatedSlip << "," << n.netSlip
          << "," << n.slaveNode;
    if (friction)
      for (int c = 0; c < dim; ++c) csv << "," << n.force[c];
    if (pairs) csv << "," << n.pair;
    csv << "," << n.pressureRecovered << "\n";
  }
}

namespace {

// The largest von Mises stress under a Hertz point contact: on the axis (where it peaks for
// nu = 0.3) sigma_z = -p0 / (1 + s^2), sigma_r = -p0 [(1 + nu)(1 - s atan(1/s)) - 1 / (2 (1 +
// s^2))] at depth s a, von Mises |sigma_r - sigma_z|, maximized over a fine grid of depths.
double hertzSphereMaxVonMises(double p0, double nu) {
  double best = 0.0;
  for (int k = 1; k <= 30000; ++k) {
    const double s = 1e-4 * k;
    const double sz = -p0 / (1 + s * s);
    const double sr = -p0 * ((1 + nu) * (1 - s * std::atan(1 / s)) - 0.5 / (1 + s * s));
    best = std::max(best, std::abs(sr - sz));
  }
  return best;
}

}  // namespace

bool lineContact(const Teuchos::ParameterList& params, int dim) {
  const auto& cp = params.sublist("Contact problem");
  const std::string zone =
      cp.isParameter("Contact zone") ? cp.get<std::string>("Contact zone") : "auto";
  if (zone == "point" && dim == 2)
    throw std::invalid_argument(
        "Contact problem: \"Contact zone\" = point needs a 3D mesh (a 2D contact is a line "
        "contact: auto or line)");
  return zone == "line" || (zone == "auto" && dim == 2);
}

void checkHertzInput(const Teuchos::ParameterList& params, int dim,
                     const std::vector<plasticity::ElasticLaw>& contactLaws) {
  const auto& hz = params.sublist("Contact problem").sublist("Hertz");
  if (!hz.get<bool>("Compare")) return;
  if (contactLaws.empty())
    throw std::invalid_argument(
        "Contact problem/Hertz: the Slave boundary lies on no body of Contact problem/Bodies; "
        "Hertz needs the materials of the bodies in contact");
  const bool line = lineContact(params, dim);
  const char* load = line ? "Line load" : "Force";
  if (!(hz.get<double>(load) > 0.0)) {
    std::ostringstream msg;
    msg << "Contact problem/Hertz: \"Compare\" = true needs \"" << load << "\" > 0 ("
        << (line ? "the line contact's force per unit length" : "the point contact's total force")
        << " of the full model), not " << hz.get<double>(load);
    throw std::invalid_argument(msg.str());
  }
}

std::optional<HertzReference> hertzReference(
    const Teuchos::ParameterList& params, double pMax, double extent, int dim,
    const std::vector<plasticity::ElasticLaw>& contactLaws) {
  const auto& hz = params.sublist("Contact problem").sublist("Hertz");
  if (!hz.get<bool>("Compare")) return std::nullopt;
  checkHertzInput(params, dim, contactLaws);
  const double R1 = hz.get<double>("Radius 1"), R2 = hz.get<double>("Radius 2");
  const double R = R2 > 0.0 ? R1 * R2 / (R1 + R2) : R1;
  // Two bodies: 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2; against a rigid obstacle the body's
  // compliance alone: E* = E / (1 - nu^2).
  const double Estar = combinedModulus(contactLaws);
  HertzReference h;
  h.line = lineContact(params, dim);
  if (!h.line) {
    // Point contact: a = (3 F R / (4 E*))^(1/3), p0 = 3 F / (2 pi a^2).
    const double F = hz.get<double>("Force");
    h.extent = std::cbrt(3.0 * F * R / (4.0 * Estar));
    h.pMax = 3.0 * F / (2.0 * M_PI * h.extent * h.extent);
    // Each body has its own stress field under the common pressure: the larger peak.
    for (const auto& law : contactLaws)
      h.maxVonMises = std::max(h.maxVonMises, hertzSphereMaxVonMises(h.pMax, law.nu));
  } else {
    const double l = hz.get<double>("Line load");
    h.extent = std::sqrt(4.0 * l * R / (M_PI * Estar));
    h.pMax = 2.0 * l / (M_PI * h.extent);
    h.maxVonMises = 0.557 * h.pMax;  // Hertz line contact, nu = 0.3, at depth 0.78 a
  }
  h.pMaxError = std::abs(pMax - h.pMax) / h.pMax;
  h.extentError = std::abs(extent - h.extent) / h.extent;
  return h;
}

void addRecoveredErrors(HertzReference& hertz, double pMaxRecovered, double maxVonMises,
                        double maxVonMisesNodal) {
  hertz.pMaxRecoveredError = std::abs(pMaxRecovered - hertz.pMax) / hertz.pMax;
  hertz.maxVonMisesError = std::abs(maxVonMises - hertz.maxVonMises) / hertz.maxVonMises;
  hertz.maxVonMisesNodalError = std::abs(maxVonMisesNodal - hertz.maxVonMises) / hertz.maxVonMises;
}

void addHertzComparison(Json& c, const HertzReference& hertz) {
  const char* extent = hertz.line ? "half_width" : "contact_radius";
  Json h = Json::object();
  h["p_max"] = hertz.pMax;
  h[extent] = hertz.extent;
  h["max_von_mises"] = hertz.maxVonMises;
  c["hertz"] = std::move(h);
  Json err = Json::object();
  err["p_max"] = hertz.pMaxError;
  err[extent] = hertz.extentError;
  err["p_max_recovered"] = hertz.pMaxRecoveredError;
  err["max_von_mises"] = hertz.maxVonMisesError;
  err["max_von_mises_nodal"] = hertz.maxVonMisesNodalError;
  c["relative_error"] = std::move(err);
}

VtuPiece stressPiece(const std::vector<SubdomainFields>& subdomains,
                     const std::vector<std::string>& extraNames) {
  VtuPiece piece;
  const int dim = subdomains.empty() ? 2 : subdomains.front().mesh->dim();
  piece.dim = dim;
  // The stress components written: the in-plane ones in 2D, all six in 3D; then von Mises.
  const std::vector<std::pair<const char*, int>> components =
      dim == 3 ? std::vector<std::pair<const char*, int>>{{"sxx", plasticity::kSxx},
                                                          {"syy", plasticity::kSyy},
                                                          {"szz", plasticity::kSzz},
                                                          {"syz", plasticity::kSyz},
                                                          {"sxz", plasticity::kSxz},
                                                          {"sxy", plasticity::kSxy},
                                                          {"von_mises", plasticity::kVonMises}}
               : std::vector<std::pair<const char*, int>>{{"sxx", plasticity::kSxx},
                                                          {"syy", plasticity::kSyy},
                                                          {"sxy", plasticity::kSxy},
                                                          {"von_mises", plasticity::kVonMises}};
  VtuField disp{"displacement", 3, {}}, sub{"subdomain", 1, {}};
  std::vector<VtuField> stress;
  for (const auto& [name, c] : components) stress.push_back({name, 1, {}});
  std::vector<VtuField> extra;
  for (const auto& name : extraNames) extra.push_back({name, 1, {}});
  for (const auto& s : subdomains) {
    const auto& em = *s.mesh;
    if (em.dim() != dim)
      throw std::invalid_argument("stressPiece: subdomain " + std::to_string(s.id) + " is " +
                                  std::to_string(em.dim()) + "D, the others " +
                                  std::to_string(dim) + "D");
    const auto& u = *s.displacement;
    const int base = static_cast<int>(piece.points.size() / dim);
    piece.points.insert(piece.points.end(), em.coords.begin(), em.coords.end());
    piece.cellTypes.insert(piece.cellTypes.end(), em.numElements(), plasticity::vtkType(em.type));
    const std::vector<int>& order = plasticity::vtkNodeOrder(em.type);
    const int npe = plasticity::nodesPerElement(em.type);
    for (int e = 0; e < em.numElements(); ++e)
      for (int k = 0; k < npe; ++k)
        piece.cellPoints.push_back(base +
                                   em.connectivity[static_cast<std::size_t>(e) * npe + order[k]]);
    for (int n = 0; n < em.numNodes(); ++n) {
      for (int c = 0; c < 3; ++c) disp.values.push_back(c < dim ? u[dim * n + c] : 0.0);
      for (std::size_t k = 0; k < components.size(); ++k)
        stress[k].values.push_back(s.stress->atNode(n, components[k].second));
    }
    if (s.extra.size() != extra.size())
      throw std::invalid_argument("stressPiece: subdomain " + std::to_string(s.id) + " has " +
                                  std::to_string(s.extra.size()) + " extra fields, expected " +
                                  std::to_string(extra.size()));
    for (std::size_t k = 0; k < extra.size(); ++k)
      extra[k].values.insert(extra[k].values.end(), s.extra[k].begin(), s.extra[k].end());
    sub.values.insert(sub.values.end(), em.numElements(), s.id);
  }
  piece.pointData = {disp};
  piece.pointData.insert(piece.pointData.end(), stress.begin(), stress.end());
  piece.pointData.insert(piece.pointData.end(), extra.begin(), extra.end());
  piece.cellData = {sub};
  return piece;
}

std::vector<double> contactPairField(const std::vector<ContactNode>& nodes,
                                     const std::vector<tfeti::GO>& globalNode) {
  std::map<tfeti::GO, int> pairOf;
  for (const auto& n : nodes) pairOf[n.slaveNode] = n.pair;
  std::vector<double> f(globalNode.size(), -1.0);
  for (std::size_t k = 0; k < globalNode.size(); ++k) {
    const auto it = pairOf.find(globalNode[k]);
    if (it != pairOf.end()) f[k] = it->second;
  }
  return f;
}

std::vector<PairForce> pairForces(const ElasticContactProblem& problem,
                                  const std::vector<ContactNode>& nodes) {
  const int dim = problem.dim();
  std::vector<PairForce> out;
  for (const auto& pair : problem.pairs)
    out.push_back({pair.spec.name, pair.spec.discretization, 0.0, std::vector<double>(dim, 0.0)});
  for (const auto& n : nodes) {
    if (n.pair < 0) continue;
    // With friction on the node its force holds the tangential part too.
    const bool full = n.frictionState >= 0;
    for (int c = 0; c < dim; ++c)
      out[n.pair].vector[c] += full ? n.force[c] : n.lambda * n.normal[c];
  }
  for (auto& p : out) {
    double s = 0.0;
    for (double v : p.vector) s += v * v;
    p.force = std::sqrt(s);
  }
  return out;
}

}  // namespace contact
