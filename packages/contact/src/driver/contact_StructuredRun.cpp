#include "contact_StructuredRun.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "contact_DryRun.hpp"
#include "contact_PrescribedDisplacement.hpp"
#include "contact_RunSummary.hpp"
#include "contact_StructuredProblem.hpp"
#include "contact_StructuredResult.hpp"
#include "contact_VtuWriter.hpp"
#include "tfeti_FetiSolver.hpp"

namespace contact {

namespace {

using Teuchos::Array;
using Teuchos::ParameterList;
using tfeti::GO;

// The dimension of a structured problem is that of Mesh/Domain: {x0, x1, y0, y1} is 2D,
// {x0, x1, y0, y1, z0, z1} is 3D; every other per-axis list must then have that many values.
StructuredProblem problemFrom(const ParameterList& p, const std::string& field) {
  StructuredProblem sp;
  sp.field = field;
  const auto& mesh = p.sublist("Mesh");
  const auto domain = mesh.get<Array<double>>("Domain");
  const auto subs = mesh.get<Array<int>>("Subdomains");
  const auto elems = mesh.get<Array<int>>("Elements per subdomain");
  if (domain.size() != 4 && domain.size() != 6)
    throw std::invalid_argument(
        "Mesh: \"Domain\" takes 4 values {x0, x1, y0, y1} (2D) or 6 values {x0, x1, y0, y1, "
        "z0, z1} (3D); got " +
        std::to_string(domain.size()));
  const int dim = static_cast<int>(domain.size()) / 2;
  const std::string axes = dim == 2 ? "{x, y}" : "{x, y, z}";
  // Only Study = single reads the Mesh sublist: say so, for an input that meant another study.
  const std::string why = " for a " + std::to_string(dim) + "D problem (\"Domain\" has " +
                          std::to_string(domain.size()) + " values; Study = single); got ";
  if (static_cast<int>(subs.size()) != dim)
    throw std::invalid_argument("Mesh: \"Subdomains\" takes " + std::to_string(dim) + " values " +
                                axes + why + std::to_string(subs.size()));
  if (static_cast<int>(elems.size()) != dim)
    throw std::invalid_argument("Mesh: \"Elements per subdomain\" takes " + std::to_string(dim) +
                                " values " + axes + why + std::to_string(elems.size()));
  for (int d = 0; d < dim; ++d)
    if (!(domain[2 * d + 1] > domain[2 * d]))
      throw std::invalid_argument(
          "Mesh/Domain: the upper bound of axis " + std::string(1, "xyz"[d]) + " (" +
          std::to_string(domain[2 * d + 1]) + ") must exceed its lower bound (" +
          std::to_string(domain[2 * d]) + ")");
  checkGridSize(mesh);
  sp.lo.assign(dim, 0.0);
  sp.hi.assign(dim, 0.0);
  for (int d = 0; d < dim; ++d) sp.lo[d] = domain[2 * d], sp.hi[d] = domain[2 * d + 1];
  sp.subdomains.assign(subs.begin(), subs.end());
  sp.elements.assign(elems.begin(), elems.end());
  const auto& mat = p.sublist("Material");
  sp.law = plasticity::ElasticLaw(mat.get<double>("Young's modulus"),
                                  mat.get<double>("Poisson's ratio"));
  const auto& load = p.sublist("Load");
  sp.source = load.get<double>("Source");
  const auto bf = load.get<Array<double>>("Body force");
  // Poisson ignores the body force (whose default is 2D); elasticity needs one per axis.
  if (field == "elasticity" && static_cast<int>(bf.size()) != dim)
    throw std::invalid_argument("Load: \"Body force\" takes " + std::to_string(dim) + " values " +
                                (dim == 2 ? "{bx, by}" : "{bx, by, bz}") + why +
                                std::to_string(bf.size()));
  sp.bodyForce.assign(dim, 0.0);
  if (static_cast<int>(bf.size()) == dim) sp.bodyForce.assign(bf.begin(), bf.end());
  sp.mesh();  // validates the sizes
  const auto& bc = p.sublist("Boundary conditions");
  const auto fixed = bc.get<Array<std::string>>("Fixed boundaries");
  sp.fixed.assign(fixed.begin(), fixed.end());
  const auto sym = bc.get<Array<std::string>>("Symmetry boundaries");
  const auto comps = bc.get<Array<int>>("Symmetry components");
  if (sym.size() != comps.size())
    throw std::invalid_argument(
        "Boundary conditions: \"Symmetry components\" needs one component (0: x, 1: y, 2: z) "
        "per entry of \"Symmetry boundaries\"");
  for (int k = 0; k < static_cast<int>(sym.size()); ++k) sp.symmetry.push_back({sym[k], comps[k]});
  sp.prescribed = prescribedDisplacements(bc, "Boundary conditions");
  try {
    sp.prescribedValues();  // validates the faces, components and values
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("Boundary conditions/") + e.what());
  }
  return sp;
}

// A row of the scalability table: the run's parameters with 1/H subdomains of H/h elements per
// axis.
ParameterList tableRowParameters(const ParameterList& params, int hinv, int ratio) {
  ParameterList run = params;
  auto& mesh = run.sublist("Mesh");
  const int dim = static_cast<int>(mesh.get<Array<double>>("Domain").size()) / 2;
  mesh.set("Subdomains", Array<int>(dim, hinv));
  mesh.set("Elements per subdomain", Array<int>(dim, ratio));
  return run;
}

// The prescribed components' rows for this rank's subdomains (at their full value).
std::vector<tfeti::EqualityRow> prescribedRows(const StructuredProblem& sp,
                                               const std::vector<tfeti::SubdomainData>& local) {
  return prescribedDisplacementRows(local, sp.prescribedValues(), 1.0);
}

// The linear model problems solve once and never update their solver: the subdomain matrices
// are freed once the preconditioners are set up, unless the input keeps them.
void freeMatricesAfterSetup(ParameterList& params) {
  auto& feti = params.sublist("FETI");
  if (feti.getEntry("Keep subdomain matrices").isDefault())
    feti.set("Keep subdomain matrices", false);
}

std::string fraction(int denominator) {
  return "1/" + std::to_string(denominator);
}

// The figures of the solve itself, taken before anything else applies F again.
StructuredRunResult solvedResult(const tfeti::Comm& comm, const StructuredProblem& sp,
                                 const tfeti::FetiSolver& solver, const tfeti::DualResult& solve,
                                 const ParameterList& feti) {
  StructuredRunResult r;
  r.problem = sp.field;
  r.ranks = comm.getSize();
  r.dimension = sp.dim();
  r.subdomains = sp.numSubdomains();
  r.elements = static_cast<long long>(sp.mesh().numGlobalElements());
  r.feti = fetiDimensions(solver, feti);
  r.solve = solve;
  r.tolerance = feti.sublist("PCPG").get<double>("Relative tolerance");
  r.preconditionerFactorBytes =
      static_cast<unsigned long long>(solver.globalPreconditionerFactorBytes());
  r.timings = solver.timings();
  return r;
}

// Output/Time dual operator: one F apply streams every subdomain factor twice (forward and
// backward substitution): its time against the factor bytes gives the achieved bandwidth.
void timeDualOperator(const tfeti::FetiSolver& solver, StructuredRunResult& r) {
  const double t = solver.timeDualApply(10);
  r.dualApplySeconds = t;
  r.iterationParts = solver.timeIterationParts(10);
  r.dualApplyBandwidthGbS = 2.0 * static_cast<double>(solver.globalFactorBytes()) / t / 1e9;
}

// The solution's norm and max |u| over all subdomain copies on every rank.
void measureSolution(const tfeti::Comm& comm, const tfeti::FetiSolver& solver,
                     StructuredRunResult& r) {
  double local[2] = {0.0, 0.0}, global[2] = {0.0, 0.0};  // sum of squares, max |u|
  for (std::size_t i = 0; i < solver.data().size(); ++i)
    for (double v : solver.solution(i)) {
      local[0] += v * v;
      local[1] = std::max(local[1], std::abs(v));
    }
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &local[0], &global[0]);
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &local[1], &global[1]);
  r.solutionNorm2 = std::sqrt(global[0]);
  r.maxAbsU = global[1];
}

