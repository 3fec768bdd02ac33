#include "contact_Friction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <tuple>

#include "contact_RigidMotions.hpp"
#include "contact_TangentialRows.hpp"
#include "tfeti_StrictParameters.hpp"

namespace contact {

void addFrictionParameters(Teuchos::ParameterList& cp) {
  auto& f = cp.sublist("Friction", false,
                       "friction on the contact pair (Problem = nonlinear_contact: friction "
                       "depends on the load path)");
  f.set("Friction law", "none",
        "none (frictionless), Tresca (|tangential traction| <= Slip bound), Coulomb (<= "
        "Friction coefficient times the pressure, by a fixed point on the slip bound in each "
        "load step)",
        tfeti::strict::choice({"none", "Tresca", "Coulomb"}));
  f.set("Slip bound", 0.0,
        "Tresca: g, the tangential traction at which the surface slips (force per unit length "
        "of the slave boundary in 2D, per unit area in 3D)",
        tfeti::strict::nonNegative());
  f.set("Friction coefficient", 0.0, "Coulomb: mu", tfeti::strict::nonNegative());
  f.set("Fixed-point tolerance", 1e-6,
        "Coulomb: the fixed point of a load step stops when the relative change of the slip "
        "bounds, ||g_new - g|| / ||g_new||, is below it",
        tfeti::strict::positive());
  f.set("Fixed-point iterations", 50,
        "Coulomb: the most fixed-point iterations of a load step (more: the step is rejected and "
        "cut back)",
        tfeti::strict::intBetween(1, 100000));
  f.set("Coulomb scheme", "in_newton",
        "Coulomb: in_newton (the bounds are set to mu lambda_N after every Newton iteration's "
        "QP; the step converges when Eta 1, Eta 2 and the Fixed-point tolerance hold together) "
        "or fixed_point (each fixed-point iteration re-solves the load step's Newton loop with "
        "the bounds of the previous one: 2-2.5x the multiplications)",
        tfeti::strict::choice({"fixed_point", "in_newton"}));
  f.set("Slave", "", "the contact pair this friction is for: its Slave (empty: the pair's)");
  f.set("Master", "", "the contact pair this friction is for: its Master (empty: the pair's)");
}

namespace {

// The friction of the sublist f of the pair (slave, master) of contact type `contactType`;
// errors start with `where`.
FrictionSpec frictionOf(const Teuchos::ParameterList& params, const Teuchos::ParameterList& f,
                        const std::string& where, const std::string& contactType,
                        const std::string& slave, const std::string& master) {
  const std::string law = f.get<std::string>("Friction law");
  const std::string fs = f.get<std::string>("Slave"), fm = f.get<std::string>("Master");
  if ((!fs.empty() && fs != slave) || (!fm.empty() && fm != master))
    throw std::invalid_argument(where + "the pair (Slave \"" + fs + "\", Master \"" + fm +
                                "\") is not a contact pair of the problem (its pair: Slave \"" +
                                slave + "\", Master \"" + master + "\")");
  FrictionSpec spec;
  const std::string scheme = f.get<std::string>("Coulomb scheme");
  if (scheme != "in_newton" && law != "Coulomb")
    throw std::invalid_argument(where + "\"Coulomb scheme\" = " + scheme +
                                " is Coulomb's; \"Friction law\" is " + law);
  spec.slipBound = f.get<double>("Slip bound");
  spec.coefficient = f.get<double>("Friction coefficient");
  if (law == "none") {
    if (spec.slipBound != 0.0 || spec.coefficient != 0.0)
      throw std::invalid_argument(where + "\"" +
                                  (spec.slipBound != 0.0 ? "Slip bound" : "Friction coefficient") +
                                  "\" is given but \"Friction law\" is none");
    return spec;
  }
  if (params.get<std::string>("Problem") != "nonlinear_contact")
    throw std::invalid_argument(where + "\"Friction law\" = " + law +
                                " needs Problem = nonlinear_contact (friction depends on the load "
                                "path: it is solved in load steps); got Problem = " +
                                params.get<std::string>("Problem"));
  if (contactType != "frictionless")
    throw std::invalid_argument(where + "\"Friction law\" = " + law + " with \"" +
                                where.substr(0, where.find("Friction: ")) +
                                "Contact type\" = " + contactType);
  if (law == "Tresca") {
    spec.law = FrictionSpec::Law::Tresca;
    if (spec.coefficient != 0.0)
      throw std::invalid_argument(where +
                                  "\"Friction coefficient\" is Coulomb's; Tresca takes "
                                  "\"Slip bound\"");
    if (!(spec.slipBound > 0.0))
      throw std::invalid_argument(where +
                                  "Tresca needs \"Slip bound\" > 0 (0 is frictionless: "
                                  "\"Friction law\" = none)");
    return spec;
  }
  spec.law = FrictionSpec::Law::Coulomb;
  if (spec.slipBound != 0.0)
    throw std::invalid_argument(where +
                                "\"Slip bound\" is Tresca's; Coulomb takes \"Friction "
                                "coefficient\"");
  spec.fixedPointTolerance = f.get<double>("Fixed-point tolerance");
  spec.maxFixedPointIterations = f.get<int>("Fixed-point iterations");
  spec.scheme =
      scheme == "in_newton" ? FrictionSpec::Scheme::InNewton : FrictionSpec::Scheme::Outer;
  return spec;
}

}  // namespace

FrictionSpec frictionSpec(const Teuchos::ParameterList& params, const std::string& slave,
                          const std::string& master) {
  const auto& cp = params.sublist("Contact problem");
  return frictionOf(params, cp.sublist("Friction"),
                    "Contact problem/Friction: ", cp.get<std::string>("Contact type"), slave,
                    master);
}

bool ModelFriction::active() const {
  return std::any_of(pairs.begin(), pairs.end(), [](const FrictionSpec& f) { return f.active(); });
}

bool ModelFriction::coulomb() const {
  return std::any_of(pairs.begin(), pairs.end(),
                     [](const FrictionSpec& f) { return f.law == FrictionSpec::Law::Coulomb; });
}

const FrictionSpec& ModelFriction::ofPair(int k) const {
  static const FrictionSpec none;
  const std::size_t i = k < 0 ? 0 : static_cast<std::size_t>(k);
  return i < pairs.size() ? pairs[i] : none;
}

namespace {

// The Coulomb controls of `f` become the model's; a second Coulomb pair must give the same.
void takeCoulombControls(ModelFriction& m, const FrictionSpec& f, const std::string& where,
                         const std::string& first) {
  if (first.empty()) {
    m.scheme = f.scheme;
    m.fixedPointTolerance = f.fixedPointTolerance;
    m.maxFixedPointIterations = f.maxFixedPointIterations;
    return;
  }
  std::string key;
  if (f.scheme != m.scheme)
    key = "Coulomb scheme";
  else if (f.fixedPointTolerance != m.fixedPointTolerance)
    key = "Fixed-point tolerance";
  else if (f.maxFixedPointIterations != m.maxFixedPointIterations)
    key = "Fixed-point iterations";
  if (!key.empty())
    throw std::invalid_argument(where + "\"" + key + "\" differs from Coulomb pair \"" + first +
                                "\"'s; the Coulomb pairs share one Newton loop, so they must "
                                "give the same Coulomb scheme, Fixed-point tolerance and "
                                "Fixed-point iterations");
}

}  // namespace

ModelFriction modelFriction(const Teuchos::ParameterList& params,
                            const std::vector<ContactPairSpec>& pairs) {
  ModelFriction out;
  if (pairs.size() == 1 && pairs.front().name.empty()) {
    out.pairs.push_back(frictionSpec(params, pairs.front().slave, pairs.front().master));
    takeCoulombControls(out, out.pairs.back(), "", "");
    return out;
  }
  const auto& list = params.sublist("Contact problem").sublist("Contact pairs");
  std::string firstCoulomb;
  for (const ContactPairSpec& pair : pairs) {
    const std::string where = pair.where + "/Friction: ";
    out.pairs.push_back(frictionOf(params, list.sublist(pair.name).sublist("Friction"), where,
                                   pair.contactType, pair.slave, pair.master));
    if (out.pairs.back().law != FrictionSpec::Law::Coulomb) continue;
    takeCoulombControls(out, out.pairs.back(), where, firstCoulomb);
    if (firstCoulomb.empty()) firstCoulomb = pair.name;
  }
  return out;
}

namespace {

std::pair<int, int> dofOfNode(const ElasticContactProblem& p, int node, int component) {
  return {p.copyOf[node].first, p.dim() * p.copyOf[node].second + component};
}

// The tangential rows friction adds beside contact row k (frictionTangentialRows).
std::vector<ContactRow> frictionTangents(const ElasticContactProblem& p, std::size_t k) {
  return frictionTangentialRows(
      p.contact.rows[k], p.dim(),
      [&](int node, int c) {
        return p.heldComponents.count({node, c}) > 0;
      },
      [&](int node, int c) {
        return p.mirroredComponents.count({node, c}) > 0;
      });
}

std::vector<double> difference(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> d(std::max(a.size(), b.size()), 0.0);
  for (std::size_t i = 0; i < d.size(); ++i)
    d[i] = (i < a.size() ? a[i] : 0.0) - (i < b.size() ? b[i] : 0.0);
  return d;
}

using EntryKey = std::vector<std::tuple<int, int, double>>;

EntryKey entryKey(const tfeti::InequalityRow& r) {
  EntryKey k;
  for (const auto& e : r.entries) k.emplace_back(e.subdomain, e.dof, e.coef);
  return k;
}

}  // namespace

std::vector<tfeti::InequalityRow> frictionRows(const ElasticContactProblem& p,
                                               const ModelFriction& friction,
                                               const SlipBounds& bounds,
                                               const std::vector<double>& stepStart,
                                               const std::vector<double>& current, int rank) {
  std::vector<tfeti::InequalityRow> out;
  if (!friction.active() || rank != 0) return out;
  const int dim = p.dim();
  const std::vector<double> back = difference(stepStart, current);
  const std::vector<double> w = contactRowWeights(p);
  auto dofOf = [&](int n, int c) { return dofOfNode(p, n, c); };
  for (std::size_t k = 0; k < p.contact.rows.size(); ++k) {
    const FrictionSpec& f = friction.ofRow(p, k);
    if (!f.active()) continue;
    double bound = f.slipBound * w[k];
    if (f.law == FrictionSpec::Law::Coulomb) {
      const auto it = bounds.find(p.contact.rows[k].slaveNode);
      bound = it == bounds.end() ? 0.0 : it->second;
    }
    // A zero bound holds the multipliers at 0: the rows would change nothing but the QP's size
    // (an open node under Coulomb, and every node in the first fixed-point iteration).
    if (!(bound > 0.0)) continue;
    const std::vector<ContactRow> tangents = frictionTangents(p, k);
    for (std::size_t j = 0; j < tangents.size(); ++j) {
      tfeti::InequalityRow row = toInequalityRow(tangents[j], dofOf);
      row.key = tangentialKey(row, j);
      row.gap = back.empty() ? 0.0 : applyRow(tangents[j], dim, back);
      row.lowerBound = -bound;
      row.upperBound = bound;
      // Two rows (3D): their multipliers in the disc |lambda_T| <= g (isotropic friction); one
      // row (2D, or 3D on a symmetry plane): the box.
      if (tangents.size() == 2) row.disc = static_cast<int>(j) + 1;
      out.push_back(std::move(row));
    }
  }
  return out;
}

SlipBounds stickingBounds(const ElasticContactSpec& spec, const ElasticContactProblem& p,
                          const ModelFriction& friction) {
  double E = 0.0;
  for (const auto& body : spec.bodies) E = std::max(E, body.law.E);
  const std::vector<double> w = contactRowWeights(p);
  SlipBounds bounds;
  for (std::size_t k = 0; k < p.contact.rows.size(); ++k)
    if (friction.ofRow(p, k).law == FrictionSpec::Law::Coulomb)
      bounds[p.contact.rows[k].slaveNode] = 10.0 * E * w[k];
  return bounds;
}

namespace {

// Coulomb's rows for the load limit: each Coulomb contact row's tangential rows, without bounds
// of their own, appended to `rows`, and the cones that tie them to their contact rows (found in
// `rows` by their entries; one not found keeps its tangential rows unbounded, without a cone).
std::vector<FrictionCone> addCoulombCones(const ElasticContactProblem& p,
                                          const ModelFriction& friction,
                                          std::vector<tfeti::InequalityRow>& rows, int rank) {
  std::vector<FrictionCone> cones;
  if (!friction.coulomb() || rank != 0) return cones;
  std::map<EntryKey, int> rowOf;
  for (std::size_t i = 0; i < rows.size(); ++i)
    rowOf.emplace(entryKey(rows[i]), static_cast<int>(i));
  auto dofOf = [&](int n, int c) { return dofOfNode(p, n, c); };
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < p.contact.rows.size(); ++k) {
    const FrictionSpec& f = friction.ofRow(p, k);
    if (!f.active() || f.law != FrictionSpec::Law::Coulomb) continue;
    FrictionCone cone;
    cone.mu = f.coefficient;
    const auto normal = rowOf.find(entryKey(toInequalityRow(p.contact.rows[k], dofOf)));
    if (normal != rowOf.end()) cone.normal = normal->second;
    const std::vector<ContactRow> tangents = frictionTangents(p, k);
    for (std::size_t j = 0; j < tangents.size(); ++j) {
      tfeti::InequalityRow row = toInequalityRow(tangents[j], dofOf);
      row.lowerBound = -inf;
      row.upperBound = inf;
      cone.tangents.push_back(static_cast<int>(rows.size()));
      rows.push_back(std::move(row));
    }
    if (cone.normal >= 0 && !cone.tangents.empty()) cones.push_back(std::move(cone));
  }
  return cones;
}

}  // namespace

