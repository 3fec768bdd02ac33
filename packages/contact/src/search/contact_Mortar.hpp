#pragma once
// Dual mortar (segment-to-segment) contact rows in 2D and 3D, in the common row form of
// contact_ContactRows.hpp, so that every QP stays box-constrained for MPRGP/SMALBE.
//
// The multiplier of slave node j is a pressure z_j times the dual basis function phi_j of the
// slave surface (biorthogonal to the slave's shape functions: int phi_j N_a = delta_ja int N_j).
// Non-penetration is required in the weak, weighted form
//     g~_j = n_j . ( sum_k M_jk x_k - sum_a D_ja x_a ) >= 0,
//     D_ja = int_Gc phi_j N_a,   M_jk = int_Gc phi_j N^m_k,
// over the part Gc of the slave surface that the master covers, n_j the slave's averaged unit
// normal at node j (pointing out of the slave, towards the master). The row of node j is this
// condition linearized about the current configuration and divided by its weight
// W_j = sum_a D_ja = int_Gc phi_j (the node's share of the contact surface):
//     -(D_jj/W_j) (n . u_j) - sum_{a != j} (D_ja/W_j) (n . u_a) + sum_k (M_jk/W_j) (n . u_k)
//         <= g~_j / W_j,       n = -n_j,
// so its multiplier is again a nodal force (z_j W_j), the row is node-to-segment's when D is
// the identity and M the master's shape functions at the projection, and the pressure is the
// multiplier divided by ContactRow::weight. D is diagonal for Line2, Line3, Tri3, Quad4 and
// Quad9 slaves; Tri6 and Quad8 slaves carry the dual basis of modified quadratic functions
// (multiplierSpace), so their rows also hold the facet's other nodes.
//
// Integration (Puso and Laursen 2004, Popp et al. 2010): each slave facet and each master facet
// facing it are projected onto the slave facet's auxiliary plane, the master polygon is clipped
// by the slave's, and the overlap is integrated by a 7-point rule per triangle (3D) or 5 Gauss
// points (2D), each point mapped back onto both facets. The dual basis of a slave facet is
// computed on its covered part only (Cichosz and Bischoff 2011), so that biorthogonality, and with
// it the patch test, holds on facets that the master covers partially at its boundary.
//
// A rigid obstacle as the master: the whole slave facet is integrated, the gap at each point taken
// from the obstacle (computeObstacleRows) and the row holds the slave nodes only.
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "contact_ContactRows.hpp"
#include "contact_GmshMesh.hpp"
#include "contact_RigidObstacle.hpp"

namespace contact {

// A body's boundary as a list of facets oriented out of the body (2D: the body on the left of
// a -> b; 3D: x_xi x x_eta outward), of one type.
struct MortarSurface {
  int dim = 3;
  ElementType type = ElementType::Tri3;
  std::vector<int> facets;
  int nodesPerFacet() const { return numNodes(type); }
  int numFacets() const { return static_cast<int>(facets.size()) / nodesPerFacet(); }
};

// A named boundary of the mesh as a mortar surface, oriented out of the body its facets belong
// to. Throws std::invalid_argument naming the file and the boundary.
MortarSurface mortarSurfaceOfBoundary(const GmshMesh& mesh, const std::string& boundary);

// The mortar integrals of one multiplier node (before the division by its weight).
struct MortarCoupling {
  std::map<int, double> slave;   // D_ja over slave nodes a
  std::map<int, double> master;  // M_jk over master nodes k
  double weight = 0.0;           // W_j = sum_a D_ja = int_Gc phi_j
};

struct MortarCouplings {
  std::map<int, MortarCoupling> byNode;  // per multiplier node j
  long long candidatePairs = 0;          // (slave facet, master facet) pairs projected
  long long overlaps = 0;                // of them with an overlap of positive measure
  int singularFacets = 0;                // covered slave facets with no dual basis (slivers)
};

// D, M and W of a slave surface against a master surface on configuration x (dim values per
// mesh node). Master facets farther than searchRadius from a slave facet's plane, facing away
// from it, or sharing a node with it are skipped. The candidates are found along each slave
// facet's normal, so the search costs about the same whatever the search radius.
MortarCouplings mortarCouplings(const std::vector<double>& x, const MortarSurface& slave,
                                const MortarSurface& master, double searchRadius);

// Per slave node: the normalized sum of the unit outward normals of its facets at the node.
std::map<int, std::array<double, 3>> slaveNodalNormals(const std::vector<double>& x,
                                                       const MortarSurface& slave);

// Per slave multiplier node: int phi_j over its whole facets (the weight it has when fully
// covered); a row whose covered weight is below kMortarMinShare of this is dropped (a node the
// master's boundary barely reaches: its row would be ill-conditioned).
std::map<int, double> fullMultiplierWeights(const std::vector<double>& x,
                                            const MortarSurface& slave);
inline constexpr double kMortarMinShare = 1e-3;

// The masters (contact_ContactRows.hpp's ContactMaster): a mesh surface, or a rigid obstacle.
// The slave surface is given here; rows() then returns the rows of those of its nodes that are
// listed and carry a multiplier, in the list's order.
std::unique_ptr<ContactMaster> makeMortarMaster(MortarSurface slave, MortarSurface master,
                                                const ContactSearchOptions& options);
std::unique_ptr<ContactMaster> makeMortarObstacleMaster(MortarSurface slave,
                                                        const RigidObstacle& obstacle,
                                                        const ContactSearchOptions& options);

}  // namespace contact
