// The load factor beyond which the contact and friction rows cannot hold the rigid motions the
// supports leave free (contact_RigidMotions.hpp, frictionLoadLimit): the linear program over
// those motions, the motion it gives evaluated exactly, and the words.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "contact_BoundedSimplex.hpp"
#include "contact_RigidModes.hpp"
#include "contact_RigidMotions.hpp"
#include "tfeti_CollectiveError.hpp"

namespace contact {

namespace {

using namespace rigid;

constexpr double kInf = std::numeric_limits<double>::infinity();

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

// The load's generalized forces on every piece's modes, r^T f for a motion r being their dot
// product: each rank its subdomains' loads, summed over the ranks.
std::vector<double> loadOnModes(const ElasticContactProblem& p, const Pieces& pieces,
                                const tfeti::Comm& comm) {
  const int dim = p.dim(), nm = modesPerPiece(dim), n = pieces.count * nm;
  std::vector<double> mine(n, 0.0), force(n, 0.0);
  for (const tfeti::SubdomainData& sd : p.local) {
    const int id = sd.mesh.id, q = pieces.ofSubdomain[id];
    const std::vector<double>& x = p.subdomains[id].coords;
    for (std::size_t d = 0; d < sd.f.size(); ++d) {
      if (sd.f[d] == 0.0) continue;
      addModeValues(pieces, q, dim, &x[dim * (d / dim)], static_cast<int>(d % dim), sd.f[d],
                    &mine[static_cast<std::size_t>(q) * nm]);
    }
  }
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, n, mine.data(), force.data());
  return force;
}

// The free motions' coordinates of a functional on the modes: (v . n_k) for each free n_k.
std::vector<double> onFree(const std::vector<std::vector<double>>& free,
                           const std::vector<double>& v) {
  std::vector<double> a(free.size());
  for (std::size_t k = 0; k < free.size(); ++k) a[k] = dot(free[k], v);
  return a;
}

// The inequality rows on the free motions: row i's B_i n_k, its bounds, and for the first row
// of a disc pair its second.
struct RowsOnMotions {
  std::vector<std::vector<double>> a;
  std::vector<double> lower, upper;
  std::vector<int> partner;  // -1: a row of its own; the first of a pair: the second's index
  std::vector<bool> second;  // the second row of a disc pair (its first one carries it)
  std::vector<FrictionCone> cones;
  std::vector<bool> inCone;  // a cone's row: the cone, not its own bounds, says what it holds
  // Functionals the motion must leave at 0 (free columns in the program): the pieces' rotations
  // where only translations are asked for.
  std::vector<std::vector<double>> held;
};

RowsOnMotions rowsOnMotions(const ElasticContactProblem& p, const Pieces& pieces,
                            const std::vector<std::vector<double>>& free,
                            const std::vector<tfeti::InequalityRow>& rows,
                            const std::vector<FrictionCone>& cones) {
  const int dim = p.dim(), nm = modesPerPiece(dim);
  RowsOnMotions out;
  std::vector<double> modes(static_cast<std::size_t>(pieces.count) * nm);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const tfeti::InequalityRow& row = rows[i];
    std::fill(modes.begin(), modes.end(), 0.0);
    for (const auto& e : row.entries) {
      const int q = pieces.ofSubdomain[e.subdomain];
      addModeValues(pieces, q, dim, &p.subdomains[e.subdomain].coords[dim * (e.dof / dim)],
                    e.dof % dim, e.coef, &modes[static_cast<std::size_t>(q) * nm]);
    }
    out.a.push_back(onFree(free, modes));
    out.lower.push_back(row.lowerBound);
    out.upper.push_back(row.upperBound);
    const bool pair = row.disc == 1 && i + 1 < rows.size() && rows[i + 1].disc == 2;
    out.partner.push_back(pair ? static_cast<int>(i + 1) : -1);
    out.second.push_back(row.disc == 2 && i > 0 && rows[i - 1].disc == 1);
  }
  out.inCone.assign(rows.size(), false);
  const auto mark = [&](int i) {
    if (i < 0 || static_cast<std::size_t>(i) >= rows.size() || out.inCone[i])
      throw std::logic_error("frictionLoadLimit: a friction cone's row " + std::to_string(i) +
                             " is not one of the " + std::to_string(rows.size()) +
                             " rows, or is another cone's");
    out.inCone[i] = true;
  };
  for (const FrictionCone& c : cones) {
    if (c.tangents.empty() || c.tangents.size() > 2 || !(c.mu >= 0.0))
      throw std::logic_error("frictionLoadLimit: a friction cone needs 1 or 2 tangents, mu >= 0");
    mark(c.normal);
    for (const int t : c.tangents) mark(t);
  }
  out.cones = cones;
  return out;
}

