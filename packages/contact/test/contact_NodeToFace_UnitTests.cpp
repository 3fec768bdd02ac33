// Node-to-face contact rows in 3D against what is exactly known: the face shape functions'
// interpolation, partition of unity and derivatives; gaps, normals and closest points on planar
// faces (closed form) and on the quadratic faces of a sphere (the closest-point conditions
// d . x_xi = d . x_eta = 0, and the gap against the sphere to the mesh's geometric error); the
// row as the first-order expansion of the gap under any displacement (error O(eps^2)); edges,
// corners and free edges; the bucket search against the all-pairs search with the pairs it
// examines; orientation errors and bad input.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact_GmshMesh.hpp"
#include "contact_NodeToFace.hpp"

namespace {

using contact::ContactRowsResult;
using contact::ContactSearchOptions;
using contact::ElementType;
using contact::MasterFaceSurface;
using contact::ProjectionKind;

const std::string kMeshDir = CONTACT_TEST_MESH_DIR;

ContactSearchOptions radius(double r) {
  ContactSearchOptions o;
  o.searchRadius = r;
  return o;
}

// Reference coordinates of the face nodes (Gmsh order).
std::vector<std::array<double, 2>> referenceNodes(ElementType t) {
  if (t == ElementType::Tri3) return {{0, 0}, {1, 0}, {0, 1}};
  if (t == ElementType::Tri6) return {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
  std::vector<std::array<double, 2>> q{{-1, -1}, {1, -1}, {1, 1},  {-1, 1}, {0, -1},
                                       {1, 0},   {0, 1},  {-1, 0}, {0, 0}};
  q.resize(contact::numNodes(t));
  return q;
}

TEUCHOS_UNIT_TEST(NodeToFace, FaceShapeFunctions) {
  for (ElementType t : {ElementType::Tri3, ElementType::Tri6, ElementType::Quad4,
                        ElementType::Quad8, ElementType::Quad9}) {
    const auto nodes = referenceNodes(t);
    const int n = static_cast<int>(nodes.size());
    double N[9], dx[9], de[9], Np[9], Nm[9];
    for (int j = 0; j < n; ++j) {  // interpolation: N_k(node j) = delta_kj
      contact::faceShapeFunctions(t, nodes[j][0], nodes[j][1], N, dx, de);
      for (int k = 0; k < n; ++k) TEST_COMPARE(std::abs(N[k] - (k == j ? 1.0 : 0.0)), <, 1e-14);
    }
    const double pts[3][2] = {{0.2, 0.3}, {0.1, 0.7}, {0.45, 0.05}};
    for (const auto& p : pts) {
      contact::faceShapeFunctions(t, p[0], p[1], N, dx, de);
      double sum = 0, sx = 0, se = 0;
      for (int k = 0; k < n; ++k) sum += N[k], sx += dx[k], se += de[k];
      TEST_COMPARE(std::abs(sum - 1.0), <, 1e-14);
      TEST_COMPARE(std::abs(sx) + std::abs(se), <, 1e-13);
      const double h = 1e-6;
      contact::faceShapeFunctions(t, p[0] + h, p[1], Np, nullptr, nullptr);
      contact::faceShapeFunctions(t, p[0] - h, p[1], Nm, nullptr, nullptr);
      for (int k = 0; k < n; ++k)
        TEST_COMPARE(std::abs((Np[k] - Nm[k]) / (2 * h) - dx[k]), <, 1e-8);
      contact::faceShapeFunctions(t, p[0], p[1] + h, Np, nullptr, nullptr);
      contact::faceShapeFunctions(t, p[0], p[1] - h, Nm, nullptr, nullptr);
      for (int k = 0; k < n; ++k)
        TEST_COMPARE(std::abs((Np[k] - Nm[k]) / (2 * h) - de[k]), <, 1e-8);
    }
  }
}

// An n x n grid of unit squares in the plane z = z0 over (0,n)^2, as Quad4 faces or split into
// Tri3 faces, oriented with normal +z (counter-clockwise seen from above). Nodes 0..(n+1)^2-1.
MasterFaceSurface planeGrid(int n, bool triangles, std::vector<double>& coords, double z0 = 0.0) {
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) coords.insert(coords.end(), {double(i), double(j), z0});
  MasterFaceSurface m;
  m.type = triangles ? ElementType::Tri3 : ElementType::Quad4;
  auto id = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (triangles)
        m.faces.insert(m.faces.end(), {a, b, c, a, c, d});
      else
        m.faces.insert(m.faces.end(), {a, b, c, d});
    }
  return m;
}

