#pragma once
// The friction state one load step hands to the next, and the restart file that keeps it.
//
// Friction depends on the path: what a step needs of the steps before it is
//   - the state its slip is measured from: the converged displacement u_0 of the previous step
//     (the restart's subdomain files hold it);
//   - Coulomb: the slip bounds g_i = mu lambda_N,i the fixed point of the previous step ended
//     with, the starting iterate of this step's fixed point (contact_FrictionStep.hpp);
//   - for output: each slave node's slip accumulated over the steps.
// Accumulated slip: per slave node, over the converged steps at whose end the node is closed
// (stick or slip; an open node's tangential motion is no slip), the path length sum |s| of
// its step slips s (the slip of the step along the tangent, ContactNode::slip: the measure of
// wear and frictional work) and the signed sum sum s (2D: the net slip along the tangent, which
// is oriented the same way at every step; 3D: along the first tangent, as the step slip).
#include <map>
#include <string>
#include <vector>

#include "contact_ContactOutput.hpp"
#include "contact_Friction.hpp"

namespace contact {

struct AccumulatedSlip {
  double path = 0.0;  // sum |s|
  double net = 0.0;   // sum s
};

struct FrictionHistory {
  std::map<int, AccumulatedSlip> slip;  // per slave node (global id) of the converged steps
  SlipBounds bounds;                    // Coulomb: the last converged step's slip bounds
};

// Sets each node's accumulatedSlip and netSlip: the committed sums plus the node's slip of the
// step being evaluated when it is closed (frictionState 1 or 2).
void addAccumulatedSlip(std::vector<ContactNode>& nodes,
                        const std::map<int, AccumulatedSlip>& committed);

// The committed sums after a converged step whose nodes were evaluated by addAccumulatedSlip:
// its nodes' sums replace theirs; a node without a row in the step keeps its sums.
void commitAccumulatedSlip(std::map<int, AccumulatedSlip>& committed,
                           const std::vector<ContactNode>& nodes);

// stepDir/friction.txt (rank 0; throws std::runtime_error naming the file). Written before the
// restart's state.txt, which names the step only once all its files exist.
void writeFrictionRestart(const std::string& stepDir, const FrictionHistory& history);
// Throws std::runtime_error naming the file when it is missing (a step written without
// friction) or malformed.
FrictionHistory readFrictionRestart(const std::string& stepDir);

}  // namespace contact
