// The bodies' materials: one "Material" for all, or "Materials" with a sublist per body.
#include "contact_Materials.hpp"

#include <algorithm>
#include <stdexcept>

#include "tfeti_StrictParameters.hpp"

namespace contact {

namespace {

using Teuchos::Array;
using Teuchos::ParameterList;

const char* const kElastic[] = {"Young's modulus", "Poisson's ratio"};

// The four parameters of a material, in the list `m` (the global one or a body's).
void setMaterialParameters(ParameterList& m) {
  m.set("Young's modulus", 1.0, "E", tfeti::strict::positive());
  m.set("Poisson's ratio", 0.3, "nu", tfeti::strict::between(-1.0, 0.5, true, true));
  m.set("Yield stress", 0.0,
        "nonlinear_contact: initial uniaxial yield stress of J2 plasticity; 0: elastic",
        tfeti::strict::nonNegative());
  m.set("Hardening modulus", 0.0,
        "nonlinear_contact: linear isotropic hardening modulus H (0: perfect plasticity)",
        tfeti::strict::nonNegative());
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "none" : s;
}

std::vector<std::string> sublistNames(const ParameterList& l) {
  std::vector<std::string> names;
  for (auto it = l.begin(); it != l.end(); ++it) names.push_back(l.name(it));
  return names;
}

BodyMaterial materialFrom(const ParameterList& m) {
  BodyMaterial b;
  b.elastic =
      plasticity::ElasticLaw(m.get<double>("Young's modulus"), m.get<double>("Poisson's ratio"));
  b.yieldStress = m.get<double>("Yield stress");
  b.hardening = m.get<double>("Hardening modulus");
  return b;
}

}  // namespace

void addMaterialParameters(ParameterList& valid) {
  setMaterialParameters(valid.sublist(
      "Material", false,
      "isotropic linear elasticity (plane strain in 2D), J2 plasticity in nonlinear_contact: "
      "one material for every body"));
  valid.sublist(
      "Materials", false,
      "elastic_contact, nonlinear_contact: a material per body instead of Material: one "
      "sublist per body of Contact problem/Bodies, named as the body, holding \"Young's "
      "modulus\" and \"Poisson's ratio\" (required) and \"Yield stress\", \"Hardening "
      "modulus\" (default 0), with the ranges of Material; every body needs one, and Material "
      "is then not given");
}

Teuchos::RCP<const ParameterList> validBodyMaterialParameters() {
  static Teuchos::RCP<ParameterList> pl;
  if (!pl.is_null()) return pl;
  pl = Teuchos::rcp(new ParameterList("Materials/<body>"));
  setMaterialParameters(*pl);
  tfeti::strict::requireNumbers(*pl);
  return pl;
}

GivenMaterials takeBodyMaterials(ParameterList& params) {
  GivenMaterials given;
  if (params.isSublist("Material")) {
    const auto& global = params.sublist("Material");
    for (auto it = global.begin(); it != global.end(); ++it)
      given.global.push_back(global.name(it));
  }
  if (params.isParameter("Materials")) {
    if (!params.isSublist("Materials"))
      throw std::invalid_argument(
          "\"Materials\" must be a sublist (one sublist per body), not a parameter");
    given.perBody = params.sublist("Materials");
    params.remove("Materials");
  }
  return given;
}

void restoreBodyMaterials(ParameterList& params, const GivenMaterials& givenMaterials) {
  const ParameterList& perBody = givenMaterials.perBody;
  const auto given = sublistNames(perBody);
  if (given.empty()) {
    // One Material for all bodies (it may be the default). The validation filled in an empty
    // "Materials" (the documented sublist): drop it, so that validating a validated list again
    // (tfeti_contact, then ContactSolver::setParameters) gives the same list.
    if (params.isSublist("Materials") && params.sublist("Materials").numParams() == 0)
      params.remove("Materials");
    return;
  }
  const std::string problem = params.get<std::string>("Problem");
  if (params.get<std::string>("Study") != "single" ||
      (problem != "elastic_contact" && problem != "nonlinear_contact"))
    throw std::invalid_argument(
        "Materials: a material per body is for Problem = elastic_contact or nonlinear_contact "
        "(Study single); " +
        (params.get<std::string>("Study") != "single" ? "Study " + params.get<std::string>("Study")
                                                      : "Problem " + problem) +
        " has one material: give it in Material");
  const auto bodyArray = params.sublist("Contact problem").get<Array<std::string>>("Bodies");
  const std::vector<std::string> bodies(bodyArray.begin(), bodyArray.end());
  std::vector<std::string> both;
  for (const auto& name : givenMaterials.global) both.push_back("\"" + name + "\"");
  if (!both.empty())
    throw std::invalid_argument("Material (" + joined(both) + ") and Materials (per body: " +
                                joined(given) + ") are both given: bodies " + joined(given) +
                                " would have two materials; give either Material (one for "
                                "every body) or Materials (one sublist per body)");
  ParameterList checked("Materials");
  for (const auto& name : given) {
    if (std::find(bodies.begin(), bodies.end(), name) == bodies.end())
      throw std::invalid_argument(
          "Materials: \"" + name +
          "\" is not a body of Contact problem/Bodies (bodies: " + joined(bodies) + ")");
    if (!perBody.isSublist(name))
      throw std::invalid_argument("Materials: \"" + name +
                                  "\" must be a sublist holding the body's material");
    ParameterList m = perBody.sublist(name);
    for (const char* required : kElastic)
      if (!m.isParameter(required))
        throw std::invalid_argument("Materials/" + name + ": \"" + required +
                                    "\" is required (no default for a body's material)");
    try {
      m.validateParametersAndSetDefaults(*validBodyMaterialParameters());
    } catch (const std::exception& e) {
      // The strict validators name the parameter's path already; Teuchos's own messages not.
      const std::string what = e.what(), path = "Materials/" + name;
      throw std::invalid_argument(what.find(path) == std::string::npos ? path + ": " + what : what);
    }
    checked.set(name, m);
  }
  std::vector<std::string> missing;
  for (const auto& b : bodies)
    if (!checked.isSublist(b)) missing.push_back("\"" + b + "\"");
  if (!missing.empty())
    throw std::invalid_argument("Materials: no material for body " + joined(missing) +
                                " of Contact problem/Bodies (given: " + joined(given) +
                                "); with Materials every body needs its sublist");
  params.remove("Material");
  params.set("Materials", checked);
}

std::vector<BodyMaterial> bodyMaterials(const ParameterList& params) {
  const auto bodies = params.sublist("Contact problem").get<Array<std::string>>("Bodies");
  std::vector<BodyMaterial> out;
  const bool perBody = params.isSublist("Materials") && params.sublist("Materials").numParams() > 0;
  for (const auto& b : bodies) {
    if (!perBody) {
      out.push_back(materialFrom(params.sublist("Material")));
      continue;
    }
    const auto& all = params.sublist("Materials");
    if (!all.isSublist(b))  // restoreBodyMaterials has checked this; a caller's own list may not
      throw std::invalid_argument("Materials: no material for body \"" + b + "\"");
    out.push_back(materialFrom(all.sublist(b)));
  }
  return out;
}

double combinedModulus(const std::vector<plasticity::ElasticLaw>& bodies) {
  if (bodies.empty() || bodies.size() > 2)
    throw std::invalid_argument("combinedModulus: one or two bodies, got " +
                                std::to_string(bodies.size()));
  double compliance = 0.0;
  for (const auto& b : bodies) compliance += (1.0 - b.nu * b.nu) / b.E;
  return 1.0 / compliance;
}

void addMaterialSummary(Json& s, const std::vector<ElasticContactSpec::Body>& bodies) {
  const auto record = [](const ElasticContactSpec::Body& b) {
    Json m = Json::object();
    m["youngs_modulus"] = b.law.E;
    m["poissons_ratio"] = b.law.nu;
    if (b.yieldStress > 0.0) {
      m["yield_stress"] = b.yieldStress;
      m["hardening_modulus"] = b.hardening;
    }
    return m;
  };
  Json all = Json::object();
  bool uniform = true;
  for (const auto& b : bodies) {
    all[b.name] = record(b);
    const auto& f = bodies.front();
    uniform = uniform && b.law.E == f.law.E && b.law.nu == f.law.nu &&
              b.yieldStress == f.yieldStress && b.hardening == f.hardening;
  }
  if (uniform && !bodies.empty()) s["material"] = record(bodies.front());
  s["materials"] = std::move(all);
}

}  // namespace contact
