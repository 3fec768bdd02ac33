// The driver's two-membrane studies: one solve with VTU, contact CSV and summary.json, and the
// scalability table (Hessian multiplications over H and H/h for each dual QP solver).
#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "contact_DriverCommon.hpp"
#include "contact_DryRun.hpp"
#include "contact_TwoMembranes.hpp"
#include "tfeti_Gather.hpp"

namespace contact {

namespace {

using Teuchos::Array;
using Teuchos::ParameterList;

TwoMembranes membranesFrom(const ParameterList& params) {
  const auto& mesh = params.sublist("Mesh");
  if (!mesh.getEntry("Domain").isDefault())
    throw std::invalid_argument(
        "Mesh: \"Domain\" does not apply to Problem = two_membranes (the membranes are "
        "(0,1)x(0,1) and (1,2)x(0,1)); remove it");
  const auto subs = mesh.get<Array<int>>("Subdomains");
  const auto elems = mesh.get<Array<int>>("Elements per subdomain");
  if (subs.size() != 2 || elems.size() != 2)
    throw std::invalid_argument(
        "Mesh: \"Subdomains\" and \"Elements per subdomain\" take 2 values {x, y}");
  checkGridSize(mesh);
  TwoMembranes tm;
  tm.subdomainsX = subs[0], tm.subdomainsY = subs[1];
  tm.elementsX = elems[0], tm.elementsY = elems[1];
  tm.validate();
  return tm;
}

Json contactJson(const tfeti::ConstraintReport& c, double expectedForce) {
  Json j = constraintJson(c);
  j["force"] = c.force;
  j["expected_force"] = expectedForce;
  return j;
}

// Along x = 1: y, lambda, u1, u2 (rank 0 writes the gathered rows, sorted by y).
void writeContactCsv(const tfeti::Comm& comm, const tfeti::FetiSolver& solver,
                     const std::string& path) {
  const auto mult = solver.inequalityMultipliersOnSubdomains();
  std::vector<double> mine;  // y, side (0: Ω1, coef +1; 1: Ω2, coef -1), lambda, u
  for (std::size_t i = 0; i < mult.size(); ++i) {
    const auto& mesh = solver.data()[i].mesh;
    for (const auto& e : mult[i])
      mine.insert(mine.end(), {mesh.coords[2 * e.dof + 1], e.coef > 0.0 ? 0.0 : 1.0, e.lambda,
                               solver.solution(i)[e.dof]});
  }
  const std::vector<double> all = tfeti::allGather(comm, mine);
  if (comm.getRank() != 0) return;
  std::map<double, std::array<double, 3>> rows;  // y -> lambda, u1, u2
  for (std::size_t k = 0; k + 3 < all.size(); k += 4) {
    auto& r = rows[all[k]];
    r[0] = all[k + 2];
    r[all[k + 1] == 0.0 ? 1 : 2] = all[k + 3];
  }
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << "y,lambda,u1,u2\n" << std::setprecision(12);
  for (const auto& [y, r] : rows) out << y << "," << r[0] << "," << r[1] << "," << r[2] << "\n";
}

VtuPiece membranePiece(const tfeti::FetiSolver& solver) {
  VtuPiece piece = vtuPiece(solver);
  // The contact multiplier at the contact nodes of both membranes (0 elsewhere).
  VtuField lambda{"contact_multiplier", 1, {}};
  const auto mult = solver.inequalityMultipliersOnSubdomains();
  for (std::size_t i = 0; i < solver.data().size(); ++i) {
    std::vector<double> values(solver.data()[i].mesh.numNodes(), 0.0);
    for (const auto& e : mult[i]) values[e.dof] = e.lambda;
    lambda.values.insert(lambda.values.end(), values.begin(), values.end());
  }
  piece.pointData.push_back(std::move(lambda));
  return piece;
}

struct MembraneRun {
  tfeti::DualResult result;
  tfeti::ConstraintReport contact;
  tfeti::FetiTimings timings;
  tfeti::GO primal = 0, dual = 0, gluing = 0, dirichlet = 0, contactRows = 0, coarse = 0;
};

}  // namespace

int runTwoMembranes(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                    const std::string& dir) {
  const bool root = comm->getRank() == 0;
  const TwoMembranes tm = membranesFrom(params);
  const auto& out = params.sublist("Output");
  const int verbosity = out.get<int>("Verbosity");
  ContactProblemData data = buildTwoMembranes(tm, *comm);
  tfeti::FetiSolver solver(comm, tm.numSubdomains(), std::move(data.local), params.sublist("FETI"),
                           data.inequalities);
  const tfeti::DualResult result = solver.solve();
  const tfeti::ConstraintReport contact = solver.constraintReport();

  Json s = Json::object();
  s["study"] = "single";
  s["problem"] = "two_membranes";
  s["ranks"] = comm->getSize();
  s["subdomains"] = tm.numSubdomains();
  s["elements"] = 2LL * tm.subdomainsX * tm.elementsX * tm.subdomainsY * tm.elementsY;
  s["H"] = 1.0 / tm.subdomainsX;
  s["h"] = 1.0 / (tm.subdomainsX * tm.elementsX);
  addSolverSummary(s, solver, result, params.sublist("FETI"));
  s["qp"] = qpJson(result);
  s["contact"] = contactJson(contact, tm.expectedContactForce());
  Json timings = timingsJson(solver.timings(), result.iterations);
  timings["per_multiplication_s"] =
      result.qp.hessianMultiplications > 0
          ? solver.timings().solve / static_cast<double>(result.qp.hessianMultiplications)
          : 0.0;
  s["timings"] = std::move(timings);
  s["peak_rss_mb"] = peakRssMb(*comm);
  double local[3] = {0.0, 0.0, 0.0}, global[3];  // sum of squares, max |u|, -min u
  for (std::size_t i = 0; i < solver.data().size(); ++i)
    for (double v : solver.solution(i)) {
      local[0] += v * v;
      local[1] = std::max(local[1], std::abs(v));
      local[2] = std::max(local[2], -v);
    }
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &local[0], &global[0]);
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 2, &local[1], &global[1]);
  s["solution_norm2"] = std::sqrt(global[0]);
  s["max_abs_u"] = global[1];
  s["min_u"] = -global[2];
  writeContactCsv(*comm, solver, dir + "/contact.csv");
  s["contact_csv"] = dir + "/contact.csv";
  if (out.get<bool>("VTU")) s["vtu"] = writeVtu(*comm, dir, "solution", membranePiece(solver));
  writeSummary(*comm, dir, s, params);
  if (root && verbosity > 0)
    std::cout << "two_membranes: " << tm.numSubdomains() << " subdomains, primal "
              << solver.primalDimension() << ", dual " << solver.dualDimension() << " ("
              << solver.inequalityRows() << " contact rows), " << result.method << ": "
              << result.qp.outerIterations << " outer iterations, "
              << result.qp.hessianMultiplications << " Hessian multiplications ("
              << (result.converged ? "converged" : "NOT CONVERGED") << "), contact force "
              << contact.force << " (expected " << tm.expectedContactForce() << "), setup "
              << solver.timings().setup() << " s, solve " << solver.timings().solve << " s\n";
  if (!result.converged && root)
    std::cerr << "tfeti_contact: " << result.method << " did not converge (" << result.qp.message
              << "); results written to " << dir << "\n";
  return result.converged ? 0 : 2;
}

