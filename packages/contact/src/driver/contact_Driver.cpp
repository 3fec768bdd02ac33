#include "contact_Driver.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

#include "contact_ContactSolver.hpp"
#include "contact_DriverCommon.hpp"
#include "contact_DryRun.hpp"
#include "contact_ElasticContactRun.hpp"
#include "contact_Json.hpp"
#include "contact_Materials.hpp"
#include "contact_NonlinearContactRun.hpp"
#include "contact_PrescribedDisplacement.hpp"
#include "contact_StructuredProblem.hpp"
#include "contact_TwoMembranes.hpp"
#include "contact_VtuWriter.hpp"
#include "tfeti_FetiSolver.hpp"
#include "tfeti_StrictParameters.hpp"

namespace contact {

namespace {

using Teuchos::Array;
using Teuchos::ParameterList;
using tfeti::GO;

Teuchos::RCP<Teuchos::StringToIntegralParameterEntryValidator<int>> choice(
    std::initializer_list<std::string> names) {
  return Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
      Array<std::string>(names.begin(), names.end()), *names.begin()));
}

template <class T>
Array<T> arr(std::initializer_list<T> values) {
  return Array<T>(values.begin(), values.end());
}

// Arrays whose length is the problem's dimension (2 or 3 values per axis) or twice it.
tfeti::strict::Validator withLength(tfeti::strict::Validator v, int lo, int hi) {
  v->lengthBetween(lo, hi);
  return v;
}

const char* kStoppingRule =
    "relative norm of the projected gradient: ||P(F lambda - d)|| <= tol * ||P d||";

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

int runSingle(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
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

  Json s = Json::object();
  s["study"] = "single";
  s["problem"] = field;
  s["ranks"] = comm->getSize();
  s["dimension"] = sp.dim();
  s["subdomains"] = sp.numSubdomains();
  s["elements"] = static_cast<long long>(sp.mesh().numGlobalElements());
  const auto& feti = params.sublist("FETI");
  addSolverSummary(s, solver, result, feti);
  s["stopping_rule"] = kStoppingRule;
  s["tolerance"] = feti.sublist("PCPG").get<double>("Relative tolerance");
  s["preconditioner_factor_bytes"] =
      static_cast<unsigned long long>(solver.globalPreconditionerFactorBytes());
  s["timings"] = timingsJson(solver.timings(), result.iterations);
  if (out.get<bool>("Time dual operator")) {
    // One F apply streams every subdomain factor twice (forward and backward substitution):
    // its time against the factor bytes gives the achieved bandwidth.
    const double t = solver.timeDualApply(10);
    s["timings"]["dual_apply_s"] = t;
    s["dual_apply_bandwidth_gb_s"] =
        2.0 * static_cast<double>(solver.globalFactorBytes()) / t / 1e9;
  }
  s["peak_rss_mb"] = peakRssMb(*comm);
  double local[2] = {0.0, 0.0}, global[2] = {0.0, 0.0};  // sum of squares, max |u|
  for (std::size_t i = 0; i < solver.data().size(); ++i)
    for (double v : solver.solution(i)) {
      local[0] += v * v;
      local[1] = std::max(local[1], std::abs(v));
    }
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &local[0], &global[0]);
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &local[1], &global[1]);
  s["solution_norm2"] = std::sqrt(global[0]);  // over all subdomain copies
  s["max_abs_u"] = global[1];
  if (!sp.prescribed.empty()) {
    s["prescribed_rows"] = static_cast<long long>(solver.userEqualityRows());
    s["equality_residual"] = solver.constraintReport().equalityResidual;
    s["prescribed"] = prescribedSummary(solver, sp.prescribed,
                                        [&](const std::string& f) { return sp.faceNodes(f); });
  }
  if (out.get<bool>("Compare with direct solve")) {
    const double err = relativeErrorAgainstDirectSolve(sp, solver);
    s["error_vs_direct"] = err;
    if (root && verbosity > 0)
      std::cout << "max relative error against direct solve: " << err << "\n";
  }
  if (out.get<bool>("VTU")) s["vtu"] = writeVtu(*comm, dir, "solution", vtuPiece(solver));
  memory.record(*comm, "output");
  s["memory"] = memoryJson(memory, solver.primalDimension());
  writeSummary(*comm, dir, s, params);
  if (root && verbosity > 0)
    std::cout << field << " " << sp.dim() << "D: " << sp.numSubdomains() << " subdomains, primal "
              << solver.primalDimension() << ", dual " << solver.dualDimension() << ", "
              << result.iterations << " iterations ("
              << (result.converged ? "converged" : "NOT CONVERGED") << "), setup "
              << solver.timings().setup() << " s, solve " << solver.timings().solve << " s\n";
  if (!result.converged && root)
    std::cerr << "tfeti_contact: PCPG did not converge (relative residual "
              << result.relativeResidual << "); results written to " << dir << "\n";
  return result.converged ? 0 : 2;
}

