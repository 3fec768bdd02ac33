// Unit tests of the mesh side of tfeti: dealing subdomains to ranks (subdomainsOfRank and its
// inverse ownerOfSubdomain), StructuredRectangle subdomains and whole mesh, and
// SubdomainMesh::boundaryNodes.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <array>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "tfeti_StructuredMesh.hpp"
#include "tfeti_SubdomainMesh.hpp"

TEUCHOS_UNIT_TEST(SubdomainMesh, DealingIsContiguousBalancedAndInvertible) {
  int bad = 0;
  for (int N = 1; N <= 40; ++N)
    for (int P = 1; P <= 12; ++P) {
      int next = 0, minCount = N, maxCount = 0;
      for (int r = 0; r < P; ++r) {
        const std::vector<int> ids = tfeti::subdomainsOfRank(r, N, P);
        minCount = std::min(minCount, static_cast<int>(ids.size()));
        maxCount = std::max(maxCount, static_cast<int>(ids.size()));
        for (int s : ids) {
          if (s != next++) ++bad;                            // contiguous, increasing
          if (tfeti::ownerOfSubdomain(s, N, P) != r) ++bad;  // inverse
        }
      }
      if (next != N || maxCount - minCount > 1) ++bad;  // partition, balanced
    }
  TEST_EQUALITY(bad, 0);
  // 16 subdomains on 3 ranks: 5, 5, 6.
  TEST_EQUALITY(tfeti::subdomainsOfRank(0, 16, 3).size(), std::size_t(5));
  TEST_EQUALITY(tfeti::subdomainsOfRank(2, 16, 3).front(), 10);
}

TEUCHOS_UNIT_TEST(StructuredRectangle, SubdomainsTileTheWholeMesh) {
  // (0,2) x (0,1), 3 x 2 subdomains of 4 x 3 elements.
  const tfeti::StructuredRectangle rect(0, 2, 0, 1, 3, 2, 4, 3);
  TEST_EQUALITY(rect.numSubdomains(), 6);
  TEST_EQUALITY(rect.elementsX(), 12);
  TEST_EQUALITY(rect.elementsY(), 6);
  TEST_EQUALITY(rect.numGlobalNodes(), tfeti::GO(13 * 7));
  const tfeti::SubdomainMesh whole = rect.wholeMesh();
  TEST_EQUALITY(whole.id, -1);
  TEST_EQUALITY(static_cast<tfeti::GO>(whole.numNodes()), rect.numGlobalNodes());
  TEST_EQUALITY(whole.numElements(), 72);
  TEST_EQUALITY(static_cast<int>(whole.dirichletNodes.size()), 7);  // the side x = 0
  for (int n = 0; n < whole.numNodes(); ++n) TEST_EQUALITY(whole.globalNode[n], tfeti::GO(n));

  std::map<tfeti::GO, int> copies;
  int elements = 0, badCoord = 0, badDirichlet = 0, negativeArea = 0;
  for (int s = 0; s < rect.numSubdomains(); ++s) {
    const tfeti::SubdomainMesh m = rect.subdomain(s);
    TEST_EQUALITY(m.id, s);
    TEST_EQUALITY(m.numNodes(), 5 * 4);
    elements += m.numElements();
    for (int n = 0; n < m.numNodes(); ++n) {
      const tfeti::GO g = m.globalNode[n];
      copies[g]++;
      // Every copy sits exactly where the untorn node is.
      if (m.coords[2 * n] != whole.coords[2 * g] || m.coords[2 * n + 1] != whole.coords[2 * g + 1])
        ++badCoord;
    }
    std::vector<char> dir(m.numNodes(), 0);
    for (int n : m.dirichletNodes) dir[n] = 1;
    for (int n = 0; n < m.numNodes(); ++n)
      if ((m.coords[2 * n] == 0.0) != (dir[n] == 1)) ++badDirichlet;
    for (int e = 0; e < m.numElements(); ++e) {  // counter-clockwise: positive signed area
      double a = 0.0;
      for (int k = 0; k < 4; ++k) {
        const int p = m.elements.nodes[4 * e + k], q = m.elements.nodes[4 * e + (k + 1) % 4];
        a += m.coords[2 * p] * m.coords[2 * q + 1] - m.coords[2 * q] * m.coords[2 * p + 1];
      }
      if (!(a > 0.0)) ++negativeArea;
    }
    // Boundary of a 4 x 3 block: all nodes but the 3 x 2 interior ones.
    TEST_EQUALITY(static_cast<int>(m.boundaryNodes().size()), 20 - 6);
  }
  TEST_EQUALITY(elements, 72);
  TEST_EQUALITY(badCoord, 0);
  TEST_EQUALITY(badDirichlet, 0);
  TEST_EQUALITY(negativeArea, 0);
  TEST_EQUALITY(static_cast<tfeti::GO>(copies.size()), rect.numGlobalNodes());
  // Multiplicities: 2 interior cross points with 4 copies; the rest of the interface has 2.
  std::map<int, int> histogram;
  for (const auto& [g, m] : copies) histogram[m]++;
  TEST_EQUALITY(histogram[4], 2);
  TEST_EQUALITY(histogram[2],
                7 + 7 + 13 - 2 * 2);  // 2 vertical lines, 1 horizontal, less crossings
}

