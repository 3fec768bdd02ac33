#pragma once
// tfeti_contact --check: the dry run. Every study's set-up up to the first solve (parameters,
// meshing, partitioning, subdomain distribution, tearing inputs, contact rows) runs through the
// same functions as a full run, so that it fails with the same message; nothing is factorized
// or solved. What it reports: the problem's bodies and boundaries, the subdomains of every
// rank, the unknowns, the contact rows and an estimate of the memory the solve will need.
#include <Teuchos_ParameterList.hpp>

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "tfeti_CsrMatrix.hpp"
#include "tfeti_FetiSolver.hpp"

namespace contact {

// A fill-reducing order of K's graph (METIS nested dissection, as CHOLMOD may choose): order[k]
// is the row eliminated k-th.
std::vector<int> fillReducingOrder(const tfeti::CsrMatrix& K);
// The exact number of entries of the Cholesky factor L (diagonal included) of the symmetric
// pattern of K eliminated in the given order (elimination tree and row subtrees).
std::size_t choleskyFactorEntries(const tfeti::CsrMatrix& K, const std::vector<int>& order);

// The line of the explicit dual operator (collective): the bytes its dense local F_s take, or
// would take, with FETI "Dual operator" = explicit, over all ranks and on the largest rank, from
// the rows of B that the set-up would build (FetiSolver::dualRowsPerSubdomain).
std::string explicitDualLine(const Teuchos::RCP<const tfeti::Comm>& comm, int numSubdomains,
                             const std::vector<tfeti::SubdomainData>& local,
                             const Teuchos::ParameterList& feti,
                             const std::vector<tfeti::InequalityRow>& inequalities = {},
                             const std::vector<tfeti::EqualityRow>& equalities = {});

// Rank 0 prints `lines` (the problem's own report), then the subdomains of every rank, the
// unknowns and the estimated memory of the subdomain matrices and their Cholesky factors (the
// largest per rank and the total), from this rank's subdomains, and against the memory each node
// has available now (the fullest node: whether the full run's check, FETI "Memory check", would
// stop it). `contactRows` < 0: no contact. Collective.
void printDryRunReport(const tfeti::Comm& comm, const std::vector<std::string>& lines,
                       const std::vector<tfeti::SubdomainData>& local, long long contactRows,
                       const Teuchos::ParameterList& feti, std::ostream& out);

}  // namespace contact