std::string fraction(int denominator) {
  return "1/" + std::to_string(denominator);
}

int runScalability(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                   const std::string& dir) {
  const bool root = comm->getRank() == 0;
  const auto& sc = params.sublist("Scalability");
  const auto problems = sc.get<Array<std::string>>("Problems");
  const auto Hinv = sc.get<Array<int>>("Subdomains per side");
  const auto ratios = sc.get<Array<int>>("H over h");
  const auto precs = sc.get<Array<std::string>>("Preconditioners");
  const double tol = params.sublist("FETI").sublist("PCPG").get<double>("Relative tolerance");
  freeMatricesAfterSetup(params);
  bool allConverged = true;

  Json table = Json::array();
  std::ostringstream printed;
  printed << std::left << std::setw(11) << "problem" << std::setw(6) << "H" << std::setw(7) << "h"
          << std::right << std::setw(9) << "primal" << std::setw(9) << "dualFETI" << std::setw(10)
          << "dualTFETI";
  for (const char* f : {"FETI", "TFETI"})
    for (const auto& p : precs) printed << std::setw(16) << (std::string(f) + ":" + p);
  printed << "\n";
  if (root) std::cout << printed.str() << std::flush;

  for (const auto& problem : problems) {
    for (int ratio : ratios)
      for (int hinv : Hinv) {
        ParameterList run = params;
        auto& mesh = run.sublist("Mesh");
        const int dim = static_cast<int>(mesh.get<Array<double>>("Domain").size()) / 2;
        mesh.set("Subdomains", Array<int>(dim, hinv));
        mesh.set("Elements per subdomain", Array<int>(dim, ratio));
        const StructuredProblem sp = problemFrom(run, problem);
        const int numSubdomains = sp.numSubdomains();
        const auto local = buildLocalSubdomains(sp, *comm);
        const auto rows = prescribedRows(sp, local);
        Json row = Json::object();
        row["problem"] = problem;
        row["H"] = 1.0 / hinv;
        row["h"] = 1.0 / (hinv * ratio);
        row["H_inverse"] = hinv;
        row["h_inverse"] = hinv * ratio;
        row["dimension"] = sp.dim();
        row["subdomains"] = numSubdomains;
        Json iterations = Json::object();
        std::ostringstream line;
        GO primal = 0, dual[2] = {0, 0};
        for (int f = 0; f < 2; ++f) {
          const std::string form = f == 0 ? "FETI" : "TFETI";
          Json its = Json::object();
          for (const auto& prec : precs) {
            ParameterList feti = run.sublist("FETI");
            feti.set("Formulation", form);
            feti.set("Preconditioner", prec);
            tfeti::FetiSolver solver(comm, numSubdomains, local, feti, {}, rows);
            const auto res = solver.solve();
            allConverged &= res.converged;
            its[prec] = res.converged ? Json(res.iterations) : Json();
            primal = solver.primalDimension();
            dual[f] = solver.dualDimension();
            line << std::setw(16) << (res.converged ? std::to_string(res.iterations) : "n/c");
          }
          iterations[f == 0 ? "feti" : "tfeti"] = std::move(its);
        }
        row["primal_dim"] = primal;
        row["dual_dim_feti"] = dual[0];
        row["dual_dim_tfeti"] = dual[1];
        row["iterations"] = std::move(iterations);
        table.push(std::move(row));
        if (root)
          std::cout << std::left << std::setw(11) << problem << std::setw(6) << fraction(hinv)
                    << std::setw(7) << fraction(hinv * ratio) << std::right << std::setw(9)
                    << primal << std::setw(9) << dual[0] << std::setw(10) << dual[1] << line.str()
                    << "\n"
                    << std::flush;
      }
  }
  Json s = Json::object();
  s["study"] = "scalability";
  s["ranks"] = comm->getSize();
  s["stopping_rule"] = kStoppingRule;
  s["tolerance"] = tol;
  s["local_solver"] = params.sublist("FETI").get<std::string>("Local solver");
  s["all_converged"] = allConverged;
  s["table"] = std::move(table);
  writeSummary(*comm, dir, s, params);
  return allConverged ? 0 : 2;
}

