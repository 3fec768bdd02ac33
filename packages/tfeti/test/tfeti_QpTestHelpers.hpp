#pragma once
// Helpers shared by the unit tests of the bound-constrained QP solvers (MPRGP, SMALBE): maps and
// vectors by global index, 1D diffusion matrices, an orthogonal projector onto a span, the KKT
// assertions and the solver parameters the tests use.
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Import.hpp>

#include <algorithm>
#include <functional>
#include <limits>
#include <vector>

#include "tfeti_MprgpSolMgr_decl.hpp"
#include "tfeti_QpChecks.hpp"
#include "tfeti_QpProblem.hpp"
#include "tfeti_SmalbeSolMgr_decl.hpp"
#include "tfeti_TestHelpers.hpp"
#include "tfeti_Types.hpp"

namespace qp_test {

using Teuchos::RCP;
using Teuchos::rcp;
using tfeti::CrsMatrix;
using tfeti::GO;
using tfeti::LO;
using tfeti::Map;
using tfeti::MultiVector;
using tfeti::Operator;
using tfeti::Vector;
using Qp = tfeti::BoundConstrainedQp<double, MultiVector, Operator>;
using Mprgp = tfeti::MprgpSolMgr<double, MultiVector, Operator>;
using Smalbe = tfeti::SmalbeSolMgr<double, MultiVector, Operator>;

using Kkt = tfeti::QpKkt;

const double kInf = std::numeric_limits<double>::infinity();

inline RCP<const tfeti::Comm> world() {
  return Tpetra::getDefaultComm();
}

inline RCP<const Map> uniformMap(GO n, const RCP<const tfeti::Comm>& comm) {
  return rcp(new Map(static_cast<Tpetra::global_size_t>(n), 0, comm));
}

// A vector with entries f(global index).
inline RCP<Vector> vectorOf(const RCP<const Map>& map, const std::function<double(GO)>& f) {
  auto v = rcp(new Vector(map));
  auto d = v->getDataNonConst();
  for (LO i = 0; i < static_cast<LO>(map->getNodeNumElements()); ++i)
    d[i] = f(map->getGlobalElement(i));
  return v;
}

// All entries of v on every rank, in global index order.
inline std::vector<double> gatherAll(const Vector& v) {
  const auto map = v.getMap();
  auto all = Tpetra::createLocalMapWithNode<LO, GO, tfeti::Node>(map->getGlobalNumElements(),
                                                                 map->getComm());
  Tpetra::Import<LO, GO, tfeti::Node> import(map, all);
  Vector r(all);
  r.doImport(v, import, Tpetra::INSERT);
  auto d = r.getData();
  return std::vector<double>(d.begin(), d.end());
}

// 1D diffusion, Dirichlet ends: rows c_{i-1/2} + c_{i+1/2} on the diagonal, -c off it, with
// c_{i+1/2} = coef(i) for the edge between unknowns i and i + 1 (coef(-1), coef(n-1): the ends).
inline RCP<CrsMatrix> diffusion1D(const RCP<const Map>& map,
                                  const std::function<double(GO)>& coef) {
  const GO n = static_cast<GO>(map->getGlobalNumElements());
  auto A = rcp(new CrsMatrix(map, 3));
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l) {
    const GO i = map->getGlobalElement(l);
    std::vector<GO> cols{i};
    std::vector<double> vals{coef(i - 1) + coef(i)};
    if (i > 0) cols.push_back(i - 1), vals.push_back(-coef(i - 1));
    if (i + 1 < n) cols.push_back(i + 1), vals.push_back(-coef(i));
    A->insertGlobalValues(i, Teuchos::arrayViewFromVector(cols),
                          Teuchos::arrayViewFromVector(vals));
  }
  A->fillComplete();
  return A;
}

inline RCP<CrsMatrix> laplacian1D(const RCP<const Map>& map) {
  return diffusion1D(map, [](GO) { return 1.0; });
}

// Orthogonal projector onto the span of the columns of V (orthonormalized here by modified
// Gram-Schmidt, twice for accuracy): Q x = U (U^T x).
class SpanProjector : public Operator {
 public:
  explicit SpanProjector(const MultiVector& V) : U_(rcp(new MultiVector(V, Teuchos::Copy))) {
    for (int pass = 0; pass < 2; ++pass)
      for (std::size_t k = 0; k < U_->getNumVectors(); ++k) {
        auto uk = U_->getVectorNonConst(k);
        for (std::size_t j = 0; j < k; ++j) {
          auto uj = U_->getVector(j);
          uk->update(-uj->dot(*uk), *uj, 1.0);
        }
        uk->scale(1.0 / uk->norm2());
      }
  }
  RCP<const Map> getDomainMap() const override { return U_->getMap(); }
  RCP<const Map> getRangeMap() const override { return U_->getMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp = Teuchos::NO_TRANS,
             double alpha = 1.0, double beta = 0.0) const override {
    for (std::size_t c = 0; c < X.getNumVectors(); ++c) {
      auto x = X.getVector(c);
      auto y = Y.getVectorNonConst(c);
      std::vector<double> coef(U_->getNumVectors());
      for (std::size_t k = 0; k < coef.size(); ++k) coef[k] = U_->getVector(k)->dot(*x);
      if (beta == 0.0)
        y->putScalar(0.0);
      else
        y->scale(beta);
      for (std::size_t k = 0; k < coef.size(); ++k)
        y->update(alpha * coef[k], *U_->getVector(k), 1.0);
    }
  }
  const MultiVector& basis() const { return *U_; }

