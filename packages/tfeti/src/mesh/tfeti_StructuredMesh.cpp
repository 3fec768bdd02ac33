#include "tfeti_StructuredMesh.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tfeti {

namespace {

std::string listOf(const std::vector<int>& v) {
  std::string s;
  for (std::size_t k = 0; k < v.size(); ++k) s += (k ? "x" : "") + std::to_string(v[k]);
  return s;
}

// Corner a of the reference cell (VTK order): its offset along each axis.
int cornerOffset(int a, int axis) {
  if (axis == 2) return a / 4;
  const int c = a % 4;  // (0,0), (1,0), (1,1), (0,1)
  return axis == 0 ? (c == 1 || c == 2) : (c >= 2);
}

}  // namespace

StructuredMesh::StructuredMesh(const std::vector<double>& lo, const std::vector<double>& hi,
                               const std::vector<int>& subdomains, const std::vector<int>& elements)
    : dim_(static_cast<int>(lo.size())), lo_(lo), hi_(hi), sub_(subdomains), elem_(elements) {
  if (dim_ != 2 && dim_ != 3)
    throw std::invalid_argument("structured mesh: the domain must be 2D or 3D (got " +
                                std::to_string(dim_) + " coordinates per corner)");
  if (hi.size() != lo.size() || subdomains.size() != lo.size() || elements.size() != lo.size())
    throw std::invalid_argument(
        "structured mesh: the corners, subdomain counts and elements per subdomain must all "
        "have " +
        std::to_string(dim_) + " entries");
  for (int d = 0; d < dim_; ++d)
    if (!(hi[d] > lo[d]))
      throw std::invalid_argument("structured mesh: the domain must have x1 > x0, y1 > y0" +
                                  std::string(dim_ == 3 ? " and z1 > z0" : ""));
  if (*std::min_element(sub_.begin(), sub_.end()) < 1 ||
      *std::min_element(elem_.begin(), elem_.end()) < 1)
    throw std::invalid_argument(
        "structured mesh: subdomain counts and elements per subdomain must be positive (got " +
        listOf(sub_) + " subdomains of " + listOf(elem_) + " elements)");
}

int StructuredMesh::numSubdomains() const {
  int n = 1;
  for (int s : sub_) n *= s;
  return n;
}

GO StructuredMesh::numGlobalNodes() const {
  GO n = 1;
  for (int d = 0; d < dim_; ++d) n *= elementsAlong(d) + 1;
  return n;
}

GO StructuredMesh::numGlobalElements() const {
  GO n = 1;
  for (int d = 0; d < dim_; ++d) n *= elementsAlong(d);
  return n;
}

std::vector<int> StructuredMesh::cells(const std::vector<int>& n) {
  const int dim = static_cast<int>(n.size());
  const int npe = 1 << dim;
  const int nx = n[0], ny = n[1], nz = dim == 3 ? n[2] : 1;
  const int sx = nx + 1, sy = ny + 1;  // node strides: y by sx, z by sx * sy
  std::vector<int> c;
  c.reserve(static_cast<std::size_t>(npe) * nx * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (int a = 0; a < npe; ++a)
          c.push_back((k + cornerOffset(a, 2)) * sx * sy + (j + cornerOffset(a, 1)) * sx + i +
                      cornerOffset(a, 0));
  return c;
}

std::vector<int> StructuredMesh::wholeCells() const {
  std::vector<int> n(dim_);
  for (int d = 0; d < dim_; ++d) n[d] = elementsAlong(d);
  return cells(n);
}

SubdomainMesh StructuredMesh::block(const std::vector<int>& first,
                                    const std::vector<int>& n) const {
  // Grid indices padded to 3 axes: a 2D mesh is one layer of nodes.
  int nn[3] = {n[0] + 1, n[1] + 1, 1}, g0[3] = {first[0], first[1], 0}, NE[3] = {0, 0, 0};
  for (int d = 0; d < dim_; ++d) NE[d] = elementsAlong(d);
  if (dim_ == 3) nn[2] = n[2] + 1, g0[2] = first[2];
  SubdomainMesh m;
  const int numNodes = nn[0] * nn[1] * nn[2];
  m.coords.resize(static_cast<std::size_t>(dim_) * numNodes);
  m.globalNode.resize(numNodes);
  for (int k = 0; k < nn[2]; ++k)
    for (int j = 0; j < nn[1]; ++j)
      for (int i = 0; i < nn[0]; ++i) {
        const int local = (k * nn[1] + j) * nn[0] + i;
        const int g[3] = {g0[0] + i, g0[1] + j, g0[2] + k};
        for (int d = 0; d < dim_; ++d)
          m.coords[dim_ * local + d] = lo_[d] + (hi_[d] - lo_[d]) * g[d] / NE[d];
        m.globalNode[local] = (static_cast<GO>(g[2]) * (NE[1] + 1) + g[1]) * (NE[0] + 1) + g[0];
        if (g[0] == 0 && dirichletAtX0_) m.dirichletNodes.push_back(local);
        const bool onFace = i == 0 || i == nn[0] - 1 || j == 0 || j == nn[1] - 1 ||
                            (dim_ == 3 && (k == 0 || k == nn[2] - 1));
        if (onFace) m.interfaceCandidates.push_back(local);
      }
  m.dim = dim_;
  // The quadrilaterals or hexahedra tell the kernel detection which nodes are rigidly connected.
  const int npe = 1 << dim_;
  const std::vector<int> c = cells(n);
  for (std::size_t e = 0; e < c.size(); e += npe)
    m.elements.add(std::vector<int>(c.begin() + e, c.begin() + e + npe));
  return m;
}

SubdomainMesh StructuredMesh::subdomain(int s) const {
  if (s < 0 || s >= numSubdomains())
    throw std::out_of_range("structured mesh: no subdomain " + std::to_string(s));
  std::vector<int> first(dim_);
  int rest = s;
  for (int d = 0; d < dim_; ++d) {
    first[d] = (rest % sub_[d]) * elem_[d];
    rest /= sub_[d];
  }
  SubdomainMesh m = block(first, elem_);
  m.id = s;
  return m;
}

std::pair<int, int> StructuredMesh::copyOfNode(const std::array<int, 3>& g) const {
  // The lowest subdomain id holding the node: along each axis the lowest block that holds it.
  int sub = 0, local = 0, subStride = 1, nodeStride = 1;
  for (int d = 0; d < dim_; ++d) {
    if (g[d] < 0 || g[d] > elementsAlong(d))
      throw std::out_of_range("structured mesh: no node with index " + std::to_string(g[d]) +
                              " along axis " + std::to_string(d));
    const int b = g[d] > 0 && g[d] % elem_[d] == 0 ? g[d] / elem_[d] - 1
                                                   : std::min(g[d] / elem_[d], sub_[d] - 1);
    sub += b * subStride;
    local += (g[d] - b * elem_[d]) * nodeStride;
    subStride *= sub_[d];
    nodeStride *= elem_[d] + 1;
  }
  return {sub, local};
}

SubdomainMesh StructuredMesh::wholeMesh() const {
  std::vector<int> n(dim_);
  for (int d = 0; d < dim_; ++d) n[d] = elementsAlong(d);
  SubdomainMesh m = block(std::vector<int>(dim_, 0), n);
  m.id = -1;
  return m;
}

}  // namespace tfeti
