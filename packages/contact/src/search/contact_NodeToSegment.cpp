#include "contact_NodeToSegment.hpp"

#include "contact_BucketGrid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace contact {

namespace {

using Vec = std::array<double, 2>;

Vec operator+(const Vec& a, const Vec& b) {
  return {a[0] + b[0], a[1] + b[1]};
}
Vec operator-(const Vec& a, const Vec& b) {
  return {a[0] - b[0], a[1] - b[1]};
}
Vec operator*(double s, const Vec& a) {
  return {s * a[0], s * a[1]};
}
double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1];
}
double norm(const Vec& a) {
  return std::hypot(a[0], a[1]);
}
// Outward normal of a tangent dx/dxi under the body-on-the-left convention.
Vec outwardNormal(const Vec& t) {
  const double len = norm(t);
  return {t[1] / len, -t[0] / len};
}

void shapeFunctions(int nodesPerSegment, double xi, double* n) {
  if (nodesPerSegment == 2) {
    n[0] = 0.5 * (1.0 - xi);
    n[1] = 0.5 * (1.0 + xi);
  } else {
    n[0] = 0.5 * xi * (xi - 1.0);
    n[1] = 0.5 * xi * (xi + 1.0);
    n[2] = 1.0 - xi * xi;
  }
}

// x(xi) = c0 + c1 xi + c2 xi^2, the monomial form of the Gmsh line, which makes the Newton
// derivatives and the bounding box cheap.
struct SegmentGeometry {
  Vec c0, c1, c2;
  Vec at(double xi) const { return c0 + xi * c1 + (xi * xi) * c2; }
  Vec tangent(double xi) const { return c1 + (2.0 * xi) * c2; }
  double chord() const { return 2.0 * norm(c1); }
};

SegmentGeometry makeGeometry(const Vec& a, const Vec& b, const Vec* m) {
  SegmentGeometry g;
  g.c1 = 0.5 * (b - a);
  if (m) {
    g.c0 = *m;
    g.c2 = 0.5 * (a + b) - *m;
  } else {
    g.c0 = 0.5 * (a + b);
    g.c2 = {0.0, 0.0};
  }
  return g;
}

struct Projection {
  double xi = 0.0;
  Vec point{};
  double dist2 = std::numeric_limits<double>::infinity();
  bool clamped = false;  // xi is an end of [-1, 1] because the minimum lies beyond it
};

Projection project(const SegmentGeometry& g, bool quadratic, const Vec& xs, int maxIterations) {
  const double c1c1 = dot(g.c1, g.c1);
  // The chord projection: exact for a straight segment, the Newton start for a curved one.
  double xi = std::clamp(dot(xs - g.c0 - g.c2, g.c1) / c1c1, -1.0, 1.0);
  if (quadratic) {
    for (int it = 0; it < maxIterations; ++it) {
      const Vec d = g.at(xi) - xs;
      const Vec t = g.tangent(xi);
      const double r = dot(d, t), tt = dot(t, t);
      double h = tt + 2.0 * dot(d, g.c2);
      // Far on the concave side the exact Hessian is small or negative and Newton would run
      // away; the Gauss-Newton term alone is always a descent direction.
      if (h < 0.1 * tt) h = tt;
      const double next = std::clamp(xi - r / h, -1.0, 1.0);
      const bool done = std::abs(next - xi) <= 1e-15;
      xi = next;
      if (done) break;
    }
  }
  Projection p;
  p.xi = xi;
  p.point = g.at(xi);
  p.dist2 = dot(p.point - xs, p.point - xs);
  if (quadratic) {
    // |x(xi) - x_s|^2 is a quartic and may have a second local minimum: the ends are the only
    // other candidates Newton could have missed within the clamped interval.
    for (double end : {-1.0, 1.0}) {
      const Vec x = g.at(end);
      const double d2 = dot(x - xs, x - xs);
      if (d2 < p.dist2) {
        p.xi = end;
        p.point = x;
        p.dist2 = d2;
      }
    }
  }
  // The minimum is at an end because it lies beyond it when the distance still decreases
  // outward there (the projected xi of a straight segment was clamped).
  if (p.xi == 1.0 || p.xi == -1.0) {
    const Vec outward = p.xi * g.tangent(p.xi);
    p.clamped = dot(xs - p.point, outward) > 0.0;
  }
  return p;
}

