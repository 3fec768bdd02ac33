#pragma once
// (T)FETI for a linear problem with equality constraints only: from subdomain matrices to the
// primal solution.
//   setup:  factorize K_s (K+), tear (B), coarse space (G, G G^T), preconditioner,
//           d = B K+ f,  e = R^T f,  lambda0 = G^T (G G^T)^{-1} e
//   solve:  PCPG on the dual problem
//   recover: alpha = (G G^T)^{-1} G (F lambda - d),  u = K+ (f - B^T lambda) + R alpha
#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <vector>

#include "tfeti_CoarseSpace.hpp"
#include "tfeti_DualOperators.hpp"
#include "tfeti_Pcpg.hpp"
#include "tfeti_SubdomainMesh.hpp"

namespace tfeti {

// What the physics layer hands over for one subdomain.
struct SubdomainData {
  SubdomainMesh mesh;
  int dofsPerNode = 1;
  CsrMatrix K;
  std::vector<double> f;
};

struct FetiTimings {
  double factorization = 0;   // subdomain K+ (and kernels)
  double tearing = 0;         // B and the maps
  double coarse = 0;          // G, G G^T and its factorization
  double preconditioner = 0;  // interior factorizations (Dirichlet) or K_bb blocks (lumped)
  double dualRhs = 0;         // d, e, lambda0
  double solve = 0;           // PCPG
  double recovery = 0;        // primal solution
  double setup() const { return factorization + tearing + coarse + preconditioner + dualRhs; }
};

class FetiSolver {
 public:
  // "Formulation" (TFETI | FETI), "Gluing" (nonredundant | redundant), "Gluing at Dirichlet
  // nodes" (true), "Preconditioner" (none | lumped | dirichlet), "Local solver" (cholmod |
  // klu2 | tacho), and the sublist "PCPG" (see Pcpg::validParameters).
  static Teuchos::RCP<const Teuchos::ParameterList> validParameters();

  // local: the subdomains assigned to this rank (see subdomainsOfRank), in increasing id order.
  FetiSolver(const Teuchos::RCP<const Comm>& comm, int numSubdomains,
             std::vector<SubdomainData> local, const Teuchos::ParameterList& params);

  PcpgResult solve();

  // Mean wall time of one application of F over `repeats` applications (slowest rank).
  double timeDualApply(int repeats) const;

  // Primal solution of the i-th local subdomain (after solve()).
  const std::vector<double>& solution(std::size_t i) const { return u_[i]; }
  const SubdomainList& subdomains() const { return subdomains_; }
  const std::vector<SubdomainData>& data() const { return data_; }

  GO primalDimension() const { return tearing_.dofOffset.back(); }
  GO dualDimension() const { return tearing_.numRows; }
  GO gluingRows() const { return tearing_.numGluingRows; }
  GO dirichletRows() const { return tearing_.numDirichletRows; }
  GO coarseDimension() const { return coarse_->dimension(); }
  long long dualOperatorApplies() const { return F_->numApplies(); }
  const FetiTimings& timings() const { return timings_; }
  // Bytes of all subdomain factors on all ranks (K+ and, if any, the preconditioner's).
  std::size_t globalFactorBytes() const;
  std::size_t globalPreconditionerFactorBytes() const;
  const Tearing& tearing() const { return tearing_; }
  const Teuchos::RCP<DualOperator>& dualOperator() const { return F_; }
  const CoarseSpace& coarseSpace() const { return *coarse_; }
  const Teuchos::RCP<const Comm>& comm() const { return comm_; }

 private:
  Teuchos::RCP<const Comm> comm_;
  Teuchos::ParameterList params_;
  std::vector<SubdomainData> data_;
  SubdomainList subdomains_;
  Tearing tearing_;
  std::unique_ptr<CoarseSpace> coarse_;
  Teuchos::RCP<PseudoInverseOperator> Kplus_;
  Teuchos::RCP<DualOperator> F_;
  Teuchos::RCP<DualPreconditioner> M_;
  Teuchos::RCP<Vector> d_, lambda0_;
  Teuchos::RCP<MultiVector> f_;
  std::vector<std::vector<double>> u_;
  FetiTimings timings_;
};

Formulation parseFormulation(const std::string& name);
PreconditionerType parsePreconditioner(const std::string& name);

}  // namespace tfeti
