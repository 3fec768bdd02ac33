#pragma once
// Elastic bodies in frictionless contact on an unstructured Gmsh mesh, torn for TFETI: every
// body is partitioned by METIS into subdomains, Dirichlet and symmetry conditions are rows of B
// (every subdomain floats, also a body held only by contact), and one slave/master pair of
// named boundaries gives the node-to-segment non-penetration rows B_I.
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "contact_ContactMaster.hpp"
#include "contact_GmshMesh.hpp"
#include "contact_NodeToSegment.hpp"
#include "contact_Partition.hpp"
#include "plasticity_ElasticLaw.hpp"
#include "plasticity_Elements.hpp"
#include "tfeti_FetiSolver.hpp"

namespace contact {

struct ElasticContactSpec {
  std::string meshFile;  // .geo (meshed now) or .msh
  MeshOptions meshOptions;
  struct Body {
    std::string name;  // a 2D physical group
    int subdomains = 1;
    plasticity::ElasticLaw law;
  };
  std::vector<Body> bodies;
  std::vector<std::string> fixed;                     // every component zero
  std::vector<std::pair<std::string, int>> symmetry;  // (boundary, component) zero
  std::vector<std::pair<std::string, std::array<double, 2>>> tractions;  // force / length
  // Body loads: the total force (per unit thickness) of a body, spread uniformly over its area.
  std::vector<std::pair<std::string, std::array<double, 2>>> bodyLoads;
  std::string slave, master;  // the contact pair
  // A rigid obstacle as the master instead of a Master boundary (its dim is set to 2 here).
  std::optional<RigidObstacle> obstacle;
  double searchRadius = 0.0;           // 0: a tenth of the mesh's extent
  std::string distribution = "graph";  // subdomains to ranks: graph (Zoltan2) or block
};

struct ElasticContactProblem {
  GmshMesh mesh;
  std::vector<UnstructuredSubdomain> subdomains;  // all of them (every rank)
  int numSubdomains() const { return static_cast<int>(subdomains.size()); }
  std::vector<int> bodyOfSubdomain;
  std::vector<int> ownerOfSubdomain;  // the rank of every subdomain
  // This rank's subdomains, their element meshes (local numbering) and materials.
  std::vector<tfeti::SubdomainData> local;
  std::vector<plasticity::ElementMesh> localElements;
  std::vector<int> localBody;
  // The contact rows (geometry for output) and their B_I form (rank 0 contributes them).
  NodeToSegmentResult contact;
  std::vector<tfeti::InequalityRow> inequalities;
  // What re-evaluating the contact on another configuration needs (updateContact).
  // The Master boundary's segments (oriented by the master body's elements) or the obstacle.
  std::shared_ptr<const ContactMaster> master;
  std::vector<std::pair<int, int>> copyOf;  // node -> (subdomain, local node) of its first copy
  std::vector<int> surfaceNodes;            // slave and master nodes, sorted
  std::vector<int> slaveNodes;              // global node ids of the slave boundary, as in contact
  std::vector<double> slaveWeights;     // per slave node: its share of the slave boundary length
  double appliedForce[2] = {0.0, 0.0};  // resultant of the tractions
};

// Throws std::invalid_argument naming the group or parameter that is wrong.
ElasticContactProblem buildElasticContactProblem(const ElasticContactSpec& spec,
                                                 const tfeti::Comm& comm);

// The contact rows on the configuration reference + displacement (2 per mesh node; only the
// surfaceNodes' entries are read): p.contact and, on rank 0, p.inequalities. Throws when no
// slave node is within the search radius.
void updateContact(ElasticContactProblem& p, const std::vector<double>& displacement, int rank,
                   const std::string& slaveName = "slave",
                   const std::string& masterName = "master");

plasticity::ElementType toPlasticityType(ElementType type);

}  // namespace contact