TEUCHOS_UNIT_TEST(NodeToFace, PlanarFacesClosedForm) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> in(0.05, 3.95), height(-0.2, 0.3);
  for (bool tri : {false, true}) {
    std::vector<double> coords;
    const MasterFaceSurface m = planeGrid(4, tri, coords);
    const int base = static_cast<int>(coords.size() / 3);
    std::vector<int> slaves;
    std::vector<std::array<double, 3>> xs;
    for (int k = 0; k < 40; ++k) {
      xs.push_back({in(rng), in(rng), height(rng)});
      coords.insert(coords.end(), xs.back().begin(), xs.back().end());
      slaves.push_back(base + k);
    }
    const ContactRowsResult r = contact::computeNodeToFace(coords, slaves, m, radius(0.5));
    TEST_EQUALITY(r.rows.size(), slaves.size());
    for (std::size_t k = 0; k < r.rows.size(); ++k) {
      const auto& row = r.rows[k];
      TEST_COMPARE(std::abs(row.gap - xs[k][2]), <, 1e-13);
      TEST_COMPARE(
          std::abs(row.normal[2] - 1.0) + std::abs(row.normal[0]) + std::abs(row.normal[1]), <,
          1e-14);
      TEST_COMPARE(std::abs(row.point[0] - xs[k][0]) + std::abs(row.point[1] - xs[k][1]) +
                       std::abs(row.point[2]),
                   <, 1e-13);
      TEST_EQUALITY(row.entries.size(), std::size_t(3 + 3 * m.nodesPerFace()));
      // Coefficients: -n on the slave; the master's shape functions (partition of unity) times n.
      double masterZ = 0.0;
      for (std::size_t e = 3; e < row.entries.size(); ++e)
        if (row.entries[e].component == 2) masterZ += row.entries[e].coef;
      TEST_COMPARE(std::abs(masterZ - 1.0), <, 1e-14);
      TEST_COMPARE(std::abs(row.entries[2].coef + 1.0), <, 1e-14);
      TEST_EQUALITY(row.entries[2].node, slaves[k]);
    }
  }
}

// Largest |g(eps u) - (g(0) - sum coef (eps u))| over the rows for random u, with the rows
// recomputed on the displaced configuration: the row is the first-order expansion of the gap.
double linearizationError(const std::vector<double>& coords, const std::vector<int>& slaves,
                          const MasterFaceSurface& m, double eps, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u01(-1, 1);
  std::vector<double> u(coords.size());
  for (double& v : u) v = eps * u01(rng);
  const ContactRowsResult r0 = contact::computeNodeToFace(coords, slaves, m, radius(0.3));
  const ContactRowsResult r1 = contact::computeNodeToFace(coords, slaves, m, radius(0.3), u);
  double worst = 0.0;
  std::size_t j = 0;
  for (const auto& row : r0.rows) {
    while (j < r1.rows.size() && r1.rows[j].slaveNode != row.slaveNode) ++j;
    if (j == r1.rows.size()) break;
    double bu = 0.0;
    for (const auto& e : row.entries) bu += e.coef * u[3 * e.node + e.component];
    worst = std::max(worst, std::abs(r1.rows[j].gap - (row.gap - bu)));
  }
  return worst;
}

