// The coarse problem of (T)FETI on 1, 2 and 3 ranks, on a 3D elastic box of 3x3x3 subdomains
// (nodes shared by up to 8 subdomains): G G^T assembled from its subdomain-pair blocks must equal
// Tpetra's sparse product G * G^T entry by entry, and the projector P = I - G^T (G G^T)^{-1} G
// built on its factor must satisfy G P x = 0 and P P x = P x to rounding; the columns of
// Q = I - P at chosen multipliers, computed from G's entries and block coarse solves (SMALBE's
// face solves), must equal Q applied to unit vectors; and a face projector built on Q's factors
// must equal the one that applies Q twice.
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <TpetraExt_MatrixMatrix.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_RowMatrixTransposer.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "tfeti_CoarseGramian.hpp"
#include "tfeti_FaceProjector.hpp"
#include "tfeti_FetiSolver.hpp"
#include "tfeti_Gather.hpp"
#include "tfeti_ProjectedOperators.hpp"
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

  // Least squares on rows (primal recovery): G diag(m) G^T from the kept transpose of G, with
  // every third multiplier left out, against Tpetra's product of the scaled copy of G.
  {
    tfeti::Vector mask(coarse.G()->getDomainMap());
    auto m = mask.getDataNonConst();
    for (std::size_t l = 0; l < static_cast<std::size_t>(m.size()); ++l)
      m[l] = mask.getMap()->getGlobalElement(static_cast<tfeti::LO>(l)) % 3 == 0 ? 0.0 : 1.0;
    m = Teuchos::null;
    tfeti::CrsMatrix GA(*coarse.G(), Teuchos::Copy);
    GA.rightScale(mask);
    const std::vector<double> maskedRef = referenceGramian(GA, nc);
    Tpetra::RowMatrixTransposer<double, tfeti::LO, tfeti::GO, tfeti::Node> transposer(coarse.G());
    const auto Gt = transposer.createTranspose();
    TEST_ASSERT(Gt->getRowMap()->isSameAs(*mask.getMap()));
    const tfeti::CsrMatrix masked =
        tfeti::assembleGramianFromTranspose(*Gt, offset, mask.getData().getRawPtr());
    const std::vector<double> maskedDense = tfeti_test::toDense(masked);
    double maskedDiff = 0.0, maskedScale = 0.0, unmaskedDiff = 0.0;
    for (std::size_t k = 0; k < maskedRef.size(); ++k) {
      const double d = std::abs(maskedDense[k] - maskedRef[k]);
      maskedDiff = d <= maskedDiff ? maskedDiff : d;  // a NaN sticks
      maskedScale = std::max(maskedScale, std::abs(maskedRef[k]));
      unmaskedDiff = std::max(unmaskedDiff, std::abs(maskedDense[k] - ref[k]));
    }
    out << "  masked G G^T: max |blocks - Tpetra product| / max = " << maskedDiff / maskedScale
        << "\n";
    TEST_COMPARE(maskedDiff, <=, 1e-14 * maskedScale);
    TEST_COMPARE(unmaskedDiff, >, 1e-3 * scale);  // the mask took rows out
  }

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

// Every multiplier id of the map, sorted, on every rank.
std::vector<long long> allMultiplierIds(const tfeti::Map& map) {
  std::vector<long long> mine;
  for (tfeti::GO g : map.getNodeElementList()) mine.push_back(g);
  std::vector<long long> all = tfeti::allGather(*map.getComm(), mine);
  std::sort(all.begin(), all.end());
  return all;
}

}  // namespace

TEUCHOS_UNIT_TEST(CoarseGramian, TfetiBlocksEqualSparseProduct) {
  checkGramian("TFETI", 3, 2, out, success);
}

TEUCHOS_UNIT_TEST(CoarseGramian, FetiWithClampedSubdomains) {
  checkGramian("FETI", 3, 2, out, success);
}

