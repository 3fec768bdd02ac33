#pragma once
// The linear model problems of the reference paper on a structured, torn rectangle: Poisson
// (-Δu = source, u = 0 on x = x0, Neumann elsewhere) and plane-strain elasticity (body force,
// clamped on x = x0). Builds this rank's subdomains for the FETI solver and, for verification,
// solves the undecomposed problem directly.
#include <string>
#include <vector>

#include "plasticity_ElasticLaw.hpp"
#include "tfeti_FetiSolver.hpp"
#include "tfeti_StructuredMesh.hpp"

namespace contact {

struct StructuredProblem {
  std::string field = "poisson";  // "poisson" | "elasticity"
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  int subdomainsX = 4, subdomainsY = 4;
  int elementsX = 16, elementsY = 16;  // per subdomain
  plasticity::ElasticLaw law;
  double source = 1.0;
  double bodyForce[2] = {0.0, -1.0};

  int dofsPerNode() const { return field == "poisson" ? 1 : 2; }
  tfeti::StructuredRectangle mesh() const {
    return tfeti::StructuredRectangle(x0, x1, y0, y1, subdomainsX, subdomainsY, elementsX,
                                      elementsY);
  }
};

// Meshes and assembles (Kokkos element kernels) the subdomains of this rank.
std::vector<tfeti::SubdomainData> buildLocalSubdomains(const StructuredProblem& problem,
                                                       const tfeti::Comm& comm);

// Max over all node copies of |u_FETI - u_direct|, relative to max |u_direct|, where u_direct
// solves the assembled undecomposed problem with CHOLMOD (on every rank: small problems only).
double relativeErrorAgainstDirectSolve(const StructuredProblem& problem,
                                       const tfeti::FetiSolver& solver);

}  // namespace contact
