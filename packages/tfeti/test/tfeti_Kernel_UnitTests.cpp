// Unit tests of the kernel detection (tfeti_Kernel.hpp) through tfeti::Subdomain, on crafted 2D
// and 3D subdomains where the kernel dimension is known exactly: a single Tet4 and Hex8, cubes
// touching at a node or along an edge, disjoint pieces, strips of a few elements, mixed element
// types; FETI Dirichlet dofs removing modes; a supplied kernel; and the errors: a kernel larger
// than the one found (pieces touching at a node without elements given), a supplied kernel that
// K does not annihilate. Every accepted subdomain passes ||K R||, R^T R = I and ||K K+ K - K||.
#include <Teuchos_UnitTestHarness.hpp>

#include <string>
#include <vector>

#include "tfeti_Kernel.hpp"
#include "tfeti_Subdomain.hpp"
#include "tfeti_SubdomainChecks.hpp"
#include "tfeti_Test3d.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

using tfeti::Formulation;

struct Crafted {
  std::string name;
  std::vector<double> coords;  // 3 per node
  tfeti::ElementConnectivity elements;
  int elasticKernel;  // expected kernel dimension, 3D elasticity
  int scalarKernel;   // expected kernel dimension, Laplacian
};

// The cube [0,1]^3 shifted by (x, y, z) and slightly sheared (a general hexahedron), nodes
// appended to coords; returns its Hex8 node list (VTK order). Node ids of corners listed in
// `reuse` (corner index -> existing node) are not added again.
std::vector<int> addCube(Crafted& c, double x, double y, double z,
                         const std::vector<std::pair<int, int>>& reuse = {}) {
  static const int order[8] = {0, 1, 3, 2, 4, 5, 7, 6};  // VTK order of corner bits (x, y, z)
  std::vector<int> ids(8, -1);
  for (const auto& [corner, node] : reuse) ids[corner] = node;
  for (int b = 0; b < 8; ++b) {
    if (ids[b] >= 0) continue;
    const double px = x + (b & 1), py = y + (b >> 1 & 1), pz = z + (b >> 2);
    ids[b] = static_cast<int>(c.coords.size() / 3);
    c.coords.insert(c.coords.end(), {px + 0.05 * py * pz, py + 0.03 * pz, pz + 0.04 * px * py});
  }
  std::vector<int> hex;
  for (int k : order) hex.push_back(ids[k]);
  return hex;
}

std::vector<Crafted> craftedSubdomains() {
  std::vector<Crafted> all;
  {
    Crafted c{"one Tet4", {0.1, 0.05, 0, 1, 0.1, 0.02, 0.2, 1.1, 0.05, 0.05, 0.1, 0.9}, {}, 6, 1};
    c.elements.add({0, 1, 2, 3});
    all.push_back(c);
  }
  {
    Crafted c{"one Hex8", {}, {}, 6, 1};
    c.elements.add(addCube(c, 0, 0, 0));
    all.push_back(c);
  }
  {
    // Corner bit 7 of the first cube is (1,1,1) (before shearing): the second cube starts there.
    Crafted c{"two cubes touching at a node", {}, {}, 9, 1};
    const std::vector<int> a = addCube(c, 0, 0, 0);
    c.elements.add(a);
    const int shared = a[6];  // VTK index 6 = corner bits 7
    c.elements.add(addCube(c, 1.05, 1.03, 1.0, {{0, shared}}));
    all.push_back(c);
  }
  {
    // The edge x = 1, y = 1 of the first cube (corner bits 3 and 7) is the edge x = 0, y = 0
    // (corner bits 0 and 4) of the second.
    Crafted c{"two cubes touching along an edge", {}, {}, 7, 1};
    const std::vector<int> a = addCube(c, 0, 0, 0);
    c.elements.add(a);
    c.elements.add(addCube(c, 1.0, 1.0, 0.0, {{0, a[2]}, {4, a[6]}}));
    all.push_back(c);
  }
  {
    Crafted c{"two disjoint cubes", {}, {}, 12, 2};
    c.elements.add(addCube(c, 0, 0, 0));
    c.elements.add(addCube(c, 2.5, 0, 0));
    all.push_back(c);
  }
  {
    // Three cubes in a row sharing faces (corner bits 1, 3, 5, 7 -> 0, 2, 4, 6).
    Crafted c{"a strip of three Hex8", {}, {}, 6, 1};
    std::vector<int> prev = addCube(c, 0, 0, 0);
    c.elements.add(prev);
    for (int i = 1; i < 3; ++i) {
      std::vector<int> next =
          addCube(c, i, 0, 0, {{0, prev[1]}, {2, prev[2]}, {4, prev[5]}, {6, prev[6]}});
      c.elements.add(next);
      prev = next;
    }
    all.push_back(c);
  }
  {
    // A Tet4 on the face x = 1 of a Hex8 (three of its four nodes): one rigid piece.
    Crafted c{"a Hex8 and a Tet4 sharing a face", {}, {}, 6, 1};
    const std::vector<int> a = addCube(c, 0, 0, 0);
    c.elements.add(a);
    c.coords.insert(c.coords.end(), {1.8, 0.4, 0.5});
    c.elements.add({a[1], a[2], a[5], static_cast<int>(c.coords.size() / 3) - 1});
    all.push_back(c);
  }
  {
    // Two Tet4 sharing one edge (a hinge) and a third hanging from a single node of the second.
    Crafted c{"tets touching along an edge and at a node", {}, {}, 6 + 1 + 3, 1};
    c.coords = {0,   0,   0,   1,  0, 0, 0,   1, 0, 0, 0, 1, 1, 1,
                0.2, 0.1, 0.2, -1, 2, 2, 0.5, 2, 1, 1, 1, 2, 1};
    c.elements.add({0, 1, 2, 3});
    c.elements.add({1, 2, 4, 5});
    c.elements.add({4, 6, 8, 7});
    all.push_back(c);
  }
  {
    // Kuhn split of a 1 x 1 x 2 box: twelve tetrahedra.
    Crafted c{"a strip of twelve Tet4", {}, {}, 6, 1};
    tfeti::SubdomainMesh m = tfeti_test::Box3d(1, 1, 1, 1, 1, 2, true).subdomain(0);
    c.coords = m.coords;
    c.elements = m.elements;
    all.push_back(c);
  }
  return all;
}

