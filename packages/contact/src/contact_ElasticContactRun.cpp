// The driver's study for Problem = elastic_contact: bodies on a Gmsh mesh in frictionless
// contact, solved by TFETI with SMALBE (or the penalty method), compared with Hertz's line
// contact when asked.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <tuple>

#include "contact_DriverCommon.hpp"
#include "contact_ElasticContactProblem.hpp"
#include "contact_ElasticContactRun.hpp"
#include "plasticity_MaterialLaw.hpp"

namespace contact {

namespace {

using Teuchos::Array;
using Teuchos::ParameterList;

template <class T>
std::vector<T> vec(const Array<T>& a) {
  return std::vector<T>(a.begin(), a.end());
}

ElasticContactSpec specFrom(const ParameterList& params) {
  const auto& cp = params.sublist("Contact problem");
  const auto& mat = params.sublist("Material");
  ElasticContactSpec spec;
  spec.meshFile = cp.get<std::string>("Mesh file");
  if (spec.meshFile.empty())
    throw std::invalid_argument("Contact problem: \"Mesh file\" is required (a .geo or .msh)");
  spec.meshOptions.order = cp.get<int>("Element order");
  spec.meshOptions.quads = cp.get<bool>("Quadrilaterals");
  spec.meshOptions.sizeFactor = cp.get<double>("Mesh size factor");
  const auto bodies = vec(cp.get<Array<std::string>>("Bodies"));
  const auto counts = vec(cp.get<Array<int>>("Subdomains per body"));
  if (bodies.empty() || bodies.size() != counts.size())
    throw std::invalid_argument(
        "Contact problem: \"Bodies\" and \"Subdomains per body\" need one entry per body (got " +
        std::to_string(bodies.size()) + " and " + std::to_string(counts.size()) + ")");
  const plasticity::ElasticLaw law(mat.get<double>("Young's modulus"),
                                   mat.get<double>("Poisson's ratio"));
  for (std::size_t b = 0; b < bodies.size(); ++b)
    spec.bodies.push_back({bodies[b], counts[b], law});
  spec.fixed = vec(cp.get<Array<std::string>>("Fixed boundaries"));
  const auto sym = vec(cp.get<Array<std::string>>("Symmetry boundaries"));
  const auto comps = vec(cp.get<Array<int>>("Symmetry components"));
  if (sym.size() != comps.size())
    throw std::invalid_argument(
        "Contact problem: \"Symmetry components\" needs one component (0: x, 1: y) per entry of "
        "\"Symmetry boundaries\"");
  for (std::size_t k = 0; k < sym.size(); ++k) spec.symmetry.push_back({sym[k], comps[k]});
  const auto tb = vec(cp.get<Array<std::string>>("Traction boundaries"));
  const auto tv = vec(cp.get<Array<double>>("Tractions"));
  if (tv.size() != 2 * tb.size())
    throw std::invalid_argument(
        "Contact problem: \"Tractions\" needs 2 values {tx, ty} (force per unit length) per entry "
        "of \"Traction boundaries\"");
  for (std::size_t k = 0; k < tb.size(); ++k)
    spec.tractions.push_back({tb[k], {tv[2 * k], tv[2 * k + 1]}});
  spec.slave = cp.get<std::string>("Slave");
  spec.master = cp.get<std::string>("Master");
  spec.searchRadius = cp.get<double>("Search radius");
  spec.distribution = cp.get<std::string>("Subdomain distribution");
  return spec;
}

struct ContactNode {
  double x, y, lambda, pressure;
};

}  // namespace

void addElasticContactParameters(ParameterList& pl) {
  auto& cp = pl.sublist("Contact problem", false,
                        "Problem = elastic_contact: bodies on a Gmsh mesh in frictionless contact");
  cp.set("Mesh file", "",
         "a .geo file (meshed now) or a .msh file; a relative path is looked up next to the input "
         "file, then in the working directory");
  cp.set("Element order", 1, "1 or 2 (.geo only)");
  cp.set("Quadrilaterals", false, "recombine into quadrilaterals (.geo only)");
  cp.set("Mesh size factor", 1.0, "scales every mesh size (.geo only)");
  cp.set("Bodies", Array<std::string>(), "the 2D physical groups that are bodies");
  cp.set("Subdomains per body", Array<int>(), "METIS parts of each body");
  cp.set("Fixed boundaries", Array<std::string>(), "1D groups where u = 0");
  cp.set("Symmetry boundaries", Array<std::string>(), "1D groups with one component zero");
  cp.set("Symmetry components", Array<int>(), "the zero component (0: x, 1: y) of each");
  cp.set("Traction boundaries", Array<std::string>(), "1D groups under a constant traction");
  cp.set("Tractions", Array<double>(), "{tx, ty} per traction boundary (force per unit length)");
  cp.set("Slave", "", "the contact pair's slave boundary (its nodes)");
  cp.set("Master", "", "the contact pair's master boundary (its segments)");
  cp.set("Search radius", 0.0,
         "slave nodes farther from the master get no row; 0: a tenth of "
         "the mesh's extent");
  cp.set("Subdomain distribution", "graph",
         "graph: Zoltan2 (Scotch) on the subdomain adjacency, balancing dofs; block: contiguous "
         "blocks of subdomain ids",
         Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
             Teuchos::tuple<std::string>("graph", "block"), "Subdomain distribution")));
  auto& h = cp.sublist("Hertz", false, "compare with Hertz's line contact of two cylinders");
  h.set("Compare", false, "report Hertz's p_max and half-width and the errors");
  h.set("Radius 1", 1.0, "R1");
  h.set("Radius 2", 0.0, "R2; 0 means infinity (a flat body)");
  h.set("Line load", 0.0, "l, force per unit length of the full (not the half) model");
}

