#include "contact_NonlinearOptions.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <cmath>
#include <stdexcept>

#include "contact_ContactParameters.hpp"
#include "tfeti_StrictParameters.hpp"

namespace contact {

using Teuchos::Array;
using Teuchos::ParameterList;

NonlinearOptions nonlinearOptionsFrom(const ParameterList& params) {
  const auto& nl = params.sublist("Nonlinear");
  NonlinearOptions o;
  o.kinematics = nl.get<bool>("Geometrically nonlinear") ? plasticity::Kinematics::TotalLagrangian
                                                         : plasticity::Kinematics::SmallStrain;
  o.steps = nl.get<int>("Load steps");
  o.maxIterations = nl.get<int>("Maximum iterations");
  o.maxCutbacks = nl.get<int>("Maximum cutbacks");
  o.stopAfter = nl.get<int>("Stop after step");
  o.eta1 = nl.get<double>("Eta 1");
  o.eta2 = nl.get<double>("Eta 2");
  o.stiffness = nl.get<std::string>("Stiffness");
  o.restart = nl.get<bool>("Restart");
  o.vtuEveryStep = nl.get<bool>("VTU every step");
  o.inexactQpFactor = nl.get<double>("Inexact QP factor");
  o.lineSearch = nl.get<std::string>("Line search") == "backtracking";
  o.lineSearchCuts = nl.get<int>("Line search cuts");
  const auto& ex = nl.sublist("Contact extent");
  o.rule.angle = ex.get<std::string>("Measure") == "angle";
  const auto c = ex.get<Array<double>>("Centre"), d = ex.get<Array<double>>("Direction"),
             a = ex.get<Array<double>>("Axis");
  if ((c.size() != 2 && c.size() != 3) || d.size() != 2 || !(std::hypot(d[0], d[1]) > 0.0))
    throw std::invalid_argument(
        "Nonlinear/Contact extent: \"Centre\" needs 2 values (2D) or 3 (3D) and \"Direction\" "
        "2, the direction non-zero");
  const double an = a.size() == 3 ? std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) : 0.0;
  if (!(an > 0.0))
    throw std::invalid_argument(
        "Nonlinear/Contact extent: \"Axis\" needs 3 values {ax, ay, az}, not all zero");
  const double dn = std::hypot(d[0], d[1]);
  o.centreValues = static_cast<int>(c.size());
  for (int k = 0; k < o.centreValues; ++k) o.rule.centre[k] = c[k];
  o.rule.direction[0] = d[0] / dn, o.rule.direction[1] = d[1] / dn;
  for (int k = 0; k < 3; ++k) o.rule.axis[k] = a[k] / an;
  const auto move = nl.get<Array<double>>("Obstacle displacement");
  o.obstacleDisplacement.assign(move.begin(), move.end());
  if (o.steps < 1) throw std::invalid_argument("Nonlinear: \"Load steps\" must be >= 1");
  if (o.maxIterations < 1)
    throw std::invalid_argument("Nonlinear: \"Maximum iterations\" must be >= 1");
  if (o.maxCutbacks < 0)
    throw std::invalid_argument("Nonlinear: \"Maximum cutbacks\" must be >= 0");
  if (!(o.inexactQpFactor >= 1.0) || !std::isfinite(o.inexactQpFactor))
    throw std::invalid_argument("Nonlinear: \"Inexact QP factor\" must be >= 1 and finite");
  if (!(o.eta1 > 0.0) || !(o.eta2 > 0.0))
    throw std::invalid_argument("Nonlinear: \"Eta 1\" and \"Eta 2\" must be positive");
  return o;
}

void checkNonlinearOptionsFor(const NonlinearOptions& o, int dim, int rigidObstacles) {
  if (dim == 3 && o.rule.angle)
    throw std::invalid_argument(
        "Nonlinear/Contact extent: \"Measure\" angle is for 2D meshes; in 3D the extent is the "
        "contact radius from \"Axis\" through \"Centre\" (Measure half_width)");
  if (dim == 2 && o.centreValues != 2)
    throw std::invalid_argument(
        "Nonlinear/Contact extent: \"Centre\" has 3 values; the mesh is 2D and needs {x, y}");
  if (o.obstacleDisplacement.empty()) return;
  if (rigidObstacles == 0)
    throw std::invalid_argument(
        "Nonlinear: \"Obstacle displacement\" is given but \"Contact problem/Rigid obstacle\" "
        "has Type none: only a rigid obstacle can be moved");
  if (rigidObstacles > 1)
    throw std::invalid_argument(
        "Nonlinear: \"Obstacle displacement\" is given but " + std::to_string(rigidObstacles) +
        " pairs of \"Contact problem/Contact pairs\" have a Rigid obstacle: it moves the one "
        "obstacle of a model (at most one pair with a Rigid obstacle then)");
  if (static_cast<int>(o.obstacleDisplacement.size()) != dim)
    throw std::invalid_argument("Nonlinear: \"Obstacle displacement\" has " +
                                std::to_string(o.obstacleDisplacement.size()) +
                                " values; the mesh is " + std::to_string(dim) + "D and needs " +
                                std::to_string(dim));
}

