// The coarse problem of (T)FETI on 1, 2 and 3 ranks, on a 3D elastic box of 3x3x3 subdomains
// (nodes shared by up to 8 subdomains): G G^T assembled from its subdomain-pair blocks must equal
// Tpetra's sparse product G * G^T entry by entry, and the projector P = I - G^T (G G^T)^{-1} G
// built on its factor must satisfy G P x = 0 and P P x = P x to rounding.
#include <Teuchos_UnitTestHarness.hpp>
#include <TpetraExt_MatrixMatrix.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tfeti_CoarseGramian.hpp"
#include "tfeti_FetiSolver.hpp"
#include "tfeti_Gather.hpp"
#include "tfeti_Test3d.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

tfeti::FetiSolver boxSolver(const std::string& formulation, int subdomainsPerSide,
                            int elementsPerSide) {
  auto comm = Tpetra::getDefaultComm();
  const int n = subdomainsPerSide, e = elementsPerSide;
  const tfeti_test::Box3d box(n, n, n, e, e, e, false);
  tfeti_test::Material3d mat;
  mat.dofsPerNode = 3;
  std::vector<tfeti::SubdomainData> local =
      tfeti_test::localBoxSubdomains(box, mat, {0, 0, -1}, *comm);
  Teuchos::ParameterList params;
  params.set("Formulation", formulation);
  return tfeti::FetiSolver(comm, box.numSubdomains(), std::move(local), params);
}

// G * G^T by Tpetra's sparse matrix-matrix product, as dense rows on every rank.
std::vector<double> referenceGramian(const tfeti::CrsMatrix& G, int nc) {
  tfeti::CrsMatrix GGt(G.getRowMap(), 0);
  Tpetra::MatrixMatrix::Multiply(G, false, G, true, GGt);
  std::vector<long long> ij;
  std::vector<double> v;
  for (std::size_t l = 0; l < GGt.getNodeNumRows(); ++l) {
    Teuchos::ArrayView<const int> cols;
    Teuchos::ArrayView<const double> vals;
    GGt.getLocalRowView(static_cast<int>(l), cols, vals);
    for (int k = 0; k < cols.size(); ++k) {
      ij.push_back(GGt.getRowMap()->getGlobalElement(static_cast<int>(l)) * nc +
                   GGt.getColMap()->getGlobalElement(cols[k]));
      v.push_back(vals[k]);
    }
  }
  const auto& comm = *G.getRowMap()->getComm();
  const std::vector<long long> allIj = tfeti::allGather(comm, ij);
  const std::vector<double> allV = tfeti::allGather(comm, v);
  std::vector<double> dense(static_cast<std::size_t>(nc) * nc, 0.0);
  for (std::size_t k = 0; k < allV.size(); ++k) dense[allIj[k]] += allV[k];
  return dense;
}

void checkGramian(const std::string& formulation, int subdomainsPerSide, int elementsPerSide,
                  Teuchos::FancyOStream& out, bool& success) {
  const int s = subdomainsPerSide;
  const tfeti::FetiSolver solver = boxSolver(formulation, s, elementsPerSide);
  const tfeti::CoarseSpace& coarse = solver.coarseSpace();
  const int nc = static_cast<int>(coarse.dimension());
  // TFETI: every subdomain floats; FETI: the s^2 on x = 0 are clamped.
  TEST_EQUALITY(nc, 6 * (formulation == "TFETI" ? s * s * s : s * s * s - s * s));
  // Every floating subdomain has the 6 rigid body modes of 3D elasticity, consecutive: the
  // first ids of this rank's blocks are its coarse ids divisible by 6.
  std::vector<tfeti::GO> firstIds;
  for (tfeti::GO g : coarse.coarseMap()->getNodeElementList())
    if (g % 6 == 0) firstIds.push_back(g);
  const std::vector<tfeti::GO> offset =
      tfeti::coarseBlockOffsets(*coarse.coarseMap()->getComm(), firstIds, nc);
  std::vector<tfeti::GO> expected;
  for (int b = 0; b <= nc / 6; ++b) expected.push_back(6 * b);
  TEST_COMPARE_ARRAYS(offset, expected);

  const tfeti::CsrMatrix A = tfeti::assembleGramian(*coarse.G(), offset);
  TEST_EQUALITY(tfeti::csrError(A, "G G^T"), std::string());
  const std::vector<double> ref = referenceGramian(*coarse.G(), nc);
  const std::vector<double> dense = tfeti_test::toDense(A);
  double diff = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < ref.size(); ++k) {
    diff = std::max(diff, std::abs(dense[k] - ref[k]));
    scale = std::max(scale, std::abs(ref[k]));
  }
  out << formulation << ": G G^T of dimension " << nc << ", " << A.nnz()
      << " entries, max |blocks - Tpetra product| / max |G G^T| = " << diff / scale << "\n";
  TEST_COMPARE(scale, >, 0.0);
  TEST_COMPARE(diff, <=, 1e-14 * scale);

  // The projector built on the coarse factor: G P x = 0 and P P x = P x.
  tfeti::Vector v(solver.tearing().multiplierMap), Pv(v.getMap()), PPv(v.getMap());
  v.randomize();
  coarse.project(v, Pv);
  coarse.project(Pv, PPv);
  tfeti::Vector GPv(coarse.coarseMap()), Gv(coarse.coarseMap());
  coarse.G()->apply(Pv, GPv);
  coarse.G()->apply(v, Gv);
  PPv.update(-1.0, Pv, 1.0);
  out << "  ||G P v|| / ||G v|| = " << GPv.norm2() / Gv.norm2()
      << ", ||P P v - P v|| / ||P v|| = " << PPv.norm2() / Pv.norm2() << "\n";
  TEST_COMPARE(GPv.norm2(), <, 1e-12 * Gv.norm2());
  TEST_COMPARE(PPv.norm2(), <, 1e-12 * Pv.norm2());
}

}  // namespace

TEUCHOS_UNIT_TEST(CoarseGramian, TfetiBlocksEqualSparseProduct) {
  checkGramian("TFETI", 3, 2, out, success);
}

TEUCHOS_UNIT_TEST(CoarseGramian, FetiWithClampedSubdomains) {
  checkGramian("FETI", 3, 2, out, success);
}
