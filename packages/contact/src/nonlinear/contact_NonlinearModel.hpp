#pragma once
// The state a nonlinear contact run carries from step to step: this rank's subdomains with their
// material laws (linear elastic or J2, one law object per subdomain holding its Gauss points'
// history), the external load at load factor 1 and the converged total displacement. One code
// path for 2D (plane strain) and 3D: the dimension is the problem's (its mesh's).
#include <memory>
#include <vector>

#include "contact_ElasticContactProblem.hpp"
#include "plasticity_J2Plasticity.hpp"
#include "plasticity_MaterialLaw.hpp"
#include "plasticity_TotalLagrangian.hpp"
#include "tfeti_FetiSolver.hpp"

namespace contact {

using Field = std::vector<std::vector<double>>;  // one vector per local subdomain

// sqrt of the sum of squares over every rank's subdomains, and the largest value of any rank.
double globalNorm(const tfeti::Comm& comm, const Field& v);
double globalMax(const tfeti::Comm& comm, double local);

struct NonlinearModel {
  ElasticContactProblem problem;
  std::vector<std::unique_ptr<plasticity::MaterialLaw>> laws;  // per local subdomain
  std::vector<plasticity::J2PlasticMaterial*> plastic;         // null for elastic bodies
  Field externalLoad;                                          // at load factor 1
  Field u;                                                     // converged total displacement

  int dim() const { return problem.dim(); }

  // The displacement of the contact surfaces' nodes (dim per mesh node, zero elsewhere), from
  // the subdomain holding each node's first copy (every rank gets all of them).
  std::vector<double> surfaceDisplacement(const tfeti::Comm& comm, const Field& disp) const;
  // The current nodal positions X + u of every local subdomain.
  Field currentCoordinates(const Field& disp) const;
  // f_int(u) per subdomain; writes the laws' trial history.
  Field internalForce(const Field& disp, plasticity::Kinematics kin) const;
  // The material tangent (without the initial-stress part, see tangentStiffness) per subdomain;
  // an empty matrix (not assembled) where `keep` (empty, or one flag per subdomain) says so:
  // FetiSolver::updateStiffness keeps that subdomain's K then.
  std::vector<tfeti::CsrMatrix> tangent(const Field& disp, plasticity::Kinematics kin,
                                        const std::vector<char>& keep = {}) const;
  // The positions whose rigid motions are the kernel of tangent(disp, kin):
  //  - small strain: the reference positions X. The strain is the symmetric gradient of the
  //    displacement, zero for a translation and for an infinitesimal rotation about X, whatever
  //    the (elastic or plastic) material tangent; a rotation about X + u is not in the kernel.
  //  - total Lagrangian: the current positions X + u. The Green-Lagrange strain's variation
  //    sym(F^T grad du) vanishes for du = W (X + u) with W skew; the initial-stress part, which
  //    does not, is left out of tangent().
  Field kernelCoordinates(const Field& disp, plasticity::Kinematics kin) const;
  // Whether some Gauss point of the laws' trial state (the last internalForce) loads plastically
  // (its equivalent plastic strain grows): otherwise the small-strain tangent is the elastic
  // stiffness everywhere. Collective.
  bool plasticLoading(const tfeti::Comm& comm) const;
  // The same per local subdomain (not collective): 1 where some Gauss point loads plastically.
  std::vector<char> plasticLoadingPerSubdomain() const;

  void commit();  // trial history -> committed (a converged step)
  void revert();  // committed -> trial (a rejected attempt)
};

// The model of `problem`: per subdomain its body's law, J2 when the body's yield stress is > 0
// (hardening modulus H), else linear elastic; the load at load factor 1 is the problem's; u = 0.
NonlinearModel makeNonlinearModel(ElasticContactProblem problem,
                                  const std::vector<ElasticContactSpec::Body>& bodies);

// Equivalent plastic strain: the largest at any Gauss point of the law's trial state, and a
// nodal field (the mean over the elements at a node of each element's Gauss point mean).
double plasticStrain(const plasticity::J2PlasticMaterial* law, const plasticity::ElementMesh& em,
                     std::vector<double>& nodal);

}  // namespace contact