InitialFriction addInitialFrictionRows(const ElasticContactSpec& spec,
                                       const ElasticContactProblem& p,
                                       const ModelFriction& friction, const SlipBounds& bounds,
                                       std::vector<tfeti::InequalityRow>& rows,
                                       const tfeti::Comm& comm) {
  const auto frictionRowsWith = [&](const SlipBounds& b) {
    return frictionRows(p, friction, b, {}, {}, comm.getRank());
  };
  const auto withRows = [&](const std::vector<tfeti::InequalityRow>& f) {
    std::vector<tfeti::InequalityRow> all = rows;
    all.insert(all.end(), f.begin(), f.end());
    return all;
  };
  const auto withFriction = [&](const SlipBounds& b) { return withRows(frictionRowsWith(b)); };
  InitialFriction out{bounds, false, std::nullopt};
  // What the rows can hold along the free rigid motions is known before any solve where the
  // loads are proportional: Tresca's bounds are the data's, Coulomb's cones mu's.
  if (p.rampedLoads.empty()) {
    std::vector<tfeti::InequalityRow> limitRows = withFriction({});  // Coulomb's: no bound yet
    const std::vector<FrictionCone> cones = addCoulombCones(p, friction, limitRows, comm.getRank());
    out.limit = frictionLoadLimit(spec, p, limitRows, cones, comm);
  }
  // Does Coulomb friction hold a body? Free without its rows (Tresca's stay), held with them
  // sticking (docs/friction.md, "A body held by friction alone"). Where the sticking rows do
  // not hold it either, the check below names the motions free without them.
  if (friction.coulomb() && !freeRigidMotions(spec, p, withFriction({}), comm).empty()) {
    SlipBounds stick = stickingBounds(spec, p, friction);
    std::vector<tfeti::InequalityRow> stuck = withFriction(stick);
    if (freeRigidMotions(spec, p, stuck, comm).empty()) {
      rows = std::move(stuck);
      out.bounds = std::move(stick);
      out.sticks = true;
      return out;
    }
  }
  std::vector<tfeti::InequalityRow> with = withFriction(bounds);
  requireRigidMotionsHeld(spec, p, with, comm);
  rows = std::move(with);
  return out;
}

