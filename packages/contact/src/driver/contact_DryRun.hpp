#pragma once
// tfeti_contact --check: the dry run. Every study's set-up up to the first solve (parameters,
// meshing, partitioning, subdomain distribution, tearing inputs, contact rows) runs through the
// same functions as a full run, so that it fails with the same message; nothing is factorized
// or solved. What it reports: the problem's bodies and boundaries, the subdomains of every
// rank, the unknowns, the contact rows and the memory the set-up will need.
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

// Rank 0 prints `lines` (the problem's own report), then what the set-up will allocate, from
// FetiSolver::forecastSetupMemory (the local solver's own symbolic analyses, the tearing the
// run builds from `local` and the caller's rows; nothing factorized): the explicit F_s' bytes
// (that Dual operator = explicit takes, or would take), the subdomains of every rank, the
// unknowns, the subdomain matrices and their factors (the largest rank and the total), the
// Dirichlet preconditioner's interior factors; each against the memory the fullest node has
// available now, with what the run's check (FETI "Memory check") would do there. A local
// solver that cannot tell its factors' bytes (KLU2, Tacho) gets a symbolic count under a METIS
// order instead, an estimate the run does not check. `contactRows` < 0: no contact. Collective.
void printDryRunReport(const Teuchos::RCP<const tfeti::Comm>& comm, int numSubdomains,
                       const std::vector<std::string>& lines,
                       const std::vector<tfeti::SubdomainData>& local, long long contactRows,
                       const Teuchos::ParameterList& feti, std::ostream& out,
                       const std::vector<tfeti::InequalityRow>& inequalities = {},
                       const std::vector<tfeti::EqualityRow>& equalities = {});

}  // namespace contact
