#include "contact_ContactOutput.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <stdexcept>
#include <tuple>

namespace contact {

std::vector<ContactNode> contactNodes(const ElasticContactProblem& problem,
                                      const tfeti::FetiSolver& solver,
                                      const ContactExtentRule& rule,
                                      const std::vector<double>& surfaceDisplacement) {
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
  std::map<int, std::size_t> slaveIndex;
  for (std::size_t k = 0; k < problem.slaveNodes.size(); ++k) slaveIndex[problem.slaveNodes[k]] = k;
  auto dofOf = [&](int n, int c) {
    return std::make_pair(problem.copyOf[n].first, 2 * problem.copyOf[n].second + c);
  };
  std::vector<ContactNode> nodes;
  for (const auto& row : problem.contact.rows) {
    const double lambda = byRow.at(key(toInequalityRow(row, dofOf)));
    const double w = problem.slaveWeights[slaveIndex.at(row.slaveNode)];
    double x = problem.mesh.coords[2 * row.slaveNode],
           y = problem.mesh.coords[2 * row.slaveNode + 1];
    if (!surfaceDisplacement.empty()) {
      x += surfaceDisplacement[2 * row.slaveNode];
      y += surfaceDisplacement[2 * row.slaveNode + 1];
    }
    const double rx = x - rule.centre[0], ry = y - rule.centre[1];
    const double d0 = rule.direction[0], d1 = rule.direction[1];
    // Signed angle from the direction to the node, counter-clockwise positive (towards +x for
    // the default direction (0, -1)).
    const double angle = std::atan2(d0 * ry - d1 * rx, d0 * rx + d1 * ry) * 180.0 / M_PI;
    nodes.push_back(
        {x, y, lambda, w > 0.0 ? lambda / w : 0.0, angle, {row.normal[0], row.normal[1]}});
  }
  std::sort(nodes.begin(), nodes.end(), [&](const ContactNode& a, const ContactNode& b) {
    return rule.angle ? a.angle < b.angle : a.x < b.x;
  });
  return nodes;
}

double maxPressure(const std::vector<ContactNode>& nodes) {
  double p = 0.0;
  for (const auto& n : nodes) p = std::max(p, n.pressure);
  return p;
}

double resultantForce(const std::vector<ContactNode>& nodes, const double direction[2]) {
  double f = 0.0;
  for (const auto& n : nodes)
    f += n.lambda * (n.normal[0] * direction[0] + n.normal[1] * direction[1]);
  return std::abs(f);
}

double contactExtent(const std::vector<ContactNode>& nodes, const ContactExtentRule& rule) {
  double extent = 0.0;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    if (!(nodes[k].lambda > 0.0)) continue;
    const double here = rule.angle ? std::abs(nodes[k].angle) : std::abs(nodes[k].x);
    double next = here;
    // The zone ends between the outermost loaded node and its unloaded neighbour outwards.
    if (k + 1 < nodes.size() && !(nodes[k + 1].lambda > 0.0))
      next = rule.angle ? std::abs(nodes[k + 1].angle) : std::abs(nodes[k + 1].x);
    extent = std::max(extent, 0.5 * (here + next));
  }
  return extent;
}

void writeContactCsv(const tfeti::Comm& comm, const std::string& path,
                     const std::vector<ContactNode>& nodes) {
  if (comm.getRank() != 0) return;
  std::ofstream csv(path);
  if (!csv) throw std::runtime_error("cannot write " + path);
  csv << "x,y,lambda,pressure,angle\n" << std::setprecision(12);
  for (const auto& n : nodes)
    csv << n.x << "," << n.y << "," << n.lambda << "," << n.pressure << "," << n.angle << "\n";
}

