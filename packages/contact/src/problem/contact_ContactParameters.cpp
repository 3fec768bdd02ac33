#include "contact_ContactParameters.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <tuple>

#include "contact_ContactOutput.hpp"
#include "contact_ContactPairs.hpp"
#include "contact_ElasticContactProblem.hpp"
#include "contact_Friction.hpp"
#include "contact_KinematicCoupling.hpp"
#include "contact_LoadRamp.hpp"
#include "contact_Materials.hpp"
#include "contact_PrescribedDisplacement.hpp"
#include "plasticity_MaterialLaw.hpp"
#include "tfeti_StrictParameters.hpp"

namespace contact {

namespace {

using Teuchos::Array;
using Teuchos::ParameterList;

template <class T>
std::vector<T> vec(const Array<T>& a) {
  return std::vector<T>(a.begin(), a.end());
}

// Values per named group (a traction per boundary, a load per body): 2 or 3 each, the same for
// all; whether that is the mesh's dimension is checked once the mesh is read.
std::vector<std::pair<std::string, std::vector<double>>> componentsPerName(
    const ParameterList& cp, const std::string& namesKey, const std::string& valuesKey) {
  const auto names = vec(cp.get<Array<std::string>>(namesKey));
  const auto values = vec(cp.get<Array<double>>(valuesKey));
  std::vector<std::pair<std::string, std::vector<double>>> out;
  if (names.empty() && values.empty()) return out;
  const std::size_t per = names.empty() ? 0 : values.size() / names.size();
  if (names.empty() || values.size() != per * names.size() || (per != 2 && per != 3))
    throw std::invalid_argument("Contact problem: \"" + valuesKey + "\" has " +
                                std::to_string(values.size()) + " values for " +
                                std::to_string(names.size()) + " entries of \"" + namesKey +
                                "\"; it needs 2 (2D: x, y) or 3 (3D: x, y, z) per entry");
  for (std::size_t k = 0; k < names.size(); ++k)
    out.push_back(
        {names[k], std::vector<double>(values.begin() + k * per, values.begin() + (k + 1) * per)});
  return out;
}

}  // namespace

ElasticContactSpec elasticContactSpec(const ParameterList& params) {
  const auto& cp = params.sublist("Contact problem");
  ElasticContactSpec spec;
  spec.meshFile = cp.get<std::string>("Mesh file");
  if (spec.meshFile.empty())
    throw std::invalid_argument("Contact problem: \"Mesh file\" is required (a .geo or .msh)");
  // Checked here, not only by the mesh reader, so that the error names the parameter.
  const std::string ext = std::filesystem::path(spec.meshFile).extension().string();
  if (ext != ".msh" && ext != ".geo")
    throw std::invalid_argument("Contact problem/Mesh file: \"" + spec.meshFile +
                                "\" is neither a .msh file (a mesh) nor a .geo file (a geometry "
                                "meshed at run time)");
  spec.meshOptions.order = cp.get<int>("Element order");
  spec.meshOptions.quads = cp.get<bool>("Quadrilaterals");
  spec.meshOptions.sizeFactor = cp.get<double>("Mesh size factor");
  const auto bodies = vec(cp.get<Array<std::string>>("Bodies"));
  const auto counts = vec(cp.get<Array<int>>("Subdomains per body"));
  if (bodies.empty() || bodies.size() != counts.size())
    throw std::invalid_argument(
        "Contact problem: \"Bodies\" and \"Subdomains per body\" need one entry per body (got " +
        std::to_string(bodies.size()) + " and " + std::to_string(counts.size()) + ")");
  const std::vector<BodyMaterial> materials = bodyMaterials(params);
  for (std::size_t b = 0; b < bodies.size(); ++b)
    spec.bodies.push_back({bodies[b], counts[b], materials[b].elastic, materials[b].yieldStress,
                           materials[b].hardening});
  spec.fixed = vec(cp.get<Array<std::string>>("Fixed boundaries"));
  const auto sym = vec(cp.get<Array<std::string>>("Symmetry boundaries"));
  const auto comps = vec(cp.get<Array<int>>("Symmetry components"));
  if (sym.size() != comps.size())
    throw std::invalid_argument(
        "Contact problem: \"Symmetry components\" needs one component (0: x, 1: y, 2: z) per "
        "entry of \"Symmetry boundaries\"");
  for (std::size_t k = 0; k < sym.size(); ++k) spec.symmetry.push_back({sym[k], comps[k]});
  spec.prescribed = prescribedDisplacements(cp, "Contact problem");
  spec.tractions = componentsPerName(cp, "Traction boundaries", "Tractions");
  {
    const auto prescribedRamps =
        loadRamps(cp, "Prescribed ramps", spec.prescribed.size(), "Contact problem");
    for (std::size_t k = 0; k < spec.prescribed.size(); ++k)
      spec.prescribed[k].ramp = prescribedRamps[k];
    spec.tractionRamps = loadRamps(cp, "Traction ramps", spec.tractions.size(), "Contact problem");
    spec.couplings = kinematicCouplings(cp, "Contact problem");
    // One solve at load factor 1 applies every entry in full: a window there would be ignored.
    if (params.get<std::string>("Problem") == "elastic_contact")
      for (const char* name : {"Prescribed ramps", "Traction ramps"})
        if (!cp.get<Array<double>>(name).empty())
          throw std::invalid_argument(std::string("Contact problem/") + name +
                                      ": load-factor windows need load steps (Problem = "
                                      "nonlinear_contact); elastic_contact solves once at the "
                                      "full load");
  }
  spec.bodyLoads = componentsPerName(cp, "Body load bodies", "Body loads");
  spec.pairs = contactPairSpecs(params);
  spec.namedPairs = !spec.pairs.front().name.empty();
  // contactPairSpecs holds every pair to one kind of row.
  spec.bonded = spec.pairs.front().contactType == "bonded";
  spec.tied = spec.pairs.front().contactType == "tied" || spec.bonded;
  spec.distribution = cp.get<std::string>("Subdomain distribution");
  spec.partitioner = cp.get<std::string>("Partitioner") == "metis"
                         ? Partitioner::Metis
                         : Partitioner::CoordinateBisection;
  spec.contactZone = cp.get<std::string>("Contact zone");
  // The nonlinear run measures its contact zone by Nonlinear/Contact extent.
  if (params.get<std::string>("Problem") != "elastic_contact" && spec.contactZone != "auto")
    throw std::invalid_argument(
        "Contact problem: \"Contact zone\" is for Problem = elastic_contact; a "
        "nonlinear_contact run measures its contact zone by Nonlinear/Contact extent");
  modelFriction(params, spec.pairs);  // validated here, used by the nonlinear run
  return spec;
}

void addElasticContactParameters(ParameterList& pl) {
  auto& cp = pl.sublist("Contact problem", false,
                        "Problem = elastic_contact: bodies on a Gmsh mesh in frictionless contact");
  cp.set("Mesh file", "",
         "a .geo file (meshed now) or a .msh file; a relative path is looked up next to the input "
         "file, then in the working directory");
  cp.set("Element order", 1, "1 or 2 (.geo only)", tfeti::strict::intBetween(1, 2));
  cp.set("Quadrilaterals", false, "recombine into quadrilaterals (.geo only)");
  cp.set("Mesh size factor", 1.0, "scales every mesh size (.geo only)", tfeti::strict::positive());
  cp.set("Bodies", Array<std::string>(),
         "the physical groups that are bodies (surfaces of a 2D mesh, volumes of a 3D mesh)");
  cp.set("Subdomains per body", Array<int>(), "the parts (subdomains) of each body",
         tfeti::strict::positiveInts(0));
  cp.set("Partitioner", "metis",
         "how a body is cut into its subdomains: metis (k-way on the elements' facet graph, "
         "contiguous parts) or coordinates (recursive bisection of the element centroids across "
         "the longest extent: equal boxes on a structured box, where FETI needs far fewer "
         "iterations than on METIS's jagged interfaces)",
         Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
             Teuchos::tuple<std::string>("metis", "coordinates"), "Partitioner")));
  cp.set("Fixed boundaries", Array<std::string>(),
         "boundary groups (curves in 2D, surfaces in 3D) where u = 0");
  cp.set("Symmetry boundaries", Array<std::string>(), "boundary groups with one component zero");
  cp.set("Symmetry components", Array<int>(), "the zero component (0: x, 1: y, 2: z) of each",
         componentsValidator());
  addPrescribedDisplacementParameters(cp);
  addLoadRampParameters(cp);
  addKinematicCouplingParameters(cp);
  cp.set("Traction boundaries", Array<std::string>(), "boundary groups under a constant traction");
  cp.set("Tractions", Array<double>(),
         "{tx, ty} (2D, force per unit length) or {tx, ty, tz} (3D, force per unit area) per "
         "traction boundary",
         tfeti::strict::doubles(0));
  cp.set("Body load bodies", Array<std::string>(), "bodies under a uniform body force");
  cp.set("Body loads", Array<double>(),
         "{Fx, Fy} (2D: per unit thickness) or {Fx, Fy, Fz} (3D) per body load body: its total "
         "force, spread uniformly over its area (volume)",
         tfeti::strict::doubles(0));
  addContactPairKeys(cp);
  addContactPairsDocumentation(cp);
  cp.set("Contact zone", "auto",
         "the contact zone's shape, how its extent is measured and which Hertz solution it is "
         "compared with: line (a line contact along z, as in 2D or in a 3D plane-strain slab: "
         "half_width, along x; in 3D on every node plane z = const of the slave nodes, "
         "averaged), point (3D: contact_radius, from the z axis through the origin); auto: line "
         "in 2D, point in 3D. elastic_contact only",
         Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
             Teuchos::tuple<std::string>("auto", "line", "point"), "Contact zone")));
  cp.set("Subdomain distribution", "graph",
         "graph: the subdomain adjacency partitioned to balance the dofs and the initial "
         "contact rows (METIS with two constraints; Zoltan2's Scotch on the dofs alone when there "
         "are no contact rows); block: contiguous blocks of subdomain ids",
         Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
             Teuchos::tuple<std::string>("graph", "block"), "Subdomain distribution")));
  addFrictionParameters(cp);
  auto& h = cp.sublist("Hertz", false,
                       "compare with Hertz: line contact of two cylinders (Contact zone line) or "
                       "point contact of two spheres (point)");
  h.set("Compare", false,
        "report Hertz's p_max and half-width (contact radius) and the errors; needs Line load "
        "(line contact) or Force (point contact) > 0");
  h.set("Radius 1", 1.0, "R1", tfeti::strict::positive());
  h.set("Radius 2", 0.0, "R2; 0 means infinity (a flat body)", tfeti::strict::nonNegative());
  h.set("Line load", 0.0,
        "line contact (2D, or a 3D slab): l, force per unit length of the full (not the half) "
        "model",
        tfeti::strict::nonNegative());
  h.set("Force", 0.0, "point contact (3D): F, the total force of the full (not the quarter) model",
        tfeti::strict::nonNegative());
}

ParameterList fetiParameters(const ParameterList& params, const ElasticContactSpec& spec) {
  ParameterList feti = params.sublist("FETI");
  if (spec.tied) {
    feti.set("Inequality rows", "equalities");
  } else if (tfeti::FetiSolver::inequalitiesTied(feti)) {
    throw std::invalid_argument(
        "FETI: \"Inequality rows\" = equalities with \"Contact problem/Contact type\" = "
        "frictionless; a tied contact pair is chosen by \"Contact type\" = tied");
  }
  return feti;
}

}  // namespace contact