std::string nodeList(const std::vector<int>& nodes) {
  std::ostringstream s;
  const std::size_t shown = std::min<std::size_t>(nodes.size(), 10);
  for (std::size_t i = 0; i < shown; ++i) s << (i ? ", " : "") << nodes[i];
  if (nodes.size() > shown) s << ", ... (" << nodes.size() << " nodes)";
  return s.str();
}

void checkSurface(const MasterSurface& master, int numNodes, const char* who) {
  const int nps = master.nodesPerSegment;
  if (nps != 2 && nps != 3)
    throw std::invalid_argument(std::string(who) + ": nodesPerSegment must be 2 or 3, not " +
                                std::to_string(nps));
  if (master.segments.size() % nps != 0)
    throw std::invalid_argument(std::string(who) + ": the segment list's size " +
                                std::to_string(master.segments.size()) +
                                " is not a multiple of nodesPerSegment");
  for (int s = 0; s < master.numSegments(); ++s) {
    const int* seg = &master.segments[static_cast<std::size_t>(s) * nps];
    for (int k = 0; k < nps; ++k)
      if (seg[k] < 0 || seg[k] >= numNodes)
        throw std::invalid_argument(std::string(who) + ": segment " + std::to_string(s) +
                                    " has node " + std::to_string(seg[k]) + " outside 0.." +
                                    std::to_string(numNodes - 1));
    if (seg[0] == seg[1])
      throw std::invalid_argument(std::string(who) + ": segment " + std::to_string(s) +
                                  " starts and ends at node " + std::to_string(seg[0]));
  }
}

int flipWhereNotLeft(MasterSurface& master, const std::vector<double>& coords,
                     const std::function<Vec(int)>& pointOf, const char* who) {
  checkSurface(master, static_cast<int>(coords.size() / 2), who);
  const int nps = master.nodesPerSegment;
  int flipped = 0;
  for (int s = 0; s < master.numSegments(); ++s) {
    int* seg = &master.segments[static_cast<std::size_t>(s) * nps];
    const Vec a{coords[2 * seg[0]], coords[2 * seg[0] + 1]};
    const Vec b{coords[2 * seg[1]], coords[2 * seg[1] + 1]};
    const Vec p = pointOf(s);
    const Vec ab = b - a, ap = p - a;
    const double cross = ab[0] * ap[1] - ab[1] * ap[0];
    // A point on the chord's line gives no side; relative to |ab| |ap| so that the test does not
    // depend on the mesh's units.
    if (!(std::abs(cross) > 1e-12 * norm(ab) * norm(ap)))
      throw std::invalid_argument(std::string(who) + ": the interior point of segment " +
                                  std::to_string(s) + " lies on the segment's line");
    if (cross < 0.0) {
      std::swap(seg[0], seg[1]);
      ++flipped;
    }
  }
  return flipped;
}

}  // namespace

std::vector<int> findOrientationErrors(const MasterSurface& master) {
  const int nps = master.nodesPerSegment;
  if (nps != 2 && nps != 3) throw std::invalid_argument("findOrientationErrors: nodesPerSegment");
  std::unordered_map<int, std::array<int, 2>> count;  // starts, ends
  for (int s = 0; s < master.numSegments(); ++s) {
    ++count[master.segments[static_cast<std::size_t>(s) * nps]][0];
    ++count[master.segments[static_cast<std::size_t>(s) * nps + 1]][1];
  }
  std::vector<int> bad;
  for (const auto& [node, c] : count)
    if (c[0] > 1 || c[1] > 1) bad.push_back(node);
  std::sort(bad.begin(), bad.end());
  return bad;
}