// The dry run of the structured problems: one (Study = single) or the table's rows, the
// subdomains of the single one or of the largest row built for the report.
void checkStructured(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                     std::ostream& out) {
  std::vector<std::string> lines;
  const bool scalability = params.get<std::string>("Study") == "scalability";
  ParameterList largest = params;
  std::string field = params.get<std::string>("Problem");
  if (scalability) {
    const auto& sc = params.sublist("Scalability");
    long long most = -1;
    for (const auto& problem : sc.get<Array<std::string>>("Problems"))
      for (int ratio : sc.get<Array<int>>("H over h"))
        for (int hinv : sc.get<Array<int>>("Subdomains per side")) {
          ParameterList run = params;
          const int dim =
              static_cast<int>(run.sublist("Mesh").get<Array<double>>("Domain").size()) / 2;
          run.sublist("Mesh").set("Subdomains", Array<int>(dim, hinv));
          run.sublist("Mesh").set("Elements per subdomain", Array<int>(dim, ratio));
          const StructuredProblem row = problemFrom(run, problem);
          std::ostringstream s;
          s << "table row " << problem << " H = " << fraction(hinv)
            << ", h = " << fraction(hinv * ratio) << ": " << row.numSubdomains() << " subdomains";
          lines.push_back(s.str());
          long long size = 1;
          for (int c = 0; c < dim; ++c) size *= static_cast<long long>(hinv) * ratio;
          if (size > most) most = size, largest = run, field = problem;
        }
    lines.push_back("the largest row:");
  }
  const StructuredProblem sp = problemFrom(largest, field);
  tfeti::FetiSolver::dualSolverFor(params.sublist("FETI"), 0);
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
    << largest.sublist("FETI").get<std::string>("Formulation") << ", preconditioner "
    << largest.sublist("FETI").get<std::string>("Preconditioner");
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
  printDryRunReport(*comm, lines, local, -1, out);
}

}  // namespace

int checkDriver(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                const std::string& outputDirectory, std::ostream& out) {
  const std::string problem = params.get<std::string>("Problem");
  const bool scalability = params.get<std::string>("Study") == "scalability";
  if (scalability
          ? params.sublist("Scalability").get<Array<std::string>>("Problems")[0] == "two_membranes"
          : problem == "two_membranes")
    checkTwoMembranes(comm, params, out);
  else if (!scalability && (problem == "elastic_contact" || problem == "nonlinear_contact"))
    checkContactProblem(comm, params, outputDirectory, out);
  else
    checkStructured(comm, params, out);
  if (comm->getRank() == 0)
    out << "check passed: the input is complete and consistent (nothing was solved)\n";
  return 0;
}

