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

// Throws std::invalid_argument on every rank naming the free motions and what would hold them.
void requireRigidMotionsHeld(const ElasticContactSpec& spec, const ElasticContactProblem& p,
                             const std::vector<tfeti::InequalityRow>& inequalities,
                             const tfeti::Comm& comm);

}  // namespace contact
