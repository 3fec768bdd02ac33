#include "contact_RigidObstacle.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace contact {

namespace {

std::string vectorName(const char* field, int component) {
  return std::string("rigid obstacle: ") + field + "[" + std::to_string(component) + "]";
}

// v / |v|, scaled by its largest component first so that |v|^2 cannot overflow (1e300).
std::array<double, 3> unit(const std::array<double, 3>& v, int dim) {
  double big = 0.0;
  for (int i = 0; i < dim; ++i) big = std::max(big, std::abs(v[i]));
  std::array<double, 3> u{};
  double len = 0.0;
  for (int i = 0; i < dim; ++i) u[i] = v[i] / big, len += u[i] * u[i];
  len = std::sqrt(len);
  for (int i = 0; i < dim; ++i) u[i] /= len;
  return u;
}

// The height-function gap of the node at x along the unit direction d: the first t with x + t d
// on the obstacle's surface (negative when x is inside it); row normal -d. False when the line
// misses a ball.
bool gapAlong(const RigidObstacle& o, const std::array<double, 3>& x,
              const std::array<double, 3>& d, ContactRow& row) {
  const int dim = o.dim;
  double t = 0.0;
  if (o.shape == RigidObstacle::Shape::HalfSpace) {
    const std::array<double, 3> n = unit(o.normal, dim);
    double xn = 0.0, dn = 0.0;
    for (int i = 0; i < dim; ++i) xn += (x[i] - o.point[i]) * n[i], dn += d[i] * n[i];
    t = -xn / dn;  // dn < 0 (validate)
  } else {
    // |x + t d - c|^2 = R^2: t^2 + 2 (w . d) t + |w|^2 - R^2 = 0 with w = x - c.
    double wd = 0.0, ww = 0.0;
    for (int i = 0; i < dim; ++i) {
      const double w = x[i] - o.point[i];
      wd += w * d[i], ww += w * w;
    }
    const double disc = wd * wd - (ww - o.radius * o.radius);
    if (disc < 0.0) return false;
    t = -wd - std::sqrt(disc);
  }
  row.gap = t;
  for (int i = 0; i < dim; ++i) {
    row.normal[i] = -d[i];
    row.point[i] = x[i] + t * d[i];
  }
  return true;
}

}  // namespace

void RigidObstacle::validate() const {
  if (dim != 2 && dim != 3)
    throw std::invalid_argument("rigid obstacle: dimension " + std::to_string(dim) +
                                " is not 2 or 3");
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(point[i]))
      throw std::invalid_argument(vectorName(shape == Shape::Ball ? "centre" : "point", i) +
                                  " is not finite");
    if (!std::isfinite(normal[i]))
      throw std::invalid_argument(vectorName("normal", i) + " is not finite");
    if (!std::isfinite(gapDirection[i]))
      throw std::invalid_argument(vectorName("gap direction", i) + " is not finite");
  }
  if (dim == 2 && gapDirection[2] != 0.0)
    throw std::invalid_argument("rigid obstacle: a 2D obstacle's gap direction has no z component");
  if (heightFunction() && shape == Shape::HalfSpace) {
    double dn = 0.0;
    for (int i = 0; i < 3; ++i) dn += gapDirection[i] * normal[i];
    if (!(dn < 0.0))
      throw std::invalid_argument(
          "rigid obstacle: the gap direction must point into the half-space (against its "
          "outward normal): gap direction . normal = " +
          std::to_string(dn));
  }
  if (dim == 2 && (point[2] != 0.0 || (shape == Shape::HalfSpace && normal[2] != 0.0)))
    throw std::invalid_argument("rigid obstacle: a 2D obstacle has no z component");
  if (shape == Shape::HalfSpace) {
    const double len =
        std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    if (!(len > 0.0)) throw std::invalid_argument("rigid obstacle: the normal is zero");
  } else if (!(radius > 0.0) || !std::isfinite(radius)) {
    throw std::invalid_argument("rigid obstacle: the radius (\"Radius\") = " +
                                std::to_string(radius) + " must be positive and finite");
  }
}

