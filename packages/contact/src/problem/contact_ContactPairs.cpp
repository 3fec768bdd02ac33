// The contact pairs of a model: the old single pair or "Contact pairs", validated, and the one
// function that makes a pair's master.
#include "contact_ContactPairs.hpp"

#include "contact_Mortar.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <algorithm>
#include <stdexcept>

#include "contact_Friction.hpp"
#include "tfeti_StrictParameters.hpp"

namespace contact {

namespace {

using Teuchos::Array;
using Teuchos::ParameterList;

template <class T>
std::vector<T> vec(const Array<T>& a) {
  return std::vector<T>(a.begin(), a.end());
}

// The keys of a pair, also the old keys directly in "Contact problem".
const char* const kPairKeys[] = {"Slave",        "Master",        "Rigid obstacle",
                                 "Contact type", "Search radius", "Contact discretization",
                                 "Friction"};

// Whether a parameter or sublist of l has a value other than its default in `valid`: a list
// validated before (tfeti_contact, then ContactSolver::setParameters) holds every default, so
// presence does not tell what the user gave. An unknown key counts as given.
bool given(const ParameterList& l, const std::string& name, const ParameterList& valid) {
  if (!l.isParameter(name)) return false;
  if (!valid.isParameter(name)) return true;
  if (!l.isSublist(name))
    return !(l.getEntry(name).getAny(false) == valid.getEntry(name).getAny(false));
  const ParameterList& s = l.sublist(name);
  if (!valid.isSublist(name)) return true;
  for (auto it = s.begin(); it != s.end(); ++it)
    if (given(s, s.name(it), valid.sublist(name))) return true;
  return false;
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "\"" : ", \"") + n + "\"";
  return s;
}

ContactPairSpec pairFrom(const ParameterList& l, const std::string& name,
                         const std::string& where) {
  ContactPairSpec p;
  p.name = name;
  p.where = where;
  p.slave = l.get<std::string>("Slave");
  p.master = l.get<std::string>("Master");
  p.searchRadius = l.get<double>("Search radius");
  p.contactType = l.get<std::string>("Contact type");
  p.discretization = l.get<std::string>("Contact discretization");
  p.obstacle = rigidObstacleFrom(l.sublist("Rigid obstacle"), where + "/Rigid obstacle");
  return p;
}

}  // namespace

std::string pairLabel(const ContactPairSpec& pair) {
  return pair.name.empty() ? std::string("the contact pair") : "pair \"" + pair.name + "\"";
}

void addContactPairKeys(ParameterList& cp) {
  cp.set("Slave", "", "the contact pair's slave boundary (its nodes)");
  cp.set("Master", "",
         "the contact pair's master boundary (its segments); empty with a Rigid obstacle");
  cp.set("Contact type", "frictionless",
         "frictionless: B_I u <= gap, contact pressure >= 0; tied: B_I u = gap, the pair bonded "
         "in the normal direction (the same rows held with equality, pressure of either sign: a "
         "linear problem solved by PCPG; elastic_contact only); bonded: tied, and the tangential "
         "rows B_T u = 0 beside them (no relative motion along the surface either)",
         Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
             Teuchos::tuple<std::string>("frictionless", "tied", "bonded"), "Contact type")));
  cp.set("Search radius", 0.0,
         "slave nodes farther from the master get no row; 0: a tenth of "
         "the mesh's extent",
         tfeti::strict::nonNegative());
  auto& ro = cp.sublist("Rigid obstacle", false,
                        "a rigid master given analytically instead of a Master boundary: the "
                        "Slave boundary is pressed against it");
  ro.set("Type", "none",
         "none, line (a half-plane) or circle (a disc) in 2D, plane (a half-space) or sphere (a "
         "ball) in 3D",
         Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
             Teuchos::tuple<std::string>("none", "line", "circle", "plane", "sphere"), "Type")));
  ro.set("Point", Array<double>(), "line/plane: {x, y[, z]} of a point on it");
  ro.set("Normal", Array<double>(), "line/plane: {nx, ny[, nz]}, pointing out of the obstacle");
  ro.set("Centre", Array<double>(), "circle/sphere: {x, y[, z]} of its centre");
  ro.set("Radius", 0.0, "circle/sphere: its radius (> 0)");
  ro.set("Gap direction", Array<double>(),
         "empty: gaps along the obstacle's normal (closest point); {dx, dy[, dz]}: gaps measured "
         "along this fixed direction from the body towards the obstacle, as a height function "
         "(the classical Signorini form of deal.II's step-41/42)");
  cp.set("Contact discretization", "node_to_segment",
         "node_to_segment: one row per slave node at its closest point on the master "
         "(collocation; segments in 2D, faces in 3D); mortar: dual mortar, one row per slave node "
         "holding the weighted gap of its dual basis function over the overlaps of the slave and "
         "master facets (accurate pressures on non-matching and unstructured meshes; Tri6/Quad8 "
         "slaves use the modified quadratic dual basis; docs/mortar_contact.md)",
         Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
             Teuchos::tuple<std::string>("node_to_segment", "mortar"), "Contact discretization")));
}