TEUCHOS_UNIT_TEST(NodeToFace, QuadraticFacesOfASphere) {
  // Master: the sphere's contact surface (Tri6 faces of the order-2 mesh, midside nodes on the
  // sphere), slave points along random directions at known distances from the sphere.
  contact::MeshOptions o;
  o.order = 2;
  const contact::GmshMesh mesh = contact::loadMesh(kMeshDir + "/sphere_on_block.geo", o);
  const MasterFaceSurface m = masterFacesOfBoundary(mesh, mesh.boundary("sphere_contact"));
  TEST_EQUALITY(static_cast<int>(m.type), static_cast<int>(ElementType::Tri6));
  std::vector<double> coords = mesh.coords;
  const int base = mesh.numNodes();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ang(0.15, 1.4), gapDist(-0.05, 0.1);
  std::vector<int> slaves;
  std::vector<double> exactGap;
  for (int k = 0; k < 60; ++k) {
    // A direction in the lower octant below the centre (0, 0, 1), away from the symmetry planes.
    const double th = ang(rng) * 0.5, ph = ang(rng);
    const double ux = std::sin(th) * std::cos(ph), uy = std::sin(th) * std::sin(ph),
                 uz = -std::cos(th);
    const double g = gapDist(rng);
    coords.insert(coords.end(), {(1 + g) * ux, (1 + g) * uy, 1.0 + (1 + g) * uz});
    slaves.push_back(base + k);
    exactGap.push_back(g);
  }
  const ContactRowsResult r = contact::computeNodeToFace(coords, slaves, m, radius(0.3));
  TEST_EQUALITY(r.rows.size(), slaves.size());
  double worstGap = 0.0, worstOrth = 0.0;
  for (std::size_t k = 0; k < r.rows.size(); ++k) {
    const auto& row = r.rows[k];
    worstGap = std::max(worstGap, std::abs(row.gap - exactGap[k]));
    // Closest point: x_s - x_m is along the normal (interior) and |gap| is the distance.
    const double* x = &coords[3 * row.slaveNode];
    const std::array<double, 3> d{x[0] - row.point[0], x[1] - row.point[1], x[2] - row.point[2]};
    const double dd = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const std::array<double, 3> dxn{d[1] * row.normal[2] - d[2] * row.normal[1],
                                    d[2] * row.normal[0] - d[0] * row.normal[2],
                                    d[0] * row.normal[1] - d[1] * row.normal[0]};
    if (row.kind == ProjectionKind::Interior)
      worstOrth =
          std::max(worstOrth, std::sqrt(dxn[0] * dxn[0] + dxn[1] * dxn[1] + dxn[2] * dxn[2]));
    TEST_COMPARE(std::abs(std::abs(row.gap) - dd), <, 1e-12);
    // The normal points away from the centre (0, 0, 1).
    TEST_COMPARE(row.normal[0] * row.point[0] + row.normal[1] * row.point[1] +
                     row.normal[2] * (row.point[2] - 1.0),
                 >, 0.95);
  }
  out << "worst |gap - exact| = " << worstGap << ", worst tangential offset = " << worstOrth
      << "\n";
  TEST_COMPARE(worstOrth, <, 1e-10);
  TEST_COMPARE(worstGap, <, 2e-3);  // the quadratic faces' distance from the sphere (h = 0.4)
  // The row is the first-order expansion of the gap: the error drops ~4x when eps halves.
  const double e1 = linearizationError(coords, slaves, m, 1e-3, 11);
  const double e2 = linearizationError(coords, slaves, m, 5e-4, 11);
  out << "linearization error " << e1 << " (eps 1e-3), " << e2 << " (eps 5e-4)\n";
  TEST_COMPARE(e1, <, 1e-4);
  TEST_COMPARE(e2, <, 0.35 * e1);
}