// K and load of a crafted subdomain: 3D elasticity (dpn 3) or the Laplacian (dpn 1), unit body
// load in x (elasticity) or 1.
struct Assembled {
  tfeti::CsrMatrix K;
  std::vector<double> f;
};
Assembled assemble(const std::vector<double>& coords, const tfeti::ElementConnectivity& elements,
                   int dpn) {
  tfeti_test::Material3d mat;
  mat.dofsPerNode = dpn;
  Assembled a;
  std::vector<double> force(dpn, 0.0);
  force[0] = 1.0;
  tfeti_test::assemble3d(coords, elements, mat, force, a.K, a.f);
  return a;
}

tfeti::KernelOptions options3d(const tfeti::ElementConnectivity& elements) {
  tfeti::KernelOptions k;
  k.dim = 3;
  k.elements = elements;
  return k;
}

TEUCHOS_UNIT_TEST(Kernel, Crafted3dSubdomainsHaveTheExactKernel) {
  for (const Crafted& c : craftedSubdomains())
    for (int dpn : {3, 1}) {
      const auto [K, f] = assemble(c.coords, c.elements, dpn);
      const int expected = dpn == 3 ? c.elasticKernel : c.scalarKernel;
      out << c.name << (dpn == 3 ? ", elasticity" : ", Laplacian") << ": expected kernel "
          << expected << "\n";
      const auto pieces =
          tfeti::rigidPieces(3, dpn, c.coords, c.elements, static_cast<int>(c.coords.size() / 3));
      out << "  " << pieces.size() << " rigid pieces\n";
      for (const std::string solver : {"cholmod", "klu2"}) {
        tfeti::Subdomain sd(3, dpn, c.coords, options3d(c.elements), K, f, {}, Formulation::TFETI,
                            solver);
        tfeti_test::checkGeneralizedInverse(sd, expected, out, success);
        out << "  regularized lambda_min / max diag = " << sd.regularizedConditionEstimate()
            << "\n";
      }
    }
}

TEUCHOS_UNIT_TEST(Kernel, TwoQuadsTouchingAtANodeIn2d) {
  // Q1 elements (quads) through the plasticity assembly: the corner (1,1) of the first is the
  // corner (0,0) of the second; 2D elasticity has 3 + 3 - 2 modes, the Laplacian 1.
  tfeti::SubdomainMesh m;
  m.id = 9;
  m.coords = {0, 0, 1, 0, 1, 1, 0, 1, 2, 1, 2, 2, 1, 2};
  m.globalNode = {0, 1, 2, 3, 4, 5, 6};
  m.elements.add({0, 1, 2, 3});
  m.elements.add({2, 4, 5, 6});
  for (const auto& ph : {tfeti_test::elasticity(), tfeti_test::poisson()}) {
    const tfeti::SubdomainData d = tfeti_test::subdomainData(m, ph);
    tfeti::KernelOptions k;
    k.elements = m.connectivity();
    tfeti::Subdomain sd(m.id, ph.dofsPerNode(), m.coords, k, d.K, d.f, {}, Formulation::TFETI,
                        "cholmod");
    out << ph.name() << "\n";
    tfeti_test::checkGeneralizedInverse(sd, ph.dofsPerNode() == 2 ? 4 : 1, out, success);
  }
}