void addContactPairsDocumentation(ParameterList& cp) {
  cp.sublist("Contact pairs", false,
             "several contact pairs instead of the single pair of Slave, Master, Rigid obstacle, "
             "Contact type, Contact discretization, Search radius and Friction: one sublist per "
             "pair, named by the user, holding those keys (Slave, and Master or a Rigid "
             "obstacle). Every pair's rows are in the one QP; a slave node may have rows in one "
             "pair only; all pairs share one Contact type; Friction on one pair at most");
}

Teuchos::RCP<const ParameterList> validContactPairParameters() {
  static Teuchos::RCP<ParameterList> pl;
  if (!pl.is_null()) return pl;
  pl = Teuchos::rcp(new ParameterList("Contact pairs/<pair>"));
  addContactPairKeys(*pl);
  addFrictionParameters(*pl);
  tfeti::strict::requireNumbers(*pl);
  return pl;
}

GivenContactPairs takeContactPairs(ParameterList& params) {
  GivenContactPairs g;
  if (!params.isSublist("Contact problem")) return g;
  ParameterList& cp = params.sublist("Contact problem");
  for (const char* key : kPairKeys)
    if (given(cp, key, *validContactPairParameters())) g.oldKeys.push_back(key);
  if (cp.isParameter("Contact pairs")) {
    if (!cp.isSublist("Contact pairs"))
      throw std::invalid_argument(
          "Contact problem: \"Contact pairs\" must be a sublist (one sublist per pair), not a "
          "parameter");
    g.pairs = cp.sublist("Contact pairs");
    cp.remove("Contact pairs");
  }
  return g;
}

void restoreContactPairs(ParameterList& params, const GivenContactPairs& g) {
  ParameterList& cp = params.sublist("Contact problem");
  std::vector<std::string> names;
  for (auto it = g.pairs.begin(); it != g.pairs.end(); ++it) names.push_back(g.pairs.name(it));
  if (names.empty()) {
    // The validation filled in the documented empty sublist: drop it, so that validating the
    // validated list again gives the same list.
    if (cp.isSublist("Contact pairs") && cp.sublist("Contact pairs").numParams() == 0)
      cp.remove("Contact pairs");
    return;
  }
  if (!g.oldKeys.empty())
    throw std::invalid_argument(
        "Contact problem: \"Contact pairs\" (" + joined(names) + ") and the single-pair key" +
        (g.oldKeys.size() > 1 ? "s " : " ") + joined(g.oldKeys) +
        " are both given; with Contact pairs every pair holds its own keys in its sublist");
  ParameterList checked("Contact pairs");
  for (const auto& name : names) {
    const std::string path = "Contact problem/Contact pairs/" + name;
    if (!g.pairs.isSublist(name))
      throw std::invalid_argument(path +
                                  ": must be a sublist holding the pair's Slave and "
                                  "Master (or Rigid obstacle)");
    ParameterList pair = g.pairs.sublist(name);
    try {
      pair.validateParametersAndSetDefaults(*validContactPairParameters());
    } catch (const std::exception& e) {
      const std::string what = e.what();
      throw std::invalid_argument(what.find(path) == std::string::npos ? path + ": " + what : what);
    }
    checked.set(name, pair);
  }
  cp.set("Contact pairs", checked);
}

std::optional<RigidObstacle> rigidObstacleFrom(const ParameterList& ro, const std::string& where) {
  const std::string type = ro.get<std::string>("Type");
  if (type == "none") return std::nullopt;
  RigidObstacle o;
  // line and circle are 2D obstacles, plane and sphere 3D ones; the mesh must agree
  // (checked by buildElasticContactProblem).
  o.dim = type == "plane" || type == "sphere" ? 3 : 2;
  o.shape = obstacleShapeFromName(type, o.dim);
  const std::string xyz = o.dim == 3 ? "{x, y, z}" : "{x, y}";
  const char* at = o.shape == RigidObstacle::Shape::Ball ? "Centre" : "Point";
  const auto point = vec(ro.get<Array<double>>(at));
  if (static_cast<int>(point.size()) != o.dim)
    throw std::invalid_argument(where + ": \"" + at + "\" needs " + std::to_string(o.dim) +
                                " values " + xyz + " for a " + type);
  for (int c = 0; c < o.dim; ++c) o.point[c] = point[c];
  if (o.shape == RigidObstacle::Shape::HalfSpace) {
    const auto normal = vec(ro.get<Array<double>>("Normal"));
    if (static_cast<int>(normal.size()) != o.dim)
      throw std::invalid_argument(where + ": \"Normal\" needs " + std::to_string(o.dim) +
                                  " values (out of the obstacle) for a " + type);
    for (int c = 0; c < o.dim; ++c) o.normal[c] = normal[c];
  } else {
    o.radius = ro.get<double>("Radius");
  }
  const auto direction = vec(ro.get<Array<double>>("Gap direction"));
  if (!direction.empty()) {
    if (static_cast<int>(direction.size()) != o.dim)
      throw std::invalid_argument(where + ": \"Gap direction\" needs " + std::to_string(o.dim) +
                                  " values " + xyz + " for a " + type +
                                  " (or none: the gap along the normal)");
    for (int c = 0; c < o.dim; ++c) o.gapDirection[c] = direction[c];
    if (!o.heightFunction())
      throw std::invalid_argument(where +
                                  ": \"Gap direction\" is zero (leave it empty for the gap along "
                                  "the normal)");
  }
  return o;
}