// The prescribed displacements' rows, residual and reactions.
void measurePrescribed(const StructuredProblem& sp, const tfeti::FetiSolver& solver,
                       StructuredRunResult& r) {
  r.prescribedRows = static_cast<long long>(solver.userEqualityRows());
  r.equalityResidual = solver.constraintReport().equalityResidual;
  r.prescribed = prescribedSummary(solver, sp.prescribed,
                                   [&](const std::string& f) { return sp.faceNodes(f); });
}

void printSingleRun(const StructuredProblem& sp, const tfeti::FetiSolver& solver,
                    const tfeti::DualResult& result) {
  std::cout << sp.field << " " << sp.dim() << "D: " << sp.numSubdomains() << " subdomains, primal "
            << solver.primalDimension() << ", dual " << solver.dualDimension() << ", "
            << result.iterations << " iterations ("
            << (result.converged ? "converged" : "NOT CONVERGED") << "), setup "
            << solver.timings().setup() << " s, solve " << solver.timings().solve << " s\n";
}

// One row of the table: the problem on 1/H x H/h, solved by FETI and TFETI with every
// preconditioner (allConverged is cleared by a solve that did not converge).
StructuredTableRow solveTableRow(const Teuchos::RCP<const tfeti::Comm>& comm,
                                 const ParameterList& params, const std::string& problem, int hinv,
                                 int ratio, const Array<std::string>& precs, bool& allConverged) {
  const ParameterList run = tableRowParameters(params, hinv, ratio);
  const StructuredProblem sp = problemFrom(run, problem);
  StructuredTableRow row;
  row.problem = problem;
  row.hInverse = hinv;
  row.hOverh = ratio;
  row.dimension = sp.dim();
  row.subdomains = sp.numSubdomains();
  for (int f = 0; f < 2; ++f) {
    auto& its = f == 0 ? row.feti : row.tfeti;
    for (const auto& prec : precs) {
      ParameterList feti = run.sublist("FETI");
      feti.set("Formulation", f == 0 ? "FETI" : "TFETI");
      feti.set("Preconditioner", prec);
      // Assembled for each solve and moved into it: a copy kept for the next solve would hold
      // every K twice while the factors are made (2.6 GiB of 3.2M unknowns in 3D, where the
      // Dirichlet row then stopped 0.08 GiB short; docs/benchmarks.md).
      auto local = buildLocalSubdomains(sp, *comm);
      const auto rows = prescribedRows(sp, local);
      tfeti::FetiSolver solver(comm, sp.numSubdomains(), std::move(local), feti, {}, rows);
      const auto res = solver.solve();
      allConverged &= res.converged;
      its.emplace_back(prec, res.converged ? std::optional<int>(res.iterations) : std::nullopt);
      row.primal = solver.primalDimension();
      (f == 0 ? row.dualFeti : row.dualTfeti) = solver.dualDimension();
    }
  }
  return row;
}