Teuchos::RCP<const ParameterList> validDriverParameters() {
  static Teuchos::RCP<ParameterList> pl;
  if (!pl.is_null()) return pl;
  pl = Teuchos::rcp(new ParameterList("tfeti_contact"));
  pl->set("Study", "single", "single: one problem; scalability: the paper's table",
          choice({"single", "scalability"}));
  pl->set(
      "Problem", "poisson",
      "poisson, elasticity: the reference paper's linear model problems; two_membranes: "
      "Dostál's scalar contact benchmark (Mesh: subdomains and elements of each membrane); "
      "elastic_contact: bodies on a Gmsh mesh in contact (Contact problem); "
      "nonlinear_contact: the same with J2 plasticity and large deformations in load steps "
      "(Contact problem, Material, Nonlinear)",
      choice({"poisson", "elasticity", "two_membranes", "elastic_contact", "nonlinear_contact"}));
  auto& mesh = pl->sublist("Mesh", false,
                           "structured Q1 mesh of a rectangle (2D) or a box (3D, trilinear "
                           "hexahedra), torn into a grid; Dirichlet face x = x0");
  mesh.set("Domain", arr<double>({0.0, 1.0, 0.0, 1.0}),
           "{x0, x1, y0, y1} (2D) or {x0, x1, y0, y1, z0, z1} (3D): decides the dimension",
           withLength(tfeti::strict::doubles(0), 4, 6));
  mesh.set("Subdomains", arr<int>({4, 4}), "subdomains per axis (1/H), one value per axis",
           withLength(tfeti::strict::positiveInts(0), 2, 3));
  mesh.set("Elements per subdomain", arr<int>({16, 16}),
           "elements per subdomain per axis (H/h), one value per axis",
           withLength(tfeti::strict::positiveInts(0), 2, 3));
  auto& bc =
      pl->sublist("Boundary conditions", false,
                  "Problem = poisson | elasticity: conditions on the faces of the box, "
                  "named x0, x1, y0, y1 (and z0, z1 in 3D) for the faces x = x0, x = x1, ...");
  bc.set("Fixed boundaries", arr<std::string>({"x0"}), "faces where u = 0 (every component)");
  bc.set("Symmetry boundaries", Array<std::string>(), "faces with one component zero");
  bc.set("Symmetry components", Array<int>(), "the zero component (0: x, 1: y, 2: z) of each",
         componentsValidator());
  addPrescribedDisplacementParameters(bc);
  addMaterialParameters(*pl);
  auto& load = pl->sublist("Load");
  load.set("Source", 1.0, "right-hand side of -Δu = source (poisson)");
  load.set("Body force", arr<double>({0.0, -1.0}),
           "{bx, by} or {bx, by, bz} per unit volume (elasticity)",
           withLength(tfeti::strict::doubles(0), 2, 3));
  pl->sublist("FETI").setParameters(*tfeti::FetiSolver::validParameters());
  addElasticContactParameters(*pl);
  addNonlinearContactParameters(*pl);
  auto& out = pl->sublist("Output");
  out.set("VTU", true, "write solution.pvtu (u and subdomain id)");
  out.set("Compare with direct solve", false,
          "solve the undecomposed problem directly on every rank and report the error "
          "(small problems only)");
  out.set("Verbosity", 1,
          "0 silent; 1 summary lines and a line per load step; 2 also a line per nonlinear "
          "iteration and per SMALBE outer iteration",
          tfeti::strict::count(0));
  out.set("Time dual operator", false,
          "time 10 extra applications of F and report the bandwidth they achieve (benchmarks)");
  auto& sc = pl->sublist("Scalability", false, "Study = scalability");
  const auto atLeastOne = tfeti::strict::positiveInts(0);
  atLeastOne->lengthBetween(1, std::numeric_limits<int>::max());
  sc.set("Problems", arr<std::string>({"poisson"}),
         "poisson and/or elasticity, or two_membranes alone");
  sc.set("Subdomains per side", arr<int>({2, 4, 8, 16}), "values of 1/H", atLeastOne);
  sc.set("H over h", arr<int>({2, 4, 8}), "elements per subdomain side", atLeastOne);
  sc.set("Preconditioners", arr<std::string>({"none", "lumped", "dirichlet"}), "columns");
  sc.set("Dual solvers", arr<std::string>({"SMALBE", "penalty"}),
         "two_membranes: the QP solvers compared (SMALBE, penalty)");
  tfeti::strict::requireNumbers(*pl);  // every number finite, also those without a range
  return pl;
}