std::vector<ContactPairSpec> contactPairSpecs(const ParameterList& params) {
  const auto& cp = params.sublist("Contact problem");
  const std::string problem = params.get<std::string>("Problem");
  std::vector<ContactPairSpec> pairs;
  const bool named = cp.isSublist("Contact pairs") && cp.sublist("Contact pairs").numParams() > 0;
  if (!named) {
    pairs.push_back(pairFrom(cp, "", "Contact problem"));
  } else {
    const auto& list = cp.sublist("Contact pairs");
    for (auto it = list.begin(); it != list.end(); ++it) {
      const std::string name = list.name(it);
      const std::string where = "Contact problem/Contact pairs/" + name;
      ContactPairSpec p = pairFrom(list.sublist(name), name, where);
      if (p.slave.empty())
        throw std::invalid_argument(where + ": \"Slave\" is required (the pair's slave boundary)");
      if (p.master.empty() && !p.obstacle)
        throw std::invalid_argument(where +
                                    ": neither \"Master\" nor a \"Rigid obstacle\" is given; a "
                                    "pair needs one of them");
      if (!p.master.empty() && p.obstacle)
        throw std::invalid_argument(where + ": \"Master\" = \"" + p.master +
                                    "\" and a \"Rigid obstacle\" are both given; a pair has "
                                    "one master");
      pairs.push_back(std::move(p));
    }
  }
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const ContactPairSpec& p = pairs[k];
    // The old pair's message is kept word for word.
    if (p.slave == p.master)
      throw std::invalid_argument(p.where + ": \"Slave\" and \"Master\" both name \"" + p.slave +
                                  "\"; a contact pair needs two different boundaries");
    if (p.contactType != "frictionless" && problem != "elastic_contact")
      throw std::invalid_argument(p.where + ": \"Contact type\" = " + p.contactType +
                                  " is available for Problem = elastic_contact only (got " +
                                  problem + ")");
    for (std::size_t j = 0; j < k; ++j) {
      const ContactPairSpec& q = pairs[j];
      // The same slave against the same master boundary twice would repeat every row (a
      // singular B_I); against two obstacles it may be a corner (the row rule decides).
      if (p.slave == q.slave && !p.master.empty() && p.master == q.master)
        throw std::invalid_argument(p.where + ": the same pair as \"" + q.name + "\" (Slave \"" +
                                    p.slave + "\", Master \"" + p.master +
                                    "\"); each pair may be given once");
      // One QP holds either inequalities or equalities (FETI "Inequality rows").
      if ((p.contactType == "frictionless") != (q.contactType == "frictionless"))
        throw std::invalid_argument(
            p.where + ": \"Contact type\" = " + p.contactType + " but pair \"" + q.name + "\" is " +
            q.contactType +
            "; the pairs of a model share one kind of row (all frictionless, or all tied or "
            "bonded)");
    }
  }
  return pairs;
}

std::shared_ptr<const ContactMaster> makePairMaster(const GmshMesh& mesh,
                                                    const ContactPairSpec& pair,
                                                    const ContactSearchOptions& options) {
  const bool mortar = pair.discretization == "mortar";
  if (pair.obstacle) {
    try {
      if (mortar)
        return makeMortarObstacleMaster(mortarSurfaceOfBoundary(mesh, pair.slave), *pair.obstacle,
                                        options);
      return makeObstacleMaster(*pair.obstacle, options);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(pair.where + "/Rigid obstacle: " + e.what());
    }
  }
  if (mortar)
    return makeMortarMaster(mortarSurfaceOfBoundary(mesh, pair.slave),
                            mortarSurfaceOfBoundary(mesh, pair.master), options);
  return makeMeshContactMaster(mesh, pair.master, options);
}

}  // namespace contact
