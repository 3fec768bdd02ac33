#pragma once
// Checks of what an application hands to FetiSolver, in the application's terms ("subdomain 3:
// K has 80 rows, the mesh has 81 nodes x 1 dof"). Everything the solver indexes by is checked
// before it is used, so that a wrong size is an error and never an over-read or a wrong answer.
// The collective checks raise the same CollectiveError on every rank.
#include <string>
#include <vector>

#include "tfeti_CollectiveError.hpp"
#include "tfeti_CsrMatrix.hpp"
#include "tfeti_FetiSolver.hpp"

namespace tfeti {

// One subdomain's data against its own mesh (sizes of K, f, coordinates, kernel; node indices
// of elements and boundary lists; finite numbers): empty when consistent. A K given as tpetraK
// is checked as the CSR arrays made of it (and not given twice).
std::string subdomainDataError(const SubdomainData& sd, int numSubdomains);
// The same for the parts of one subdomain, coords (mesh.dim per node) standing for mesh.coords.
std::string subdomainDataError(const SubdomainMesh& mesh, const std::vector<double>& coords,
                               int dofsPerNode, const CsrMatrix& K, const std::vector<double>& f,
                               const std::vector<double>& kernel, int numSubdomains);

// Collective: every local subdomain checked, the dofs per node equal on all subdomains, and
// every id in [0, numSubdomains) held by exactly one rank.
void checkSubdomainInput(const Comm& comm, int numSubdomains,
                         const std::vector<SubdomainData>& local);

}  // namespace tfeti
