#pragma once
// Dostál's two-membrane benchmark, the scalar contact problem: membranes Ω1 = (0,1)x(0,1) and
// Ω2 = (1,2)x(0,1),  -Δu = f  with f = -3 on (0,1)x[0.75,1) and -1 on (1,2)x[0,0.25) (0 on the
// rest), u = 0 on {0}x(0,1), Neumann elsewhere, and on the common side x = 1 the non-penetration
// condition u2 - u1 >= 0. Ω2 floats: only contact holds it, so the contact force balances its
// load, 0.25. Each membrane is torn into a grid of square subdomains; the contact rows pair the
// two membranes' nodes at the same height:  u1 - u2 <= 0,  lambda >= 0.
#include <Teuchos_ParameterList.hpp>

#include <vector>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_StructuredMesh.hpp"

namespace contact {

struct TwoMembranes {
  int subdomainsX = 2, subdomainsY = 2;  // per membrane
  int elementsX = 8, elementsY = 8;      // per subdomain

  // Throws std::invalid_argument unless the load's jumps (y = 0.25, 0.75) lie on element edges.
  void validate() const;
  int numSubdomains() const { return 2 * subdomainsX * subdomainsY; }
  tfeti::StructuredRectangle membrane(int which) const;  // 0: Ω1, 1: Ω2
  double expectedContactForce() const { return 0.25; }
};

struct ContactProblemData {
  std::vector<tfeti::SubdomainData> local;         // this rank's subdomains, by increasing id
  std::vector<tfeti::InequalityRow> inequalities;  // the contact rows this rank contributes
};

ContactProblemData buildTwoMembranes(const TwoMembranes& problem, const tfeti::Comm& comm);

// The driver's studies of this problem: contact_TwoMembranesRun.hpp.

}  // namespace contact
