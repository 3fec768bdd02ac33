#pragma once
// Tpetra at FetiSolver's interfaces: a subdomain matrix given as a Tpetra::CrsMatrix, and the
// primal solution gathered onto a caller's untorn (global) map.
//  - A subdomain matrix as a CrsMatrix (SubdomainData::tpetraK) belongs to the one rank that holds
//    the subdomain: its row map must own all its rows on that rank (a serial communicator, e.g.
//    Tpetra::SerialComm or MPI_COMM_SELF, or a locally replicated map), with global ids 0 .. n-1
//    = the subdomain's local dofs (dofsPerNode * local node + component); the domain and range
//    maps are those rows too.
//  - The untorn solution: entry dofsPerNode * globalNode + component of the caller's map (any
//    distribution, any order; every dof of every subdomain must be on it, and it must hold no
//    other dof). A dof shared by several subdomains gets the mean of their values, which agree to
//    the solver's tolerance (the gluing rows).
#include <vector>

#include "tfeti_CsrMatrix.hpp"
#include "tfeti_Types.hpp"

namespace tfeti {

// The CSR arrays of K; throws std::invalid_argument saying what is wrong, prefixed by `what`
// (e.g. "subdomain 3: tpetraK").
CsrMatrix csrFromTpetra(const CrsMatrix& K, const std::string& what);

// Collective over map's communicator. values[s][dof] of the local subdomains with the given
// untorn global nodes gathered onto `map` (means at shared dofs). Throws CollectiveError on every
// rank when a subdomain dof is not on the map or a map entry belongs to no subdomain.
Teuchos::RCP<MultiVector> untornVector(const Teuchos::RCP<const Map>& map,
                                       const std::vector<std::vector<GO>>& globalNodes,
                                       int dofsPerNode,
                                       const std::vector<std::vector<double>>& values);

}  // namespace tfeti
