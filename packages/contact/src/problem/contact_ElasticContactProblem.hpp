#pragma once
// Elastic bodies in frictionless contact on an unstructured Gmsh mesh, 2D (plane strain) or 3D,
// torn for TFETI: every body is partitioned by METIS into subdomains, Dirichlet and symmetry
// conditions are rows of B (every subdomain floats, also a body held only by contact), and the
// contact pairs (slave/master pairs of named boundaries, or a slave boundary against a rigid
// obstacle; contact_ContactPairs.hpp) give the non-penetration rows B_I (node-to-segment in 2D,
// node-to-face in 3D), every pair's rows in the one B_I. The dimension is the mesh's: one code
// path, dim unknowns per node.
#include <array>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "contact_ContactMaster.hpp"
#include "contact_ContactPairs.hpp"
#include "contact_GmshMesh.hpp"
#include "contact_KinematicCoupling.hpp"
#include "contact_LoadRamp.hpp"
#include "contact_NodeToSegment.hpp"
#include "contact_Partition.hpp"
#include "contact_PrescribedDisplacement.hpp"
#include "plasticity_ElasticLaw.hpp"
#include "plasticity_Elements.hpp"
#include "tfeti_FetiSolver.hpp"

namespace contact {

struct ElasticContactSpec {
  std::string meshFile;  // .geo (meshed now) or .msh
  MeshOptions meshOptions;
  struct Body {
    std::string name;  // a physical group of the mesh's dimension (surface in 2D, volume in 3D)
    int subdomains = 1;
    plasticity::ElasticLaw law;
    double yieldStress = 0.0;  // J2 (nonlinear_contact); 0: elastic
    double hardening = 0.0;    // linear isotropic hardening modulus
  };
  std::vector<Body> bodies;
  std::vector<std::string> fixed;                     // every component zero
  std::vector<std::pair<std::string, int>> symmetry;  // (boundary, component) zero
  std::vector<PrescribedDisplacement> prescribed;     // (boundary, component) = value
  // Constant tractions: dim components per boundary (force per length in 2D, per area in 3D);
  // a different count is an error naming the boundary once the mesh's dimension is known.
  std::vector<std::pair<std::string, std::vector<double>>> tractions;
  std::vector<LoadRamp> tractionRamps;  // per traction (empty: all {0, 1}, proportional)
  // Kinematic couplings: a component of a boundary's nodes tied to one common value.
  std::vector<KinematicCoupling> couplings;
  // Body loads: the total force (per unit thickness in 2D) of a body, dim components, spread
  // uniformly over its area (volume in 3D).
  std::vector<std::pair<std::string, std::vector<double>>> bodyLoads;
  // The contact pairs (at least one): the old keys' single pair, or those of Contact pairs.
  std::vector<ContactPairSpec> pairs;
  bool namedPairs = false;  // given by Contact pairs: the output names every row's pair
  bool tied = false;        // Contact type = tied or bonded: the rows held with equality
  // Contact type = bonded: the contact rows' tangential rows join them (held with equality too).
  bool bonded = false;
  std::string distribution = "graph";            // subdomains to ranks: graph (Zoltan2) or block
  Partitioner partitioner = Partitioner::Metis;  // bodies into subdomains
  // The contact zone's shape (how its extent is reported): auto, line or point; point needs a
  // 3D mesh.
  std::string contactZone = "auto";
};

struct ElasticContactProblem {
  GmshMesh mesh;
  int dim() const { return mesh.dim; }
  std::vector<UnstructuredSubdomain> subdomains;  // all of them (every rank)
  int numSubdomains() const { return static_cast<int>(subdomains.size()); }
  std::vector<int> bodyOfSubdomain;
  std::vector<int> ownerOfSubdomain;  // the rank of every subdomain
  // How ownerOfSubdomain balances the work (summary.json "subdomain_distribution"): the
  // partitioner (see tfeti::distributeSubdomains), the largest rank's share of the dofs and of the
  // initial contact rows over the mean (1 = even) and the interface nodes cut between ranks.
  struct Distribution {
    std::string partitioner;
    double dofImbalance = 1.0, contactImbalance = 1.0, edgeCut = 0.0;
  } distribution;
  // This rank's subdomains, their element meshes (local numbering) and materials.
  std::vector<tfeti::SubdomainData> local;
  std::vector<plasticity::ElementMesh> localElements;
  std::vector<int> localBody;
  // The contact rows (geometry for output) and their B_I form (rank 0 contributes them).
  NodeToSegmentResult contact;
  std::vector<tfeti::InequalityRow> inequalities;
  // The prescribed displacements: values per (node, component), and this rank's rows of them at
  // their full value (prescribedDisplacementRows at load factor 1).
  PrescribedValues prescribed;
  // Every (mesh node, component) a Dirichlet condition holds: the Fixed boundaries' nodes (all
  // components), the Symmetry boundaries' and the prescribed ones. Friction leaves out the
  // tangents in which both sides of a contact row are held (frictionTangentialRows).
  std::set<std::pair<int, int>> heldComponents;
  // The (mesh node, component) pairs a Symmetry boundary holds: friction leaves out the tangent
  // normal to a symmetry plane at a slave node on it, whatever the master's weights.
  std::set<std::pair<int, int>> mirroredComponents;
  std::vector<tfeti::EqualityRow> equalities;
  // The kinematic couplings' rows (rank 0 holds them; included in `equalities`).
  std::vector<tfeti::EqualityRow> couplingRows;
  long long couplingRowCount = 0;  // of all ranks
  // The parts of the local loads (`local[i].f`, every load at its full value) that follow a
  // ramp other than {0, 1}, one per such traction, and the rest (which grows with t itself).
  struct RampedLoad {
    LoadRamp ramp;
    std::vector<std::vector<double>> f;  // per local subdomain
    double force[3] = {0.0, 0.0, 0.0};   // its resultant
  };
  std::vector<RampedLoad> rampedLoads;
  std::vector<std::vector<double>> proportionalLoad;  // per local subdomain (when rampedLoads)
  // What re-evaluating the contact on another configuration needs (updateContact): per pair.
  struct Pair {
    ContactPairSpec spec;
    // The Master boundary's segments (oriented by the master body's elements) or the obstacle.
    std::shared_ptr<const ContactMaster> master;
    double searchRadius = 0.0;    // the radius in force (the spec's, or a tenth of the extent)
    std::vector<int> slaveNodes;  // global node ids of the slave boundary, sorted
    // Per slave node: its share of the slave boundary's length (2D) or area (3D).
    std::vector<double> slaveWeights;
    // The bodies (indices into spec.bodies) of the Slave and Master boundaries (-1 for a rigid
    // obstacle as the master): whose materials Hertz's combined modulus takes.
    int slaveBody = -1, masterBody = -1;
  };
  std::vector<Pair> pairs;
  bool namedPairs = false;   // given by Contact pairs: the output names every row's pair
  std::vector<int> rowPair;  // per row of contact.rows: its pair (index into pairs)
  std::vector<std::pair<int, int>> copyOf;   // node -> (subdomain, local node) of its first copy
  std::vector<int> surfaceNodes;             // every pair's slave and master nodes, sorted
  double appliedForce[3] = {0.0, 0.0, 0.0};  // resultant of the tractions and body loads
};

// The external load at load factor t, per local subdomain: t f, or with ramped tractions
// t f_proportional + sum_k ramp_k(t) f_k. And its resultant (dim components, all ranks').
std::vector<std::vector<double>> loadAt(const ElasticContactProblem& p, double t);
std::vector<double> appliedForceAt(const ElasticContactProblem& p, double t);

// The equality rows of an increment from `current` (per local subdomain; empty: zero) at load
// factor t: the prescribed values' rows and the kinematic couplings' rows.
std::vector<tfeti::EqualityRow> equalityRowsAt(const ElasticContactProblem& p, double t,
                                               const std::vector<std::vector<double>>& current);

// Loads the mesh, partitions every body into subdomains, gathers the Dirichlet conditions and
// couplings, distributes the subdomains to ranks, assembles this rank's stiffness and loads, and
// sets up the contact pair (see the steps in the .cpp). Throws std::invalid_argument naming the
// group or parameter that is wrong.
ElasticContactProblem buildElasticContactProblem(const ElasticContactSpec& spec,
                                                 const tfeti::Comm& comm);

// The contact rows of every pair on the configuration reference + displacement (dim per mesh
// node; only the surfaceNodes' entries are read), concatenated pair by pair: p.contact,
// p.rowPair and, on rank 0, p.inequalities. Throws std::invalid_argument naming the pair when
// no slave node of a pair is within its search radius, and naming the node's coordinates and
// both pairs when a slave node has rows in two pairs (the rule: one pair per slave node).
void updateContact(ElasticContactProblem& p, const std::vector<double>& displacement, int rank);

// p.inequalities from p.contact's rows (rank 0 contributes them; the others none).
void setInequalitiesFromRows(ElasticContactProblem& p, int rank);

// Per row of p.contact: its slave node's share of its pair's slave boundary (the weight that
// turns the row's multiplier into a pressure); a mortar row's own weight.
std::vector<double> contactRowWeights(const ElasticContactProblem& p);

// The elastic laws of the first contact pair's bodies (slave, then master; one with a rigid
// obstacle), for Hertz's combined modulus.
std::vector<plasticity::ElasticLaw> contactBodyLaws(const ElasticContactSpec& spec,
                                                    const ElasticContactProblem& p);

// A body's element type checked to be one the assembly takes (the catalogue's complete body
// types: Tri3, Quad4, Tri6, Quad9, Tet4, Tet10, Hex8, Hex27); throws std::invalid_argument naming
// them otherwise (a Hex20 mesh).
ElementType checkedBodyType(ElementType type);

// The untorn nodes of a boundary group, sorted; throws std::invalid_argument naming it.
std::vector<int> boundaryNodeIds(const GmshMesh& mesh, const std::string& name);

}  // namespace contact