 private:
  RCP<MultiVector> U_;
};

// Jacobi: x ./ diag(A), for preconditioning in face.
class DiagonalInverse : public Operator {
 public:
  explicit DiagonalInverse(const CrsMatrix& A) : d_(rcp(new Vector(A.getRowMap()))) {
    A.getLocalDiagCopy(*d_);
    d_->reciprocal(*d_);
  }
  RCP<const Map> getDomainMap() const override { return d_->getMap(); }
  RCP<const Map> getRangeMap() const override { return d_->getMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp = Teuchos::NO_TRANS,
             double alpha = 1.0, double beta = 0.0) const override {
    Y.elementWiseMultiply(alpha, *d_, X, beta);
  }

 private:
  RCP<Vector> d_;
};

inline double maxAbsDiff(const Vector& a, const Vector& b) {
  Vector d(a, Teuchos::Copy);
  d.update(-1.0, b, 1.0);
  return d.normInf();
}

inline Teuchos::ParameterList mprgpParams(double tol, int maxIter = 10000) {
  Teuchos::ParameterList p;
  p.set("Relative tolerance", tol);
  p.set("Maximum iterations", maxIter);
  return p;
}

inline Teuchos::ParameterList smalbeParams(double tol) {
  Teuchos::ParameterList p;
  p.set("Relative tolerance", tol);
  p.set("Equality tolerance", tol);
  return p;
}

// Asserts the KKT conditions (tfeti::qpKkt): l <= x <= u exactly, |g_i| <= gTol on free
// components, the active side's multiplier >= -gTol, complementarity <= gTol * max(1, the largest
// distance to a finite bound).
inline void expectKkt(const Kkt& k, double gTol, Teuchos::FancyOStream& out, bool& success) {
  TEST_COMPARE(k.infeasibility, <=, 0.0);
  TEST_COMPARE(k.freeGradient, <=, gTol);
  TEST_COMPARE(k.negativeMultiplier, <=, gTol);
  TEST_COMPARE(k.complementarity, <=, gTol * std::max(1.0, k.gapRange));
}

// The rank count does not change the results: a solve on sub-communicators of 1, 2, ..., P
// ranks gives the same steps and the same x to rounding.
struct RankRun {
  std::vector<double> x;
  long long steps[3] = {0, 0, 0};  // CG, expansion, proportioning (summed over SMALBE's inner)
  long long outer = 0;
  long long face[2] = {0, 0};  // face solves, their CG steps
};

// fn on the sub-communicator of the first `size` ranks, for size = 1 .. P; rank 0's results
// broadcast to all.
inline std::vector<RankRun> onEveryRankCount(
    const std::function<RankRun(RCP<const tfeti::Comm>)>& fn) {
  const auto comm = world();
  std::vector<RankRun> runs;
  for (int size = 1; size <= comm->getSize(); ++size) {
    const int rank = comm->getRank();
    auto sub = comm->split(rank < size ? 0 : 1, rank);
    RankRun r;
    if (rank < size) r = fn(sub);
    std::size_t n = r.x.size();
    Teuchos::broadcast(*comm, 0, &n);
    r.x.resize(n);
    Teuchos::broadcast(*comm, 0, static_cast<int>(n), r.x.data());
    Teuchos::broadcast(*comm, 0, 3, r.steps);
    Teuchos::broadcast(*comm, 0, &r.outer);
    Teuchos::broadcast(*comm, 0, 2, r.face);
    runs.push_back(r);
  }
  return runs;
}

inline void expectSameRuns(const std::vector<RankRun>& runs, Teuchos::FancyOStream& out,
                           bool& success) {
  for (std::size_t s = 0; s < runs.size(); ++s)
    out << s + 1 << " ranks: " << runs[s].steps[0] << " CG, " << runs[s].steps[1] << " expansion, "
        << runs[s].steps[2] << " proportioning, " << runs[s].outer << " outer\n";
  for (std::size_t s = 1; s < runs.size(); ++s) {
    for (int k = 0; k < 3; ++k) TEST_EQUALITY(runs[s].steps[k], runs[0].steps[k]);
    TEST_EQUALITY(runs[s].outer, runs[0].outer);
    for (int k = 0; k < 2; ++k) TEST_EQUALITY(runs[s].face[k], runs[0].face[k]);
    double d = 0.0;
    for (std::size_t i = 0; i < runs[0].x.size(); ++i)
      d = std::max(d, std::abs(runs[s].x[i] - runs[0].x[i]));
    TEST_COMPARE(d, <=, 1e-12 * tfeti_test::maxAbs(runs[0].x));
  }
}

inline RankRun rankRun(const tfeti::QpCounters& c, const Vector& x) {
  RankRun r;
  r.x = gatherAll(x);
  r.steps[0] = c.cgSteps;
  r.steps[1] = c.expansionSteps;
  r.steps[2] = c.proportioningSteps;
  r.outer = c.outerIterations;
  return r;
}

}  // namespace qp_test
