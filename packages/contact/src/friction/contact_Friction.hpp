#pragma once
// Friction on the contact pairs, Tresca and Coulomb: the parameters of `Contact problem/Friction`
// (or of each pair's `Friction` sublist, one FrictionSpec per pair in a ModelFriction), the
// tangential rows B_T of a load-step iteration with their multipliers' box or disc, and the
// per-node friction results.
//
// The increment QP of a load step (contact_NonlinearIteration.hpp) gets, beside each
// non-penetration row, dim - 1 tangential rows (contact_TangentialRows.hpp; fewer where both
// sides are held along a tangent, frictionTangentialRows) with the bounds
// -g_i <= lambda_T <= g_i, g_i = g w_i (w_i the slave node's share of the slave boundary, the
// same lumping that turns the normal multiplier into the pressure, so g is a force per unit
// length in 2D). The term g_i |s_i| of the step's dissipation is in the slip s_i = -B_T,i (u -
// u_0) of the whole step (u_0 the converged state the step starts from): with the increment du
// of an iteration from u, B_T,i du - c_T,i is minus that slip for c_T,i = B_T,i (u_0 - u).
// Friction depends on the path, so it is a nonlinear_contact (load-stepped) feature.
//
// Coulomb, g_i = mu lambda_N,i, by a fixed point on the slip bound within each load step
// (contact_FrictionStep.hpp): the step is solved as Tresca with the bounds of the previous
// iterate (the previous step's at the first, zero at the first step: the frictionless solve),
// the bounds are set to mu times the normal multipliers found, until their relative change
// ||g_new - g|| / ||g_new|| (2-norm over the slave nodes) is below the tolerance.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "contact_ContactOutput.hpp"
#include "contact_ElasticContactProblem.hpp"
#include "contact_RigidMotions.hpp"

