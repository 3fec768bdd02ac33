#include "contact_Driver.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>

#include "contact_ContactPairs.hpp"
#include "contact_ContactParameters.hpp"
#include "contact_Materials.hpp"
#include "contact_NonlinearOptions.hpp"
#include "contact_PrescribedDisplacement.hpp"
#include "contact_Runners.hpp"
#include "tfeti_FetiSolver.hpp"
#include "tfeti_StrictParameters.hpp"

namespace contact {

namespace {

using Teuchos::Array;
using Teuchos::ParameterList;

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

// Teuchos names a sublist by its path from the root list, whose name is the XML's or Teuchos'
// "ANONYMOUS": the user's file has no such list, so the paths start below it.
std::string withoutRootName(std::string message, const std::string& root) {
  auto replaceAll = [&message](const std::string& from, const std::string& to) {
    for (std::size_t at = message.find(from); at != std::string::npos;
         at = message.find(from, at + to.size()))
      message.replace(at, from.size(), to);
  };
  replaceAll("the sublist \"" + root + "\"", "the top-level list");
  replaceAll("\"" + root + "->", "\"");
  return message;
}

}  // namespace

int checkDriver(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                const std::string& outputDirectory, std::ostream& out) {
  runnerFor(params).check(comm, params, outputDirectory, out);
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
          "time 10 extra applications of F and report the bandwidth they achieve, and 10 of "
          "the projector, the preconditioner and an iteration's vector updates (benchmarks)");
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
    // So is "Contact problem/Contact pairs", named by the user's pairs.
    const GivenContactPairs pairs = takeContactPairs(params);
    params.validateParametersAndSetDefaults(*validDriverParameters());
    restoreBodyMaterials(params, materials);
    restoreContactPairs(params, pairs);
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
    throw std::invalid_argument(source + ": invalid parameters:\n" +
                                withoutRootName(e.what(), params.name()));
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
  return runnerFor(params).run(comm, params, outputDirectory);
}

}  // namespace contact