void printTableHeader(const Array<std::string>& precs) {
  std::ostringstream printed;
  printed << std::left << std::setw(11) << "problem" << std::setw(6) << "H" << std::setw(7) << "h"
          << std::right << std::setw(9) << "primal" << std::setw(9) << "dualFETI" << std::setw(10)
          << "dualTFETI";
  for (const char* f : {"FETI", "TFETI"})
    for (const auto& p : precs) printed << std::setw(16) << (std::string(f) + ":" + p);
  printed << "\n";
  std::cout << printed.str() << std::flush;
}

void printTableRow(const StructuredTableRow& row) {
  std::ostringstream line;
  for (const auto* its : {&row.feti, &row.tfeti})
    for (const auto& [prec, n] : *its) line << std::setw(16) << (n ? std::to_string(*n) : "n/c");
  std::cout << std::left << std::setw(11) << row.problem << std::setw(6) << fraction(row.hInverse)
            << std::setw(7) << fraction(row.hInverse * row.hOverh) << std::right << std::setw(9)
            << row.primal << std::setw(9) << row.dualFeti << std::setw(10) << row.dualTfeti
            << line.str() << "\n"
            << std::flush;
}

// The dry run's report of one structured problem (run: its parameters), after `lines`.
void reportStructured(const Teuchos::RCP<const tfeti::Comm>& comm, const ParameterList& run,
                      const std::string& field, std::vector<std::string> lines, std::ostream& out) {
  const StructuredProblem sp = problemFrom(run, field);
  tfeti::FetiSolver::dualSolverFor(run.sublist("FETI"), 0);
  std::ostringstream s;
  auto axes = [&](auto value) {
    std::ostringstream a;
    for (int c = 0; c < sp.dim(); ++c) a << (c ? " x " : "") << value(c);
    return a.str();
  };
  s << "problem: " << field << " " << sp.dim() << "D on " << axes([&](int c) {
    std::ostringstream interval;
    interval << "[" << sp.lo[c] << ", " << sp.hi[c] << "]";
    return interval.str();
  }) << ", "
    << axes([&](int c) { return sp.subdomains[c]; }) << " subdomains of "
    << axes([&](int c) { return sp.elements[c]; }) << " Q1 elements; "
    << run.sublist("FETI").get<std::string>("Formulation") << ", preconditioner "
    << run.sublist("FETI").get<std::string>("Preconditioner");
  lines.push_back(s.str());
  const auto face = [&](const std::string& role, const std::string& name) {
    std::ostringstream f;
    f << "boundary \"" << name << "\" (" << role << "): " << sp.faceNodes(name).size() << " nodes";
    lines.push_back(f.str());
  };
  for (const auto& name : sp.fixed) face("fixed", name);
  for (const auto& [name, c] : sp.symmetry)
    face(describePrescribed({name, c, 0.0, {}}, sp.dofsPerNode()) + ", symmetry", name);
  for (const auto& p : sp.prescribed)
    face("prescribed " + describePrescribed(p, sp.dofsPerNode()) + " m", p.boundary);
  const auto local = buildLocalSubdomains(sp, *comm);
  const long long prescribed = static_cast<long long>(prescribedRows(sp, local).size());
  long long allPrescribed = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &prescribed, &allPrescribed);
  if (!sp.prescribed.empty())
    lines.push_back("prescribed rows: " + std::to_string(allPrescribed) +
                    " (one per subdomain copy of a prescribed node and component)");
  printDryRunReport(comm, sp.numSubdomains(), lines, local, -1, run.sublist("FETI"), out, {},
                    prescribedRows(sp, local));
}

}  // namespace