NodeToSegmentResult computeNodeToSegment(const std::vector<double>& coords,
                                         const std::vector<int>& slaveNodes,
                                         const MasterSurface& master,
                                         const NodeToSegmentOptions& options,
                                         const std::vector<double>& displacement) {
  const char* who = "computeNodeToSegment";
  if (coords.size() % 2 != 0)
    throw std::invalid_argument("computeNodeToSegment: coords must hold x, y per node");
  const int numNodes = static_cast<int>(coords.size() / 2);
  if (!displacement.empty() && displacement.size() != coords.size())
    throw std::invalid_argument(
        "computeNodeToSegment: the displacement must be empty or hold x, y per node (" +
        std::to_string(coords.size()) + " values), not " + std::to_string(displacement.size()));
  validateSearchOptions(options, who);
  checkSurface(master, numNodes, who);
  for (int s : slaveNodes)
    if (s < 0 || s >= numNodes)
      throw std::invalid_argument("computeNodeToSegment: slave node " + std::to_string(s) +
                                  " outside 0.." + std::to_string(numNodes - 1));
  // Corners need each segment's neighbours, and a neighbour running the other way would turn
  // the outward normal inward on one side of the corner.
  const std::vector<int> bad = findOrientationErrors(master);
  if (!bad.empty())
    throw std::invalid_argument(
        "computeNodeToSegment: the master surface is not a head-to-tail chain (inconsistently "
        "oriented or branching segments) at node(s) " +
        nodeList(bad) + "; orient it with orientSegmentsByElements or orientSegmentsByPoints");

  const int nps = master.nodesPerSegment, numSegments = master.numSegments();
  const bool quadratic = nps == 3;
  auto position = [&](int n) -> Vec {
    Vec x{coords[2 * n], coords[2 * n + 1]};
    if (!displacement.empty()) x = x + Vec{displacement[2 * n], displacement[2 * n + 1]};
    return x;
  };
  auto segNode = [&](int s, int k) {
    return master.segments[static_cast<std::size_t>(s) * nps + k];
  };

  std::vector<SegmentGeometry> geom(numSegments);
  std::vector<double> boxes(4 * static_cast<std::size_t>(numSegments));
  std::unordered_map<int, int> startsAt;  // node -> the segment whose a it is
  double extentSum = 0.0;
  for (int s = 0; s < numSegments; ++s) {
    const Vec a = position(segNode(s, 0)), b = position(segNode(s, 1));
    Vec m;
    if (quadratic) m = position(segNode(s, 2));
    geom[s] = makeGeometry(a, b, quadratic ? &m : nullptr);
    if (!(norm(geom[s].c1) > 0.0))
      throw std::invalid_argument("computeNodeToSegment: segment " + std::to_string(s) +
                                  " has zero length");
    // The curve lies in the convex hull of its Bezier control points a, b and c0 - c2.
    const Vec q = geom[s].c0 - geom[s].c2;
    const double r = options.searchRadius;
    double* box = &boxes[4 * static_cast<std::size_t>(s)];
    box[0] = std::min({a[0], b[0], q[0]}) - r, box[1] = std::min({a[1], b[1], q[1]}) - r;
    box[2] = std::max({a[0], b[0], q[0]}) + r, box[3] = std::max({a[1], b[1], q[1]}) + r;
    extentSum += std::max(box[2] - box[0], box[3] - box[1]) - 2.0 * r;
    startsAt[segNode(s, 0)] = s;
  }
  std::vector<int> next(numSegments, -1), prev(numSegments, -1);
  for (int s = 0; s < numSegments; ++s) {
    const auto it = startsAt.find(segNode(s, 1));
    if (it != startsAt.end()) {
      next[s] = it->second;
      prev[it->second] = s;
    }
  }

  NodeToSegmentResult result;
  result.allPairs = static_cast<long long>(slaveNodes.size()) * numSegments;
  std::unique_ptr<BucketGrid> grid;
  std::vector<int> everySegment;
  if (options.bruteForce) {
    everySegment.resize(numSegments);
    for (int s = 0; s < numSegments; ++s) everySegment[s] = s;
  } else if (numSegments > 0) {
    const double h = options.cellSize > 0.0
                         ? options.cellSize
                         : std::max(extentSum / numSegments, options.searchRadius);
    grid = std::make_unique<BucketGrid>(2, boxes, h);
    result.gridCells = grid->occupiedCells();
    result.cellSize = grid->cellSize();
  }

  std::vector<double> shape(nps);
  for (int slave : slaveNodes) {
    const Vec xs = position(slave);
    const std::vector<int>* cand = options.bruteForce ? &everySegment : nullptr;
    if (grid) cand = grid->candidates(xs.data());
    int best = -1;
    Projection bestP;
    if (cand) {
      for (int s : *cand) {
        // A node of the segment itself (self-contact of one surface) is not opposite it.
        bool own = false;
        for (int k = 0; k < nps; ++k) own = own || segNode(s, k) == slave;
        if (own) continue;
        ++result.candidatePairs;
        const Projection p = project(geom[s], quadratic, xs, options.maxNewtonIterations);
        // On a near tie (a node on the normal through a corner) an interior projection wins,
        // so the normal changes continuously as the node leaves the corner's cone.
        const double tie = 1e-12 * bestP.dist2;
        const bool better = best < 0 || p.dist2 < bestP.dist2 - tie ||
                            (p.dist2 <= bestP.dist2 + tie && bestP.clamped && !p.clamped);
        if (better) {
          best = s;
          bestP = p;
        }
      }
    }
    if (best < 0 || std::sqrt(bestP.dist2) > options.searchRadius) {
      ++result.beyondRadius;
      continue;
    }
    const SegmentGeometry& g = geom[best];
    // A node on a vertex (to rounding) projects into both segments that meet there, and which
    // one is nearer is decided by rounding: its row would take either segment's normal, and a
    // node that sticks there keeps whichever it got (the 2D Cattaneo cylinders: the centre node
    // took one normal on 2 ranks and the other on 1 and 3). On the vertex it is a corner, with
    // the averaged normal from either side.
    if (!bestP.clamped && std::abs(bestP.xi) != 1.0 && 1.0 - std::abs(bestP.xi) < kVertexSnap &&
        (bestP.xi > 0.0 ? next[best] : prev[best]) >= 0) {
      bestP.xi = bestP.xi > 0.0 ? 1.0 : -1.0;
      bestP.point = g.at(bestP.xi);
    }
    const Vec d = xs - bestP.point;
    Vec n = outwardNormal(g.tangent(bestP.xi));
    ProjectionKind kind = ProjectionKind::Interior;
    const bool atEnd = bestP.xi == 1.0 || bestP.xi == -1.0;
    if (atEnd) {
      const int neighbour = bestP.xi > 0.0 ? next[best] : prev[best];
      if (neighbour >= 0) {
        kind = ProjectionKind::Corner;
        const Vec n2 = outwardNormal(geom[neighbour].tangent(-bestP.xi));
        const Vec sum = n + n2;
        // A fold back onto itself (n2 = -n) has no average direction: keep this segment's.
        const Vec avg = norm(sum) > 1e-12 ? (1.0 / norm(sum)) * sum : n;
        // d / |d| outside the corner's cone, unless d may be noise (kCornerSnap).
        const double dist = norm(d);
        n = (dist > kCornerSnap * g.chord() && dot(d, avg) > 0.0) ? (1.0 / dist) * d : avg;
      } else if (bestP.clamped) {
        const Vec outward = bestP.xi * g.tangent(bestP.xi);
        const double beyond = dot(d, outward) / norm(outward);
        if (beyond > options.endTolerance * g.chord()) {
          if (options.endPolicy == EndPolicy::Drop) {
            ++result.beyondEnd;
            continue;
          }
          kind = ProjectionKind::End;
        }
      }
    }
    NodeToSegmentRow row;
    row.slaveNode = slave;
    row.facet = best;
    row.xi = {bestP.xi, 0.0};
    row.kind = kind;
    row.point = {bestP.point[0], bestP.point[1], 0.0};
    row.normal = {n[0], n[1], 0.0};
    row.gap = dot(d, n);
    shapeFunctions(nps, bestP.xi, shape.data());
    row.entries.reserve(2 + 2 * nps);
    row.entries.push_back({slave, 0, -n[0]});
    row.entries.push_back({slave, 1, -n[1]});
    for (int k = 0; k < nps; ++k) {
      row.entries.push_back({segNode(best, k), 0, shape[k] * n[0]});
      row.entries.push_back({segNode(best, k), 1, shape[k] * n[1]});
    }
    result.rows.push_back(std::move(row));
  }
  return result;
}