void addHertzComparison(Json& c, const Teuchos::ParameterList& params, double pMax,
                        double halfWidth) {
  const auto& hz = params.sublist("Contact problem").sublist("Hertz");
  if (!hz.get<bool>("Compare")) return;
  const auto& mat = params.sublist("Material");
  const double E = mat.get<double>("Young's modulus"), nu = mat.get<double>("Poisson's ratio");
  const double R1 = hz.get<double>("Radius 1"), R2 = hz.get<double>("Radius 2");
  const double R = R2 > 0.0 ? R1 * R2 / (R1 + R2) : R1;
  // Two bodies of one material: 1/E* = 2 (1 - nu^2) / E; against a rigid obstacle the body's
  // compliance alone: E* = E / (1 - nu^2).
  const auto& cp = params.sublist("Contact problem");
  const bool rigid = cp.isSublist("Rigid obstacle") &&
                     cp.sublist("Rigid obstacle").isParameter("Type") &&
                     cp.sublist("Rigid obstacle").get<std::string>("Type") != "none";
  const double Estar = E / ((rigid ? 1.0 : 2.0) * (1.0 - nu * nu));
  const double l = hz.get<double>("Line load");
  const double a = std::sqrt(4.0 * l * R / (M_PI * Estar));
  const double p0 = 2.0 * l / (M_PI * a);
  Json h = Json::object();
  h["p_max"] = p0;
  h["half_width"] = a;
  h["max_von_mises"] = 0.557 * p0;  // Hertz line contact, nu = 0.3, at depth 0.78 a
  c["hertz"] = std::move(h);
  Json err = Json::object();
  err["p_max"] = std::abs(pMax - p0) / p0;
  err["half_width"] = std::abs(halfWidth - a) / a;
  c["relative_error"] = std::move(err);
}

int vtkCellType(plasticity::ElementType type) {
  switch (type) {
    case plasticity::ElementType::Tri3:
      return kVtkTriangle;
    case plasticity::ElementType::Quad4:
      return kVtkQuad;
    case plasticity::ElementType::Tri6:
      return kVtkQuadraticTriangle;
    case plasticity::ElementType::Quad9:
      return kVtkBiquadraticQuad;
    default:  // 3D cells need their VTK node permutations first (Tet10, Hex27 differ from Gmsh)
      break;
  }
  throw std::invalid_argument("vtkCellType: no VTK cell for " +
                              plasticity::elementTypeName(type));
}

VtuPiece stressPiece(const std::vector<SubdomainFields>& subdomains,
                     const std::vector<std::string>& extraNames) {
  VtuPiece piece;
  VtuField disp{"displacement", 3, {}}, sxx{"sxx", 1, {}}, syy{"syy", 1, {}}, sxy{"sxy", 1, {}},
      vm{"von_mises", 1, {}}, sub{"subdomain", 1, {}};
  std::vector<VtuField> extra;
  for (const auto& name : extraNames) extra.push_back({name, 1, {}});
  for (const auto& s : subdomains) {
    const auto& em = *s.mesh;
    const auto& u = *s.displacement;
    const int base = static_cast<int>(piece.points.size() / 2);
    piece.points.insert(piece.points.end(), em.coords.begin(), em.coords.end());
    piece.cellTypes.insert(piece.cellTypes.end(), em.numElements(), vtkCellType(em.type));
    for (int c : em.connectivity) piece.cellPoints.push_back(base + c);
    for (int n = 0; n < em.numNodes(); ++n) {
      disp.values.insert(disp.values.end(), {u[2 * n], u[2 * n + 1], 0.0});
      sxx.values.push_back(s.stress->atNode(n, plasticity::kSxx));
      syy.values.push_back(s.stress->atNode(n, plasticity::kSyy));
      sxy.values.push_back(s.stress->atNode(n, plasticity::kSxy));
      vm.values.push_back(s.stress->atNode(n, plasticity::kVonMises));
    }
    if (s.extra.size() != extra.size())
      throw std::invalid_argument("stressPiece: subdomain " + std::to_string(s.id) + " has " +
                                  std::to_string(s.extra.size()) + " extra fields, expected " +
                                  std::to_string(extra.size()));
    for (std::size_t k = 0; k < extra.size(); ++k)
      extra[k].values.insert(extra[k].values.end(), s.extra[k].begin(), s.extra[k].end());
    sub.values.insert(sub.values.end(), em.numElements(), s.id);
  }
  piece.pointData = {disp, sxx, syy, sxy, vm};
  piece.pointData.insert(piece.pointData.end(), extra.begin(), extra.end());
  piece.cellData = {sub};
  return piece;
}

}  // namespace contact