RigidObstacle::Shape obstacleShapeFromName(const std::string& name, int dim) {
  const char* half = dim == 3 ? "plane" : "line";
  const char* ball = dim == 3 ? "sphere" : "circle";
  if (name == half) return RigidObstacle::Shape::HalfSpace;
  if (name == ball) return RigidObstacle::Shape::Ball;
  throw std::invalid_argument("rigid obstacle type \"" + name + "\" is not valid in " +
                              std::to_string(dim) + "D; valid: \"" + half + "\", \"" + ball + "\"");
}

ContactRowsResult computeObstacleRows(const RigidObstacle& obstacle,
                                      const std::vector<double>& coords,
                                      const std::vector<int>& slaveNodes,
                                      const ContactSearchOptions& options,
                                      const std::vector<double>& displacement) {
  obstacle.validate();
  validateSearchOptions(options, "computeObstacleRows");
  const int dim = obstacle.dim;
  if (coords.size() % dim != 0)
    throw std::invalid_argument("computeObstacleRows: coords must hold " + std::to_string(dim) +
                                " values per node");
  if (!displacement.empty() && displacement.size() != coords.size())
    throw std::invalid_argument("computeObstacleRows: the displacement must be empty or hold " +
                                std::to_string(dim) + " values per node");
  const int numNodes = static_cast<int>(coords.size()) / dim;
  std::array<double, 3> n0{};
  if (obstacle.shape == RigidObstacle::Shape::HalfSpace) {
    double len = 0.0;
    for (int i = 0; i < dim; ++i) len += obstacle.normal[i] * obstacle.normal[i];
    len = std::sqrt(len);
    for (int i = 0; i < dim; ++i) n0[i] = obstacle.normal[i] / len;
  }
  const bool along = obstacle.heightFunction();
  const std::array<double, 3> d = along ? unit(obstacle.gapDirection, dim) : n0;
  ContactRowsResult result;
  result.allPairs = static_cast<long long>(slaveNodes.size());
  for (int s : slaveNodes) {
    if (s < 0 || s >= numNodes)
      throw std::invalid_argument("computeObstacleRows: slave node " + std::to_string(s) +
                                  " outside 0.." + std::to_string(numNodes - 1));
    ++result.candidatePairs;
    std::array<double, 3> x{};
    for (int i = 0; i < dim; ++i)
      x[i] = coords[dim * s + i] + (displacement.empty() ? 0.0 : displacement[dim * s + i]);
    if (along && obstacle.heightAtReference && !displacement.empty()) {
      // Only the displacement along d moves the node relative to the height function.
      double ud = 0.0;
      for (int i = 0; i < dim; ++i) ud += displacement[dim * s + i] * d[i];
      for (int i = 0; i < dim; ++i) x[i] = coords[dim * s + i] + ud * d[i];
    }
    ContactRow row;
    row.slaveNode = s;
    if (along) {
      if (!gapAlong(obstacle, x, d, row)) {
        ++result.beyondRadius;  // the line along d misses the ball
        continue;
      }
    } else if (obstacle.shape == RigidObstacle::Shape::HalfSpace) {
      row.normal = n0;
      for (int i = 0; i < dim; ++i) row.gap += (x[i] - obstacle.point[i]) * n0[i];
      for (int i = 0; i < dim; ++i) row.point[i] = x[i] - row.gap * n0[i];
    } else {
      double dist = 0.0;
      for (int i = 0; i < dim; ++i) dist += (x[i] - obstacle.point[i]) * (x[i] - obstacle.point[i]);
      dist = std::sqrt(dist);
      if (!(dist > 1e-12 * obstacle.radius))
        throw std::invalid_argument("computeObstacleRows: slave node " + std::to_string(s) +
                                    " is at the obstacle's centre (no normal)");
      for (int i = 0; i < dim; ++i) {
        row.normal[i] = (x[i] - obstacle.point[i]) / dist;
        row.point[i] = obstacle.point[i] + obstacle.radius * row.normal[i];
      }
      row.gap = dist - obstacle.radius;
    }
    if (std::abs(row.gap) > options.searchRadius) {
      ++result.beyondRadius;
      continue;
    }
    for (int i = 0; i < dim; ++i) row.entries.push_back({s, i, -row.normal[i]});
    result.rows.push_back(std::move(row));
  }
  return result;
}

}  // namespace contact
