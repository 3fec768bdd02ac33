#include "tfeti_StructuredMesh.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tfeti {

StructuredRectangle::StructuredRectangle(double x0, double x1, double y0, double y1, int sx, int sy,
                                         int ex, int ey)
    : x0_(x0), x1_(x1), y0_(y0), y1_(y1), sx_(sx), sy_(sy), ex_(ex), ey_(ey) {
  if (!(x1 > x0) || !(y1 > y0))
    throw std::invalid_argument("structured mesh: the domain must have x1 > x0 and y1 > y0");
  if (sx < 1 || sy < 1 || ex < 1 || ey < 1)
    throw std::invalid_argument(
        "structured mesh: subdomain counts and elements per subdomain must be positive (got " +
        std::to_string(sx) + "x" + std::to_string(sy) + " subdomains of " + std::to_string(ex) +
        "x" + std::to_string(ey) + " elements)");
}

SubdomainMesh StructuredRectangle::block(int i0, int j0, int nx, int ny) const {
  const int NX = elementsX(), NY = elementsY();
  SubdomainMesh m;
  const int nnx = nx + 1, nny = ny + 1;
  m.coords.resize(2 * nnx * nny);
  m.globalNode.resize(nnx * nny);
  for (int j = 0; j < nny; ++j)
    for (int i = 0; i < nnx; ++i) {
      const int n = j * nnx + i;
      const int gi = i0 + i, gj = j0 + j;
      m.coords[2 * n] = x0_ + (x1_ - x0_) * gi / NX;
      m.coords[2 * n + 1] = y0_ + (y1_ - y0_) * gj / NY;
      m.globalNode[n] = static_cast<GO>(gj) * (NX + 1) + gi;
      if (gi == 0 && dirichletAtX0_) m.dirichletNodes.push_back(n);
    }
  m.quads.reserve(4 * nx * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int n = j * nnx + i;
      m.quads.insert(m.quads.end(), {n, n + 1, n + 1 + nnx, n + nnx});
    }
  return m;
}

SubdomainMesh StructuredRectangle::subdomain(int s) const {
  if (s < 0 || s >= numSubdomains())
    throw std::out_of_range("structured mesh: no subdomain " + std::to_string(s));
  SubdomainMesh m = block((s % sx_) * ex_, (s / sx_) * ey_, ex_, ey_);
  m.id = s;
  return m;
}

std::pair<int, int> StructuredRectangle::copyOfNode(int gi, int gj) const {
  if (gi < 0 || gi > elementsX() || gj < 0 || gj > elementsY())
    throw std::out_of_range("structured mesh: no node (" + std::to_string(gi) + ", " +
                            std::to_string(gj) + ")");
  // The lowest subdomain id holding the node: the lowest block row, then the lowest column.
  const int bi = gi > 0 && gi % ex_ == 0 ? gi / ex_ - 1 : std::min(gi / ex_, sx_ - 1);
  const int bj = gj > 0 && gj % ey_ == 0 ? gj / ey_ - 1 : std::min(gj / ey_, sy_ - 1);
  const int li = gi - bi * ex_, lj = gj - bj * ey_;
  return {bj * sx_ + bi, lj * (ex_ + 1) + li};
}

SubdomainMesh StructuredRectangle::wholeMesh() const {
  SubdomainMesh m = block(0, 0, elementsX(), elementsY());
  m.id = -1;
  return m;
}

}  // namespace tfeti