TEUCHOS_UNIT_TEST(StructuredRectangle, InvalidArgumentsThrow) {
  TEST_THROW(tfeti::StructuredRectangle(0, 1, 0, 1, 0, 2, 2, 2), std::invalid_argument);
  TEST_THROW(tfeti::StructuredRectangle(0, 1, 0, 1, 2, 2, 2, -1), std::invalid_argument);
  TEST_THROW(tfeti::StructuredRectangle(1, 1, 0, 1, 2, 2, 2, 2), std::invalid_argument);
  const tfeti::StructuredRectangle rect(0, 1, 0, 1, 2, 2, 2, 2);
  TEST_THROW(rect.subdomain(4), std::out_of_range);
  TEST_THROW(rect.subdomain(-1), std::out_of_range);
}

TEUCHOS_UNIT_TEST(SubdomainMesh, BoundaryNodesAreTheInterfaceCandidatesOrEveryNode) {
  // 3 elements in an L: nodes of the 2x2 block minus the top-right element.
  //   6 7
  //   3 4 5
  //   0 1 2
  tfeti::SubdomainMesh m;
  m.coords = {0, 0, 1, 0, 2, 0, 0, 1, 1, 1, 2, 1, 0, 2, 1, 2};
  m.globalNode = {0, 1, 2, 3, 4, 5, 6, 7};
  m.elements.add({0, 1, 4, 3});
  m.elements.add({1, 2, 5, 4});
  m.elements.add({3, 4, 7, 6});
  TEST_EQUALITY(m.numElements(), 3);
  // No candidates listed: every node may be shared.
  TEST_COMPARE_ARRAYS(m.boundaryNodes(), std::vector<int>({0, 1, 2, 3, 4, 5, 6, 7}));
  // Candidates: sorted, each once.
  m.interfaceCandidates = {7, 2, 0, 2, 5};
  TEST_COMPARE_ARRAYS(m.boundaryNodes(), std::vector<int>({0, 2, 5, 7}));
}

TEUCHOS_UNIT_TEST(StructuredRectangle, SubdomainsListTheirQuadrilateralsAndBlockSides) {
  // A block of 3 x 3 elements: its 12 side nodes are the candidates (the 4 interior ones not),
  // its elements the Q1 cells in VTK order, counter-clockwise.
  const tfeti::StructuredRectangle rect(0, 3, 0, 3, 2, 1, 3, 3);
  const tfeti::SubdomainMesh q = rect.subdomain(1);
  TEST_EQUALITY(q.numElements(), 9);
  TEST_COMPARE_ARRAYS(q.elements.nodes, rect.subdomainCells());
  for (int e = 0; e < q.numElements(); ++e)
    TEST_EQUALITY(q.elements.offsets[e + 1] - q.elements.offsets[e], 4);
  const std::vector<int> qb = q.boundaryNodes();
  TEST_EQUALITY(static_cast<int>(qb.size()), 12);
  for (int n : {5, 6, 9, 10}) TEST_ASSERT(std::find(qb.begin(), qb.end(), n) == qb.end());
  TEST_ASSERT(std::is_sorted(qb.begin(), qb.end()));
}

