// Guide program 3 (docs/cpp_guide.md): MPRGP alone on a bound-constrained QP of one's own.
//
// A string on (0, 1), fixed at both ends, pushed down by a unit load onto an obstacle below it:
//   min 1/2 x^T A x - b^T x  subject to  x >= l,
// A the finite-difference Laplacian of n interior nodes (a Tpetra::CrsMatrix distributed over
// the ranks, used as a Tpetra::Operator), b the load, l the obstacle's height at the nodes. The
// string lies on the obstacle in the middle and is free near the ends. tfeti::MprgpSolMgr solves
// it the Belos way (setProblem, setParameters, solve); the program then checks the KKT
// conditions itself, from A x - b computed anew, and exits non-zero when they fail.
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "tfeti_MprgpSolMgr_decl.hpp"
#include "tfeti_Types.hpp"

using tfeti::GO;
using Qp = tfeti::BoundConstrainedQp<tfeti::Scalar, tfeti::MultiVector, tfeti::Operator>;
using Mprgp = tfeti::MprgpSolMgr<tfeti::Scalar, tfeti::MultiVector, tfeti::Operator>;

namespace {
constexpr GO kNodes = 199;  // interior nodes
constexpr double kH = 1.0 / (kNodes + 1);
double obstacle(double x) {
  return -0.08 + 0.04 * x;
}  // a tilted line under the string

// A = tridiag(-1, 2, -1) / h on `map`: each rank inserts the rows it owns.
Teuchos::RCP<tfeti::CrsMatrix> laplacian(const Teuchos::RCP<const tfeti::Map>& map) {
  auto A = Teuchos::rcp(new tfeti::CrsMatrix(map, 3));
  for (GO i : map->getNodeElementList()) {
    std::vector<GO> cols;
    std::vector<double> vals;
    for (GO j = std::max<GO>(i - 1, 0); j <= std::min<GO>(i + 1, kNodes - 1); ++j) {
      cols.push_back(j);
      vals.push_back((i == j ? 2.0 : -1.0) / kH);
    }
    A->insertGlobalValues(i, Teuchos::arrayViewFromVector(cols),
                          Teuchos::arrayViewFromVector(vals));
  }
  A->fillComplete();
  return A;
}
}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  const bool root = comm->getRank() == 0;

  auto map = Teuchos::rcp(new tfeti::Map(kNodes, 0, comm));
  Teuchos::RCP<const tfeti::Operator> A = laplacian(map);
  auto b = Teuchos::rcp(new tfeti::Vector(map));
  auto lower = Teuchos::rcp(new tfeti::Vector(map));
  auto x = Teuchos::rcp(new tfeti::Vector(map));  // initial guess 0: above the obstacle
  b->putScalar(-kH);                              // the unit downward load, times h
  {
    auto l = lower->getDataNonConst(0);
    for (std::size_t k = 0; k < l.size(); ++k)
      l[k] = obstacle(static_cast<double>(map->getGlobalElement(k) + 1) * kH);
  }

  Mprgp mprgp;
  mprgp.setProblem(Qp{A, b, lower, x});
  Teuchos::ParameterList params;
  params.set("Convergence Tolerance", 1e-10);  // Belos's name, an alias of "Relative tolerance"
  params.set("Maximum Iterations", 2000);
  params.set("Expansion step", "projected CG");
  mprgp.setParameters(params);
  const Belos::ReturnType ret = mprgp.solve();

  // KKT, from g = A x - b computed here: x >= l; g = 0 where x > l (free); g >= 0 where x = l
  // (the obstacle pushes up); measured by the projected gradient g^P relative to ||b||.
  tfeti::Vector g(map);
  A->apply(*x, g);
  g.update(-1.0, *b, 1.0);
  auto xv = x->getData(0), lv = lower->getData(0), gv = g.getData(0);
  double local[3] = {0.0, 0.0, 0.0};  // sum (g^P)^2, max violation of x >= l, active count
  for (std::size_t k = 0; k < xv.size(); ++k) {
    const bool active = xv[k] <= lv[k];
    const double gp = active ? std::min(gv[k], 0.0) : gv[k];
    local[0] += gp * gp;
    local[1] = std::max(local[1], lv[k] - xv[k]);
    local[2] += active ? 1.0 : 0.0;
  }
  double global[3];
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &local[0], &global[0]);
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &local[1], &global[1]);
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &local[2], &global[2]);
  const double kkt = std::sqrt(global[0]) / b->norm2();
  const int active = static_cast<int>(global[2]);

  const tfeti::QpCounters& c = mprgp.counters();
  if (root)
    std::cout << "mprgp_obstacle: " << (ret == Belos::Converged ? "converged" : "NOT converged")
              << " in " << mprgp.getNumIters() << " steps (" << c.cgSteps << " CG, "
              << c.expansionSteps << " expansion, " << c.proportioningSteps << " proportioning; "
              << c.hessianMultiplications << " multiplications by A), achievedTol "
              << mprgp.achievedTol() << "; " << active << " of " << kNodes
              << " nodes on the obstacle, ||g^P||/||b|| = " << kkt << ", max(l - x) = " << global[1]
              << "\n";
  // The string must touch the obstacle without lying on it everywhere, and meet KKT.
  const bool ok =
      ret == Belos::Converged && kkt < 1e-9 && global[1] <= 0.0 && active > 0 && active < kNodes;
  if (!ok && root) std::cerr << "mprgp_obstacle: WRONG ANSWER\n";
  return ok ? 0 : 1;
}