namespace {

// A node's tangential force, slip, bound and state from its tangential rows' multipliers and
// bounds (none: held in every tangent; one: a box; two: a disc). `step` is the step's surface
// displacement, w the node's weight.
void setNodeFriction(ContactNode& node, const ContactRow& row,
                     const std::vector<ContactRow>& tangents, const std::vector<double>& lambda,
                     const std::vector<double>& bound, bool sticks, const FrictionSpec& friction,
                     int dim, const std::vector<double>& step, double w) {
  if (tangents.empty()) {
    // Held in every tangential direction: no slip, and the supports carry the tangential
    // force. The bound is the one the rows would have had (Coulomb: of the final state).
    const auto basis = tangentBasis(row.normal, dim);
    for (int c = 0; c < 3; ++c) node.tangent[c] = basis[0][c];
    node.tangentialForce = 0.0;
    node.slip = 0.0;
    node.slipBound = friction.law == FrictionSpec::Law::Tresca
                         ? friction.slipBound * w
                         : friction.coefficient * std::max(node.lambda, 0.0);
    node.frictionState = node.lambda > 0.0 ? 1 : 0;
  } else if (tangents.size() == 1) {
    // One tangent (2D; 3D on a symmetry plane): the signed force along it.
    node.slipBound = bound[0];
    node.tangentialForce = lambda[0];
    node.slip = step.empty() ? 0.0 : -applyRow(tangents[0], dim, step);
    for (int c = 0; c < 3; ++c) node.tangent[c] = tangents[0].normal[c];
  } else {
    // A disc: the tangent is the direction of the tangential force (the first tangent where
    // it is zero), tangentialForce its magnitude, slip the step's slip along it; slip where
    // |lambda_T| is at the disc's radius.
    node.slipBound = bound[0];
    const double l1 = lambda[0], l2 = lambda[1], lt = std::hypot(l1, l2);
    const double c1 = lt > 0.0 ? l1 / lt : 1.0, c2 = lt > 0.0 ? l2 / lt : 0.0;
    node.tangentialForce = lt;
    for (int c = 0; c < 3; ++c)
      node.tangent[c] = c1 * tangents[0].normal[c] + c2 * tangents[1].normal[c];
    node.slip =
        step.empty()
            ? 0.0
            : -(c1 * applyRow(tangents[0], dim, step) + c2 * applyRow(tangents[1], dim, step));
  }
  // Stick where the solver's rows hold with equality (its primal fit's), slip at the bound.
  if (!tangents.empty()) node.frictionState = !(node.lambda > 0.0) ? 0 : sticks ? 1 : 2;
  node.tangentialTraction = w > 0.0 ? node.tangentialForce / w : 0.0;
}

}  // namespace

