#pragma once
// One subdomain of the torn problem: its stiffness matrix K and load f, the kernel R of K
// (rigid body modes of its pieces, or supplied; orthonormal columns), and a generalized inverse
// K+ with K K+ K = K.
//
// K+ comes from fixing-dof regularization, which keeps the sparsity of K: a set F of
// kernelDim() dofs is chosen so that R(F, :) is well conditioned; K_reg is K with the rows and
// columns of F replaced by their diagonal, and K+ = [K_rr^{-1} 0; 0 0]. Because no kernel vector
// vanishes on F, K_rr has the rank of K and K+ is a generalized inverse.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tfeti_CsrMatrix.hpp"
#include "tfeti_LocalSolver.hpp"
#include "tfeti_SubdomainMesh.hpp"

namespace tfeti {

// TFETI: Dirichlet conditions are multiplier rows, every subdomain floats.
// FETI: Dirichlet dofs are eliminated in K (their rows and columns become the identity scaled
// by the diagonal), so only subdomains without Dirichlet dofs float.
enum class Formulation { TFETI, FETI };

enum class PreconditionerType { None, Lumped, Dirichlet };

// Where the kernel of K comes from and how it is checked (see tfeti_Kernel.hpp).
struct KernelOptions {
  int dim = 2;  // coordinates per node
  // The subdomain's elements: rigid pieces and where they touch. Empty: the connected
  // components of the graph of K (pieces touching at a node are then an error, not detected).
  ElementConnectivity elements;
  // A kernel supplied by the caller (column-major numDofs x k, any basis): used instead of the
  // rigid modes, and checked like them.
  std::vector<double> kernel;
  // ||K R||_F / ||K||_F above this is an error naming the subdomain. <= 0: not checked.
  double residualTolerance = 1e-8;
};

// When the constructor factorizes: at once, or later by factorize(), so that the memory of all
// the factors can be told (predictFactorMemory) and checked before any is made.
enum class Factorization { Now, Deferred };

// What K+ of this K will allocate (Subdomain::predictFactorMemory, without a Subdomain: the dry
// run's forecast): the factor `solver` will make of K (its analysis, kept for it), and the
// factorization's transient, with the copy of K whose fixing dofs are decoupled where there are
// any (decoupledCopy).
MemoryPrediction predictPseudoInverseMemory(const CsrMatrix& K, bool decoupledCopy,
                                            LocalSolver& solver);
// What pseudoInverseBlock on `dofs` will allocate at its peak, its block included
// (Subdomain::predictInverseBlockMemory without a Subdomain): the local solver's inverse block on
// the dofs that are not fixing dofs, made on the copy of K with the fixing dofs decoupled where
// there are any. Negative where the solver has no inverse block.
std::ptrdiff_t predictPseudoInverseBlockMemory(const CsrMatrix& K, const std::vector<int>& dofs,
                                               const std::vector<int>& fixing, LocalSolver& solver);
// The dofs 0..n-1 not among interfaceDofs, in increasing order (a preconditioner's interior).
std::vector<int> interiorDofs(int n, const std::vector<int>& interfaceDofs);
// What a Dirichlet preconditioner on these interface dofs of K will allocate
// (Subdomain::predictPreconditionerMemory without a Subdomain): K_bb, K_bi and the interior
// factor `solver` will make (its analysis, kept for it); the copy of K_ii and the
// factorization's transient.
MemoryPrediction predictDirichletMemory(const CsrMatrix& K, const std::vector<int>& interfaceDofs,
                                        LocalSolver& solver);

class Subdomain {
 public:
  // coords: kernel.dim per node; dofs are interleaved (dof = dofsPerNode * node + component).
  // Throws (naming the subdomain) on inconsistent sizes, a kernel that K does not annihilate,
  // and a K whose kernel is larger than the one found.
  Subdomain(int id, int dofsPerNode, const std::vector<double>& coords, const KernelOptions& kernel,
            CsrMatrix K, std::vector<double> f, const std::vector<int>& dirichletDofs,
            Formulation formulation, const std::string& localSolver,
            Factorization when = Factorization::Now);
  // 2D, kernel from the graph of K (the release-1 interface).
  Subdomain(int id, int dofsPerNode, const std::vector<double>& coords, CsrMatrix K,
            std::vector<double> f, const std::vector<int>& dirichletDofs, Formulation formulation,
            const std::string& localSolver);