// What the rows can do along r at most (with phi . r = 1: the load factor r certifies), and
// whether r is admissible: it presses into no push-only row and moves along no row whose
// multiplier is unbounded that way (beyond rounding).
struct Evaluation {
  bool admissible = true;
  double capacity = 0.0;
  int lifted = 0;
};

Evaluation evaluate(const RowsOnMotions& rows, const std::vector<double>& r) {
  const double rNorm = std::sqrt(dot(r, r));
  const auto along = [&](std::size_t i, double& tol) {
    tol = 1e-9 * std::sqrt(dot(rows.a[i], rows.a[i])) * rNorm;
    return dot(rows.a[i], r);
  };
  Evaluation e;
  for (std::size_t i = 0; i < rows.a.size(); ++i) {
    if (rows.second[i] || rows.inCone[i]) continue;
    double tol = 0.0;
    const double s = along(i, tol);
    if (rows.partner[i] >= 0) {
      double tol2 = 0.0;
      const double s2 = along(static_cast<std::size_t>(rows.partner[i]), tol2);
      const double g = std::max(std::abs(rows.lower[i]), std::abs(rows.upper[i]));
      const double slip = std::hypot(s, s2);
      if (slip <= std::max(tol, tol2)) continue;
      if (g == kInf) e.admissible = false;
      e.capacity += g * slip;
      continue;
    }
    if (std::abs(s) <= tol) continue;
    const double bound = s > 0.0 ? rows.upper[i] : rows.lower[i];
    if (std::abs(bound) == kInf) e.admissible = false;
    e.capacity += bound * s;
    if (rows.lower[i] == 0.0 && rows.upper[i] == kInf && s < 0.0) ++e.lifted;
  }
  // Coulomb's cone does work only along a motion that presses into it (s_N + mu |s_T| > 0),
  // and then without bound.
  for (const FrictionCone& c : rows.cones) {
    double tolN = 0.0, slip2 = 0.0, tolT = 0.0;
    const double sN = along(static_cast<std::size_t>(c.normal), tolN);
    for (const int t : c.tangents) {
      double tol = 0.0;
      const double sT = along(static_cast<std::size_t>(t), tol);
      slip2 += sT * sT;
      tolT = std::max(tolT, tol);
    }
    if (sN + c.mu * std::sqrt(slip2) > tolN + c.mu * tolT) e.admissible = false;
    if (sN < -tolN) ++e.lifted;
  }
  return e;
}

// A disc |lambda| <= g as a regular 2K-gon around it that the program's bounds can say: the sum
// of K segments nu_j e_j, |nu_j| <= g tan(pi / 2K), along directions e_j at angle + j pi / K
// (a zonotope; its support function lies between g and g / cos(pi / 2K), 1.9 % above the disc's
// at most, and is g along each e_j). Each segment is a column with bounds of its own, so the
// program keeps its few rows.
constexpr int kSpokes = 8;