void addNonlinearContactParameters(ParameterList& pl) {
  auto& nl = pl.sublist("Nonlinear", false, "Problem = nonlinear_contact: load steps, iterations");
  nl.set("Geometrically nonlinear", true,
         "total Lagrangian kinematics (Green-Lagrange strain); false: small strain");
  nl.set("Load steps", 1, "equal load increments up to the full load", tfeti::strict::count());
  nl.set("Maximum iterations", 50, "iterations per load step before it is cut back",
         tfeti::strict::count());
  nl.set("Eta 1", 1e-6, "stop when ||du|| / ||u|| < Eta 1 ...", tfeti::strict::positive());
  nl.set("Eta 2", 1e-6,
         "... and ||f - B^T lambda - f_int|| / ||f|| < Eta 2 (||f_int|| when no load is applied)",
         tfeti::strict::positive());
  nl.set("Maximum cutbacks", 4,
         "consecutive halvings of a load increment that does not converge before the run stops; no "
         "increment below 1 / (Load steps 2^Maximum cutbacks) is tried",
         tfeti::strict::count(0));
  nl.set("Stiffness", "initial",
         "initial: K of the undeformed elastic body, factorized once (the paper's algorithm); "
         "step: the material tangent at the start of every load step; iteration: at every "
         "iteration (both refactorize)",
         Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
             Teuchos::tuple<std::string>("initial", "step", "iteration"), "Stiffness")));
  nl.set("Inexact QP factor", 1.0,
         "inexact Newton: an iteration's QP stops at up to this factor times the FETI solver's "
         "tolerances, min(this, ||res|| / (Eta 2 ||f||)) from the previous iteration's residual "
         "(this for a step's first iteration); a step converges only on an iteration solved to "
         "the tolerances themselves. 1: every QP as configured",
         tfeti::strict::positive());
  nl.set("Line search", "none",
         "none: full Newton steps; backtracking: halve the step (and the multipliers' change) "
         "until ||res|| decreases, at most \"Line search cuts\" times",
         Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
             Teuchos::tuple<std::string>("none", "backtracking"), "Line search")));
  nl.set("Line search cuts", 5, "halvings of a step the line search tries", tfeti::strict::count());
  nl.set("Restart", false,
         "continue from the last converged load step saved in the output directory's restart/");
  nl.set("Stop after step", 0,
         "stop (successfully) once this load step has converged, to be continued with Restart; "
         "0: run to the full load",
         tfeti::strict::count(0));
  nl.set("VTU every step", true, "write step_NNNN.pvtu at every converged step");
  nl.set("Obstacle displacement", Array<double>(),
         "{dx, dy[, dz]}: the Rigid obstacle moves by load factor times this (indentation by a "
         "prescribed displacement); empty: it stays",
         tfeti::strict::doubles(0));
  auto& ex = nl.sublist("Contact extent", false, "how contact_extent is measured");
  ex.set("Measure", "half_width",
         "half_width: half the contact width along x (metres; in 3D the contact radius from "
         "Axis through Centre); angle (2D): the half-angle (degrees) seen from Centre, from "
         "Direction",
         Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
             Teuchos::tuple<std::string>("half_width", "angle"), "Measure")));
  ex.set("Centre", Array<double>(std::vector<double>{0.0, 0.0}),
         "{x, y} (2D angle) or {x, y, z} (3D: a point of the contact axis)",
         tfeti::strict::doubles(0));
  ex.set("Direction", Array<double>(std::vector<double>{0.0, -1.0}),
         "{dx, dy}: where the angle is zero (angle)", tfeti::strict::doubles(2));
  ex.set("Axis", Array<double>(std::vector<double>{0.0, 0.0, 1.0}),
         "{ax, ay, az}: the contact axis (3D), the contact radius is measured from it",
         tfeti::strict::doubles(3));
}

void checkNonlinearParameters(const ParameterList& params) {
  nonlinearOptionsFrom(params);
  elasticContactSpec(params);
}

}  // namespace contact