// The error when the kernel is larger than the one found: cubes touching at a node described
// without their elements (the graph of K is connected, so 6 modes are found, not 9).
TEUCHOS_UNIT_TEST(Kernel, LargerKernelThanFoundIsAnErrorNamingTheSubdomain) {
  const Crafted c = craftedSubdomains()[2];
  const auto [K, f] = assemble(c.coords, c.elements, 3);
  for (const std::string solver : {"cholmod", "klu2"}) {
    bool threw = false;
    try {
      tfeti::Subdomain sd(41, 3, c.coords, options3d({}), K, f, {}, Formulation::TFETI, solver);
      out << solver << ": accepted, lambda_min estimate " << sd.regularizedConditionEstimate()
          << "\n";
    } catch (const std::runtime_error& e) {
      threw = true;
      const std::string what = e.what();
      out << solver << ": " << what << "\n";
      TEST_INEQUALITY(what.find("subdomain 41"), std::string::npos);
      TEST_INEQUALITY(what.find("larger kernel"), std::string::npos);
    }
    TEST_ASSERT(threw);
  }
}

// FETI eliminates Dirichlet dofs: the kernel keeps the rigid motions that vanish on them.
TEUCHOS_UNIT_TEST(Kernel, FetiDirichletDofsLeaveTheRemainingModes3d) {
  const Crafted c = craftedSubdomains()[5];  // strip of three Hex8
  const auto [K, f] = assemble(c.coords, c.elements, 3);
  struct Case {
    std::vector<int> dofs;
    int kernel;
  };
  // Node 0 fixed: the 3 rotations about it; nodes 0 and 1 (an edge): the rotation about it; a
  // face (nodes 0..3): none; one component of node 0: 5.
  const std::vector<Case> cases = {{{0, 1, 2}, 3},
                                   {{0, 1, 2, 3, 4, 5}, 1},
                                   {{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}, 0},
                                   {{2}, 5}};
  for (const auto& cs : cases) {
    out << cs.dofs.size() << " Dirichlet dofs\n";
    tfeti::Subdomain sd(2, 3, c.coords, options3d(c.elements), K, f, cs.dofs, Formulation::FETI,
                        "cholmod");
    tfeti_test::checkGeneralizedInverse(sd, cs.kernel, out, success);
    for (int q = 0; q < sd.kernelDim(); ++q)
      for (int d : cs.dofs) TEST_EQUALITY(sd.kernel()[std::size_t(q) * sd.numDofs() + d], 0.0);
  }
}

// A supplied kernel: any basis of the rigid modes is accepted (and orthonormalized); a vector
// outside the kernel of K and a kernel missing a mode are errors naming the subdomain.
TEUCHOS_UNIT_TEST(Kernel, SuppliedKernelIsCheckedByKR) {
  const Crafted c = craftedSubdomains()[5];
  const auto [K, f] = assemble(c.coords, c.elements, 3);
  const int n = K.rows, nodes = n / 3;
  // Raw modes about the origin, mixed: column j = mode j + mode (j+1) mod 6 / 2 (independent).
  std::vector<std::vector<double>> raw(6, std::vector<double>(n, 0.0));
  for (int a = 0; a < nodes; ++a) {
    const double x = c.coords[3 * a], y = c.coords[3 * a + 1], z = c.coords[3 * a + 2];
    for (int i = 0; i < 3; ++i) raw[i][3 * a + i] = 1.0;
    raw[3][3 * a + 1] = -z, raw[3][3 * a + 2] = y;
    raw[4][3 * a + 2] = -x, raw[4][3 * a] = z;
    raw[5][3 * a] = -y, raw[5][3 * a + 1] = x;
  }
  std::vector<double> mixed;
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < n; ++i) mixed.push_back(raw[j][i] + 0.5 * raw[(j + 1) % 6][i]);
  tfeti::KernelOptions opt;
  opt.dim = 3;
  opt.kernel = mixed;
  {
    tfeti::Subdomain sd(5, 3, c.coords, opt, K, f, {}, Formulation::TFETI, "cholmod");
    tfeti_test::checkGeneralizedInverse(sd, 6, out, success);
  }
  // A stretch u = (x, 0, 0) instead of the last column: not in the kernel.
  std::vector<double> wrong = mixed;
  for (int a = 0; a < nodes; ++a) wrong[5 * n + 3 * a] = c.coords[3 * a];
  // Five of the six modes: the sixth is missing.
  std::vector<double> missing(mixed.begin(), mixed.begin() + 5 * n);
  for (const auto& [kernel, expect] : {std::make_pair(wrong, std::string("not in the kernel of K")),
                                       std::make_pair(missing, std::string("larger kernel"))}) {
    opt.kernel = kernel;
    bool threw = false;
    try {
      tfeti::Subdomain sd(5, 3, c.coords, opt, K, f, {}, Formulation::TFETI, "cholmod");
    } catch (const std::runtime_error& e) {
      threw = true;
      out << e.what() << "\n";
      TEST_INEQUALITY(std::string(e.what()).find("subdomain 5"), std::string::npos);
      TEST_INEQUALITY(std::string(e.what()).find(expect), std::string::npos);
    }
    TEST_ASSERT(threw);
  }
}

