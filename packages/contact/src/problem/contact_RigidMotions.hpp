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

// A load beyond what the contact and friction rows hold (contact_LoadLimit.cpp). Along a rigid
// motion r that the supports and couplings leave free, equilibrium reads
// r^T f(t) = sum_i lambda_i (B_i r) over the inequality rows (the stiffness and the other rows
// do no work along r). A contact row pushes only (lambda_i >= 0): it does work only where r
// presses into it (B_i r > 0), and none where r lifts its node off. A friction row with a fixed
// bound (Tresca's: |lambda_i| <= g_i; a 3D node's disc pair: |(lambda_1, lambda_2)| <= g_i)
// does at most g_i |B_i r| (pairs: g_i |(B_1 r, B_2 r)|). So along an r that presses into no
// contact row, the rows do at most C(r) = sum g_i |B_i r|, and with proportional loads
// f(t) = t f no equilibrium exists beyond the load factor C(r) / r^T f. The smallest such
// factor over all those motions, with their combinations, is a linear program in the free
// motions' coefficients (contact_BoundedSimplex.hpp); C(r) is evaluated exactly at the r it
// gives. A necessary condition at the reference geometry: the bodies' deformation and the
// contact rows' changes are not in it. 0: the load pulls the bodies off what holds them
// (requireLoadHeld names the motion). Rows without a finite bound (a Coulomb row's multiplier
// is only bounded by mu lambda_N) hold any force along the motions they see, unless a
// FrictionCone ties them to their contact row: then the node's force lies in Coulomb's cone
// |lambda_T| <= mu lambda_N, which does no work along a motion that lifts the node off by at
// least mu times its slip, and no motion may press into it (so Coulomb alone gives the limit 0
// or none). None for tied and bonded pairs (their rows hold both ways).
struct FrictionLoadLimit {
  std::string motion;       // as freeRigidMotions describes it, r of unit length
  double load = 0.0;        // r^T f at load factor 1 (> 0)
  double capacity = 0.0;    // C(r)
  double loadFactor = 0.0;  // capacity / load
  int liftedRows = 0;       // contact rows whose node r lifts off (B_i r < 0)
};
// "the friction rows' bounds can hold <motion> only up to the load factor X (...)": the run's
// and the dry run's line.
std::string frictionLimitText(const FrictionLoadLimit& limit);
// A contact node's Coulomb cone: its contact row and its one or two tangential rows (indices
// into the limit's rows, whose own bounds the cone replaces) and mu.
struct FrictionCone {
  int normal = -1;
  std::vector<int> tangents;
  double mu = 0.0;
};
// The smallest such load factor, if some free motion meets the load (rank 0's answer on every
// rank). `rows`: every inequality row with the bounds the limit takes, `cones` Coulomb's
// (rank 0's; the other ranks pass theirs, which are empty). The loads are p.local's
// (collective).
std::optional<FrictionLoadLimit> frictionLoadLimit(const ElasticContactSpec& spec,
                                                   const ElasticContactProblem& p,
                                                   const std::vector<tfeti::InequalityRow>& rows,
                                                   const std::vector<FrictionCone>& cones,
                                                   const tfeti::Comm& comm);
// Throws std::invalid_argument where the limit is 0 (below 1e-9: rounding): no load step can
// converge. The motion, the load's work along it and the contact rows it lifts off are named.
void requireLoadHeld(const std::optional<FrictionLoadLimit>& limit);

// Throws std::invalid_argument on every rank naming the free motions and what would hold them.
void requireRigidMotionsHeld(const ElasticContactSpec& spec, const ElasticContactProblem& p,
                             const std::vector<tfeti::InequalityRow>& inequalities,
                             const tfeti::Comm& comm);

}  // namespace contact
