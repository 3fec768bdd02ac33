#pragma once
// The linear model problems of the reference paper on a structured, torn box (a rectangle in
// 2D, a cuboid in 3D): Poisson (-Δu = source, u = 0 on the face x = x0, Neumann elsewhere) and
// linear elasticity (body force, clamped on the face x = x0; plane strain in 2D). The dimension
// is the number of corner coordinates. Builds this rank's subdomains for the FETI solver and,
// for verification, solves the undecomposed problem directly.
#include <string>
#include <vector>

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

  int dim() const { return static_cast<int>(lo.size()); }
  plasticity::Field q1Field() const {
    return field == "poisson" ? plasticity::Field::Scalar : plasticity::Field::Elasticity;
  }
  int dofsPerNode() const { return plasticity::dofsPerNode(q1Field(), dim()); }
  tfeti::StructuredMesh mesh() const { return tfeti::StructuredMesh(lo, hi, subdomains, elements); }
  int numSubdomains() const { return mesh().numSubdomains(); }
};

// Meshes and assembles (Kokkos element kernels) the subdomains of this rank.
std::vector<tfeti::SubdomainData> buildLocalSubdomains(const StructuredProblem& problem,
                                                       const tfeti::Comm& comm);

// Max over all node copies of |u_FETI - u_direct|, relative to max |u_direct|, where u_direct
// solves the assembled undecomposed problem with CHOLMOD (on every rank: small problems only).
double relativeErrorAgainstDirectSolve(const StructuredProblem& problem,
                                       const tfeti::FetiSolver& solver);

}  // namespace contact