// max t subject to sum_i lambda_i a_i = t phi within the rows' bounds, a disc pair's disc
// replaced by the 2K-gon around it (so that the program's value bounds the limit from above,
// never from below); returns the multipliers' motion r (phi . r = 1), empty where the program is
// unbounded (no limit) or failed.
std::vector<double> limitMotion(const RowsOnMotions& rows, const std::vector<double>& phi,
                                const std::vector<double>& angle) {
  const int m = static_cast<int>(phi.size());
  BoundedLp lp;
  lp.rows = m;
  const auto add = [&](const std::vector<double>& a, double lower, double upper) {
    lp.matrix.insert(lp.matrix.end(), a.begin(), a.end());
    lp.objective.push_back(0.0);
    lp.lower.push_back(lower);
    lp.upper.push_back(upper);
  };
  const double pi = std::acos(-1.0), half = std::tan(pi / (2 * kSpokes));
  std::vector<double> spoke(m);
  for (std::size_t i = 0; i < rows.a.size(); ++i) {
    if (rows.second[i] || rows.inCone[i]) continue;
    if (rows.partner[i] < 0) {
      add(rows.a[i], rows.lower[i], rows.upper[i]);
      continue;
    }
    const std::vector<double>& b = rows.a[static_cast<std::size_t>(rows.partner[i])];
    const double g = std::max(std::abs(rows.lower[i]), std::abs(rows.upper[i]));
    if (g == kInf) {  // any tangential force: the two rows as they are
      add(rows.a[i], -kInf, kInf);
      add(b, -kInf, kInf);
      continue;
    }
    for (int j = 0; j < kSpokes; ++j) {
      const double theta = angle[i] + j * pi / kSpokes;
      const double c = std::cos(theta), s = std::sin(theta);
      for (int k = 0; k < m; ++k) spoke[k] = c * rows.a[i][k] + s * b[k];
      add(spoke, -g * half, g * half);
    }
  }
  // Coulomb's cone as the cone over a regular 2K-gon around its disc of radius mu (so, again,
  // from above): its rays through the polygon's corners, a_N + mu / cos(pi / 2K)
  // (cos theta_j a_T1 + sin theta_j a_T2), or a_N +- mu a_T with one tangent (exact); each a
  // column with the bounds [0, inf).
  for (const FrictionCone& c : rows.cones) {
    const std::vector<double>& n = rows.a[static_cast<std::size_t>(c.normal)];
    const std::vector<double>& t1 = rows.a[static_cast<std::size_t>(c.tangents[0])];
    const int edges = c.tangents.size() == 1 ? 2 : 2 * kSpokes;
    const double radius = c.tangents.size() == 1 ? c.mu : c.mu / std::cos(pi / edges);
    for (int j = 0; j < edges; ++j) {
      // With two tangents a side's middle, where the polygon is the disc, along angle[]: the
      // slip turnTo found.
      const double theta =
          (c.tangents.size() == 2 ? angle[c.normal] + pi / edges : 0.0) + 2.0 * pi * j / edges;
      const double ct = std::cos(theta), st = c.tangents.size() == 1 ? 0.0 : std::sin(theta);
      for (int k = 0; k < m; ++k) {
        spoke[k] = n[k] + radius * ct * t1[k];
        if (c.tangents.size() == 2) spoke[k] += radius * st * rows.a[c.tangents[1]][k];
      }
      add(spoke, 0.0, kInf);
    }
  }
  for (const std::vector<double>& h : rows.held) add(h, -kInf, kInf);
  for (int k = 0; k < m; ++k) lp.matrix.push_back(-phi[k]);
  lp.objective.push_back(1.0);
  lp.lower.push_back(0.0);
  lp.upper.push_back(kInf);
  const BoundedLpSolution sol = maximizeFromZero(lp);
  if (sol.status != BoundedLpSolution::Status::optimal) return {};
  // t's reduced cost 1 + y . phi is 0 (t > 0) or <= 0 (t = 0): y . phi <= -1.
  const double yPhi = dot(sol.y, phi);
  if (!(yPhi < 0.0)) return {};
  std::vector<double> r(sol.y);
  for (double& x : r) x /= yPhi;
  return r;
}

struct Found {
  std::vector<double> r;  // on the free motions, phi . r = 1
  Evaluation at;
};

// The load's own direction among the free motions (the load's projection onto their span), on
// them, with phi . r = 1: where it certifies the smallest factor as well (a pull straight off
// the contact), it is the motion named, rather than the program's vertex (a turn about an edge).
std::vector<double> loadDirection(const std::vector<std::vector<double>>& free,
                                  const std::vector<double>& phi) {
  const int k = static_cast<int>(free.size());
  std::vector<double> gram(static_cast<std::size_t>(k) * k), r(phi);
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b) gram[a + b * k] = dot(free[a], free[b]);
  std::vector<int> pivots(k);
  int info = 0;
  Teuchos::LAPACK<int, double>().GESV(k, 1, gram.data(), k, pivots.data(), r.data(), k, &info);
  const double work = dot(phi, r);
  if (info != 0 || !(work > 0.0)) return {};
  for (double& x : r) x /= work;
  return r;
}