TEUCHOS_UNIT_TEST(NodeToFace, WarpedQuad4Faces) {
  // The saddle z = c x y over (0, 3)^2 on a grid of unit squares: bilinear, so the Quad4 faces
  // through its grid points (each warped: its corners are not coplanar) are the saddle exactly.
  // A slave node at distance g along the saddle's normal from a point p has p as its closest
  // point and g as its gap (|g| well below the curvature radius, >= 1/c). Strong warping makes
  // the closest-point Newton need the face's mixed derivative x_xi_eta, which a bilinear face
  // has although x_xi_xi = x_eta_eta = 0.
  const double c = 2.0;
  std::vector<double> coords;
  MasterFaceSurface m = planeGrid(3, false, coords);
  for (std::size_t k = 0; k < coords.size(); k += 3) coords[k + 2] = c * coords[k] * coords[k + 1];
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> frac(0.05, 0.95), gapDist(-0.15, 0.3);
  std::uniform_int_distribution<int> cell(0, 2);
  const int base = static_cast<int>(coords.size() / 3);
  std::vector<int> slaves;
  std::vector<std::array<double, 4>> exact;  // p and g
  for (int k = 0; k < 60; ++k) {
    const double x = cell(rng) + frac(rng), y = cell(rng) + frac(rng), g = gapDist(rng);
    const double nn = std::sqrt(c * c * (x * x + y * y) + 1.0);
    const double n[3] = {-c * y / nn, -c * x / nn, 1.0 / nn};
    coords.insert(coords.end(), {x + g * n[0], y + g * n[1], c * x * y + g * n[2]});
    slaves.push_back(base + k);
    exact.push_back({x, y, c * x * y, g});
  }
  const ContactRowsResult r = contact::computeNodeToFace(coords, slaves, m, radius(0.5));
  TEST_EQUALITY(r.rows.size(), slaves.size());
  double worstPoint = 0.0, worstGap = 0.0, worstNormal = 0.0;
  for (std::size_t k = 0; k < r.rows.size(); ++k) {
    const auto& row = r.rows[k];
    const auto& e = exact[k];
    const double nn = std::sqrt(c * c * (e[0] * e[0] + e[1] * e[1]) + 1.0);
    worstPoint =
        std::max(worstPoint, std::abs(row.point[0] - e[0]) + std::abs(row.point[1] - e[1]) +
                                 std::abs(row.point[2] - e[2]));
    worstGap = std::max(worstGap, std::abs(row.gap - e[3]));
    worstNormal = std::max(worstNormal, std::abs(row.normal[0] + c * e[1] / nn) +
                                            std::abs(row.normal[1] + c * e[0] / nn) +
                                            std::abs(row.normal[2] - 1.0 / nn));
    TEST_EQUALITY(static_cast<int>(row.kind), static_cast<int>(ProjectionKind::Interior));
  }
  out << "worst |x_m - p| " << worstPoint << ", |gap - g| " << worstGap << ", normal "
      << worstNormal << "\n";
  TEST_COMPARE(worstPoint, <, 1e-12);
  TEST_COMPARE(worstGap, <, 1e-12);
  TEST_COMPARE(worstNormal, <, 1e-12);
  // The row is the first-order expansion of the gap on warped faces too.
  const double e1 = linearizationError(coords, slaves, m, 1e-3, 13);
  const double e2 = linearizationError(coords, slaves, m, 5e-4, 13);
  out << "linearization error " << e1 << " (eps 1e-3), " << e2 << " (eps 5e-4)\n";
  TEST_COMPARE(e1, <, 1e-4);
  TEST_COMPARE(e2, <, 0.35 * e1);
}

