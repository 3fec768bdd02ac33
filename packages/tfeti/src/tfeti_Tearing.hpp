#pragma once
// The constraint matrix B of the torn problem: gluing rows (u_a - u_b = 0 between two copies of
// one node) and, in TFETI, Dirichlet rows (u = 0 on every subdomain copy of a Dirichlet node).
//
// Rows are grouped by (untorn node, component); rows of different groups touch disjoint dofs, so
// B B^T is block diagonal by group, which the preconditioner's scaling uses. Every rank derives
// the same global list of rows from the gathered subdomain boundaries; the row numbering depends
// only on the mesh, not on the number of ranks, and a group's rows are owned by the rank of its
// lowest-numbered subdomain.
#include <vector>

#include "tfeti_Subdomain.hpp"
#include "tfeti_SubdomainMesh.hpp"
#include "tfeti_Types.hpp"

namespace tfeti {

enum class Gluing { NonRedundant, Redundant };

struct TearingOptions {
  Formulation formulation = Formulation::TFETI;
  Gluing gluing = Gluing::NonRedundant;
  // The paper counts gluing rows also at interface nodes on the Dirichlet boundary. In TFETI
  // these rows are linearly dependent on the Dirichlet rows; false drops them.
  bool gluingAtDirichletNodes = true;
};

// A local subdomain as the tearing sees it.
struct TearingInput {
  int id;
  int numDofs;
  std::vector<int> boundaryNodes;      // local nodes that may be shared
  std::vector<GO> boundaryGlobal;      // their untorn ids
  std::vector<int> boundaryDirichlet;  // per boundary node: bit c set if component c is prescribed
};

// One term of a constraint row: coefficient times a dof of a subdomain (global subdomain id).
struct ConstraintEntry {
  int subdomain;
  int dof;
  double coef;
};

// A non-penetration row  sum coef * u <= gap  (contact): its multiplier is bounded below by 0.
struct InequalityRow {
  std::vector<ConstraintEntry> entries;
  double gap = 0.0;
};

struct RowEntry {
  GO row;       // multiplier id
  int dof;      // local dof of the subdomain
  double coef;  // +1 or -1
};

struct Tearing {
  Teuchos::RCP<const Map> primalMap;      // all subdomain dofs, owned by the subdomain's rank
  Teuchos::RCP<const Map> multiplierMap;  // rows of B
  Teuchos::RCP<CrsMatrix> B;
  std::vector<GO> dofOffset;  // first global dof of every subdomain
  // For each local subdomain (same order as the input): the rows that touch it.
  std::vector<std::vector<RowEntry>> subdomainRows;
  // Locally owned groups: local row indices and the pseudo-inverse of their B B^T block.
  std::vector<std::vector<LO>> groupRows;
  std::vector<std::vector<double>> groupScaling;
  GO numRows = 0, numGluingRows = 0, numDirichletRows = 0;
  // Inequality rows come last: global rows [firstInequalityRow, numRows).
  GO numInequalityRows = 0, firstInequalityRow = 0;
  // Every inequality row (all ranks), in the canonical order of their multipliers.
  std::vector<InequalityRow> inequalityRows;
  // Right-hand side c of B u = c (equality) and B u <= c (inequality), on multiplierMap.
  Teuchos::RCP<Vector> rhs;
  bool isInequality(GO row) const { return row >= firstInequalityRow; }
};

// inequalities: the non-penetration rows this rank contributes (any rank may contribute any
// row; they are gathered and numbered in a canonical order independent of the rank count).
Tearing buildTearing(const Teuchos::RCP<const Comm>& comm, int numSubdomains,
                     const std::vector<TearingInput>& local, int dofsPerNode,
                     const TearingOptions& options,
                     const std::vector<InequalityRow>& inequalities = {});

}  // namespace tfeti
