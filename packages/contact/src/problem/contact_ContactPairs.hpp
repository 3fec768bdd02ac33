#pragma once
// The contact pairs of a model: one Slave boundary against a Master boundary or a rigid
// obstacle each, with its own contact type, discretization, search radius and friction. Either
// the single pair of the old keys directly in "Contact problem" (Slave, Master, Rigid obstacle,
// Contact type, Search radius, Friction), or "Contact problem/Contact pairs" with one named
// sublist per pair holding those keys:
//
//   <ParameterList name="Contact pairs">
//     <ParameterList name="upper">
//       <Parameter name="Slave" type="string" value="ball_top"/>
//       <Parameter name="Master" type="string" value="upper_plate_bottom"/>
//     </ParameterList>
//     <ParameterList name="lower"> ... </ParameterList>
//   </ParameterList>
//
// Giving both is an error. Every pair's rows go into the one QP (B_I is their concatenation);
// the rule that keeps them independent: a slave node has rows in one pair only.
#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "contact_ContactMaster.hpp"
#include "contact_GmshMesh.hpp"
#include "contact_RigidObstacle.hpp"

namespace contact {

struct ContactPairSpec {
  std::string name;    // the sublist's name in Contact pairs; empty for the old keys' pair
  std::string where;   // "Contact problem" or "Contact problem/Contact pairs/<name>" (errors)
  std::string slave;   // the slave boundary (its nodes)
  std::string master;  // the master boundary (its segments or faces); empty with an obstacle
  std::optional<RigidObstacle> obstacle;     // a rigid master instead (its dim is the mesh's)
  std::string contactType = "frictionless";  // frictionless, tied or bonded
  std::string discretization = "node_to_segment";
  double searchRadius = 0.0;  // 0: a tenth of the mesh's extent
};

// The valid keys of a pair (those of the old single pair) but Friction
// (addFrictionParameters): Slave, Master, Contact type, Search radius, Rigid obstacle, Contact
// discretization.
void addContactPairKeys(Teuchos::ParameterList& pl);
// The documentation entry of "Contact pairs" in the valid "Contact problem" list.
void addContactPairsDocumentation(Teuchos::ParameterList& contactProblem);
Teuchos::RCP<const Teuchos::ParameterList> validContactPairParameters();

// Before the Teuchos validation: "Contact problem/Contact pairs" taken out of the parameters
// (its sublists are named by the user, which a fixed valid list cannot know) and whether any of
// the old pair keys is given explicitly.
struct GivenContactPairs {
  Teuchos::ParameterList pairs{"Contact pairs"};
  std::vector<std::string> oldKeys;  // the old single-pair keys given in "Contact problem"
};
GivenContactPairs takeContactPairs(Teuchos::ParameterList& params);

// After the validation: every pair validated against validContactPairParameters (unknown keys
// rejected, defaults filled) and put back. Throws std::invalid_argument naming the pair and the
// parameter: the old keys given too, a pair that is not a sublist, an empty list.
void restoreContactPairs(Teuchos::ParameterList& params, const GivenContactPairs& given);

// The pairs of the validated parameters, in input order: the one of the old keys, or those of
// Contact pairs. Throws std::invalid_argument naming the pair and parameter: no Slave, Slave
// equal to Master, neither or both of Master and Rigid obstacle (with pairs), the same pair
// twice, pairs of different contact types (the QP holds all rows as inequalities or all as
// equalities), a tied pair outside elastic_contact.
std::vector<ContactPairSpec> contactPairSpecs(const Teuchos::ParameterList& params);

// The rigid obstacle of a "Rigid obstacle" sublist (none for Type none); errors name `where`.
std::optional<RigidObstacle> rigidObstacleFrom(const Teuchos::ParameterList& ro,
                                               const std::string& where);

// The master of a pair, whatever its discretization: the one place a pair's master is made.
// node_to_segment: the obstacle, or the Master boundary's segments (faces) oriented out of their
// body; mortar: dual mortar rows of the Slave boundary against the Master boundary or the
// obstacle (contact_Mortar.hpp).
std::shared_ptr<const ContactMaster> makePairMaster(const GmshMesh& mesh,
                                                    const ContactPairSpec& pair,
                                                    const ContactSearchOptions& options);

// "pair \"name\"" for messages about a pair of Contact pairs, "the contact pair" for the old one.
std::string pairLabel(const ContactPairSpec& pair);

}  // namespace contact