TEUCHOS_UNIT_TEST(NodeToFace, EdgesCornersAndFreeEdges) {
  // A roof: two Quad4 faces meeting at the ridge x = 0 (z = 1 - |x|), y in (0, 1).
  std::vector<double> coords{-1, 0, 0, 0, 0, 1, 1, 0, 0, -1, 1, 0, 0, 1, 1, 1, 1, 0};
  MasterFaceSurface roof;
  roof.type = ElementType::Quad4;
  roof.faces = {0, 1, 4, 3, 1, 2, 5, 4};  // normals (-1, 0, 1)/sqrt2 and (1, 0, 1)/sqrt2
  coords.insert(coords.end(),
                {0.05, 0.5, 1.2, 0.0, 0.5, 0.9, 0.5, 1.3, 0.7, 0.5, -0.2, 0.7, 0.0, 0.5, 1.0});
  const ContactRowsResult r =
      contact::computeNodeToFace(coords, {6, 7, 8, 9, 10}, roof, radius(0.5));
  // Node 6 above the ridge, in the wedge of normals: the closest point is the ridge point
  // (0, 0.5, 1), the normal points to the node and the gap is the distance.
  for (const auto& row : r.rows)
    out << "node " << row.slaveNode << " kind " << static_cast<int>(row.kind) << " gap " << row.gap
        << "\n";
  out << "beyond end " << r.beyondEnd << ", beyond radius " << r.beyondRadius << "\n";
  TEST_EQUALITY(r.rows.size(), 3u);
  TEST_EQUALITY(r.beyondEnd, 2);  // nodes 8, 9: beyond the free edges y = 1 and y = 0
  const auto& a = r.rows[0];
  TEST_EQUALITY(static_cast<int>(a.kind), static_cast<int>(ProjectionKind::Edge));
  const double dist = std::hypot(0.05, 0.2);
  TEST_COMPARE(std::abs(a.gap - dist), <, 1e-13);
  TEST_COMPARE(std::abs(a.normal[0] - 0.05 / dist) + std::abs(a.normal[2] - 0.2 / dist), <, 1e-13);
  // Node 7 under the ridge (0.1 below it): its feet on both faces' planes are inside the faces
  // and closer than the ridge: an interior row of the first face, gap -0.1/sqrt2.
  const auto& b = r.rows[1];
  TEST_EQUALITY(static_cast<int>(b.kind), static_cast<int>(ProjectionKind::Interior));
  TEST_COMPARE(std::abs(b.normal[2] - 1.0 / std::sqrt(2.0)), <, 1e-13);
  TEST_COMPARE(std::abs(b.gap + 0.1 / std::sqrt(2.0)), <, 1e-13);
  // Node 10 on the ridge: the averaged normal (0, 0, 1), gap 0.
  const auto& e = r.rows[2];
  TEST_EQUALITY(static_cast<int>(e.kind), static_cast<int>(ProjectionKind::Edge));
  TEST_COMPARE(std::abs(e.normal[2] - 1.0), <, 1e-13);
  TEST_COMPARE(std::abs(e.gap), <, 1e-15);
  // Clamp keeps the nodes beyond the free edges, with the face's plane as the obstacle.
  ContactSearchOptions clamp = radius(0.5);
  clamp.endPolicy = contact::EndPolicy::Clamp;
  const ContactRowsResult c = contact::computeNodeToFace(coords, {8}, roof, clamp);
  TEST_EQUALITY(c.rows.size(), 1u);
  TEST_EQUALITY(static_cast<int>(c.rows[0].kind), static_cast<int>(ProjectionKind::End));
  // Node 8 (0.5, 1.3, 0.7) against the plane z = 1 - x of the right face: (0.7 - 0.5)/sqrt2.
  TEST_COMPARE(std::abs(c.rows[0].gap - 0.2 / std::sqrt(2.0)), <, 1e-13);

  // A vertex: the apex of a pyramid of four triangles (apex 4 at (0, 0, 1)).
  std::vector<double> p{-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0, 0, 0, 1, 0.1, 0.05, 1.3};
  MasterFaceSurface pyr;
  pyr.faces = {0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
  const ContactRowsResult v = contact::computeNodeToFace(p, {5}, pyr, radius(0.5));
  TEST_EQUALITY(v.rows.size(), 1u);
  TEST_EQUALITY(static_cast<int>(v.rows[0].kind), static_cast<int>(ProjectionKind::Corner));
  TEST_COMPARE(std::abs(v.rows[0].gap - std::sqrt(0.01 + 0.0025 + 0.09)), <, 1e-13);

  // A node clearly off the apex, inside its cone, gets the direction to it.
  p.insert(p.end(), {1e-4, 0.0, 1.0 + 3e-4});
  const ContactRowsResult off = contact::computeNodeToFace(p, {6}, pyr, radius(0.5));
  TEST_EQUALITY(off.rows.size(), 1u);
  if (off.rows.size() == 1) {
    const double dist = std::hypot(1e-4, 3e-4);
    TEST_EQUALITY(static_cast<int>(off.rows[0].kind), static_cast<int>(ProjectionKind::Corner));
    TEST_COMPARE(std::abs(off.rows[0].normal[0] - 1e-4 / dist), <, 1e-12);
    TEST_COMPARE(std::abs(off.rows[0].gap - dist), <, 1e-15);
  }
  // The corner of a flat master cut by two symmetry planes (the nonlinear Hertz sphere's axis
  // node): the slave node sits on it up to the solver's noise, held on the planes to 1e-12. d is
  // then mostly sideways, and d / |d| would make the row nearly a combination of the symmetry
  // rows, whose multiplier then drifts. Below kCornerSnap * size the averaged normal is kept.
  std::vector<double> q{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1e-12, -5e-12, 1e-12};
  MasterFaceSurface flat;
  flat.type = ElementType::Quad4;
  flat.faces = {0, 1, 2, 3};
  const ContactRowsResult noisy = contact::computeNodeToFace(q, {4}, flat, radius(0.5));
  TEST_EQUALITY(noisy.rows.size(), 1u);
  if (noisy.rows.size() == 1) {
    TEST_EQUALITY(static_cast<int>(noisy.rows[0].kind), static_cast<int>(ProjectionKind::Corner));
    TEST_COMPARE(std::abs(noisy.rows[0].normal[2] - 1.0), <, 1e-14);
    TEST_COMPARE(std::abs(noisy.rows[0].gap - 1e-12), <, 1e-20);
  }
}

TEUCHOS_UNIT_TEST(NodeToFace, GridSearchEqualsBruteForceAndStaysNearLinear) {
  long long prevCand = 0;
  std::size_t prevSlaves = 0;
  for (double factor : {1.0, 0.5}) {
    contact::MeshOptions o;
    o.sizeFactor = factor;
    const contact::GmshMesh mesh = contact::loadMesh(kMeshDir + "/sphere_on_block.geo", o);
    // Block nodes against the sphere and sphere nodes against the block.
    for (int pass = 0; pass < 2; ++pass) {
      const auto& master = mesh.boundary(pass == 0 ? "sphere_contact" : "block_contact");
      const auto& slave = mesh.boundary(pass == 0 ? "block_contact" : "sphere_contact");
      const MasterFaceSurface m = masterFacesOfBoundary(mesh, master);
      std::vector<int> slaves(slave.edges.begin(), slave.edges.end());
      std::sort(slaves.begin(), slaves.end());
      slaves.erase(std::unique(slaves.begin(), slaves.end()), slaves.end());
      // A search radius of a few elements, as in use (it scales with the mesh size).
      ContactSearchOptions grid = radius(0.3 * factor), brute = radius(0.3 * factor);
      brute.bruteForce = true;
      const ContactRowsResult a = contact::computeNodeToFace(mesh.coords, slaves, m, grid);
      const ContactRowsResult b = contact::computeNodeToFace(mesh.coords, slaves, m, brute);
      TEST_EQUALITY(a.rows.size(), b.rows.size());
      TEST_COMPARE(a.rows.size(), >, 0u);
      for (std::size_t k = 0; k < std::min(a.rows.size(), b.rows.size()); ++k) {
        TEST_EQUALITY(a.rows[k].slaveNode, b.rows[k].slaveNode);
        TEST_EQUALITY(a.rows[k].facet, b.rows[k].facet);
        TEST_EQUALITY(a.rows[k].gap, b.rows[k].gap);
      }
      TEST_EQUALITY(a.beyondRadius, b.beyondRadius);
      TEST_EQUALITY(b.candidatePairs, b.allPairs);
      out << "size factor " << factor << ", pass " << pass << ": " << slaves.size()
          << " slave nodes, " << m.numFaces() << " faces, pairs examined " << a.candidatePairs
          << " of " << a.allPairs << ", rows " << a.rows.size() << "\n";
      TEST_COMPARE(a.candidatePairs, <, a.allPairs / 4);
      if (pass == 0) {
        // Refining by 2 multiplies the surface nodes by ~4: the pairs examined per slave node
        // stay bounded (the all-pairs count per node grows ~4x).
        if (prevSlaves > 0)
          TEST_COMPARE(double(a.candidatePairs) / slaves.size(), <,
                       2.0 * double(prevCand) / prevSlaves);
        prevCand = a.candidatePairs;
        prevSlaves = slaves.size();
      }
    }
  }
}

TEUCHOS_UNIT_TEST(NodeToFace, BadInput) {
  std::vector<double> coords;
  MasterFaceSurface m = planeGrid(2, false, coords);
  coords.insert(coords.end(), {0.5, 0.5, 0.1});
  TEST_THROW(contact::computeNodeToFace(coords, {9}, m, radius(0.0)), std::invalid_argument);
  TEST_THROW(contact::computeNodeToFace(coords, {10}, m, radius(1.0)), std::invalid_argument);
  TEST_THROW(contact::computeNodeToFace({0, 0}, {}, m, radius(1.0)), std::invalid_argument);
  MasterFaceSurface flipped = m;
  std::swap(flipped.faces[1], flipped.faces[3]);  // face 0 now points down
  TEST_ASSERT(!contact::findFaceOrientationErrors(flipped).empty());
  TEST_THROW(contact::computeNodeToFace(coords, {9}, flipped, radius(1.0)), std::invalid_argument);
  MasterFaceSurface lines = m;
  lines.type = ElementType::Line2;
  TEST_THROW(contact::computeNodeToFace(coords, {9}, lines, radius(1.0)), std::invalid_argument);
  TEST_ASSERT(contact::findFaceOrientationErrors(m).empty());
  const contact::GmshMesh mesh2d = contact::loadMesh(kMeshDir + "/rectangle.geo");
  TEST_THROW(masterFacesOfBoundary(mesh2d, mesh2d.boundaries[0]), std::invalid_argument);
}

}  // namespace