int runTwoMembranesScalability(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                               const std::string& dir) {
  const bool root = comm->getRank() == 0;
  const auto& sc = params.sublist("Scalability");
  const auto Hinv = sc.get<Array<int>>("Subdomains per side");
  const auto ratios = sc.get<Array<int>>("H over h");
  const auto solvers = sc.get<Array<std::string>>("Dual solvers");
  bool allConverged = true;
  Json table = Json::array();
  if (root) {
    std::cout << std::left << std::setw(8) << "H" << std::setw(8) << "h" << std::right
              << std::setw(10) << "primal" << std::setw(9) << "dual";
    for (const auto& m : solvers) std::cout << std::setw(22) << (m + " outer/Hessian");
    std::cout << "\n";
  }
  for (int ratio : ratios)
    for (int hinv : Hinv) {
      TwoMembranes tm;
      tm.subdomainsX = tm.subdomainsY = hinv;
      tm.elementsX = tm.elementsY = ratio;
      tm.validate();
      Json row = Json::object();
      row["problem"] = "two_membranes";
      row["H_inverse"] = hinv;
      row["h_inverse"] = hinv * ratio;
      row["H_over_h"] = ratio;
      row["subdomains"] = tm.numSubdomains();
      Json bySolver = Json::object();
      std::ostringstream line;
      tfeti::GO primal = 0, dual = 0;
      for (const auto& method : solvers) {
        ContactProblemData data = buildTwoMembranes(tm, *comm);
        ParameterList feti = params.sublist("FETI");
        feti.set("Dual solver", method);
        tfeti::FetiSolver solver(comm, tm.numSubdomains(), std::move(data.local), feti,
                                 data.inequalities);
        const auto res = solver.solve();
        const auto contact = solver.constraintReport();
        allConverged &= res.converged;
        Json j = qpJson(res);
        j["contact"] = contactJson(contact, tm.expectedContactForce());
        j["setup_s"] = solver.timings().setup();
        j["solve_s"] = solver.timings().solve;
        j["max_abs_u"] = maxAbsSolution(*comm, solver);
        bySolver[method] = std::move(j);
        primal = solver.primalDimension();
        dual = solver.dualDimension();
        line << std::setw(22)
             << (std::to_string(res.qp.outerIterations) + "/" +
                 std::to_string(res.qp.hessianMultiplications) + (res.converged ? "" : " n/c"));
      }
      row["primal_dim"] = primal;
      row["dual_dim"] = dual;
      row["solvers"] = std::move(bySolver);
      table.push(std::move(row));
      if (root)
        std::cout << std::left << std::setw(8) << ("1/" + std::to_string(hinv)) << std::setw(8)
                  << ("1/" + std::to_string(hinv * ratio)) << std::right << std::setw(10) << primal
                  << std::setw(9) << dual << line.str() << "\n"
                  << std::flush;
    }
  Json s = Json::object();
  s["study"] = "scalability";
  s["problem"] = "two_membranes";
  s["ranks"] = comm->getSize();
  s["all_converged"] = allConverged;
  s["table"] = std::move(table);
  writeSummary(*comm, dir, s, params);
  return allConverged ? 0 : 2;
}

