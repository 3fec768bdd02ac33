// The recovered contact pressure (contact_RecoveredFields.hpp): the patch fit reproduces a
// linear field exactly on irregular patches in a tilted plane (3D) and along a line (2D), and a
// quadratic one with degree 2, is
// the patch mean on a patch symmetric about its node, and leaves a node whose patch cannot
// determine a slope (all points on one line in 3D, a single point) at its own value. The mirror
// images across symmetry planes, and a half ring with its images fitted as the whole ring. The
// nodal von Mises stresses averaged per body.
#include <Teuchos_UnitTestHarness.hpp>

#include <array>
#include <cmath>
#include <vector>

#include <Teuchos_DefaultComm.hpp>

#include "contact_RecoveredFields.hpp"

namespace {

using Points = std::vector<std::array<double, 3>>;

std::vector<int> linear(std::size_t n) {
  return std::vector<int>(n, 1);
}

// An irregular planar patch in the plane through o spanned by the unit vectors u and v: a centre
// and six neighbours at uneven angles and distances, each node's patch all of them.
struct TiltedPatch {
  Points x, n;
  std::vector<std::vector<int>> patch;
};

TiltedPatch tiltedPatch() {
  const double o[3] = {0.3, -0.2, 1.1};
  const double u[3] = {std::cos(0.4), std::sin(0.4), 0.0};
  const double s = 1.0 / std::sqrt(1.0 + 0.25);
  // v orthogonal to u, tilted out of the x-y plane.
  const double v[3] = {-std::sin(0.4) * s, std::cos(0.4) * s, 0.5 * s};
  const double nn[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                        u[0] * v[1] - u[1] * v[0]};
  const double ab[7][2] = {{0.0, 0.0},   {1.1, 0.1},   {0.4, 0.9}, {-0.6, 1.2},
                           {-1.3, -0.2}, {-0.2, -0.8}, {0.9, -1.1}};
  TiltedPatch t;
  for (const auto& p : ab) {
    t.x.push_back({o[0] + p[0] * u[0] + p[1] * v[0], o[1] + p[0] * u[1] + p[1] * v[1],
                   o[2] + p[0] * u[2] + p[1] * v[2]});
    t.n.push_back({nn[0], nn[1], nn[2]});
  }
  t.patch.assign(t.x.size(), {0, 1, 2, 3, 4, 5, 6});
  return t;
}

double linearField(const std::array<double, 3>& x) {
  return 2.0 + 0.7 * x[0] - 1.3 * x[1] + 0.4 * x[2];
}

TEUCHOS_UNIT_TEST(RecoveredFields, LinearFieldIsExactOnATiltedIrregularPatch) {
  const TiltedPatch t = tiltedPatch();
  std::vector<double> v;
  for (const auto& x : t.x) v.push_back(linearField(x));
  // Noise on the others does not matter for the check at a node only if the field is linear:
  // every value here is exact, so every node's fit is.
  const auto r = contact::patchRecovery(t.x, t.n, v, t.patch, 3, linear(t.x.size()));
  for (std::size_t i = 0; i < v.size(); ++i) TEST_FLOATING_EQUALITY(r[i], v[i], 1e-12);
}

TEUCHOS_UNIT_TEST(RecoveredFields, QuadraticFieldIsExactOnATiltedPatchWithDegree2) {
  // A quadratic in the patch plane's coordinates: the quadratic fit reproduces it at every
  // node, the linear one flattens the centre's value (the bias the quadratic facets avoid).
  TiltedPatch t = tiltedPatch();
  // Five more points in the same plane, so that every node's patch fixes six coefficients well.
  const double o[3] = {t.x[0][0], t.x[0][1], t.x[0][2]};
  const double u[3] = {t.x[1][0] - o[0], t.x[1][1] - o[1], t.x[1][2] - o[2]};
  const double w[3] = {t.x[2][0] - o[0], t.x[2][1] - o[1], t.x[2][2] - o[2]};
  const double more[5][2] = {{1.4, 1.2}, {-0.9, 0.3}, {0.2, -1.5}, {-1.1, -1.0}, {1.6, -0.4}};
  for (const auto& m : more) {
    t.x.push_back({o[0] + m[0] * u[0] + m[1] * w[0], o[1] + m[0] * u[1] + m[1] * w[1],
                   o[2] + m[0] * u[2] + m[1] * w[2]});
    t.n.push_back(t.n[0]);
  }
  std::vector<int> all(t.x.size());
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
  t.patch.assign(t.x.size(), all);
  // x, y and z are linear in the in-plane coordinates: this is a quadratic of them.
  auto field = [](const std::array<double, 3>& x) {
    return 1.0 - 0.3 * x[0] * x[0] + 0.2 * x[0] * x[1] - 0.5 * x[1] * x[1] + 0.1 * x[2];
  };
  std::vector<double> v;
  for (const auto& x : t.x) v.push_back(field(x));
  const auto r = contact::patchRecovery(t.x, t.n, v, t.patch, 3, std::vector<int>(v.size(), 2));
  for (std::size_t i = 0; i < v.size(); ++i) TEST_FLOATING_EQUALITY(r[i], v[i], 1e-11);
  const auto r1 = contact::patchRecovery(t.x, t.n, v, t.patch, 3, linear(v.size()));
  TEST_ASSERT(std::abs(r1[0] - v[0]) > 1e-3);
}

TEUCHOS_UNIT_TEST(RecoveredFields, LinearFieldIsExactAlongALine2D) {
  // Uneven spacing along the line through (1, 2) with tangent (0.6, -0.8).
  const double s[5] = {-1.0, -0.3, 0.0, 0.45, 1.2};
  Points x, n;
  std::vector<double> v;
  for (double t : s) {
    x.push_back({1.0 + 0.6 * t, 2.0 - 0.8 * t, 0.0});
    n.push_back({0.8, 0.6, 0.0});
    v.push_back(5.0 - 2.5 * t);
  }
  const std::vector<std::vector<int>> patch{{0, 1}, {0, 1, 2}, {1, 2, 3}, {2, 3, 4}, {3, 4}};
  const auto r = contact::patchRecovery(x, n, v, patch, 2, linear(x.size()));
  for (std::size_t i = 0; i < v.size(); ++i) TEST_FLOATING_EQUALITY(r[i], v[i], 1e-12);
}

TEUCHOS_UNIT_TEST(RecoveredFields, SymmetricPatchGivesItsMean) {
  // A regular hexagon around the centre: the fit at the centre is the mean of the seven values,
  // whatever they are (the noise a recovery averages out).
  Points x{{0.0, 0.0, 0.0}}, n{{0.0, 0.0, 1.0}};
  for (int k = 0; k < 6; ++k) {
    x.push_back({std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0.0});
    n.push_back({0.0, 0.0, 1.0});
  }
  const std::vector<double> v{1.00, 1.03, 0.98, 1.01, 0.97, 1.04, 0.99};
  double mean = 0.0;
  for (double y : v) mean += y / 7.0;
  std::vector<std::vector<int>> patch(7);
  patch[0] = {0, 1, 2, 3, 4, 5, 6};
  const auto r = contact::patchRecovery(x, n, v, patch, 3, linear(x.size()));
  TEST_FLOATING_EQUALITY(r[0], mean, 1e-14);
  // The other nodes' patches are empty: they keep their values.
  for (int i = 1; i < 7; ++i) TEST_EQUALITY(r[i], v[i]);
}

TEUCHOS_UNIT_TEST(RecoveredFields, UndeterminedSlopeKeepsTheValue) {
  // Three points on one line in 3D: the slope across the line is undetermined.
  const Points x{{0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}, {-0.5, -0.5, 0.0}};
  const Points n(3, {0.0, 0.0, 1.0});
  const std::vector<double> v{1.0, 2.0, 7.0};
  const std::vector<std::vector<int>> patch(3, {0, 1, 2});
  const auto r = contact::patchRecovery(x, n, v, patch, 3, linear(x.size()));
  for (int i = 0; i < 3; ++i) TEST_EQUALITY(r[i], v[i]);
  // A patch of one point, in 2D, asking for degree 2: no degree is determined.
  const auto r2 =
      contact::patchRecovery({{0.0, 0.0, 0.0}}, {{0.0, 1.0, 0.0}}, {3.0}, {{0}}, 2, {2});
  TEST_EQUALITY(r2[0], 3.0);
}

TEUCHOS_UNIT_TEST(RecoveredFields, MirrorImagesAcrossSymmetryPlanes) {
  const std::array<double, 3> origin{0.0, 0.0, 0.5};
  // Off both planes x = 0 and y = 0: three images.
  auto im = contact::mirrorImages(origin, {0, 1}, {1.0, 2.0, 3.0}, 1e-12);
  TEST_EQUALITY(im.size(), 3u);
  const std::vector<std::array<double, 3>> want{
      {-1.0, 2.0, 3.0}, {1.0, -2.0, 3.0}, {-1.0, -2.0, 3.0}};
  for (std::size_t k = 0; k < want.size(); ++k)
    for (int c = 0; c < 3; ++c) TEST_EQUALITY(im[k][c], want[k][c]);
  // On the plane x = 0: its own image there, one image across y = 0.
  im = contact::mirrorImages(origin, {0, 1}, {0.0, 2.0, 3.0}, 1e-12);
  TEST_EQUALITY(im.size(), 1u);
  TEST_EQUALITY(im[0][0], 0.0);
  TEST_EQUALITY(im[0][1], -2.0);
  // One plane only (x = 0.25): one image.
  im = contact::mirrorImages({0.25, 0.0, 0.0}, {0}, {1.0, 2.0, 3.0}, 1e-12);
  TEST_EQUALITY(im.size(), 1u);
  TEST_FLOATING_EQUALITY(im[0][0], -0.5, 1e-15);
}

TEUCHOS_UNIT_TEST(RecoveredFields, HalfRingWithImagesIsTheWholeRing) {
  // A node on the plane y = 0 with the half of a hexagonal ring in y > 0 (and the two ring
  // points on the plane): with the images of the off-plane points the patch is the whole ring,
  // and the fit at the node the mean of the whole ring's values, which the half ring alone
  // (a fit that extrapolates across the plane) is not.
  Points x{{0.0, 0.0, 0.0}}, n{{0.0, 0.0, 1.0}};
  std::vector<double> v{1.00};
  const double vals[4] = {1.02, 0.97, 1.05, 0.99};  // at angles 0, 60, 120, 180 degrees
  for (int k = 0; k < 4; ++k) {
    x.push_back({std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0.0});
    n.push_back({0.0, 0.0, 1.0});
    v.push_back(vals[k]);
  }
  std::vector<std::vector<int>> patch(x.size());
  patch[0] = {0, 1, 2, 3, 4};
  const double half = contact::patchRecovery(x, n, v, patch, 3, linear(x.size()))[0];
  for (int j = 1; j <= 4; ++j)
    for (const auto& image : contact::mirrorImages(x[0], {1}, x[j], 1e-12)) {
      patch[0].push_back(static_cast<int>(x.size()));
      x.push_back(image);
      n.push_back(n[0]);
      v.push_back(v[j]);
      patch.emplace_back();
    }
  TEST_EQUALITY(patch[0].size(), 7u);  // the centre, six ring points
  const double whole = contact::patchRecovery(x, n, v, patch, 3, linear(x.size()))[0];
  const double mean = (1.00 + 1.02 + 2 * 0.97 + 2 * 1.05 + 0.99) / 7.0;
  TEST_FLOATING_EQUALITY(whole, mean, 1e-14);
  TEST_ASSERT(std::abs(half - mean) > 1e-3);
}

// The nodal von Mises stresses average each body's elements apart: a Tri3 of body 0 (stress
// A, von Mises 1) whose three nodes all belong to the three Tri3 of body 1 around it (stress
// 0) keeps A at its nodes. Averaged across the bodies its nodes would hold A / 3.
TEUCHOS_UNIT_TEST(RecoveredFields, NodalVonMisesAveragesEachBodyApart) {
  // Nodes 0-2: the inner triangle; 3-5: the outer triangles' tips. One subdomain per triangle.
  const std::vector<double> xy{0, 0, 1, 0, 0, 1, 0.5, -1, 1.2, 1.2, -1, 0.5};
  const std::vector<std::vector<int>> tri{{0, 1, 2}, {1, 0, 3}, {2, 1, 4}, {0, 2, 5}};
  contact::ElasticContactProblem problem;
  problem.mesh.dim = 2;
  problem.mesh.coords = xy;
  problem.mesh.gmshNodes.resize(6);
  std::vector<plasticity::StressField> stresses;
  for (int k = 0; k < 4; ++k) {
    contact::UnstructuredSubdomain sub;
    sub.id = k;
    sub.globalNode.assign(tri[k].begin(), tri[k].end());
    problem.subdomains.push_back(sub);
    problem.bodyOfSubdomain.push_back(k == 0 ? 0 : 1);
    plasticity::ElementMesh em;
    em.type = plasticity::ElementType::Tri3;
    for (int g : tri[k]) em.coords.insert(em.coords.end(), {xy[2 * g], xy[2 * g + 1]});
    em.connectivity = {0, 1, 2};
    problem.localElements.push_back(em);
    tfeti::SubdomainData d;
    d.mesh.id = k;
    d.mesh.globalNode.assign(tri[k].begin(), tri[k].end());
    problem.local.push_back(d);
    problem.localBody.push_back(k == 0 ? 0 : 1);
    plasticity::StressField st;
    st.nodal.assign(3 * plasticity::kNumStressComponents, 0.0);
    if (k == 0)
      for (int a = 0; a < 3; ++a)
        st.nodal[a * plasticity::kNumStressComponents + plasticity::kSxx] = 1.0;
    stresses.push_back(st);
  }
  const auto comm = Teuchos::DefaultComm<int>::getComm();
  if (comm->getSize() != 1) return;  // the subdomains are all this rank's
  TEST_FLOATING_EQUALITY(contact::maxNodalVonMises(*comm, problem, stresses), 1.0, 1e-14);
  // One body: the inner nodes average A with the two outer triangles at each.
  problem.bodyOfSubdomain.assign(4, 0);
  problem.localBody.assign(4, 0);
  TEST_FLOATING_EQUALITY(contact::maxNodalVonMises(*comm, problem, stresses), 1.0 / 3.0, 1e-14);
}

}  // namespace