TEUCHOS_UNIT_TEST(CoarseGramian, ComplementColumnsEqualQOnUnitVectors) {
  const tfeti::FetiSolver solver = boxSolver("TFETI", 3, 2);
  const tfeti::CoarseSpace& coarse = solver.coarseSpace();
  const auto map = solver.tearing().multiplierMap;
  const auto& comm = *map->getComm();
  // Candidates C: every 5th multiplier id; columns J: every 3rd candidate, in reverse order.
  const std::vector<long long> all = allMultiplierIds(*map);
  std::vector<long long> C, J;
  for (std::size_t k = 0; k < all.size(); k += 5) C.push_back(all[k]);
  for (std::size_t k = 0; k < C.size(); k += 3) J.insert(J.begin(), C[k]);
  TEST_COMPARE(J.size(), >, std::size_t(50));

  tfeti::CoarseComplementColumns structured(coarse);
  structured.setCandidates(C);
  std::vector<double> columns;
  structured.columns(J, columns);
  TEST_EQUALITY(columns.size(), C.size() * J.size());

  const tfeti::ComplementProjector Q(map, coarse);
  tfeti::Vector e(map), qe(map);
  double diff = 0.0, scale = 0.0;
  for (std::size_t c = 0; c < J.size(); ++c) {
    e.putScalar(0.0);
    const tfeti::LO l = map->getLocalElement(static_cast<tfeti::GO>(J[c]));
    if (l != Teuchos::OrdinalTraits<tfeti::LO>::invalid()) e.replaceLocalValue(l, 1.0);
    Q.apply(e, qe);
    std::vector<double> at(C.size(), 0.0), sum(C.size(), 0.0);
    auto v = qe.getData();
    for (std::size_t i = 0; i < C.size(); ++i) {
      const tfeti::LO li = map->getLocalElement(static_cast<tfeti::GO>(C[i]));
      if (li != Teuchos::OrdinalTraits<tfeti::LO>::invalid()) at[i] = v[li];
    }
    Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, static_cast<int>(C.size()), at.data(),
                       sum.data());
    for (std::size_t i = 0; i < C.size(); ++i) {
      diff = std::max(diff, std::abs(columns[c * C.size() + i] - sum[i]));
      scale = std::max(scale, std::abs(sum[i]));
    }
  }
  out << C.size() << " candidates, " << J.size() << " columns: max |structured - Q e_j| = " << diff
      << ", max |Q e_j| = " << scale << "\n";
  TEST_COMPARE(scale, >, 0.1);
  TEST_COMPARE(diff, <=, 1e-13 * scale);

  // A column that is not a candidate is an error, not a silent zero.
  std::vector<long long> notCandidate{all[1]};
  TEST_THROW(structured.columns(notCandidate, columns), std::logic_error);
}

namespace {

// A face projector built on Q's factors against the one that applies Q twice, on a face of
// every unitStep-th multiplier and circles at every circleStep-th: the same P_F x, multipliers
// and affine projection to rounding; P_F x in ker G and zero on the rows.
void checkFactoredFace(std::size_t unitStep, std::size_t circleStep, bool coarseSide,
                       Teuchos::FancyOStream& out, bool& success) {
  using Face = tfeti::FaceProjector<double, tfeti::MultiVector, tfeti::Operator>;
  const tfeti::FetiSolver solver = boxSolver("TFETI", 3, 2);
  const tfeti::CoarseSpace& coarse = solver.coarseSpace();
  const auto map = solver.tearing().multiplierMap;
  const auto& comm = *map->getComm();
  const std::vector<long long> all = allMultiplierIds(*map);
  std::vector<long long> active;
  // Circles: the pairs (k, k + 1) clear of the unit rows.
  std::vector<tfeti::FaceCircle<double>> circles;
  for (std::size_t k = 0; k < all.size(); k += unitStep) active.push_back(all[k]);
  for (std::size_t k = 3; k + 1 < all.size(); k += circleStep) {
    const bool clear = !std::binary_search(active.begin(), active.end(), all[k]) &&
                       !std::binary_search(active.begin(), active.end(), all[k + 1]) &&
                       map->getLocalElement(static_cast<tfeti::GO>(all[k])) !=
                           Teuchos::OrdinalTraits<tfeti::LO>::invalid();
    int here = clear && map->getLocalElement(static_cast<tfeti::GO>(all[k + 1])) !=
                            Teuchos::OrdinalTraits<tfeti::LO>::invalid()
                   ? 1
                   : 0,
        everywhere = 0;
    Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &here, &everywhere);
    const double angle = 0.3 * static_cast<double>(k);
    if (everywhere == 1) circles.push_back({all[k], std::cos(angle), std::sin(angle)});
  }
  TEST_COMPARE(circles.size(), >, std::size_t(2));
  const Teuchos::RCP<const tfeti::Operator> Q =
      Teuchos::rcp(new tfeti::ComplementProjector(map, coarse));
  const tfeti::CoarseComplementFactors factors(coarse);
  tfeti::Vector like(map);
  const Face twice(Q, active, like, nullptr, circles);
  const Face once(Q, active, like, nullptr, circles, &factors);
  TEST_ASSERT(twice.valid() && once.valid());
  // More rows than G (162 here): the coarse side, with G G^T in place of S.
  TEST_EQUALITY(once.coarseSide(), coarseSide);
  TEST_ASSERT(!twice.coarseSide());

