#pragma once
// The constraint matrix B of the torn problem and its right-hand side c: gluing rows (u_a - u_b =
// 0 between two copies of one node), in TFETI Dirichlet rows (u = 0 on every subdomain copy of a
// Dirichlet node), the caller's equality rows (sum coef * u = rhs: a non-zero prescribed value, a
// multi-point constraint, a periodic pair, a tied interface) and the caller's inequality rows
// (sum coef * u <= gap: contact).
//
// Row order (global multiplier ids): the automatic rows (gluing and Dirichlet) by (untorn node,
// component), then the caller's equality rows, then the inequality rows, the caller's rows each
// in a canonical order (by their entries, then the right-hand side) so that the numbering
// depends on the mesh and the rows, not on the number of ranks or on which rank passed a row.
//
// Scaling groups: rows that share a dof (transitively) form a group, whose rows are owned by
// the rank of the group's lowest-numbered subdomain and whose block of B B^T is pseudo-inverted
// for the preconditioner's scaling Q = (B B^T)^+ (block diagonal by group, so Q is exactly the
// pseudo-inverse of B B^T). The automatic rows of one (node, component) are a group (they touch
// disjoint dofs from other groups); a caller's equality row joins the groups it touches, and so
// does an inequality row (a tied or contact row on a node that a cut shares between subdomains
// joins that node's gluing group) unless TearingOptions::inequalityScaling is Separate, which
// makes every inequality row its own group (weight 1/||row||^2, the scaling before issue 13).
// A group of at most kMaxDenseScalingGroup rows keeps a dense pseudo-inverse; a larger one (a
// contact surface whose node-to-face rows share master nodes chains all its rows into one
// group) a sparse factorization (SparsePseudoInverse).
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "tfeti_SparsePseudoInverse.hpp"
#include "tfeti_Subdomain.hpp"
#include "tfeti_SubdomainMesh.hpp"
#include "tfeti_Types.hpp"