void checkTwoMembranes(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                       std::ostream& out) {
  const bool scalability = params.get<std::string>("Study") == "scalability";
  std::vector<std::string> lines;
  TwoMembranes largest;
  if (scalability) {
    const auto& sc = params.sublist("Scalability");
    for (int ratio : sc.get<Array<int>>("H over h"))
      for (int hinv : sc.get<Array<int>>("Subdomains per side")) {
        TwoMembranes tm;
        tm.subdomainsX = tm.subdomainsY = hinv;
        tm.elementsX = tm.elementsY = ratio;
        tm.validate();
        std::ostringstream s;
        s << "table row H = 1/" << hinv << ", h = 1/" << hinv * ratio << ": " << tm.numSubdomains()
          << " subdomains";
        lines.push_back(s.str());
        if (tm.numSubdomains() * ratio * ratio >=
            largest.numSubdomains() * largest.elementsX * largest.elementsY)
          largest = tm;
      }
    lines.push_back("the largest row:");
  } else {
    largest = membranesFrom(params);
  }
  ContactProblemData data = buildTwoMembranes(largest, *comm);
  long long mine = static_cast<long long>(data.inequalities.size()), rows = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &mine, &rows);
  const auto methods =
      scalability ? params.sublist("Scalability").get<Array<std::string>>("Dual solvers")
                  : Array<std::string>(1, params.sublist("FETI").get<std::string>("Dual solver"));
  for (const auto& m : methods) {
    ParameterList feti = params.sublist("FETI");
    feti.set("Dual solver", m);
    tfeti::FetiSolver::dualSolverFor(feti, rows);
  }
  std::ostringstream s;
  s << "problem: two_membranes, " << largest.subdomainsX << " x " << largest.subdomainsY
    << " subdomains of " << largest.elementsX << " x " << largest.elementsY
    << " elements per membrane; contact rows along x = 1: " << rows;
  lines.push_back(s.str());
  printDryRunReport(*comm, lines, data.local, rows, out);
}

}  // namespace contact