int runElasticContact(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                      const std::string& dir) {
  const bool root = comm->getRank() == 0;
  const ElasticContactSpec spec = specFrom(params);
  const int verbosity = params.sublist("Output").get<int>("Verbosity");
  ElasticContactProblem problem = buildElasticContactProblem(spec, *comm);
  tfeti::FetiSolver solver(comm, problem.numSubdomains(), problem.local, params.sublist("FETI"),
                           problem.inequalities);
  const tfeti::DualResult result = solver.solve();
  const tfeti::ConstraintReport report = solver.constraintReport();

  // Multipliers back to the slave nodes: the tearing numbers its rows canonically, so match
  // them to the node-to-segment rows by content.
  const auto lambdas = solver.inequalityMultipliers();
  std::map<std::tuple<std::vector<std::tuple<int, int, double>>, double>, double> byRow;
  const auto& rows = solver.tearing().inequalityRows;
  auto key = [](const tfeti::InequalityRow& r) {
    std::vector<std::tuple<int, int, double>> k;
    for (const auto& e : r.entries) k.emplace_back(e.subdomain, e.dof, e.coef);
    return std::make_tuple(k, r.gap);
  };
  for (std::size_t i = 0; i < rows.size(); ++i) byRow[key(rows[i])] = lambdas[i];
  std::map<int, std::size_t> slaveIndex;
  for (std::size_t k = 0; k < problem.slaveNodes.size(); ++k) slaveIndex[problem.slaveNodes[k]] = k;
  std::vector<int> copySub(problem.mesh.numNodes(), -1), copyLocal(problem.mesh.numNodes(), -1);
  for (const auto& s : problem.subdomains)
    for (int n = 0; n < s.numNodes(); ++n)
      if (copySub[s.globalNode[n]] < 0)
        copySub[s.globalNode[n]] = s.id, copyLocal[s.globalNode[n]] = n;
  std::vector<ContactNode> nodes;
  double force = 0.0;
  for (const auto& row : problem.contact.rows) {
    const auto ineq = toInequalityRow(
        row, [&](int n, int c) { return std::make_pair(copySub[n], 2 * copyLocal[n] + c); });
    const double lambda = byRow.at(key(ineq));
    const double w = problem.slaveWeights[slaveIndex.at(row.slaveNode)];
    const double x = problem.mesh.coords[2 * row.slaveNode],
                 y = problem.mesh.coords[2 * row.slaveNode + 1];
    nodes.push_back({x, y, lambda, w > 0.0 ? lambda / w : 0.0});
    force += lambda;
  }
  std::sort(nodes.begin(), nodes.end(),
            [](const ContactNode& a, const ContactNode& b) { return a.x < b.x; });
  double pMax = 0.0, halfWidth = 0.0;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    pMax = std::max(pMax, nodes[k].pressure);
    // The contact ends between the outermost loaded node and the next one.
    if (nodes[k].lambda > 0.0)
      halfWidth = k + 1 < nodes.size() ? 0.5 * (nodes[k].x + nodes[k + 1].x) : nodes[k].x;
  }

  // Stresses per subdomain (nodal values averaged within the subdomain).
  double maxVm = 0.0;
  VtuPiece piece;
  VtuField disp{"displacement", 3, {}}, sxx{"sxx", 1, {}}, syy{"syy", 1, {}}, sxy{"sxy", 1, {}},
      vm{"von_mises", 1, {}}, sub{"subdomain", 1, {}};
  for (std::size_t i = 0; i < problem.local.size(); ++i) {
    const auto& em = problem.localElements[i];
    const auto& u = solver.solution(i);
    const plasticity::LinearElasticMaterial law(spec.bodies[problem.localBody[i]].law);
    const auto stress = plasticity::recoverStresses(em, law, u);
    for (int e = 0; e < em.numElements(); ++e)
      for (int q = 0; q < stress.gaussPointsPerElement; ++q)
        maxVm = std::max(maxVm, stress.atGaussPoint(e, q, plasticity::kVonMises));
    const int base = static_cast<int>(piece.points.size() / 2);
    piece.points.insert(piece.points.end(), em.coords.begin(), em.coords.end());
    int vtkType = kVtkTriangle;
    switch (em.type) {
      case plasticity::ElementType::Tri3:
        vtkType = kVtkTriangle;
        break;
      case plasticity::ElementType::Quad4:
        vtkType = kVtkQuad;
        break;
      case plasticity::ElementType::Tri6:
        vtkType = kVtkQuadraticTriangle;
        break;
      case plasticity::ElementType::Quad9:
        vtkType = kVtkBiquadraticQuad;
        break;
    }
    for (int e = 0; e < em.numElements(); ++e) piece.cellTypes.push_back(vtkType);
    for (int c : em.connectivity) piece.cellPoints.push_back(base + c);
    for (int n = 0; n < em.numNodes(); ++n) {
      disp.values.insert(disp.values.end(), {u[2 * n], u[2 * n + 1], 0.0});
      sxx.values.push_back(stress.atNode(n, plasticity::kSxx));
      syy.values.push_back(stress.atNode(n, plasticity::kSyy));
      sxy.values.push_back(stress.atNode(n, plasticity::kSxy));
      vm.values.push_back(stress.atNode(n, plasticity::kVonMises));
    }
    sub.values.insert(sub.values.end(), em.numElements(), problem.local[i].mesh.id);
  }
  double globalVm = 0.0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &maxVm, &globalVm);
  piece.pointData = {disp, sxx, syy, sxy, vm};
  piece.cellData = {sub};

  Json s = Json::object();
  s["study"] = "single";
  s["problem"] = "elastic_contact";
  s["ranks"] = comm->getSize();
  s["subdomains"] = problem.numSubdomains();
  s["nodes"] = problem.mesh.numNodes();
  addSolverSummary(s, solver, result, params.sublist("FETI"));
  s["qp"] = qpJson(result);
  const double applied = std::hypot(problem.appliedForce[0], problem.appliedForce[1]);
  Json c = constraintJson(report);
  c["p_max"] = pMax;
  c["half_width"] = halfWidth;
  c["force"] = force;
  c["applied_force"] = applied;
  c["force_relative_error"] = applied > 0.0 ? std::abs(force - applied) / applied : 0.0;
  const auto& hz = params.sublist("Contact problem").sublist("Hertz");
  if (hz.get<bool>("Compare")) {
    const auto& mat = params.sublist("Material");
    const double E = mat.get<double>("Young's modulus"), nu = mat.get<double>("Poisson's ratio");
    const double R1 = hz.get<double>("Radius 1"), R2 = hz.get<double>("Radius 2");
    const double R = R2 > 0.0 ? R1 * R2 / (R1 + R2) : R1;
    const double Estar = 1.0 / (2.0 * (1.0 - nu * nu) / E);
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
  s["contact"] = std::move(c);
  s["max_von_mises"] = globalVm;
  s["max_abs_u"] = maxAbsSolution(*comm, solver);
  s["timings"] = timingsJson(solver.timings(), result.iterations);
  s["peak_rss_mb"] = peakRssMb(*comm);
  if (root) {
    std::ofstream csv(dir + "/contact_pressure.csv");
    if (!csv) throw std::runtime_error("cannot write " + dir + "/contact_pressure.csv");
    csv << "x,y,lambda,pressure\n" << std::setprecision(12);
    for (const auto& n : nodes)
      csv << n.x << "," << n.y << "," << n.lambda << "," << n.pressure << "\n";
  }
  s["contact_csv"] = dir + "/contact_pressure.csv";
  if (params.sublist("Output").get<bool>("VTU")) s["vtu"] = writeVtu(*comm, dir, "solution", piece);
  writeSummary(*comm, dir, s);
  if (root && verbosity > 0)
    std::cout << "elastic_contact: " << problem.numSubdomains() << " subdomains, primal "
              << solver.primalDimension() << ", dual " << solver.dualDimension() << " ("
              << solver.inequalityRows() << " contact rows), " << result.method << ": "
              << result.qp.hessianMultiplications << " Hessian multiplications ("
              << (result.converged ? "converged" : "NOT CONVERGED") << "); p_max " << pMax
              << ", half-width " << halfWidth << ", force " << force << " (applied " << applied
              << "), max von Mises " << globalVm << "\n";
  if (!result.converged && root)
    std::cerr << "tfeti_contact: " << result.method << " did not converge (" << result.qp.message
              << "); results written to " << dir << "\n";
  return result.converged ? 0 : 2;
}

}  // namespace contact