// Each disc's and 3D cone's polygon turned to the slip that r gives its node, so that along it
// the polygon is the disc (a disc's segment lies along it, a cone's side has its middle there).
void turnTo(const RowsOnMotions& rows, const std::vector<double>& r, std::vector<double>& angle) {
  const auto slipAngle = [&](int t1, int t2) {
    return std::atan2(dot(rows.a[static_cast<std::size_t>(t2)], r),
                      dot(rows.a[static_cast<std::size_t>(t1)], r));
  };
  for (std::size_t i = 0; i < rows.a.size(); ++i)
    if (rows.partner[i] >= 0) angle[i] = slipAngle(static_cast<int>(i), rows.partner[i]);
  for (const FrictionCone& c : rows.cones)
    if (c.tangents.size() == 2) angle[c.normal] = slipAngle(c.tangents[0], c.tangents[1]);
}

// The smallest admissible load factor found, evaluated exactly: the program with the polygons
// turned to the load's own direction `own` (if given), then again turned to the slip of the
// motion found, while that lowers it.
std::optional<Found> smallestLimit(const RowsOnMotions& rows, const std::vector<double>& phi,
                                   const std::vector<double>& own) {
  std::vector<double> angle(rows.a.size(), 0.0);
  if (!own.empty()) turnTo(rows, own, angle);
  const bool polygons = !rows.cones.empty() || std::any_of(rows.partner.begin(), rows.partner.end(),
                                                           [](int k) { return k >= 0; });
  std::optional<Found> best;
  for (int round = 0; round < (polygons ? 3 : 1); ++round) {
    std::vector<double> r = limitMotion(rows, phi, angle);
    if (r.empty()) break;
    const Evaluation e = evaluate(rows, r);
    if (e.admissible) {
      if (best && !(e.capacity < best->at.capacity * (1.0 - 1e-12))) break;
      best = Found{r, e};
    }
    turnTo(rows, r, angle);
  }
  return best;
}

// Where several motions certify 0 the program's choice may turn about a far axis: a
// translation that certifies 0 as well reads better (a block sliding off its cones), and the
// load's own direction best of all where it certifies as small a factor.
Found readableMotion(Found limit, RowsOnMotions& rows, const std::vector<double>& phi,
                     const std::vector<double>& own, const std::vector<std::vector<double>>& free,
                     const Pieces& pieces, int dim) {
  if (limit.at.capacity <= 1e-9) {
    const int nm = modesPerPiece(dim);
    for (int q = 0; q < pieces.count; ++q)
      for (int i = dim; i < nm; ++i) {  // the rotations held at 0
        std::vector<double> rotation(free.size());
        for (std::size_t k = 0; k < free.size(); ++k) rotation[k] = free[k][q * nm + i];
        rows.held.push_back(std::move(rotation));
      }
    const std::optional<Found> sliding = smallestLimit(rows, phi, own);
    rows.held.clear();
    if (sliding && sliding->at.capacity <= 1e-9) limit = *sliding;
  }
  if (!own.empty()) {
    const Evaluation e = evaluate(rows, own);
    if (e.admissible && e.capacity <= limit.at.capacity * (1.0 + 1e-9)) limit = Found{own, e};
  }
  return limit;
}

}  // namespace