namespace tfeti {

// None: no gluing rows at all; the caller's equality rows must join the subdomains.
enum class Gluing { NonRedundant, Redundant, None };

struct TearingOptions {
  Formulation formulation = Formulation::TFETI;
  Gluing gluing = Gluing::NonRedundant;
  // The paper counts gluing rows also at interface nodes on the Dirichlet boundary. In TFETI
  // these rows are linearly dependent on the Dirichlet rows; false drops them.
  bool gluingAtDirichletNodes = true;
  // Joined: the inequality rows join the scaling groups of the rows whose dofs they share;
  // Separate: each is its own group (docs/qp_solvers.md, "Scaling groups of the inequality rows").
  enum class InequalityScaling { Joined, Separate };
  InequalityScaling inequalityScaling = InequalityScaling::Joined;
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

// A row whose multiplier is bounded, lowerBound <= lambda <= upperBound, with the right-hand
// side `gap` (c). The default bounds [0, +inf) make it a non-penetration row  sum coef * u <= gap
// (contact: lambda > 0 only where it holds with equality). A box [-g, g] makes it a tangential
// (friction) row: lambda is the friction force, the term g |B u - c| of the primal energy
// (Tresca), so B u = c (stick) where |lambda| < g, and B u - c has the sign of lambda (slip)
// where lambda is at a bound. One rule covers both: B u - c <= 0 where lambda = lowerBound,
// >= 0 where lambda = upperBound, = 0 in between.
struct InequalityRow {
  std::vector<ConstraintEntry> entries;
  double gap = 0.0;
  double lowerBound = 0.0;
  double upperBound = std::numeric_limits<double>::infinity();
  // Friction in 3D: 1 on the first of a contact node's two tangential rows, 2 on the second.
  // Their multipliers lie in the disc |(lambda_1, lambda_2)| <= upperBound (both rows with
  // lowerBound = -upperBound) instead of the box. The caller passes the second row right after
  // the first (from one rank); the tearing keeps it there in its canonical order (the pair is
  // ordered by its first row), puts both in one scaling group and so gives both to the group's
  // owner, next to each other in the multiplier map. 0: a row of its own.
  int disc = 0;
  // The caller's identity of the row across updates of the rows (FetiSolver::update): a row with
  // the key of a previous row continues it, so the previous solution's multiplier is the warm
  // start of the new one (contact: the slave node and which of its rows). -1: none; the warm
  // start then needs the same rows in the same order. A key two rows share matches neither;
  // keys below -1 or from 2^53 on are an error (buildTearing).
  long long key = -1;
  bool isNonPenetration() const {
    return lowerBound == 0.0 && upperBound == std::numeric_limits<double>::infinity();
  }
  // -1: lambda at the lower bound, +1: at the upper bound, 0: strictly between (the row holds
  // with equality). A bound of 0 is met exactly by the QP solvers (lambda~ + (0 - lambda~)); a
  // non-zero bound b only to rounding, so within 1e-10 |b|.
  int boundActive(double lambda) const {
    auto at = [](double l, double b) {
      return l == b || (std::isfinite(b) && std::abs(l - b) <= 1e-10 * std::abs(b));
    };
    if (lambda <= lowerBound || at(lambda, lowerBound)) return -1;
    if (lambda >= upperBound || at(lambda, upperBound)) return 1;
    return 0;
  }
};

// An equality row  sum coef * u = rhs  given by the caller: its multiplier is free. Entries on
// the same dof add up. Each row is passed once, by any rank (rows are gathered from all ranks;
// a row passed twice is a duplicate row, which leaves B rank deficient but consistent).
struct EqualityRow {
  std::vector<ConstraintEntry> entries;
  double rhs = 0.0;
};

// Rows of a scaling group with a dense pseudo-inverse at most; larger groups are factorized
// sparsely (see above).
constexpr int kMaxDenseScalingGroup = 64;

// Locally owned scaling groups: local row indices (ascending) and the pseudo-inverse of their
// B B^T block: dense (column-major) for groups of at most kMaxDenseScalingGroup rows, otherwise
// dense[g] is empty and sparse[g] is set.
struct ScalingGroups {
  std::vector<std::vector<LO>> rows;
  std::vector<std::vector<double>> dense;
  std::vector<std::shared_ptr<const SparsePseudoInverse>> sparse;
  // x = Q x on the locally owned rows of x (the local values of a vector on multiplierMap).
  void apply(double* x) const;
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
  // The preconditioner's scaling Q, by locally owned group.
  ScalingGroups scaling;
  // Over all ranks: the number of scaling groups, the rows of the largest and the number of
  // groups factorized sparsely.
  GO numScalingGroups = 0, largestScalingGroup = 0, numSparseScalingGroups = 0;
  GO numRows = 0, numGluingRows = 0, numDirichletRows = 0;
  // The caller's equality rows: global rows [firstUserEqualityRow, firstInequalityRow).
  GO numUserEqualityRows = 0, firstUserEqualityRow = 0;
  // Inequality rows come last: global rows [firstInequalityRow, numRows).
  GO numInequalityRows = 0, firstInequalityRow = 0;
  // Every caller's equality row and every inequality row (all ranks), in the canonical order of
  // their multipliers.
  std::vector<EqualityRow> userEqualityRows;
  std::vector<InequalityRow> inequalityRows;
  // Right-hand side c of B u = c (equality) and B u <= c (inequality), on multiplierMap.
  Teuchos::RCP<Vector> rhs;
  bool isInequality(GO row) const { return row >= firstInequalityRow; }
  bool isUserEquality(GO row) const {
    return row >= firstUserEqualityRow && row < firstInequalityRow;
  }
};

// m_s of every local subdomain: the distinct rows of B that touch it (t.subdomainRows).
std::vector<long long> subdomainRowCounts(const Tearing& t);
// The distinct dofs of local subdomain i that rows of B touch, in increasing order (the
// preconditioner's interface; the dofs of the explicit F_s's Schur complement).
std::vector<int> subdomainDualDofs(const Tearing& t, std::size_t i);

// inequalities, equalities: the caller's rows this rank contributes (any rank may contribute any
// row; they are gathered and numbered in a canonical order independent of the rank count).
// Throws std::invalid_argument, on every rank alike, for a row that refers to a dof that does
// not exist, has no entries or only zero coefficients, or a value that is not finite.
Tearing buildTearing(const Teuchos::RCP<const Comm>& comm, int numSubdomains,
                     const std::vector<TearingInput>& local, int dofsPerNode,
                     const TearingOptions& options,
                     const std::vector<InequalityRow>& inequalities = {},
                     const std::vector<EqualityRow>& equalities = {});

// The caller's rows of an existing tearing with new values (a Newton iteration whose contact rows
// kept their entries: a height-function obstacle in small strain, or tied rows): the rows are
// gathered, checked and ordered as buildTearing does. Where every equality and inequality row has
// the entries (and disc pairing) of t's row in its place, t takes their right-hand sides, bounds
// and keys, keeps B, its maps and the scaling groups, and this returns true; otherwise t is left
// as it was and it returns false (the caller builds the tearing anew). Collective: every rank
// returns the same.
bool updateTearingValues(const Teuchos::RCP<const Comm>& comm, Tearing& t,
                         const std::vector<InequalityRow>& inequalities,
                         const std::vector<EqualityRow>& equalities = {});

}  // namespace tfeti
