#pragma once
// The linear model problems of the reference paper on a structured, torn box (a rectangle in
// 2D, a cuboid in 3D): Poisson (-Δu = source, u = 0 on the face x = x0, Neumann elsewhere) and
// linear elasticity (body force, clamped on the face x = x0; plane strain in 2D). The dimension
// is the number of corner coordinates. Other conditions on the faces (named x0, x1, y0, y1, z0,
// z1: the face x = x0, ...) may replace the clamp: fixed faces, symmetry faces (one component
// zero) and prescribed (non-zero) components. Builds this rank's subdomains for the FETI solver
// and, for verification, solves the undecomposed problem directly.
#include <string>
#include <vector>

#include "contact_PrescribedDisplacement.hpp"
#include "plasticity_ElasticLaw.hpp"
#include "plasticity_Q1Assembly.hpp"
#include "tfeti_FetiSolver.hpp"
#include "tfeti_StructuredMesh.hpp"

namespace contact {

struct StructuredProblem {
  std::string field = "poisson";  // "poisson" | "elasticity"
  // The box's corners and the grids, one entry per axis (2 or 3).
  std::vector<double> lo = {0, 0}, hi = {1, 1};
  std::vector<int> subdomains = {4, 4};
  std::vector<int> elements = {16, 16};  // per subdomain
  plasticity::ElasticLaw law;
  double source = 1.0;
  std::vector<double> bodyForce = {0.0, -1.0};  // one entry per axis
  // Conditions on the faces: every component zero, one component zero, one component given.
  std::vector<std::string> fixed = {"x0"};
  std::vector<std::pair<std::string, int>> symmetry;
  std::vector<PrescribedDisplacement> prescribed;

  int dim() const { return static_cast<int>(lo.size()); }
  plasticity::Field q1Field() const {
    return field == "poisson" ? plasticity::Field::Scalar : plasticity::Field::Elasticity;
  }
  int dofsPerNode() const { return plasticity::dofsPerNode(q1Field(), dim()); }
  tfeti::StructuredMesh mesh() const { return tfeti::StructuredMesh(lo, hi, subdomains, elements); }
  int numSubdomains() const { return mesh().numSubdomains(); }
  // The untorn nodes of a face (x0, x1, y0, y1, and z0, z1 in 3D); throws std::invalid_argument
  // naming the valid faces for another name.
  std::vector<long long> faceNodes(const std::string& face) const;
  // The prescribed values, checked (prescribedValues in contact_PrescribedDisplacement.hpp).
  PrescribedValues prescribedValues() const;
  // Sets the fixed and symmetry conditions of the faces on a subdomain (or the whole) mesh.
  void applyFaceConditions(tfeti::SubdomainMesh& mesh) const;
};

// Meshes and assembles (Kokkos element kernels) the subdomains of this rank.
std::vector<tfeti::SubdomainData> buildLocalSubdomains(const StructuredProblem& problem,
                                                       const tfeti::Comm& comm);

// Max over all node copies of |u_FETI - u_direct|, relative to max |u_direct|, where u_direct
// solves the assembled undecomposed problem with CHOLMOD (on every rank: small problems only).
double relativeErrorAgainstDirectSolve(const StructuredProblem& problem,
                                       const tfeti::FetiSolver& solver);

// Mesh/Subdomains times Mesh/Elements per subdomain within what the structured grids can number
// (throws std::invalid_argument naming the parameters).
void checkGridSize(const Teuchos::ParameterList& mesh);

}  // namespace contact
