#pragma once
// What holds the bodies: the rigid motions that no row of B holds, found before any solve.
//
// TFETI's coarse problem G G^T (G = R^T B^T) is singular exactly when some rigid motion of the
// subdomains satisfies every row of B homogeneously. The gluing rows make the subdomains that
// share nodes move as one piece (a body, or bodies that share nodes), so what matters is the
// pieces' rigid motions (3 in 2D, 6 in 3D) against the other rows: Fixed, Symmetry and
// Prescribed components, the kinematic couplings, and the inequality rows (contact, bonded,
// friction). A motion that none of them sees leaves the bodies' stiffness singular with
// nothing to hold it; without this check the solver could only say "coarse problem G G^T is
// singular" after the factorizations, and the dry run would pass.
#include <optional>
#include <string>
#include <vector>

#include "contact_ElasticContactProblem.hpp"

namespace contact {

// The free rigid motions of the bodies of `spec` set up as p, one description each ("body \"box\":
// translation along x"); empty when every piece is held. `inequalities` are the inequality rows the
// solver is given (rank 0's; the other ranks pass theirs, which are empty); every rank gets rank
// 0's answer.
std::vector<std::string> freeRigidMotions(const ElasticContactSpec& spec,
                                          const ElasticContactProblem& p,
                                          const std::vector<tfeti::InequalityRow>& inequalities,
                                          const tfeti::Comm& comm);

// A load beyond what friction holds. Where every row but the friction rows leaves a rigid motion
// r free, equilibrium along r reads r^T f(t) = sum_i lambda_i (B_i r) over the friction rows
// alone (the other rows do no work along r, nor the stiffness), and friction rows with fixed
// bounds |lambda_i| <= g_i (Tresca's; a 3D node's disc pair: |(lambda_1, lambda_2)| <= g_i)
// can do at most C(r) = sum_i g_i |B_i r| (pairs: g_i |(B_1 r, B_2 r)|). So no equilibrium exists
// beyond the load factor C(r) / |r^T f| with proportional loads f(t) = t f. Tried along each free
// motion and along the load's own direction within them (the reference geometry; a necessary
// condition: with several free motions a combination may give out earlier, and the contact rows
// count as holding both ways, so a motion that lifts nodes off, e.g. rolling, is not tried).
struct FrictionLoadLimit {
  std::string motion;       // as freeRigidMotions describes it
  double load = 0.0;        // |r^T f| at load factor 1
  double capacity = 0.0;    // C(r)
  double loadFactor = 0.0;  // capacity / load
};
// "friction can hold <motion> only up to the load factor X (...)": the run's and the dry run's
// line.
std::string frictionLimitText(const FrictionLoadLimit& limit);
// The smallest such load factor, if some free motion meets the load (rank 0's answer on every
// rank). `others`: every inequality row but the friction rows; `friction`: those (rank 0's).
// The loads are p.local's.
std::optional<FrictionLoadLimit> frictionLoadLimit(
    const ElasticContactSpec& spec, const ElasticContactProblem& p,
    const std::vector<tfeti::InequalityRow>& others,
    const std::vector<tfeti::InequalityRow>& friction, const tfeti::Comm& comm);

// Throws std::invalid_argument on every rank naming the free motions and what would hold them.
void requireRigidMotionsHeld(const ElasticContactSpec& spec, const ElasticContactProblem& p,
                             const std::vector<tfeti::InequalityRow>& inequalities,
                             const tfeti::Comm& comm);

}  // namespace contact