void addFrictionResults(std::vector<ContactNode>& nodes, const ElasticContactProblem& p,
                        const tfeti::FetiSolver& solver, const ModelFriction& friction,
                        const std::vector<double>& stepStart, const std::vector<double>& current) {
  if (!friction.active()) return;
  const int dim = p.dim();
  // Tangential rows differ from every other row in their entries (the coefficients are the
  // tangent's, not the normal's), whatever their right-hand side was in the last iteration.
  const auto lambdas = solver.inequalityMultipliers();
  // Stick or slip as the solver's primal fit took each row (FetiSolver::inequalityRowsHolding).
  const auto holding = solver.inequalityRowsHolding();
  const auto& rows = solver.tearing().inequalityRows;
  std::map<EntryKey, std::size_t> byEntries;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (!rows[i].isNonPenetration()) byEntries[entryKey(rows[i])] = i;
  std::map<int, ContactNode*> bySlave;
  for (auto& n : nodes) bySlave[n.slaveNode] = &n;
  const std::vector<double> step = difference(current, stepStart);
  const std::vector<double> w = contactRowWeights(p);
  auto dofOf = [&](int n, int c) { return dofOfNode(p, n, c); };
  for (std::size_t k = 0; k < p.contact.rows.size(); ++k) {
    const FrictionSpec& f = friction.ofRow(p, k);
    if (!f.active()) continue;
    const ContactRow& row = p.contact.rows[k];
    ContactNode& node = *bySlave.at(row.slaveNode);
    const std::vector<ContactRow> tangents = frictionTangents(p, k);
    // Each tangential row's multiplier and bound; a node without its rows had a zero bound
    // (frictionRows leaves them out): multipliers 0.
    std::vector<double> lambda, bound;
    bool sticks = true;
    for (const ContactRow& t : tangents) {
      const auto it = byEntries.find(entryKey(toInequalityRow(t, dofOf)));
      if (it == byEntries.end() && !lambda.empty())
        throw std::logic_error("addFrictionResults: one tangential row of slave node " +
                               std::to_string(row.slaveNode) + " is not in the solver's rows");
      if (it == byEntries.end()) break;
      lambda.push_back(lambdas[it->second]);
      bound.push_back(rows[it->second].upperBound);
      sticks = sticks && holding[it->second] != 0.0;
    }
    // A node without its rows (a zero bound) slips.
    sticks = sticks && lambda.size() == tangents.size();
    lambda.resize(tangents.size(), 0.0);
    bound.resize(tangents.size(), 0.0);
    for (int c = 0; c < 3; ++c) node.force[c] = node.lambda * node.normal[c];
    for (std::size_t j = 0; j < tangents.size(); ++j)
      for (int c = 0; c < dim; ++c) node.force[c] += lambda[j] * tangents[j].normal[c];
    setNodeFriction(node, row, tangents, lambda, bound, sticks, f, dim, step, w[k]);
  }
}