  tfeti::Vector x(map), y1(map), y2(map);
  x.randomize();
  const auto maxDiff = [](const tfeti::Vector& a, const tfeti::Vector& b) {
    tfeti::Vector d(a, Teuchos::Copy);
    d.update(-1.0, b, 1.0);
    return d.normInf() / std::max(a.normInf(), 1e-300);
  };
  twice.apply(x, y1);
  once.apply(x, y2);
  out << active.size() << " unit rows, " << circles.size() << " circles"
      << (coarseSide ? " (coarse side)" : "") << ": P_F x differs by " << maxDiff(y1, y2)
      << " (relative, max norm)\n";
  TEST_COMPARE(maxDiff(y1, y2), <=, 1e-13);
  // P_F x lies in ker G and vanishes on the rows.
  tfeti::Vector Gy(coarse.coarseMap()), Gx(coarse.coarseMap());
  coarse.G()->apply(y2, Gy);
  coarse.G()->apply(x, Gx);
  TEST_COMPARE(Gy.norm2(), <=, 1e-12 * Gx.norm2());
  const std::vector<double> rows = once.gatherRows(y2);
  double rowMax = 0.0;
  for (double r : rows) rowMax = std::max(rowMax, std::abs(r));
  TEST_COMPARE(rowMax, <=, 1e-13 * y2.normInf());
  // In place, as the face CG applies it.
  Tpetra::deep_copy(y1, x);
  once.apply(y1, y1);
  TEST_COMPARE(maxDiff(y1, y2), <=, 1e-15);

  const std::vector<double> s1 = twice.activeMultipliers(x), s2 = once.activeMultipliers(x);
  TEST_EQUALITY(s1.size(), s2.size());
  double sDiff = 0.0, sScale = 0.0;
  for (std::size_t k = 0; k < s1.size(); ++k)
    sDiff = std::max(sDiff, std::abs(s1[k] - s2[k])), sScale = std::max(sScale, std::abs(s1[k]));
  TEST_COMPARE(sDiff, <=, 1e-13 * sScale);

  std::vector<double> r(s1.size());
  for (std::size_t k = 0; k < r.size(); ++k) r[k] = std::sin(1.0 + static_cast<double>(k));
  Tpetra::deep_copy(y1, x);
  Tpetra::deep_copy(y2, x);
  twice.projectAffine(r, y1);
  once.projectAffine(r, y2);
  TEST_COMPARE(maxDiff(y1, y2), <=, 1e-13);
  const std::vector<double> held = once.gatherRows(y2);
  double heldDiff = 0.0;
  for (std::size_t k = 0; k < r.size(); ++k)
    heldDiff = std::max(heldDiff, std::abs(held[k] - r[k]));
  TEST_COMPARE(heldDiff, <=, 1e-13);
}

}  // namespace

// Q's factors give P_F in one pass over G and one over G^T, with S (fewer rows than G) or with
// G G^T on the coarse side (more rows than G).
TEUCHOS_UNIT_TEST(CoarseGramian, FaceProjectorFromFactorsEqualsTwoProjections) {
  checkFactoredFace(40, 60, false, out, success);
  checkFactoredFace(7, 11, true, out, success);
}