void validateDriverParameters(ParameterList& params, const std::string& source) {
  try {
    if (params.isSublist("FETI"))
      tfeti::FetiSolver::rejectMisplacedParameters(params.sublist("FETI"));
    // "Materials" is named by the user's bodies: checked on its own against them.
    const GivenMaterials materials = takeBodyMaterials(params);
    params.validateParametersAndSetDefaults(*validDriverParameters());
    restoreBodyMaterials(params, materials);
    const auto& sc = params.sublist("Scalability");
    const auto problems = sc.get<Array<std::string>>("Problems");
    for (const auto& p : problems)
      if (p != "poisson" && p != "elasticity" && p != "two_membranes")
        throw std::invalid_argument("Scalability: \"Problems\" has \"" + p +
                                    "\"; valid: poisson, elasticity, two_membranes");
    if (problems.size() > 1 &&
        std::find(problems.begin(), problems.end(), "two_membranes") != problems.end())
      throw std::invalid_argument(
          "Scalability: \"Problems\": two_membranes is a study of its own, not combined with "
          "poisson or elasticity");
    for (int hinv : sc.get<Array<int>>("Subdomains per side"))
      for (int ratio : sc.get<Array<int>>("H over h"))
        if (static_cast<long long>(hinv) * ratio > (1 << 15))
          throw std::invalid_argument(
              "Scalability: \"Subdomains per side\" " + std::to_string(hinv) + " x \"H over h\" " +
              std::to_string(ratio) + " elements per side; at most " + std::to_string(1 << 15));
    for (const auto& p : sc.get<Array<std::string>>("Dual solvers"))
      if (p != "SMALBE" && p != "penalty")
        throw std::invalid_argument("Scalability: \"Dual solvers\" has \"" + p +
                                    "\"; valid: SMALBE, penalty");
    for (const auto& p : sc.get<Array<std::string>>("Preconditioners"))
      if (p != "none" && p != "lumped" && p != "dirichlet")
        throw std::invalid_argument("Scalability: \"Preconditioners\" has \"" + p +
                                    "\"; valid: none, lumped, dirichlet");
  } catch (const std::exception& e) {
    throw std::invalid_argument(source + ": invalid parameters:\n" + e.what());
  }
  // A relative mesh file is looked up next to the input file first, then in the working
  // directory, so that inputs and their meshes can travel together.
  auto& cp = params.sublist("Contact problem");
  const std::string mesh = cp.get<std::string>("Mesh file");
  if (!mesh.empty() && std::filesystem::path(mesh).is_relative()) {
    const auto beside = std::filesystem::path(source).parent_path() / mesh;
    if (std::filesystem::exists(beside)) cp.set("Mesh file", beside.string());
  }
}

void applyOutputVerbosity(ParameterList& params) {
  // Output verbosity 2 shows the progress of every contact QP: a line per SMALBE outer
  // iteration (unless the SMALBE sublist asks for its own verbosity).
  auto& smalbe = params.sublist("FETI").sublist("SMALBE");
  if (params.sublist("Output").get<int>("Verbosity") >= 2 &&
      smalbe.getEntry("Verbosity").isDefault())
    smalbe.set("Verbosity", 2);
}

int runDriver(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
              const std::string& outputDirectory) {
  if (comm->getRank() == 0) std::filesystem::create_directories(outputDirectory);
  comm->barrier();
  applyOutputVerbosity(params);
  if (params.get<std::string>("Study") == "scalability") {
    if (params.sublist("Scalability").get<Array<std::string>>("Problems")[0] == "two_membranes")
      return runTwoMembranesScalability(comm, params, outputDirectory);
    return runScalability(comm, params, outputDirectory);
  }
  if (params.get<std::string>("Problem") == "two_membranes")
    return runTwoMembranes(comm, params, outputDirectory);
  const std::string problem = params.get<std::string>("Problem");
  if (problem == "elastic_contact" || problem == "nonlinear_contact")
    return runContactProblem(comm, params, outputDirectory);
  return runSingle(comm, params, outputDirectory);
}

}  // namespace contact
