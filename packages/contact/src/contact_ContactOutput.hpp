#pragma once
// What the contact drivers report of a solved contact problem: the multiplier and pressure of
// every slave node, p_max and the extent of the contact zone, and the stress fields of the
// subdomains as a VTU piece.
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
  double x, y;       // position (reference, or current when a displacement is given)
  double lambda;     // the row's multiplier: force per unit thickness at the node
  double pressure;   // lambda over the node's share of the slave boundary length
  double angle;      // degrees, seen from ContactExtentRule::centre, from its direction
  double normal[2];  // the master's outward normal of the row: lambda * normal is the force
                     // on the slave node
};

// How the contact zone's extent is measured: the half-width along x (a contact centred at
// x = 0 on a symmetry line), or the half-angle seen from a centre, measured from a direction.
struct ContactExtentRule {
  bool angle = false;
  double centre[2] = {0.0, 0.0};
  double direction[2] = {0.0, -1.0};
};

// The multiplier of every row of the last solve at its slave node, sorted by x (or angle).
// surfaceDisplacement: 2 per mesh node (only surface nodes read) or empty for the reference.
std::vector<ContactNode> contactNodes(const ElasticContactProblem& problem,
                                      const tfeti::FetiSolver& solver,
                                      const ContactExtentRule& rule,
                                      const std::vector<double>& surfaceDisplacement = {});

double maxPressure(const std::vector<ContactNode>& nodes);
// The resultant contact force on the slave body, sum of lambda * normal, along `direction`
// (a unit vector; e.g. the applied load's direction: symmetry rows carry the other component
// of the contact force on a half model).
double resultantForce(const std::vector<ContactNode>& nodes, const double direction[2]);
// Between the outermost loaded node and the next one (metres, or degrees for an angle rule).
double contactExtent(const std::vector<ContactNode>& nodes, const ContactExtentRule& rule);

// Rank 0 writes the nodes as CSV (x,y,lambda,pressure,angle); throws naming the file.
void writeContactCsv(const tfeti::Comm& comm, const std::string& path,
                     const std::vector<ContactNode>& nodes);

// When "Contact problem"/"Hertz"/"Compare" is set: Hertz's line contact of two cylinders
// (radii, line load l of the full model, E and nu of "Material" for both bodies) as
// c["hertz"] = {p_max, half_width, max_von_mises} and c["relative_error"] = {p_max, half_width}.
void addHertzComparison(Json& c, const Teuchos::ParameterList& params, double pMax,
                        double halfWidth);

// The VTK cell type of a plane element.
int vtkCellType(plasticity::ElementType type);

// One VTU piece for this rank's subdomains: displacement, the stress components and von Mises
// (from the nodal fields of `stress`), extra nodal fields, and the subdomain id per cell.
struct SubdomainFields {
  const plasticity::ElementMesh* mesh;
  int id;
  const std::vector<double>* displacement;
  const plasticity::StressField* stress;
  std::vector<std::vector<double>> extra;  // one value per node for each of extraNames
};
VtuPiece stressPiece(const std::vector<SubdomainFields>& subdomains,
                     const std::vector<std::string>& extraNames = {});

}  // namespace contact