namespace contact {

struct FrictionSpec {
  enum class Law { None, Tresca, Coulomb };
  Law law = Law::None;
  double slipBound = 0.0;    // Tresca: g, force per unit length (2D) of the slave boundary
  double coefficient = 0.0;  // Coulomb: mu
  double fixedPointTolerance = 1e-6;
  int maxFixedPointIterations = 50;
  // Coulomb: the bounds updated after every Newton iteration (InNewton, the default), or a fixed
  // point around the step's Newton loop (Outer, `Coulomb scheme` = fixed_point;
  // contact_FrictionStep.hpp).
  enum class Scheme { Outer, InNewton };
  Scheme scheme = Scheme::InNewton;
  bool active() const { return law != Law::None; }
};

// The friction of a model: one FrictionSpec per contact pair (law none on a pair without
// friction), so that pairs may differ in law and bound. Coulomb's fixed-point controls (scheme,
// tolerance, iterations) belong to the model's one Newton loop: modelFriction takes them from
// the Coulomb pairs, which must agree on them.
struct ModelFriction {
  std::vector<FrictionSpec> pairs;  // per pair of ElasticContactProblem::pairs (old keys: one)
  FrictionSpec::Scheme scheme = FrictionSpec::Scheme::InNewton;
  double fixedPointTolerance = 1e-6;
  int maxFixedPointIterations = 50;
  bool active() const;   // some pair has friction
  bool coulomb() const;  // some pair has Coulomb friction
  // The friction of pair k (-1, a ContactNode of the old keys' pair: the first); law none for a
  // pair the model does not have.
  const FrictionSpec& ofPair(int k) const;
  // The friction of contact row k of p.contact.
  const FrictionSpec& ofRow(const ElasticContactProblem& p, std::size_t k) const {
    return ofPair(p.rowPair[k]);
  }
};

// Per slave node (global id): its slip bound as a force, g_i (Coulomb: mu lambda_N,i).
using SlipBounds = std::map<int, double>;

// `Contact problem/Friction`: Friction law, Slip bound, Friction coefficient, Slave, Master.
void addFrictionParameters(Teuchos::ParameterList& contactProblem);

// The validated friction of `params` for the contact pair (slave, master; master empty for a
// rigid obstacle). Throws std::invalid_argument naming the parameter: a pair other than the
// contact pair, a parameter of a law not chosen (a Slip bound with Coulomb), Tresca without a
// positive Slip bound, friction with Problem other than nonlinear_contact, Coulomb (its fixed
// Negative values are refused by the parameters' validators.
FrictionSpec frictionSpec(const Teuchos::ParameterList& params, const std::string& slave,
                          const std::string& master);

// The friction of the model: that of the old keys' pair (frictionSpec), or of each pair of
// Contact pairs from its Friction sublist. Throws std::invalid_argument as frictionSpec for a
// pair's sublist, and naming both pairs when two Coulomb pairs differ in Coulomb scheme,
// Fixed-point tolerance or Fixed-point iterations (one Newton loop updates all bounds).
ModelFriction modelFriction(const Teuchos::ParameterList& params,
                            const std::vector<ContactPairSpec>& pairs);

// The friction rows of the contact rows p.contact (rank 0 contributes them, as the normal rows):
// per contact row the rows of frictionTangentialRows (dim - 1 unless a tangent is held; 3D: two
// rows form a disc, one a box) with the bound g_i (Tresca: slipBound times the slave node's
// weight; Coulomb: `bounds`, 0 for a node it lacks) and c_T = B_T (stepStart - current) (surface
// displacements, dim per mesh node). A row whose bound is 0 is left out (its multiplier is 0).
std::vector<tfeti::InequalityRow> frictionRows(const ElasticContactProblem& p,
                                               const ModelFriction& friction,
                                               const SlipBounds& bounds,
                                               const std::vector<double>& stepStart,
                                               const std::vector<double>& current, int rank);

// The friction rows the solver is built with, appended to `rows` (the first solve's contact rows),
// then the check that every rigid motion is held (requireRigidMotionsHeld: collective, throws on
// every rank naming the free motions). Rows with a bound from the start: Tresca's, and Coulomb's
// from `bounds` (a restart's). Coulomb without bounds solves its first iteration frictionless,
// and a step starts from the previous step's bounds. Where Coulomb friction alone holds a body
// along the surface, the first would be singular and the second may not hold the new load: the
// Coulomb rows then start every step from stickingBounds (`sticks` is set, and the bounds the
// first step starts from are returned; otherwise `bounds`).
struct InitialFriction {
  SlipBounds bounds;
  bool sticks = false;
  // Proportional loads: the load factor beyond which the contact and friction rows cannot hold
  // a rigid motion the supports leave free (contact_RigidMotions.hpp, frictionLoadLimit), where
  // the load meets one. Finite and positive only with Tresca rows (Coulomb's cones and the
  // push-only contact rows give none or 0); 0 where the load pulls a body off, tips it over or
  // asks more of the cones than mu allows (the caller's requireLoadHeld says so, a restart's
  // state aside).
  std::optional<FrictionLoadLimit> limit;
};
InitialFriction addInitialFrictionRows(const ElasticContactSpec& spec,
                                       const ElasticContactProblem& p,
                                       const ModelFriction& friction, const SlipBounds& bounds,
                                       std::vector<tfeti::InequalityRow>& rows,
                                       const tfeti::Comm& comm);

// A bound no tangential force reaches, per slave node of the Coulomb pairs' contact rows: ten
// times the largest Young's modulus of the bodies times the node's weight (a traction of 10 E).
// The solve with it sticks; mu lambda_N replaces it after.
SlipBounds stickingBounds(const ElasticContactSpec& spec, const ElasticContactProblem& p,
                          const ModelFriction& friction);

// Per contact node: the tangential force and traction, the slip of the step and the state, from
// the solver's last multipliers (matched to the rows by their entries). 3D: the tangential
// force's magnitude |lambda_T|, its direction as the node's tangent, the slip along it, slip
// where |lambda_T| is at the disc's radius. `nodes` come from
// contactNodes on the same problem; stepStart and current as for frictionRows.
// The bound of each row is read from the solver's rows.
void addFrictionResults(std::vector<ContactNode>& nodes, const ElasticContactProblem& p,
                        const tfeti::FetiSolver& solver, const ModelFriction& friction,
                        const std::vector<double>& stepStart, const std::vector<double>& current);

// The friction keys of summary.json's contact record c: friction_law, slip_bound (Tresca),
// normal_force (the sum of the normal multipliers, P of a flat contact), tangential_force (the
// resultant of the tangential forces along x), slip_nodes, stick_nodes,
// stick_half_width (2D: half the x extent of the stick nodes), contact_radius and stick_radius
// (3D: the largest distance from the contact axis of the closed and of the stick nodes; with
// Coulomb a cattaneo_mindlin record against c/a = (1 - Q/(mu P))^(1/3), 2D against
// sqrt(1 - Q/(mu P))), max_tangential_ratio (max
// |lambda_T| / its bound over the closed nodes: 1 at a slipping node), max_slip_increment (max
// |slip of the step| over the closed nodes), max_accumulated_slip and max_net_slip (the largest
// path length and |signed sum| of the slip over the steps, contact_FrictionHistory.hpp).
// With several pairs of friction the keys are over all their nodes, friction_law is "mixed"
// where their laws differ (slip_bound and friction_coefficient only where the pairs share them),
// and there is no cattaneo_mindlin record; each pair's own record is addPairFrictionJson's.
void addFrictionJson(Json& c, const std::vector<ContactNode>& nodes, const ModelFriction& friction,
                     int dim);

// The record of addFrictionJson for the nodes of contact pair k alone, as the object "friction"
// of its entry in summary.json's contact.pairs (no-op for a pair without friction).
void addPairFrictionJson(Json& pairEntry, const std::vector<ContactNode>& nodes,
                         const ModelFriction& friction, int k, int dim);

const char* frictionStateName(int state);  // 0 open, 1 stick, 2 slip

}  // namespace contact