std::optional<FrictionLoadLimit> frictionLoadLimit(const ElasticContactSpec& spec,
                                                   const ElasticContactProblem& p,
                                                   const std::vector<tfeti::InequalityRow>& rows,
                                                   const std::vector<FrictionCone>& cones,
                                                   const tfeti::Comm& comm) {
  // Tied and bonded pairs hold their rows with equality (FETI "Inequality rows" = equalities),
  // both ways: requireRigidMotionsHeld is all there is to check.
  if (spec.tied) return std::nullopt;
  Pieces pieces = joinSubdomains(p);
  measurePieces(p, pieces);
  const std::vector<double> force = loadOnModes(p, pieces, comm);
  double found[5] = {0.0, 0.0, 0.0, 0.0, 0.0};  // load, capacity, factor, lifted, found (1)
  std::vector<std::string> motion;
  // Rank 0 holds the inequality and coupling rows; an error there is every rank's (the others
  // would wait in the broadcast).
  tfeti::collectively(comm, [&] {
    if (comm.getRank() != 0) return;
    Gram gram = gramOfRows(p, pieces, {});  // the supports and couplings alone
    const std::vector<std::vector<double>> free = nullSpace(gram);
    const std::vector<double> phi = onFree(free, force);
    double scale = 0.0, work = 0.0;
    for (const double x : force) scale = std::max(scale, std::abs(x));
    for (const double x : phi) work = std::max(work, std::abs(x));
    if (free.empty() || !(work > 1e-12 * scale)) return;
    RowsOnMotions onMotions = rowsOnMotions(p, pieces, free, rows, cones);
    const std::vector<double> own = loadDirection(free, phi);
    std::optional<Found> limit = smallestLimit(onMotions, phi, own);
    if (!limit) return;
    limit = readableMotion(*limit, onMotions, phi, own, free, pieces, p.dim());
    std::vector<double> r(force.size(), 0.0);  // on the pieces' modes, r . f = 1
    for (std::size_t k = 0; k < free.size(); ++k)
      for (std::size_t j = 0; j < r.size(); ++j) r[j] += limit->r[k] * free[k][j];
    const double length = std::sqrt(dot(r, r));
    // A load of rounding's size along the motion (opposite pressures on a body that only
    // push-only rows hold, say) certifies nothing: the solve would take it.
    if (!(1.0 / length > 1e-10 * scale)) return;
    for (double& x : r) x /= length;
    found[0] = 1.0 / length;
    found[1] = limit->at.capacity / length;
    found[2] = limit->at.capacity;
    found[3] = limit->at.lifted;
    found[4] = 1.0;
    // Rounding leaves traces of other modes (1e-12 of a turn in a translation): named without
    // them, as nullSpace does.
    for (double& x : r)
      if (std::abs(x) < 1e-9) x = 0.0;
    motion = describe(spec, p, pieces, {r});
  });
  Teuchos::broadcast(comm, 0, 5, found);
  motion = broadcastLines(motion, comm);
  if (found[4] == 0.0) return std::nullopt;
  FrictionLoadLimit limit;
  limit.motion = motion.empty() ? "" : motion.front();
  limit.load = found[0];
  limit.capacity = found[1];
  limit.loadFactor = found[2];
  limit.liftedRows = static_cast<int>(found[3]);
  return limit;
}

std::string frictionLimitText(const FrictionLoadLimit& limit) {
  std::ostringstream s;
  s << "the friction rows' bounds can hold " << limit.motion << " only up to the load factor "
    << limit.loadFactor << " (along it the load at factor 1 does " << limit.load
    << ", the friction rows at most " << limit.capacity;
  if (limit.liftedRows > 0)
    s << "; it lifts " << limit.liftedRows << " contact row" << (limit.liftedRows > 1 ? "s" : "")
      << " off, which pull nothing";
  s << "): no equilibrium exists beyond it";
  return s.str();
}

void requireLoadHeld(const std::optional<FrictionLoadLimit>& limit) {
  if (!limit || limit->loadFactor > 1e-9) return;
  std::ostringstream s;
  s << "nothing holds " << limit->motion << " against the load: along it the load at factor 1 does "
    << limit->load << ", ";
  if (limit->liftedRows > 0)
    s << "it lifts " << limit->liftedRows << " contact row" << (limit->liftedRows > 1 ? "s" : "")
      << " off (a contact row pushes, never pulls) ";
  else
    s << "no contact row pushes against it ";
  s << "and no friction row resists it: no equilibrium exists at any load factor, so no load "
       "step can converge (the "
       "supports, couplings, contact and friction rows of the first solve, at the reference "
       "geometry)";
  throw std::invalid_argument(s.str());
}

}  // namespace contact
