#pragma once
// The ContactMaster implementations (contact_ContactRows.hpp): what a contact pair's set-up
// builds once and calls on every configuration, whatever the master is.
#include <memory>
#include <string>

#include "contact_ContactRows.hpp"
#include "contact_GmshMesh.hpp"
#include "contact_NodeToFace.hpp"
#include "contact_NodeToSegment.hpp"
#include "contact_RigidObstacle.hpp"

namespace contact {

// 2D segments (computeNodeToSegment); the surface must be oriented (orientSegments*).
std::unique_ptr<ContactMaster> makeSegmentMaster(MasterSurface master,
                                                 const ContactSearchOptions& options);
// 3D faces (computeNodeToFace), oriented outward.
std::unique_ptr<ContactMaster> makeFaceMaster(MasterFaceSurface master,
                                              const ContactSearchOptions& options);
// A rigid obstacle (computeObstacleRows); validated here.
std::unique_ptr<ContactMaster> makeObstacleMaster(const RigidObstacle& obstacle,
                                                  const ContactSearchOptions& options);

// A 2D boundary's segments oriented out of the body it belongs to (orientSegmentsByElements with
// the body of its first related edge), the 2D counterpart of masterFacesOfBoundary. Throws
// std::invalid_argument naming the file and the boundary when it is on no body.
MasterSurface masterSegmentsOfBoundary(const GmshMesh& mesh, const GmshBoundary& boundary);

// The named boundary of a mesh as master, oriented out of the body it belongs to: segments in
// 2D (orientSegmentsByElements with the body of its first related edge), faces in 3D
// (masterFacesOfBoundary). Throws std::invalid_argument naming the file and the boundary (an
// unknown name lists the valid ones; a boundary on no body).
std::unique_ptr<ContactMaster> makeMeshContactMaster(const GmshMesh& mesh,
                                                     const std::string& boundary,
                                                     const ContactSearchOptions& options);

}  // namespace contact
