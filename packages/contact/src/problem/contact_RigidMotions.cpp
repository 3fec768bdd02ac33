// The rigid motions no row of B holds: the pieces (subdomains joined by shared nodes), their
// rigid modes, the Gram matrix of the rows against them and its null space, described.
#include "contact_RigidMotions.hpp"

#include "contact_RigidModes.hpp"
#include "tfeti_CollectiveError.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace contact {

namespace rigid {

int findRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// The piece of every subdomain (numbered by first appearance) and of every mesh node (-1: in
// no subdomain).
Pieces joinSubdomains(const ElasticContactProblem& p) {
  const int ns = p.numSubdomains();
  std::vector<int> parent(ns), first(p.mesh.coords.size() / p.dim(), -1);
  std::iota(parent.begin(), parent.end(), 0);
  for (int s = 0; s < ns; ++s)
    for (long long g : p.subdomains[s].globalNode) {
      int& f = first[static_cast<std::size_t>(g)];
      if (f < 0)
        f = s;
      else
        parent[findRoot(parent, s)] = findRoot(parent, f);
    }
  Pieces pieces;
  std::map<int, int> index;
  for (int s = 0; s < ns; ++s) {
    const int root = findRoot(parent, s);
    pieces.ofSubdomain.push_back(index.emplace(root, static_cast<int>(index.size())).first->second);
  }
  pieces.count = static_cast<int>(index.size());
  pieces.ofNode.assign(first.size(), -1);
  for (std::size_t g = 0; g < first.size(); ++g)
    if (first[g] >= 0) pieces.ofNode[g] = pieces.ofSubdomain[first[g]];
  return pieces;
}

// Each piece's centroid (of its nodes) and size (the largest side of its bounding box).
void measurePieces(const ElasticContactProblem& p, Pieces& pieces) {
  const int dim = p.dim();
  std::vector<std::array<double, 3>> lo(pieces.count, {1e300, 1e300, 1e300}),
      hi(pieces.count, {-1e300, -1e300, -1e300}), sum(pieces.count, {0.0, 0.0, 0.0});
  std::vector<long long> n(pieces.count, 0);
  for (std::size_t g = 0; g < pieces.ofNode.size(); ++g) {
    const int q = pieces.ofNode[g];
    if (q < 0) continue;
    ++n[q];
    for (int c = 0; c < dim; ++c) {
      const double x = p.mesh.coords[dim * g + c];
      sum[q][c] += x;
      lo[q][c] = std::min(lo[q][c], x);
      hi[q][c] = std::max(hi[q][c], x);
    }
  }
  for (int q = 0; q < pieces.count; ++q) {
    std::array<double, 3> c{0.0, 0.0, 0.0};
    double extent = 0.0;
    for (int k = 0; k < dim; ++k) {
      c[k] = sum[q][k] / static_cast<double>(std::max(n[q], 1LL));
      extent = std::max(extent, hi[q][k] - lo[q][k]);
    }
    pieces.centre.push_back(c);
    pieces.length.push_back(extent > 0.0 ? extent : 1.0);
  }
}

int modesPerPiece(int dim) {
  return dim == 3 ? 6 : 3;
}

// Component c at x of the piece's rigid modes: the translations, then the rotations about the
// axes through its centre, scaled by its size so that all modes are of one magnitude.
void modeValues(const Pieces& pieces, int q, int dim, const double* x, int c, double* out) {
  std::array<double, 3> r{0.0, 0.0, 0.0};
  for (int k = 0; k < dim; ++k) r[k] = (x[k] - pieces.centre[q][k]) / pieces.length[q];
  for (int k = 0; k < dim; ++k) out[k] = k == c ? 1.0 : 0.0;
  if (dim == 2) {
    out[2] = c == 0 ? -r[1] : r[0];  // about z: (-y, x)
    return;
  }
  // about x: (0, -z, y); about y: (z, 0, -x); about z: (-y, x, 0)
  const double rot[3][3] = {{0.0, -r[2], r[1]}, {r[2], 0.0, -r[0]}, {-r[1], r[0], 0.0}};
  for (int a = 0; a < 3; ++a) out[3 + a] = rot[a][c];
}

void addModeValues(const Pieces& pieces, int q, int dim, const double* x, int c, double coef,
                   double* out) {
  double m[6];
  modeValues(pieces, q, dim, x, c, m);
  for (int i = 0; i < modesPerPiece(dim); ++i) out[i] += coef * m[i];
}

// The rows' entries on subdomain dofs: the node's coordinates are the subdomain's copy's.
template <class Row>
void addRows(Gram& gram, const ElasticContactProblem& p, const Pieces& pieces,
             const std::vector<Row>& rows) {
  const int dim = p.dim();
  for (const Row& row : rows) {
    gram.beginRow();
    for (const auto& e : row.entries) {
      const UnstructuredSubdomain& s = p.subdomains[e.subdomain];
      gram.add(pieces.ofSubdomain[e.subdomain], &s.coords[dim * (e.dof / dim)], e.dof % dim,
               e.coef);
    }
    gram.endRow();
  }
}

// The Gram matrix of every row of B but the gluing: Fixed, Symmetry and Prescribed components
// (one row per held node and component), the couplings (rank 0 holds them) and `inequalities`.
Gram gramOfRows(const ElasticContactProblem& p, const Pieces& pieces,
                const std::vector<tfeti::InequalityRow>& inequalities) {
  const int dim = p.dim();
  Gram gram(pieces, dim);
  for (const auto& [node, c] : p.heldComponents) {
    const int q = pieces.ofNode[node];
    if (q < 0) continue;
    gram.beginRow();
    gram.add(q, &p.mesh.coords[static_cast<std::size_t>(dim) * node], c, 1.0);
    gram.endRow();
  }
  addRows(gram, p, pieces, p.couplingRows);
  addRows(gram, p, pieces, inequalities);
  return gram;
}

// The null space of the Gram matrix, k x n row-major in reduced row echelon form (each vector
// with its own leading mode, the translations before the rotations), tiny entries zeroed.
std::vector<std::vector<double>> nullSpace(Gram& gram) {
  const int n = gram.size();
  std::vector<double>& M = gram.matrix();
  std::vector<double> w(n);
  Teuchos::LAPACK<int, double> lapack;
  int info = 0, lwork = std::max(1, 3 * n);
  std::vector<double> work(lwork);
  lapack.SYEV('V', 'U', n, M.data(), n, w.data(), work.data(), lwork, &info);
  if (info != 0)
    throw std::runtime_error("rigid motions: the eigensolver failed (info " + std::to_string(info) +
                             ")");
  const double wMax = n > 0 ? std::max(w[n - 1], 0.0) : 0.0;
  std::vector<std::vector<double>> v;
  for (int k = 0; k < n; ++k)
    if (!(w[k] > 1e-12 * wMax))
      v.emplace_back(M.begin() + static_cast<std::ptrdiff_t>(k) * n,
                     M.begin() + static_cast<std::ptrdiff_t>(k + 1) * n);
  std::size_t rank = 0;
  for (int col = 0; col < n && rank < v.size(); ++col) {
    std::size_t best = rank;
    for (std::size_t r = rank; r < v.size(); ++r)
      if (std::abs(v[r][col]) > std::abs(v[best][col])) best = r;
    if (!(std::abs(v[best][col]) > 1e-8)) continue;
    std::swap(v[rank], v[best]);
    const double pivot = v[rank][col];
    for (double& x : v[rank]) x /= pivot;
    for (std::size_t r = 0; r < v.size(); ++r)
      if (r != rank) {
        const double f = v[r][col];
        for (int j = 0; j < n; ++j) v[r][j] -= f * v[rank][j];
      }
    ++rank;
  }
  for (auto& x : v)
    for (double& y : x)
      if (std::abs(y) < 1e-8) y = 0.0;
  return v;
}

std::string number(double x) {
  std::ostringstream s;
  s.precision(4);
  s << (std::abs(x) < 1e-12 ? 0.0 : x);
  return s.str();
}

std::string point(const double* x, int dim) {
  std::string s = "(";
  for (int k = 0; k < dim; ++k) s += (k ? ", " : "") + number(x[k]);
  return s + ")";
}

// "along x" for an axis, else "along (a, b, c)" (unit length, its largest component positive:
// a free motion's sign says nothing).
std::string direction(const double* a, int dim) {
  double norm = 0.0;
  int largest = 0;
  for (int k = 0; k < dim; ++k) {
    norm += a[k] * a[k];
    if (std::abs(a[k]) > std::abs(a[largest])) largest = k;
  }
  norm = std::sqrt(norm);
  for (int k = 0; k < dim; ++k)
    if (std::abs(std::abs(a[k]) - norm) <= 1e-9 * norm) return std::string("along ") + "xyz"[k];
  const double sign = a[largest] < 0.0 ? -1.0 : 1.0;
  double u[3];
  for (int k = 0; k < dim; ++k) u[k] = sign * a[k] / norm;
  return "along " + point(u, dim);
}

// One piece's part of a free motion: u(x) = t + omega x (x - centre).
std::string describePart(const Pieces& pieces, int q, int dim, const double* v) {
  const int nr = dim == 3 ? 3 : 1;
  double t[3] = {0.0, 0.0, 0.0}, omega[3] = {0.0, 0.0, 0.0};
  double tNorm = 0.0, oNorm = 0.0;
  for (int k = 0; k < dim; ++k) t[k] = v[k], tNorm += t[k] * t[k];
  for (int k = 0; k < nr; ++k)
    omega[k] = v[dim + k] / pieces.length[q], oNorm += v[dim + k] * v[dim + k];
  if (!(oNorm > 0.0)) return "translation " + direction(t, dim);
  const double* c0 = pieces.centre[q].data();
  double c[3] = {c0[0], c0[1], c0[2]};
  if (dim == 2) {
    // u = 0 at c: the centre of the rotation.
    c[0] -= t[1] / omega[0];
    c[1] += t[0] / omega[0];
    return "rotation about " + point(c, 2);
  }
  const double o2 = omega[0] * omega[0] + omega[1] * omega[1] + omega[2] * omega[2];
  const double cross[3] = {omega[1] * t[2] - omega[2] * t[1], omega[2] * t[0] - omega[0] * t[2],
                           omega[0] * t[1] - omega[1] * t[0]};
  for (int k = 0; k < 3; ++k) c[k] += cross[k] / o2;  // the axis' point nearest the centre
  std::string d = direction(omega, 3);
  d = d.size() <= 8 ? "the " + d.substr(6) + " axis" : "the axis " + d.substr(6);
  std::string s = "rotation about " + d + " through " + point(c, 3);
  const double along = (t[0] * omega[0] + t[1] * omega[1] + t[2] * omega[2]) / std::sqrt(o2);
  if (std::abs(along) > 1e-9 * std::sqrt(tNorm + o2)) s += " with a translation along that axis";
  return s;
}

std::string pieceName(const ElasticContactSpec& spec, const ElasticContactProblem& p,
                      const Pieces& pieces, int q) {
  std::vector<int> bodies;
  for (int s = 0; s < p.numSubdomains(); ++s)
    if (pieces.ofSubdomain[s] == q) bodies.push_back(p.bodyOfSubdomain[s]);
  std::sort(bodies.begin(), bodies.end());
  bodies.erase(std::unique(bodies.begin(), bodies.end()), bodies.end());
  std::string name = bodies.size() == 1 ? "body " : "bodies ";
  for (std::size_t i = 0; i < bodies.size(); ++i)
    name += (i ? ", \"" : "\"") + spec.bodies[bodies[i]].name + "\"";
  // A body in several pieces (disjoint regions of one group): say which.
  int piecesOfBody = 0;
  std::vector<int> seen;
  for (int s = 0; s < p.numSubdomains(); ++s)
    if (p.bodyOfSubdomain[s] == bodies.front() &&
        std::find(seen.begin(), seen.end(), pieces.ofSubdomain[s]) == seen.end()) {
      seen.push_back(pieces.ofSubdomain[s]);
      ++piecesOfBody;
    }
  if (piecesOfBody > 1)
    name += " (its part around " + point(pieces.centre[q].data(), p.dim()) + ")";
  return name;
}

std::vector<std::string> describe(const ElasticContactSpec& spec, const ElasticContactProblem& p,
                                  const Pieces& pieces,
                                  const std::vector<std::vector<double>>& motions) {
  const int dim = p.dim(), nm = modesPerPiece(dim);
  std::vector<std::string> out;
  for (const auto& v : motions) {
    std::string s;
    for (int q = 0; q < pieces.count; ++q) {
      const double* part = &v[static_cast<std::size_t>(q) * nm];
      if (std::all_of(part, part + nm, [](double x) { return x == 0.0; })) continue;
      s += (s.empty() ? "" : ", with ") + pieceName(spec, p, pieces, q) + ": " +
           describePart(pieces, q, dim, part);
    }
    out.push_back(s);
  }
  return out;
}

// Rank 0's lines on every rank.
std::vector<std::string> broadcastLines(const std::vector<std::string>& lines,
                                        const tfeti::Comm& comm) {
  std::string text;
  for (const std::string& l : lines) text += l + "\n";
  long long size = static_cast<long long>(text.size());
  Teuchos::broadcast(comm, 0, &size);
  text.resize(static_cast<std::size_t>(size));
  if (size > 0) Teuchos::broadcast(comm, 0, static_cast<int>(size), text.data());
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

}  // namespace rigid

using namespace rigid;

std::vector<std::string> freeRigidMotions(const ElasticContactSpec& spec,
                                          const ElasticContactProblem& p,
                                          const std::vector<tfeti::InequalityRow>& inequalities,
                                          const tfeti::Comm& comm) {
  std::vector<std::string> motions;
  // Rank 0 holds the inequality and coupling rows; an error there is every rank's.
  tfeti::collectively(comm, [&] {
    if (comm.getRank() != 0) return;
    Pieces pieces = joinSubdomains(p);
    measurePieces(p, pieces);
    Gram gram = gramOfRows(p, pieces, inequalities);
    motions = describe(spec, p, pieces, nullSpace(gram));
  });
  return broadcastLines(motions, comm);
}

void requireRigidMotionsHeld(const ElasticContactSpec& spec, const ElasticContactProblem& p,
                             const std::vector<tfeti::InequalityRow>& inequalities,
                             const tfeti::Comm& comm) {
  const std::vector<std::string> free = freeRigidMotions(spec, p, inequalities, comm);
  if (free.empty()) return;
  std::string list;
  for (std::size_t i = 0; i < free.size(); ++i) list += (i ? "; " : "") + free[i];
  const bool one = free.size() == 1;
  throw std::invalid_argument(
      std::string("nothing holds ") + (one ? "this rigid motion" : "these rigid motions") + " (" +
      list + "): no Fixed, Symmetry or Prescribed boundary, kinematic coupling, contact row or " +
      "friction row acts against " + (one ? "it" : "them") +
      ", so the stiffness is singular (a contact row holds only along its normal, and only "
      "where a slave node is within the search radius)");
}

}  // namespace contact