int orientSegmentsByPoints(MasterSurface& master, const std::vector<double>& coords,
                           const std::vector<double>& interiorPoints) {
  if (interiorPoints.size() != 2 * static_cast<std::size_t>(std::max(master.numSegments(), 0)))
    throw std::invalid_argument("orientSegmentsByPoints: one interior point (x, y) per segment");
  return flipWhereNotLeft(
      master, coords,
      [&](int s) {
        return Vec{interiorPoints[2 * s], interiorPoints[2 * s + 1]};
      },
      "orientSegmentsByPoints");
}

int orientSegmentsTowardPoint(MasterSurface& master, const std::vector<double>& coords, double x,
                              double y) {
  return flipWhereNotLeft(
      master, coords,
      [&](int) {
        return Vec{x, y};
      },
      "orientSegmentsTowardPoint");
}

int orientSegmentsByElements(MasterSurface& master, const std::vector<double>& coords,
                             ElementType type, const std::vector<int>& connectivity) {
  const char* who = "orientSegmentsByElements";
  const int numNodes = static_cast<int>(coords.size() / 2);
  checkSurface(master, numNodes, who);
  const int npe = contact::numNodes(type), nc = numCorners(type);
  if (connectivity.size() % npe != 0)
    throw std::invalid_argument(
        "orientSegmentsByElements: connectivity size is not a multiple "
        "of the element's node count");
  auto key = [](int a, int b) {
    return (static_cast<long long>(std::min(a, b)) << 32) | static_cast<unsigned>(std::max(a, b));
  };
  // edge -> element, or -2 for an edge of two elements
  std::unordered_map<long long, int> edgeElement;
  const int numElements = static_cast<int>(connectivity.size()) / npe;
  for (int e = 0; e < numElements; ++e) {
    const int* el = &connectivity[static_cast<std::size_t>(e) * npe];
    for (int k = 0; k < nc; ++k) {
      if (el[k] < 0 || el[k] >= numNodes)
        throw std::invalid_argument("orientSegmentsByElements: element " + std::to_string(e) +
                                    " has node " + std::to_string(el[k]) + " outside 0.." +
                                    std::to_string(numNodes - 1));
      const auto [it, inserted] = edgeElement.emplace(key(el[k], el[(k + 1) % nc]), e);
      if (!inserted) it->second = -2;
    }
  }
  const int nps = master.nodesPerSegment;
  std::vector<double> points(2 * static_cast<std::size_t>(master.numSegments()));
  for (int s = 0; s < master.numSegments(); ++s) {
    const int a = master.segments[static_cast<std::size_t>(s) * nps];
    const int b = master.segments[static_cast<std::size_t>(s) * nps + 1];
    const auto it = edgeElement.find(key(a, b));
    if (it == edgeElement.end() || it->second < 0)
      throw std::invalid_argument("orientSegmentsByElements: segment " + std::to_string(s) +
                                  " (nodes " + std::to_string(a) + ", " + std::to_string(b) +
                                  ") is " +
                                  (it == edgeElement.end() ? "no element's edge"
                                                           : "an edge of two elements, not on "
                                                             "the boundary"));
    const int* el = &connectivity[static_cast<std::size_t>(it->second) * npe];
    // The corners' centroid is on the body side of every edge's chord for a valid (convex)
    // element, also when the edge itself is curved.
    double cx = 0.0, cy = 0.0;
    for (int k = 0; k < nc; ++k) {
      cx += coords[2 * el[k]];
      cy += coords[2 * el[k] + 1];
    }
    points[2 * s] = cx / nc;
    points[2 * s + 1] = cy / nc;
  }
  return orientSegmentsByPoints(master, coords, points);
}

}  // namespace contact
