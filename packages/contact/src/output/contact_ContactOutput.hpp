#pragma once
// What the contact drivers report of a solved contact problem: the multiplier and pressure of
// every slave node, p_max and the extent of the contact zone, and the stress fields of the
// subdomains as a VTU piece.
#include <optional>
#include <string>
#include <vector>

#include <Teuchos_ParameterList.hpp>

#include "contact_ElasticContactProblem.hpp"
#include "contact_Json.hpp"
#include "contact_VtuWriter.hpp"
#include "plasticity_Elements.hpp"
#include "tfeti_FetiSolver.hpp"

namespace contact {

struct ContactNode {
  double x, y, z;      // position (reference, or current when a displacement is given); z = 0 in 2D
  double lambda;       // the row's multiplier: force (per unit thickness in 2D) at the node
  double pressure;     // lambda over the node's share of the slave boundary length (area in 3D)
  double angle;        // 2D: degrees, seen from ContactExtentRule::centre, from its direction
  double radius;       // 3D: distance from the contact axis (ContactExtentRule::centre, axis)
  double normal[3];    // the master's outward normal of the row: lambda * normal is the force
                       // on the slave node
  double gap;          // the row's gap left by the solve, c_I - B_I u (>= 0; 0 in contact); the
                       // row's gap before it when contactNodes is given no solution
  int slaveNode = -1;  // its global node id
  int pair = -1;       // its row's contact pair (index of Contact pairs); -1 for the old keys'
  // Friction (addFrictionResults; state -1 without friction): the tangential multiplier (force
  // along the tangent t = (-n_y, n_x) in 2D), it over the node's share (traction), the slave's
  // slip relative to the master along t in the load step, state 0 open, 1 stick, 2 slip.
  int frictionState = -1;
  double tangentialForce = 0.0, tangentialTraction = 0.0, slip = 0.0, tangent[3] = {0, 0, 0};
  double slipBound = 0.0;  // the bound of |tangentialForce| in the last solve
  // Over the load steps so far, this one included (contact_FrictionHistory.hpp): the slip's
  // path length, sum |slip| over the steps that ended with the node closed, and its signed sum
  // along the node's tangent (2D; 3D: along the first tangent).
  double accumulatedSlip = 0.0, netSlip = 0.0;
  // The contact force on the slave node, lambda * normal plus every tangential multiplier times
  // its tangent (B^T lambda on the node's dofs, negated). Unlike the split into lambda and
  // tangentialForce it does not depend on the frame: a slave node on a master node where the
  // master kinks takes either segment's normal, as rounding decides (docs/friction.md).
  double force[3] = {0.0, 0.0, 0.0};
  // The pressure smoothed over the node's facet neighbours (recoverContactPressures in
  // contact_RecoveredFields.hpp): a least-squares fit of their pressures, evaluated at the node;
  // zero where pressure is.
  double pressureRecovered = 0.0;
};

// How the contact zone's extent is measured. 2D: the half-width along x (a contact centred at
// x = 0 on a symmetry line), or the half-angle seen from a centre, measured from a direction.
// 3D, point contact: the radius from the contact axis, the line through centre along axis (an
// axisymmetric contact, e.g. a sphere pressed along -z onto a flat at the origin). 3D, line
// contact (`line`): a contact along z (e.g. a cylinder in a plane-strain slab), its half-width
// along x on every node plane z = const of the slave nodes (the 2D rule on each), averaged.
struct ContactExtentRule {
  bool angle = false;
  bool line = false;
  double centre[3] = {0.0, 0.0, 0.0};
  double direction[2] = {0.0, -1.0};
  double axis[3] = {0.0, 0.0, 1.0};  // a unit vector
};

// "Contact problem/Contact zone" for a mesh of dimension dim: true for a line contact (2D, or
// `line` in 3D), false for a point contact (`point`, or `auto` in 3D). Throws
// std::invalid_argument for `point` in 2D.
bool lineContact(const Teuchos::ParameterList& params, int dim);

// The multiplier of every row of the last solve at its slave node, sorted by x (or angle; the
// radius in 3D). surfaceDisplacement: dim per mesh node (only surface nodes read) or empty for
// the reference. surfaceSolution: the solve's primal solution (the increment of a nonlinear
// iteration) in the same layout, for the gaps it leaves; empty: the rows' gaps. The recovered
// pressures are left at zero (recoverContactPressures sets them where a run reports them).
std::vector<ContactNode> contactNodes(const ElasticContactProblem& problem,
                                      const tfeti::FetiSolver& solver,
                                      const ContactExtentRule& rule,
                                      const std::vector<double>& surfaceDisplacement = {},
                                      const std::vector<double>& surfaceSolution = {});

double maxPressure(const std::vector<ContactNode>& nodes);
// The resultant contact force on the slave body, sum of lambda * normal (with friction the
// nodes' whole force, ContactNode::force, tangential part included), along `direction`
// (a unit vector; e.g. the applied load's direction: symmetry rows carry the other component
// of the contact force on a half model). 2D: direction has 2 entries, 3D: 3.
double resultantForce(const std::vector<ContactNode>& nodes, const double direction[], int dim = 2);
// Between the outermost loaded node and the next one outwards (metres, or degrees for an angle
// rule); in 3D between the largest radius of a node with a positive multiplier and the next
// larger radius if that node's multiplier is zero (nodes sorted by radius); for a 3D line
// contact (rule.line) the mean of halfWidthPerPlane.
double contactExtent(const std::vector<ContactNode>& nodes, const ContactExtentRule& rule,
                     int dim = 2);

// A 3D line contact's half-width along x on one node plane z = const of the slave nodes.
struct PlaneHalfWidth {
  double z;
  int nodes;  // slave nodes with a row on the plane
  double halfWidth;
};
// The planes by increasing z; nodes within 1e-9 of the nodes' extent in z are on one plane.
std::vector<PlaneHalfWidth> halfWidthPerPlane(const std::vector<ContactNode>& nodes);

// Rank 0 writes the nodes as CSV: x,y,lambda,pressure,angle (2D) or x,y,z,lambda,pressure,radius
// (3D), with friction then tangential_force,tangential_traction,slip_increment,state,
// accumulated_slip,net_slip,node (the slave node's global id), with Contact pairs then pair (the
// row's pair index, in the order of Contact pairs), and last pressure_recovered; throws naming
// the file.
void writeContactCsv(const tfeti::Comm& comm, const std::string& path,
                     const std::vector<ContactNode>& nodes, int dim = 2);

// Hertz's closed form for the run's contact, when "Contact problem"/"Hertz"/"Compare" is set:
// for a line contact (lineContact: 2D, or a 3D slab) the line contact of two cylinders (radii,
// line load l of the full model per unit length), for a 3D point contact that of two spheres
// (radii, total force F of the full model). contactLaws: the materials of the bodies in contact
// (contactBodyLaws; one against a rigid obstacle), combined as 1/E* = sum (1 - nu^2)/E.
struct HertzReference {
  bool line = true;          // extent is a half-width (line) or a contact radius (point)
  double pMax = 0.0;         // p0
  double extent = 0.0;       // a
  double maxVonMises = 0.0;  // the largest von Mises stress below the surface
  double pMaxError = 0.0;    // |p_max - p0| / p0 of the run's p_max
  double extentError = 0.0;  // |extent - a| / a of the run's extent
  // The same for the recovered p_max and the largest von Mises stresses (Gauss points and
  // averaged nodes), set by addRecoveredErrors.
  double pMaxRecoveredError = 0.0, maxVonMisesError = 0.0, maxVonMisesNodalError = 0.0;
};
// Before a run: where Hertz/Compare is set, the Slave boundary lies on a body (contactLaws not
// empty) and the load of the contact's closed form, Force (point) or Line load (line), is
// positive; otherwise std::invalid_argument naming the parameter (the reference would be 0/0).
void checkHertzInput(const Teuchos::ParameterList& params, int dim,
                     const std::vector<plasticity::ElasticLaw>& contactLaws);
// Empty when Hertz/Compare is not set; checkHertzInput's errors otherwise.
std::optional<HertzReference> hertzReference(
    const Teuchos::ParameterList& params, double pMax, double extent, int dim,
    const std::vector<plasticity::ElasticLaw>& contactLaws);
// The relative errors of the recovered p_max and of the largest von Mises stresses.
void addRecoveredErrors(HertzReference& hertz, double pMaxRecovered, double maxVonMises,
                        double maxVonMisesNodal);
// c["hertz"] = {p_max, half_width | contact_radius, max_von_mises} and c["relative_error"] =
// {p_max, half_width | contact_radius, p_max_recovered, max_von_mises, max_von_mises_nodal}.
void addHertzComparison(Json& c, const HertzReference& hertz);

// One VTU piece for this rank's subdomains (cells of the catalogue's VTK type, nodes in its VTK
// order: plasticity::vtkType, plasticity::vtkNodeOrder): displacement, the stress components (2D:
// sxx, syy, sxy; 3D: sxx, syy, szz, syz, sxz, sxy) and von Mises (from the nodal fields of
// `stress`), extra nodal fields, and the subdomain id per cell.
struct SubdomainFields {
  const plasticity::ElementMesh* mesh;
  int id;
  const std::vector<double>* displacement;
  const plasticity::StressField* stress;
  std::vector<std::vector<double>> extra;  // one value per node for each of extraNames
};
VtuPiece stressPiece(const std::vector<SubdomainFields>& subdomains,
                     const std::vector<std::string>& extraNames = {});

// The point field "contact_pair" of a subdomain (its nodes' global ids): the pair index of the
// node's contact row, -1 at a node without one.
std::vector<double> contactPairField(const std::vector<ContactNode>& nodes,
                                     const std::vector<tfeti::GO>& globalNode);

// Per contact pair (of Contact pairs): its name, the resultant of the contact forces on its
// slave nodes (ContactNode::force with friction, lambda * normal without) and its magnitude.
struct PairForce {
  std::string name;
  std::string discretization;  // node_to_segment or mortar
  double force = 0.0;
  std::vector<double> vector;  // dim components
};
std::vector<PairForce> pairForces(const ElasticContactProblem& problem,
                                  const std::vector<ContactNode>& nodes);

}  // namespace contact
