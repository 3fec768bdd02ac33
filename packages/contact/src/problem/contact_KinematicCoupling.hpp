#pragma once
// Kinematic coupling: one component of every node of a named boundary tied to one common,
// unknown value, as a rigid loading plate that translates without rotating (what other codes
// call a rigid-surface or *EQUATION constraint). The coupling is a set of equality rows of B,
//   u_{n_k, c} - u_{n_0, c} = 0   (k = 1 .. m-1; n_0 the boundary's lowest node id),
// on the first subdomain copy of every node (the gluing rows tie the other copies), so it goes
// through the tearing and the dual problem as the Dirichlet rows do, whichever subdomains and
// ranks the boundary crosses. A load on the boundary (a traction) then moves it as one.
//
// Parameters ("Contact problem"):
//   "Coupled boundaries"  names, one per coupled component (a name may repeat)
//   "Coupled components"  0 (x), 1 (y), 2 (z) of each
#include <Teuchos_ParameterList.hpp>

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "contact_Json.hpp"
#include "tfeti_FetiSolver.hpp"

namespace contact {

struct KinematicCoupling {
  std::string boundary;
  int component = 0;
};

void addKinematicCouplingParameters(Teuchos::ParameterList& list);

// The couplings of `list` (validated); throws std::invalid_argument naming `where` when the two
// arrays differ in length or a (boundary, component) is given twice.
std::vector<KinematicCoupling> kinematicCouplings(const Teuchos::ParameterList& list,
                                                  const std::string& where);

// What the rows need of the problem: the untorn nodes of a boundary (throwing
// std::invalid_argument naming it when there is none), a node's first copy (subdomain id, local
// node), and what already holds a (node, component) ("" when nothing: fixed, symmetry and
// prescribed conditions would make the coupling's rows dependent on theirs).
struct CouplingContext {
  int dim = 2;
  std::function<std::vector<long long>(const std::string&)> nodesOf;
  std::function<std::pair<int, int>(long long)> firstCopy;
  std::function<std::string(long long, int)> heldBy;
};

// The rows of every coupling (m - 1 per boundary of m nodes), checked on every rank alike: a
// component below dim, a boundary of at least two nodes, no (node, component) held by another
// condition or by two couplings. Every rank gets them; pass them from one rank only (the
// tearing gathers the rows of all ranks).
std::vector<tfeti::EqualityRow> kinematicCouplingRows(
    const std::vector<KinematicCoupling>& couplings, const CouplingContext& context);

// The summary's record of the couplings for the displacement `u` (per local subdomain of
// `local`): per coupling boundary, component, nodes, displacement (the common value) and
// spread (the largest minus the smallest value over the boundary's nodes: zero to the solver's
// tolerance). Collective.
Json couplingSummary(const tfeti::Comm& comm, const std::vector<KinematicCoupling>& couplings,
                     const std::vector<tfeti::SubdomainData>& local,
                     const std::vector<std::vector<double>>& u,
                     const std::function<std::vector<long long>(const std::string&)>& nodesOf);

}  // namespace contact