// Sizes that do not match are errors in the caller's terms.
TEUCHOS_UNIT_TEST(Kernel, InconsistentSizesAreErrors) {
  const Crafted c = craftedSubdomains()[1];
  const Assembled a = assemble(c.coords, c.elements, 3);
  const tfeti::CsrMatrix& K = a.K;
  const std::vector<double>& f = a.f;
  const std::vector<double> shortCoords(c.coords.begin(), c.coords.end() - 3);
  const std::vector<double> shortLoad(f.begin(), f.end() - 1);
  auto throws = [&](const std::vector<double>& coords, const std::vector<double>& load, int dim,
                    int dpn, const std::string& expect) {
    tfeti::KernelOptions opt = options3d(c.elements);
    opt.dim = dim;
    try {
      tfeti::Subdomain sd(8, dpn, coords, opt, K, load, {}, Formulation::TFETI, "cholmod");
    } catch (const std::invalid_argument& e) {
      out << e.what() << "\n";
      return std::string(e.what()).find("subdomain 8") != std::string::npos &&
             std::string(e.what()).find(expect) != std::string::npos;
    }
    return false;
  };
  TEST_ASSERT(throws(shortCoords, f, 3, 3, "K has 24 rows, the coordinates give 7 nodes"));
  TEST_ASSERT(throws(c.coords, shortLoad, 3, 3, "the load has 23 entries"));
  TEST_ASSERT(throws(c.coords, f, 3, 2, "2 dofs per node in 3D"));
  TEST_ASSERT(throws(c.coords, f, 4, 3, "spatial dimension 4"));
}

}  // namespace

namespace {

// The extra-kernel check must not reject real subdomains: on the largest subdomains the tests
// use (and larger) the smallest eigenvalue of the regularized K stays orders of magnitude above
// the threshold 1e-11 (measured: see the output), while a missed kernel vector gives ~1e-17.
TEUCHOS_UNIT_TEST(Kernel, LargeSubdomainsPassTheExtraKernelCheck) {
  for (int e : {4, 8, 12})
    for (int dpn : {1, 3}) {
      const tfeti::SubdomainMesh m = tfeti_test::Box3d(1, 1, 1, e, e, e, false).subdomain(0);
      const auto [K, f] = assemble(m.coords, m.elements, dpn);
      tfeti::Subdomain sd(0, dpn, m.coords, options3d(m.elements), K, f, {}, Formulation::TFETI,
                          "cholmod");
      out << e << "^3 Hex8, " << (dpn == 1 ? "Laplacian" : "elasticity")
          << ": lambda_min / max diag = " << sd.regularizedConditionEstimate()
          << ", ||K R|| / ||K|| = " << sd.kernelResidual() << "\n";
      TEST_EQUALITY(sd.kernelDim(), dpn == 1 ? 1 : 6);
      TEST_COMPARE(sd.regularizedConditionEstimate(), >, 1e-8);
    }
  for (int e : {16, 64}) {
    const tfeti::StructuredRectangle rect(0, 1, 0, 1, 1, 1, e, e);
    const tfeti::SubdomainMesh m = rect.subdomain(0);
    for (const auto& ph : {tfeti_test::poisson(), tfeti_test::elasticity()}) {
      const tfeti::SubdomainData d = tfeti_test::subdomainData(m, ph);
      tfeti::Subdomain sd(0, ph.dofsPerNode(), m.coords, d.K, d.f, {}, Formulation::TFETI,
                          "cholmod");
      out << e << "^2 Q1, " << ph.name()
          << ": lambda_min / max diag = " << sd.regularizedConditionEstimate() << "\n";
      TEST_COMPARE(sd.regularizedConditionEstimate(), >, 1e-8);
    }
  }
}

}  // namespace