  // Factorization::Deferred: the bytes factorize() will allocate for K+ (held: LocalSolver::
  // predictFactorMemory; transient: the local solver's, and the copy of K with the fixing dofs
  // decoupled that it factorizes; negative where the local solver cannot tell; 0 and 0 once
  // factorized), and the factorization itself, which throws as the constructor would. Solves
  // need it done.
  MemoryPrediction predictFactorMemory();
  void factorize();
  bool factorized() const { return factorVersion_ != 0; }

  int id() const { return id_; }
  int numDofs() const { return numDofs_; }
  int dofsPerNode() const { return dofsPerNode_; }
  // K as given (FETI: with the Dirichlet dofs decoupled); empty (0 x 0) after releaseStiffness().
  const CsrMatrix& stiffness() const { return K_; }
  // Frees K once the preconditioner is set up, for a solve that needs it no more: K+, the kernel
  // and the preconditioner stay (in 2D K takes about 200 bytes per unknown, 40 % of what the
  // factors take). setupPreconditioner() is then an error.
  void releaseStiffness();
  bool hasStiffness() const { return !K_.rowPtr.empty(); }
  const std::vector<double>& load() const { return f_; }
  // A new load (FETI: zero on the eliminated Dirichlet dofs, as in the constructor).
  void setLoad(std::vector<double> f);
  int kernelDim() const { return kernelDim_; }
  // Column-major numDofs() x kernelDim(), orthonormal columns.
  const std::vector<double>& kernel() const { return R_; }
  const std::vector<int>& fixingDofs() const { return fixing_; }
  // ||K R||_F / ||K||_F of the kernel used.
  double kernelResidual() const { return kernelResidual_; }
  // Estimate of the smallest eigenvalue of the regularized K (K with the fixing dofs decoupled)
  // relative to the largest diagonal entry of K: near machine precision when K has a kernel
  // vector that R misses.
  double regularizedConditionEstimate() const { return lambdaMinRelative_; }

  // New values of K on the same pattern of dofs, kernel and Dirichlet dofs (a new material
  // tangent): ||K R|| is checked as in the constructor and K+ is refactorized in place, which
  // renews factorVersion(). The preconditioner is not rebuilt (call setupPreconditioner()).
  // A K equal to the one factorized (CsrMatrix::digest: the elastic part of a plastic body,
  // whose tangent stays the elastic one) keeps its factor and version: returns false then.
  bool refactorize(CsrMatrix K, double kernelTolerance = 1e-8);

  // x = K+ b for nrhs columns (leading dimension numDofs()).
  void applyPseudoInverse(const double* b, double* x, int nrhs = 1);

  // The block of K+ on the given distinct dofs (k x k, column-major, in their order) into
  // block: zero in the fixing dofs' rows and columns (K+ is zero there), elsewhere the inverse of
  // the Schur complement of K_reg onto those dofs (LocalSolver::inverseBlock: one factorization
  // of K_reg with them ordered last, not kept). Returns false where K was released or the local
  // solver cannot: applyPseudoInverse() on the unit columns gives the same block then.
  bool pseudoInverseBlock(const std::vector<int>& dofs, std::vector<double>& block);
  // The bytes pseudoInverseBlock(dofs, block) will allocate at its peak, block included, the rest
  // freed before it returns (predictPseudoInverseBlockMemory); negative where it would return
  // false.
  std::ptrdiff_t predictInverseBlockMemory(const std::vector<int>& dofs);

