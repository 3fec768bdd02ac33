#pragma once
// One subdomain of the torn problem: its stiffness matrix K and load f, the kernel R of K
// (rigid body modes, orthonormal columns), and a generalized inverse K+ with K K+ K = K.
//
// K+ comes from fixing-dof regularization, which keeps the sparsity of K: a set F of
// kernelDim() dofs is chosen so that R(F, :) is well conditioned; K_reg is K with the rows and
// columns of F replaced by their diagonal, and K+ = [K_rr^{-1} 0; 0 0]. Because no kernel vector
// vanishes on F, K_rr has the rank of K and K+ is a generalized inverse.
#include <memory>
#include <string>
#include <vector>

#include "tfeti_CsrMatrix.hpp"
#include "tfeti_LocalSolver.hpp"

namespace tfeti {

// TFETI: Dirichlet conditions are multiplier rows, every subdomain floats.
// FETI: Dirichlet dofs are eliminated in K (their rows and columns become the identity scaled
// by the diagonal), so only subdomains without Dirichlet dofs float.
enum class Formulation { TFETI, FETI };

enum class PreconditionerType { None, Lumped, Dirichlet };

class Subdomain {
 public:
  // coords: 2 per node; dofs are interleaved (dof = dofsPerNode * node + component).
  Subdomain(int id, int dofsPerNode, const std::vector<double>& coords, CsrMatrix K,
            std::vector<double> f, const std::vector<int>& dirichletDofs, Formulation formulation,
            const std::string& localSolver);

  int id() const { return id_; }
  int numDofs() const { return K_.rows; }
  int dofsPerNode() const { return dofsPerNode_; }
  const CsrMatrix& stiffness() const { return K_; }
  const std::vector<double>& load() const { return f_; }
  // A new load (FETI: zero on the eliminated Dirichlet dofs, as in the constructor).
  void setLoad(std::vector<double> f);
  int kernelDim() const { return kernelDim_; }
  // Column-major numDofs() x kernelDim(), orthonormal columns.
  const std::vector<double>& kernel() const { return R_; }
  const std::vector<int>& fixingDofs() const { return fixing_; }

  // x = K+ b for nrhs columns (leading dimension numDofs()).
  void applyPseudoInverse(const double* b, double* x, int nrhs = 1);

  // The dofs the multipliers act on, in the order the preconditioner block uses them.
  void setupPreconditioner(const std::vector<int>& interfaceDofs, PreconditionerType type,
                           const std::string& localSolver);
  const std::vector<int>& interfaceDofs() const { return interface_; }
  // y_b = S v_b (Dirichlet: Schur complement on the interface) or K_bb v_b (lumped).
  void applyPreconditionerBlock(const double* vb, double* yb);

  std::size_t factorBytes() const;
  std::size_t preconditionerFactorBytes() const;

 private:
  void computeKernel(const std::vector<double>& coords, const std::vector<int>& dirichletDofs);
  void chooseFixingDofs();

  int id_;
  int dofsPerNode_;
  Formulation formulation_;
  CsrMatrix K_;
  std::vector<double> f_;
  std::vector<int> dirichlet_;
  int kernelDim_ = 0;
  std::vector<double> R_;
  std::vector<int> fixing_;
  std::unique_ptr<LocalSolver> factor_;
  std::vector<double> work_;

  PreconditionerType precType_ = PreconditionerType::None;
  std::vector<int> interface_, interior_;
  CsrMatrix Kbb_, Kbi_, Kib_;
  std::unique_ptr<LocalSolver> interiorFactor_;
  std::vector<double> wi_, zi_;
};

}  // namespace tfeti
