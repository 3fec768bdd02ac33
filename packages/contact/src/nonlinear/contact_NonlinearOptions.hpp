#pragma once
// The "Nonlinear" sublist of a nonlinear contact run, validated: kinematics, load steps,
// iterations and tolerances, the stiffness update, cut-back, restart, how the contact zone's
// extent is measured, and the prescribed motion of a rigid obstacle.
#include <Teuchos_ParameterList.hpp>

#include <string>
#include <vector>

#include "contact_ContactOutput.hpp"
#include "plasticity_TotalLagrangian.hpp"

namespace contact {

struct NonlinearOptions {
  plasticity::Kinematics kinematics = plasticity::Kinematics::TotalLagrangian;
  int steps = 1, maxIterations = 50, maxCutbacks = 4, stopAfter = 0;
  double eta1 = 1e-6, eta2 = 1e-6;
  std::string stiffness = "initial";  // initial | step | iteration
  bool restart = false, vtuEveryStep = true;
  ContactExtentRule rule;
  int centreValues = 2;  // "Contact extent"/"Centre" was given with 2 (2D) or 3 (3D) values
  // "Obstacle displacement": the rigid obstacle's motion at load factor 1 (it moves by t times
  // it); empty: the obstacle stays where it is.
  std::vector<double> obstacleDisplacement;
  // Inexact Newton ("Inexact QP factor"): an iteration's QP stops at f times the FETI
  // tolerances, f = min(inexactQpFactor, ||res|| / (eta2 ||f||)) from the previous iteration's
  // residual (the first iteration of a step: inexactQpFactor); 1: every QP as configured.
  double inexactQpFactor = 1.0;
  // "Line search": none, or backtracking on the residual norm (halving the step up to
  // lineSearchCuts times until the residual decreases).
  bool lineSearch = false;
  int lineSearchCuts = 5;
  // The one-step case of a linear problem (elastic_contact: small strain, linear laws, one
  // increment from u = 0), set by its run policy (api/contact_ElasticContactPolicy.cpp).
  // solveAsBuilt: the first increment is the one the solver was built with (loads f, the contact
  // rows of the reference geometry, the prescribed rows at their full value), so the iteration
  // neither searches the contact, nor evaluates f_int(0) = 0, nor updates the solver before it.
  bool solveAsBuilt = false;
  // singleIncrement: that increment solves the problem, so the step ends after it with its QP's
  // convergence; a QP that did not converge still leaves a complete state to report.
  bool singleIncrement = false;
};

// Throws std::invalid_argument naming the parameter that is wrong.
NonlinearOptions nonlinearOptionsFrom(const Teuchos::ParameterList& params);
// Adds "Nonlinear" to the driver's valid parameters (the materials: contact_Materials.hpp).
void addNonlinearContactParameters(Teuchos::ParameterList& valid);

// The checks of the "Nonlinear", "Material" and "Contact problem" parameters a run makes before
// it meshes (throw std::invalid_argument as the run does).
void checkNonlinearParameters(const Teuchos::ParameterList& params);

// The checks that need the problem's dimension (2 or 3) and how many of its contact pairs have a
// rigid obstacle as the master: the extent rule and the obstacle displacement must fit them
// (the displacement moves the one obstacle; with several it would be ambiguous).
void checkNonlinearOptionsFor(const NonlinearOptions& options, int dim, int rigidObstacles);

}  // namespace contact
