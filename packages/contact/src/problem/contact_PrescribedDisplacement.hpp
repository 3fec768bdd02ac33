#pragma once
// Prescribed (non-zero) displacements: one component of u given on a named boundary, in 2D and
// 3D, for the structured problems (faces x0, x1, y0, y1, z0, z1 of the box) and the Gmsh meshes
// (physical boundary groups). They become the caller's equality rows of the TFETI solver, one
// per subdomain copy of every prescribed (node, component):  u_{s,dof} = t g - u0_{s,dof}  (t a
// load factor, g the value, u0 a displacement the solve starts from; B_E u = c_E with c_E the
// right-hand sides), so that every copy meets the value as a Dirichlet row of TFETI would.
//
// Parameters (the same three in "Boundary conditions" and "Contact problem"):
//   "Prescribed boundaries"   names, one per prescribed component (a name may repeat)
//   "Prescribed components"   0 (x), 1 (y), 2 (z) of each; 0 for the scalar problem
//   "Prescribed displacements" the value of each, in m (the unknown's unit for Poisson)
#include <Teuchos_ParameterList.hpp>

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "contact_Json.hpp"
#include "contact_LoadRamp.hpp"
#include "tfeti_FetiSolver.hpp"
#include "tfeti_StrictParameters.hpp"

namespace contact {

struct PrescribedDisplacement {
  std::string boundary;
  int component = 0;
  double value = 0.0;
  LoadRamp ramp;  // the load-factor window over which the value is applied (contact_LoadRamp)
};

// A prescribed value and the window of the load factor over which it grows.
struct PrescribedValue {
  double value = 0.0;
  LoadRamp ramp;
  double at(double loadFactor) const { return ramp.factor(loadFactor) * value; }
};

// (untorn node, component) -> prescribed value.
using PrescribedValues = std::map<std::pair<long long, int>, PrescribedValue>;

// A validator of component lists: ints 0 (x), 1 (y), 2 (z).
tfeti::strict::Validator componentsValidator();

// Adds the three parameters to a validated list (strict: components 0..2, finite values).
void addPrescribedDisplacementParameters(Teuchos::ParameterList& list);

// The triples of `list` (validated); `where` names the list in errors ("Contact problem").
// Throws std::invalid_argument when the three arrays differ in length.
std::vector<PrescribedDisplacement> prescribedDisplacements(const Teuchos::ParameterList& list,
                                                            const std::string& where);

// The untorn nodes of a named boundary; throws std::invalid_argument naming it (and the valid
// names) when there is no such boundary.
using BoundaryNodes = std::function<std::vector<long long>(const std::string&)>;

// The prescribed values per (node, component) of a problem with dofsPerNode unknowns per node,
// checked: a component must be below dofsPerNode, a boundary must exist, and a (node,
// component) given twice (two prescribed boundaries meeting at an edge, or a prescribed and a
// fixed or symmetry boundary) must have one value (and one ramp); where a fixed or symmetry
// condition already holds the component at zero, the prescribed zero is dropped. Every rank derives
// the same result (the boundaries are known on every rank), so errors are raised on every rank
// alike.
PrescribedValues prescribedValues(const std::vector<PrescribedDisplacement>& prescribed,
                                  int dofsPerNode, const BoundaryNodes& nodesOf,
                                  const std::vector<std::string>& fixed,
                                  const std::vector<std::pair<std::string, int>>& symmetry);

// The equality rows of the prescribed values for this rank's subdomains at load factor t:
//   u_{s, dpn n + c} = ramp(t) * value(node, c) - current[i][dpn n + c]
// (ramp(t) = t for the default window {0, 1})
// for every local subdomain i (id s) and local node n of a prescribed (node, c). `current`
// (empty: zero) is the displacement the solve starts from: in a nonlinear loop, the Newton
// increment's rows have the right-hand side c_E(t) - B_E u (see docs/boundary_conditions.md).
std::vector<tfeti::EqualityRow> prescribedDisplacementRows(
    const std::vector<tfeti::SubdomainData>& local, const PrescribedValues& values,
    double loadFactor, const std::vector<std::vector<double>>& current = {});

// Per prescribed entry (after a solve): the reaction, the force the constraints exert on the body
// in the entry's component summed over the boundary's nodes, -sum (B^T lambda) over every copy
// (gluing forces between copies of a node cancel). Reduced over the ranks.
std::vector<double> prescribedReactions(const tfeti::FetiSolver& solver,
                                        const std::vector<PrescribedDisplacement>& prescribed,
                                        const BoundaryNodes& nodesOf);

// The summary's record of the prescribed entries after a solve: per entry boundary, component,
// value and reaction (prescribedReactions). Collective.
Json prescribedSummary(const tfeti::FetiSolver& solver,
                       const std::vector<PrescribedDisplacement>& prescribed,
                       const BoundaryNodes& nodesOf);

// "u_x = 0.001" (u for a scalar problem): for reports.
std::string describePrescribed(const PrescribedDisplacement& p, int dofsPerNode);

}  // namespace contact