  // The bytes setupPreconditioner(interfaceDofs, type, localSolver) will allocate for the
  // Dirichlet preconditioner: held, its blocks K_bb and K_bi and the interior factor (from its
  // symbolic analysis, kept for it like predictFactorMemory's); transient, the interior block
  // K_ii copied for its factorization and the local solver's transient. 0 and 0 for the other
  // types and without K; negative where the local solver cannot tell.
  MemoryPrediction predictPreconditionerMemory(const std::vector<int>& interfaceDofs,
                                               PreconditionerType type,
                                               const std::string& localSolver);
  // The dofs the multipliers act on, in the order the preconditioner block uses them.
  void setupPreconditioner(const std::vector<int>& interfaceDofs, PreconditionerType type,
                           const std::string& localSolver);
  const std::vector<int>& interfaceDofs() const { return interface_; }
  // Throws std::logic_error after releaseStiffness() (type None excepted).
  // y_b = S v_b (Dirichlet: Schur complement on the interface) or K_bb v_b (lumped), for nrhs
  // columns (leading dimension interfaceDofs().size()): one interior solve with nrhs right-hand
  // sides.
  void applyPreconditionerBlock(const double* vb, double* yb, int nrhs = 1);

  std::size_t factorBytes() const;
  // What applyPseudoInverse of nrhs columns would leave with K+'s factor
  // (LocalSolver::solveKeeps: Tacho's workspace; 0 for the other solvers).
  std::size_t pseudoInverseSolveKeeps(int nrhs) const;
  // What K+'s factor holds (LocalSolver::factorMemory: what predictFactorMemory told).
  std::size_t factorMemory() const;
  std::size_t preconditionerFactorBytes() const;
  // What the Dirichlet preconditioner's interior factor holds (LocalSolver::factorMemory).
  std::size_t preconditionerFactorMemory() const;
  // What the Dirichlet preconditioner holds, as predictPreconditionerMemory counts it: its
  // blocks K_bb and K_bi and the interior factor (0 for the other types).
  std::size_t preconditionerMemory() const;
  // Identifies the factorization behind K+: unique over every subdomain of the process and
  // renewed by every (re)factorization, so that what is derived from K+ (the explicit local dual
  // operator B_s K_s+ B_s^T, tfeti_ExplicitDualOperator.hpp) can tell that it is stale.
  unsigned long long factorVersion() const { return factorVersion_; }

 private:
  void computeKernel(const std::vector<double>& coords, const KernelOptions& options,
                     const std::vector<std::vector<int>>& pieces,
                     const std::vector<int>& dirichletDofs);
  void chooseFixingDofs();
  void checkKernelResidual(double tolerance);
  void checkNoExtraKernel();
  std::string name() const;

  int id_;
  int dofsPerNode_;
  int numDofs_ = 0;
  Formulation formulation_;
  CsrMatrix K_;
  std::vector<double> f_;
  std::vector<int> dirichlet_;
  int kernelDim_ = 0;
  std::vector<double> R_;
  std::vector<int> fixing_;
  double kernelResidual_ = 0.0, lambdaMinRelative_ = 0.0;
  std::unique_ptr<LocalSolver> factor_;
  unsigned long long factorVersion_ = 0;
  std::array<std::uint64_t, 2> factoredDigest_{};  // of K_ when factorized

  PreconditionerType precType_ = PreconditionerType::None;
  std::vector<int> interface_, interior_;
  // K_ib = K_bi^T is applied as the transpose of K_bi, not stored.
  CsrMatrix Kbb_, Kbi_;
  std::unique_ptr<LocalSolver> interiorFactor_;
  // predictPreconditionerMemory's solver, its analysis made, for those interior dofs.
  std::unique_ptr<LocalSolver> pendingInterior_;
  std::vector<int> pendingInteriorDofs_;
};

}  // namespace tfeti
