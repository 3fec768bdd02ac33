#include "contact_TwoMembranesRun.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "contact_DryRun.hpp"
#include "contact_RunSummary.hpp"
#include "contact_StructuredProblem.hpp"
#include "contact_TwoMembranes.hpp"
#include "contact_TwoMembranesResult.hpp"
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

// The solution's norm, max |u| and min u over all subdomain copies on every rank.
void measureSolution(const tfeti::Comm& comm, const tfeti::FetiSolver& solver,
                     TwoMembranesResult& r) {
  double local[3] = {0.0, 0.0, 0.0}, global[3];  // sum of squares, max |u|, -min u
  for (std::size_t i = 0; i < solver.data().size(); ++i)
    for (double v : solver.solution(i)) {
      local[0] += v * v;
      local[1] = std::max(local[1], std::abs(v));
      local[2] = std::max(local[2], -v);
    }
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &local[0], &global[0]);
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 2, &local[1], &global[1]);
  r.solutionNorm2 = std::sqrt(global[0]);
  r.maxAbsU = global[1];
  r.minU = -global[2];
}

// The figures of the solve itself.
TwoMembranesResult solvedResult(const tfeti::Comm& comm, const TwoMembranes& tm,
                                const tfeti::FetiSolver& solver, const tfeti::DualResult& solve,
                                const ParameterList& feti) {
  TwoMembranesResult r;
  r.ranks = comm.getSize();
  r.subdomains = tm.numSubdomains();
  r.elements = 2LL * tm.subdomainsX * tm.elementsX * tm.subdomainsY * tm.elementsY;
  r.H = 1.0 / tm.subdomainsX;
  r.h = 1.0 / (tm.subdomainsX * tm.elementsX);
  r.feti = fetiDimensions(solver, feti);
  r.solve = solve;
  r.memory = solver.memory();
  r.contact = solver.constraintReport();
  r.expectedContactForce = tm.expectedContactForce();
  r.timings = solver.timings();
  return r;
}

void printSingleRun(const TwoMembranes& tm, const tfeti::FetiSolver& solver,
                    const TwoMembranesResult& r) {
  const tfeti::DualResult& result = r.solve;
  std::cout << "two_membranes: " << tm.numSubdomains() << " subdomains, primal "
            << solver.primalDimension() << ", dual " << solver.dualDimension() << " ("
            << solver.inequalityRows() << " contact rows), " << result.method << ": "
            << result.qp.outerIterations << " outer iterations, "
            << result.qp.hessianMultiplications << " Hessian multiplications ("
            << (result.converged ? "converged" : "NOT CONVERGED") << "), contact force "
            << r.contact.force << " (expected " << tm.expectedContactForce() << "), setup "
            << solver.timings().setup() << " s, solve " << solver.timings().solve << " s\n";
}

// The membranes of a table row: 1/H subdomains of H/h elements per side of each membrane.
TwoMembranes tableRowMembranes(int hinv, int ratio) {
  TwoMembranes tm;
  tm.subdomainsX = tm.subdomainsY = hinv;
  tm.elementsX = tm.elementsY = ratio;
  tm.validate();
  return tm;
}

// One row of the table: the membranes on 1/H x H/h, solved by every QP solver (allConverged is
// cleared by a solve that did not converge).
TwoMembranesTableRow solveTableRow(const Teuchos::RCP<const tfeti::Comm>& comm,
                                   const ParameterList& params, int hinv, int ratio,
                                   const Array<std::string>& methods, bool& allConverged) {
  const TwoMembranes tm = tableRowMembranes(hinv, ratio);
  TwoMembranesTableRow row;
  row.hInverse = hinv;
  row.hOverh = ratio;
  row.subdomains = tm.numSubdomains();
  for (const auto& method : methods) {
    ContactProblemData data = buildTwoMembranes(tm, *comm);
    ParameterList feti = params.sublist("FETI");
    feti.set("Dual solver", method);
    tfeti::FetiSolver solver(comm, tm.numSubdomains(), std::move(data.local), feti,
                             data.inequalities);
    TwoMembranesSolve m;
    m.method = method;
    m.result = solver.solve();
    m.contact = solver.constraintReport();
    m.expectedContactForce = tm.expectedContactForce();
    m.setupSeconds = solver.timings().setup();
    m.solveSeconds = solver.timings().solve;
    m.maxAbsU = maxAbsSolution(*comm, solver);
    allConverged &= m.result.converged;
    row.solvers.push_back(std::move(m));
    row.primal = solver.primalDimension();
    row.dual = solver.dualDimension();
  }
  return row;
}