int runStructured(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                  const std::string& dir) {
  freeMatricesAfterSetup(params);
  const bool root = comm->getRank() == 0;
  const std::string field = params.get<std::string>("Problem");
  const StructuredProblem sp = problemFrom(params, field);
  const auto& out = params.sublist("Output");
  const int verbosity = out.get<int>("Verbosity");

  // Memory per phase: the libraries and parameters, this rank's subdomains meshed and
  // assembled, the solver's phases, the output.
  tfeti::MemoryLog memory;
  memory.record(*comm, "start");
  auto subdomains = buildLocalSubdomains(sp, *comm);
  const auto rows = prescribedRows(sp, subdomains);
  memory.record(*comm, "assembly");
  tfeti::FetiSolver solver(comm, sp.numSubdomains(), std::move(subdomains), params.sublist("FETI"),
                           {}, rows);
  const tfeti::DualResult result = solver.solve();
  memory.append(solver.memory());

  StructuredRunResult r = solvedResult(*comm, sp, solver, result, params.sublist("FETI"));
  if (out.get<bool>("Time dual operator")) timeDualOperator(solver, r);
  r.peakRssMb = peakRssMb(*comm);
  measureSolution(*comm, solver, r);
  if (!sp.prescribed.empty()) measurePrescribed(sp, solver, r);
  if (out.get<bool>("Compare with direct solve")) {
    r.errorVsDirect = relativeErrorAgainstDirectSolve(sp, solver);
    if (root && verbosity > 0)
      std::cout << "max relative error against direct solve: " << *r.errorVsDirect << "\n";
  }
  if (out.get<bool>("VTU")) r.vtu = writeVtu(*comm, dir, "solution", vtuPiece(solver));
  memory.record(*comm, "output");
  r.memory = memory;
  writeSummary(*comm, dir, summaryJson(r), params);

  if (root && verbosity > 0) printSingleRun(sp, solver, result);
  if (!result.converged && root)
    std::cerr << "tfeti_contact: PCPG did not converge (relative residual "
              << result.relativeResidual << "); results written to " << dir << "\n";
  return result.converged ? 0 : 2;
}