const char* frictionStateName(int state) {
  return state == 0 ? "open" : state == 1 ? "stick" : state == 2 ? "slip" : "none";
}

namespace {

// Cattaneo-Mindlin (bodies of one material, a tangential force Q below mu P at a constant normal
// force P): a centred stick zone, c = a sqrt(1 - Q/(mu P)) for cylinders (2D, a and c
// half-widths), c = a (1 - Q/(mu P))^(1/3) for spheres (3D, radii).
void addCattaneoMindlin(Json& f, const FrictionSpec& friction, double q, double p, double a,
                        double c, int dim) {
  if (friction.law != FrictionSpec::Law::Coulomb || !(a > 0.0) || !(p > 0.0) ||
      !(friction.coefficient > 0.0))
    return;
  const double ratio = q / (friction.coefficient * p);
  Json cm = Json::object();
  cm["normal_force"] = p;
  cm["tangential_force"] = q;
  cm[dim == 2 ? "contact_half_width" : "contact_radius"] = a;
  cm[dim == 2 ? "stick_half_width" : "stick_radius"] = c;
  cm["q_over_mu_p"] = ratio;
  cm["stick_ratio"] = c / a;
  if (ratio <= 1.0) {
    const double closedForm = dim == 2 ? std::sqrt(1.0 - ratio) : std::cbrt(1.0 - ratio);
    cm["stick_ratio_closed_form"] = closedForm;
    cm["stick_ratio_error"] =
        closedForm > 0.0 ? std::abs(c / a - closedForm) / closedForm : std::abs(c / a);
  }
  f["cattaneo_mindlin"] = std::move(cm);
}

// The friction record over `nodes`, those of the friction pairs `pairs` (each node's bound from
// its own pair's law).
void frictionRecord(Json& f, const std::vector<ContactNode>& nodes, const ModelFriction& friction,
                    const std::vector<int>& pairs, int dim) {
  double force = 0.0, ratio = 0.0, stickLo = 0.0, stickHi = 0.0, closedLo = 0.0, closedHi = 0.0;
  double stickRadius = 0.0, contactRadius = 0.0;  // 3D: from the contact axis
  long long slip = 0, stick = 0, closed = 0;
  double normal = 0.0, maxPath = 0.0, maxNet = 0.0, maxStep = 0.0;
  for (const auto& n : nodes) {
    force += n.tangentialForce * n.tangent[0];
    normal += n.lambda;
    maxPath = std::max(maxPath, n.accumulatedSlip);
    maxNet = std::max(maxNet, std::abs(n.netSlip));
    if (n.frictionState == 0) continue;
    maxStep = std::max(maxStep, std::abs(n.slip));
    contactRadius = std::max(contactRadius, n.radius);
    if (n.frictionState == 1) stickRadius = std::max(stickRadius, n.radius);
    closedLo = closed ? std::min(closedLo, n.x) : n.x;
    closedHi = closed ? std::max(closedHi, n.x) : n.x;
    ++closed;
    // Coulomb: against mu lambda_N of the final state (the bound in force is the last
    // fixed-point iterate's, equal to it within the fixed point's tolerance).
    const FrictionSpec& law = friction.ofPair(n.pair);
    const double bound =
        law.law == FrictionSpec::Law::Coulomb ? law.coefficient * n.lambda : n.slipBound;
    if (bound > 0.0) ratio = std::max(ratio, std::abs(n.tangentialForce) / bound);
    if (n.frictionState == 2) ++slip;
    if (n.frictionState == 1) {
      stickLo = stick ? std::min(stickLo, n.x) : n.x;
      stickHi = stick ? std::max(stickHi, n.x) : n.x;
      ++stick;
    }
  }
  // The law, and its parameter where all the pairs share it.
  const FrictionSpec& first = friction.ofPair(pairs.front());
  bool sameLaw = true, sameParameter = true;
  for (int k : pairs) {
    const FrictionSpec& other = friction.ofPair(k);
    sameLaw = sameLaw && other.law == first.law;
    sameParameter = sameParameter && other.slipBound == first.slipBound &&
                    other.coefficient == first.coefficient;
  }
  f["friction_law"] = !sameLaw                                 ? "mixed"
                      : first.law == FrictionSpec::Law::Tresca ? "Tresca"
                                                               : "Coulomb";
  if (sameLaw && sameParameter && first.law == FrictionSpec::Law::Tresca)
    f["slip_bound"] = first.slipBound;
  if (sameLaw && sameParameter && first.law == FrictionSpec::Law::Coulomb)
    f["friction_coefficient"] = first.coefficient;
  // Cattaneo-Mindlin's stick zone is one pair's.
  const FrictionSpec& single = pairs.size() == 1 ? first : FrictionSpec();
  f["normal_force"] = normal;
  f["tangential_force"] = force;
  // The resultant of the contact forces on the slave nodes: unlike the sums above it does not
  // depend on the frame a node at a master kink takes (ContactNode::force).
  Json resultant = Json::array();
  for (int c = 0; c < dim; ++c) {
    double sum = 0.0;
    for (const auto& n : nodes) sum += n.force[c];
    resultant.push(sum);
  }
  f["contact_force"] = std::move(resultant);
  f["slip_nodes"] = slip;
  f["stick_nodes"] = stick;
  if (dim == 2) f["stick_half_width"] = stick ? 0.5 * (stickHi - stickLo) : 0.0;
  f["max_tangential_ratio"] = ratio;
  f["max_slip_increment"] = maxStep;
  f["max_accumulated_slip"] = maxPath;
  f["max_net_slip"] = maxNet;
  if (dim == 3) {
    // The largest distance from the contact axis of the closed and of the stick nodes: the
    // contact radius a and the stick radius c of a point contact (ContactExtentRule).
    f["contact_radius"] = contactRadius;
    f["stick_radius"] = stickRadius;
    addCattaneoMindlin(f, single, std::abs(force), normal, contactRadius, stickRadius, 3);
  }
  if (dim == 2) {
    // Half the x extent of the closed nodes: the contact half-width a that goes with the stick
    // half-width c (both measured on the nodes, so that their ratio shares the mesh's bias).
    const double a = closed ? 0.5 * (closedHi - closedLo) : 0.0;
    f["contact_half_width"] = a;
    addCattaneoMindlin(f, single, std::abs(force), normal, a,
                       stick ? 0.5 * (stickHi - stickLo) : 0.0, 2);
  }
}

}  // namespace

void addFrictionJson(Json& f, const std::vector<ContactNode>& allNodes,
                     const ModelFriction& friction, int dim) {
  // The nodes of the pairs with friction (all of them for the old keys' pair).
  std::vector<ContactNode> nodes;
  for (const auto& n : allNodes)
    if (friction.ofPair(n.pair).active()) nodes.push_back(n);
  std::vector<int> pairs;
  for (std::size_t k = 0; k < friction.pairs.size(); ++k)
    if (friction.pairs[k].active()) pairs.push_back(static_cast<int>(k));
  if (!pairs.empty()) frictionRecord(f, nodes, friction, pairs, dim);
}

void addPairFrictionJson(Json& pairEntry, const std::vector<ContactNode>& allNodes,
                         const ModelFriction& friction, int k, int dim) {
  if (!friction.ofPair(k).active()) return;
  std::vector<ContactNode> nodes;
  for (const auto& n : allNodes)
    if (n.pair == k) nodes.push_back(n);
  Json f = Json::object();
  frictionRecord(f, nodes, friction, {k}, dim);
  pairEntry["friction"] = std::move(f);
}

}  // namespace contact