void printTableHeader(const Array<std::string>& methods) {
  std::cout << std::left << std::setw(8) << "H" << std::setw(8) << "h" << std::right
            << std::setw(10) << "primal" << std::setw(9) << "dual";
  for (const auto& m : methods) std::cout << std::setw(22) << (m + " outer/Hessian");
  std::cout << "\n";
}

void printTableRow(const TwoMembranesTableRow& row) {
  std::ostringstream line;
  for (const auto& m : row.solvers)
    line << std::setw(22)
         << (std::to_string(m.result.qp.outerIterations) + "/" +
             std::to_string(m.result.qp.hessianMultiplications) +
             (m.result.converged ? "" : " n/c"));
  std::cout << std::left << std::setw(8) << ("1/" + std::to_string(row.hInverse)) << std::setw(8)
            << ("1/" + std::to_string(row.hInverse * row.hOverh)) << std::right << std::setw(10)
            << row.primal << std::setw(9) << row.dual << line.str() << "\n"
            << std::flush;
}

// The dry run's report of the membranes `tm` solved by each of `methods`, after `lines`.
void reportMembranes(const Teuchos::RCP<const tfeti::Comm>& comm, const ParameterList& params,
                     const TwoMembranes& tm, const Array<std::string>& methods,
                     std::vector<std::string> lines, std::ostream& out) {
  ContactProblemData data = buildTwoMembranes(tm, *comm);
  long long mine = static_cast<long long>(data.inequalities.size()), rows = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &mine, &rows);
  for (const auto& m : methods) {
    ParameterList feti = params.sublist("FETI");
    feti.set("Dual solver", m);
    tfeti::FetiSolver::dualSolverFor(feti, rows);
  }
  std::ostringstream s;
  s << "problem: two_membranes, " << tm.subdomainsX << " x " << tm.subdomainsY << " subdomains of "
    << tm.elementsX << " x " << tm.elementsY
    << " elements per membrane; contact rows along x = 1: " << rows;
  lines.push_back(s.str());
  printDryRunReport(comm, tm.numSubdomains(), lines, data.local, rows, params.sublist("FETI"), out,
                    data.inequalities);
}

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

  TwoMembranesResult r = solvedResult(*comm, tm, solver, result, params.sublist("FETI"));
  r.peakRssMb = peakRssMb(*comm);
  measureSolution(*comm, solver, r);
  r.contactCsv = dir + "/contact.csv";
  writeContactCsv(*comm, solver, r.contactCsv);
  if (out.get<bool>("VTU")) r.vtu = writeVtu(*comm, dir, "solution", membranePiece(solver));
  writeSummary(*comm, dir, summaryJson(r), params);

  if (root && verbosity > 0) printSingleRun(tm, solver, r);
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
  const auto methods = sc.get<Array<std::string>>("Dual solvers");
  TwoMembranesScalabilityResult r;
  r.ranks = comm->getSize();
  if (root) printTableHeader(methods);
  for (int ratio : ratios)
    for (int hinv : Hinv) {
      r.table.push_back(solveTableRow(comm, params, hinv, ratio, methods, r.allConverged));
      if (root) printTableRow(r.table.back());
    }
  writeSummary(*comm, dir, summaryJson(r), params);
  return r.allConverged ? 0 : 2;
}

void checkTwoMembranes(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                       std::ostream& out) {
  const Array<std::string> method(1, params.sublist("FETI").get<std::string>("Dual solver"));
  reportMembranes(comm, params, membranesFrom(params), method, {}, out);
}

void checkTwoMembranesScalability(const Teuchos::RCP<const tfeti::Comm>& comm,
                                  ParameterList& params, std::ostream& out) {
  // The table's rows, the largest built for the report.
  std::vector<std::string> lines;
  TwoMembranes largest;
  const auto& sc = params.sublist("Scalability");
  for (int ratio : sc.get<Array<int>>("H over h"))
    for (int hinv : sc.get<Array<int>>("Subdomains per side")) {
      const TwoMembranes tm = tableRowMembranes(hinv, ratio);
      std::ostringstream s;
      s << "table row H = 1/" << hinv << ", h = 1/" << hinv * ratio << ": " << tm.numSubdomains()
        << " subdomains";
      lines.push_back(s.str());
      if (tm.numSubdomains() * ratio * ratio >=
          largest.numSubdomains() * largest.elementsX * largest.elementsY)
        largest = tm;
    }
  lines.push_back("the largest row:");
  reportMembranes(comm, params, largest, sc.get<Array<std::string>>("Dual solvers"),
                  std::move(lines), out);
}

}  // namespace contact