TEUCHOS_UNIT_TEST(StructuredMesh, BoxSubdomainsTileTheWholeMesh) {
  // (0,2) x (0,1) x (0,3), 2 x 3 x 2 subdomains of 2 x 1 x 3 elements: 4 x 3 x 6 elements.
  const tfeti::StructuredMesh box({0, 0, 0}, {2, 1, 3}, {2, 3, 2}, {2, 1, 3});
  TEST_EQUALITY(box.dim(), 3);
  TEST_EQUALITY(box.numSubdomains(), 12);
  TEST_EQUALITY(box.numGlobalNodes(), tfeti::GO(5 * 4 * 7));
  TEST_EQUALITY(box.numGlobalElements(), tfeti::GO(4 * 3 * 6));
  const tfeti::SubdomainMesh whole = box.wholeMesh();
  TEST_EQUALITY(static_cast<tfeti::GO>(whole.numNodes()), box.numGlobalNodes());
  TEST_EQUALITY(static_cast<int>(whole.dirichletNodes.size()), 4 * 7);  // the face x = 0
  TEST_EQUALITY(static_cast<int>(box.wholeCells().size()), 8 * 72);
  const std::vector<int> cells = box.subdomainCells();
  TEST_EQUALITY(static_cast<int>(cells.size()), 8 * 6);

  std::map<tfeti::GO, int> copies;
  int badCoord = 0, badVolume = 0, badCopy = 0;
  for (int s = 0; s < box.numSubdomains(); ++s) {
    const tfeti::SubdomainMesh m = box.subdomain(s);
    TEST_EQUALITY(m.id, s);
    TEST_EQUALITY(m.numNodes(), 3 * 2 * 4);
    // Every node of a block of 2 x 1 x 3 elements is on its faces.
    TEST_EQUALITY(static_cast<int>(m.interfaceCandidates.size()), 3 * 2 * 4);
    for (int n = 0; n < m.numNodes(); ++n) {
      const tfeti::GO g = m.globalNode[n];
      copies[g]++;
      for (int d = 0; d < 3; ++d)
        if (m.coords[3 * n + d] != whole.coords[3 * g + d]) ++badCoord;
      // The lowest-id copy found by copyOfNode is this one or one of a lower subdomain.
      const std::array<int, 3> gi = {int(g % 5), int((g / 5) % 4), int(g / 20)};
      const auto [cs, cn] = box.copyOfNode(gi);
      if (cs > s || box.subdomain(cs).globalNode[cn] != g) ++badCopy;
    }
    // Hexahedra in VTK order have a positive volume: (x1-x0) x (x3-x0) . (x4-x0) > 0.
    for (std::size_t e = 0; e < cells.size(); e += 8) {
      double a[3][3];
      const int corner[3] = {1, 3, 4};
      for (int k = 0; k < 3; ++k)
        for (int d = 0; d < 3; ++d)
          a[k][d] = m.coords[3 * cells[e + corner[k]] + d] - m.coords[3 * cells[e] + d];
      const double vol = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) * a[2][0] +
                         (a[0][2] * a[1][0] - a[0][0] * a[1][2]) * a[2][1] +
                         (a[0][0] * a[1][1] - a[0][1] * a[1][0]) * a[2][2];
      if (!(vol > 0.0)) ++badVolume;
    }
  }
  TEST_EQUALITY(badCoord, 0);
  TEST_EQUALITY(badVolume, 0);
  TEST_EQUALITY(badCopy, 0);
  TEST_EQUALITY(static_cast<tfeti::GO>(copies.size()), box.numGlobalNodes());
  // Copies per node: the product over the axes of 2 on an interior subdomain boundary, else 1.
  // Interior boundaries: x = 2 (of 0..4), y = 1, 2 (of 0..3), z = 3 (of 0..6).
  int bad = 0;
  for (const auto& [g, m] : copies) {
    const int i = int(g % 5), j = int((g / 5) % 4), k = int(g / 20);
    const int expected = (i == 2 ? 2 : 1) * (j == 1 || j == 2 ? 2 : 1) * (k == 3 ? 2 : 1);
    if (m != expected) ++bad;
  }
  TEST_EQUALITY(bad, 0);
}

TEUCHOS_UNIT_TEST(StructuredMesh, InconsistentListsThrow) {
  TEST_THROW(tfeti::StructuredMesh({0, 0, 0}, {1, 1}, {2, 2, 2}, {2, 2, 2}), std::invalid_argument);
  TEST_THROW(tfeti::StructuredMesh({0, 0, 0}, {1, 1, 1}, {2, 2}, {2, 2, 2}), std::invalid_argument);
  TEST_THROW(tfeti::StructuredMesh({0}, {1}, {2}, {2}), std::invalid_argument);
  TEST_THROW(tfeti::StructuredMesh({0, 0, 0}, {1, 1, 0}, {2, 2, 2}, {2, 2, 2}),
             std::invalid_argument);
  TEST_THROW(tfeti::StructuredMesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {2, 0, 2}),
             std::invalid_argument);
}
