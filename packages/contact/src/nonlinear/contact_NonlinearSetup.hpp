#pragma once
// Problem = nonlinear_contact of the tfeti_contact driver: the reference paper's algorithm for
// contact with geometric and material nonlinearities ("FETI with contact and other
// non-linearities"), in load steps.
//
// The bodies, loads and contact pair are those of elastic_contact ("Contact problem"); the
// material may yield (J2, "Yield stress" of "Material" or of a body in "Materials") and the
// kinematics may be total Lagrangian ("Nonlinear"/"Geometrically nonlinear"). Per load step, with
// load factor t:
//   K and B_E are assembled (and K factorized) once;
//   iterate: B_I and the gaps on the current geometry x = X + u;
//            the contact QP for the increment: K du + B^T lambda = t f - f_int(u),
//              B_E du = 0, B_I du <= g(u), lambda_I >= 0 (TFETI, SMALBE/MPRGP);
//            u += du; res = t f - B^T lambda - f_int(u);
//            stop when ||du|| / ||u|| < eta1 and ||res|| / ||t f|| < eta2.
// lambda is the total multiplier (the paper's lambda^{i-1} + dlambda): B_I changes with the
// geometry, so its previous value would act through rows that no longer exist.
// A step that does not converge (iterations, QP, an inverted element) is cut back (halved) and
// retried; every converged step writes its VTU, CSV rows and restart files. The run is
// contact::ContactSolver's (contact_ContactSolver.hpp); its parameters are in
// contact_NonlinearOptions.hpp. This header holds the run's set-up: the problem it solves, the
// restart state it continues from and the load it needs.
#include <Teuchos_ParameterList.hpp>

#include <string>
#include <vector>

#include "tfeti_FetiSolver.hpp"

#include "contact_ElasticContactProblem.hpp"
#include "contact_FrictionHistory.hpp"
#include "contact_NonlinearHistory.hpp"
#include "contact_NonlinearOptions.hpp"

namespace contact {

// The contact problem a nonlinear run solves: elasticContactSpec's, 2D (plane strain) or 3D as
// its mesh is (one code path: J2 in six Voigt components, total Lagrangian kernels, node-to-
// segment or node-to-face contact, rigid obstacles).
ElasticContactSpec nonlinearContactSpec(const Teuchos::ParameterList& params);
// The restart state in `restartDir` (OUTPUT/restart) and this rank's subdomain files of its
// last step, checked against the problem's subdomains (throws std::runtime_error naming the file).
// friction: when given (a frictional run), the step's friction state (friction.txt) is read
// into it.
NonlinearHistory readRestart(const std::string& restartDir, const ElasticContactProblem& problem,
                             std::vector<SubdomainRestart>& subdomains,
                             FrictionHistory* friction = nullptr);
// The norm of the external load of the subdomains (every rank); throws when no load is applied.
double requireLoad(const tfeti::Comm& comm, const std::vector<tfeti::SubdomainData>& local);
// As requireLoad, but a prescribed obstacle motion ("Nonlinear"/"Obstacle displacement") or a
// prescribed displacement of a boundary (`prescribedMotion`) may drive the run alone: then 0 when
// no load is applied.
double requireLoadOrMotion(const tfeti::Comm& comm, const std::vector<tfeti::SubdomainData>& local,
                           const NonlinearOptions& options, bool prescribedMotion);

}  // namespace contact