int runStructuredScalability(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                             const std::string& dir) {
  const bool root = comm->getRank() == 0;
  const auto& sc = params.sublist("Scalability");
  const auto problems = sc.get<Array<std::string>>("Problems");
  const auto Hinv = sc.get<Array<int>>("Subdomains per side");
  const auto ratios = sc.get<Array<int>>("H over h");
  const auto precs = sc.get<Array<std::string>>("Preconditioners");
  freeMatricesAfterSetup(params);

  StructuredScalabilityResult r;
  r.ranks = comm->getSize();
  r.tolerance = params.sublist("FETI").sublist("PCPG").get<double>("Relative tolerance");
  r.localSolver = params.sublist("FETI").get<std::string>("Local solver");
  if (root) printTableHeader(precs);
  for (const auto& problem : problems)
    for (int ratio : ratios)
      for (int hinv : Hinv) {
        r.table.push_back(solveTableRow(comm, params, problem, hinv, ratio, precs, r.allConverged));
        if (root) printTableRow(r.table.back());
      }
  writeSummary(*comm, dir, summaryJson(r), params);
  return r.allConverged ? 0 : 2;
}

void checkStructured(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                     std::ostream& out) {
  freeMatricesAfterSetup(params);  // as the run: the forecast frees K where the run frees it
  reportStructured(comm, params, params.get<std::string>("Problem"), {}, out);
}

void checkStructuredScalability(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                                std::ostream& out) {
  // The table's rows, the subdomains of the largest built for the report.
  std::vector<std::string> lines;
  ParameterList largest = params;
  std::string field = params.get<std::string>("Problem");
  const auto& sc = params.sublist("Scalability");
  long long most = -1;
  for (const auto& problem : sc.get<Array<std::string>>("Problems"))
    for (int ratio : sc.get<Array<int>>("H over h"))
      for (int hinv : sc.get<Array<int>>("Subdomains per side")) {
        const ParameterList run = tableRowParameters(params, hinv, ratio);
        const StructuredProblem row = problemFrom(run, problem);
        std::ostringstream s;
        s << "table row " << problem << " H = " << fraction(hinv)
          << ", h = " << fraction(hinv * ratio) << ": " << row.numSubdomains() << " subdomains";
        lines.push_back(s.str());
        long long size = 1;
        for (int c = 0; c < row.dim(); ++c) size *= static_cast<long long>(hinv) * ratio;
        if (size > most) most = size, largest = run, field = problem;
      }
  // Its most demanding solve: the FETI formulation (the Dirichlet dofs inside the subdomains,
  // so the largest interiors) with the Dirichlet preconditioner where the table has it.
  freeMatricesAfterSetup(largest);
  const auto precs = sc.get<Array<std::string>>("Preconditioners");
  auto& feti = largest.sublist("FETI");
  feti.set("Formulation", "FETI");
  feti.set("Preconditioner", std::find(precs.begin(), precs.end(), "dirichlet") != precs.end()
                                 ? std::string("dirichlet")
                                 : precs.front());
  lines.push_back("the largest row, its most demanding solve:");
  reportStructured(comm, largest, field, std::move(lines), out);
}

}  // namespace contact
