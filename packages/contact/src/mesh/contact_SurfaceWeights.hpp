#pragma once
// Lumping weights of a boundary's nodes: each node's share of the boundary's length (2D) or area
// (3D), the measure a contact multiplier (a nodal force) is divided by to give a pressure.
#include <map>

#include "contact_GmshMesh.hpp"

namespace contact {

// Per node of the boundary: its share of the boundary's measure; the shares sum to that measure.
//  - 2D edges: Line2 half the length to each end; Line3 the consistent (Simpson) weights L/6,
//    L/6, 2L/3 (the edge as the polyline through its middle node).
//  - 3D faces: Tri3 and Quad4 the integral of each node's linear (bilinear) shape function over
//    the face; Tri6 and Quad9 the same on their four linear sub-faces through the midside (and
//    centre) nodes. Consistent quadratic weights would give the corners of a Tri6 zero area (its
//    corner shape functions integrate to zero), hence no pressure there.
// Throws std::invalid_argument naming the boundary for a face type without a rule (Quad8).
std::map<int, double> boundaryNodeWeights(const GmshMesh& mesh, const GmshBoundary& boundary);

}  // namespace contact
