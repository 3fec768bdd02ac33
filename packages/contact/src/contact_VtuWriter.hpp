#pragma once
// ParaView output: every rank writes its subdomains as one unstructured-grid piece
// (<base>_<rank>.vtu), rank 0 writes <base>.pvtu naming the pieces. Torn meshes are written
// torn: every subdomain keeps its own node copies, so jumps across interfaces stay visible.
#include <string>
#include <vector>

#include "tfeti_Types.hpp"

namespace contact {

struct VtuField {
  std::string name;
  int components = 1;          // 1 or 3 (vectors are written with 3 components)
  std::vector<double> values;  // components per point (or per cell)
};

struct VtuPiece {
  std::vector<double> points;  // x, y per point (z = 0)
  std::vector<int> quads;      // 4 point indices per cell
  std::vector<VtuField> pointData;
  std::vector<VtuField> cellData;
};

// Writes the piece of this rank and the .pvtu index; returns the .pvtu path. Throws naming the
// file when it cannot be written.
std::string writeVtu(const tfeti::Comm& comm, const std::string& directory,
                     const std::string& basename, const VtuPiece& piece);

}  // namespace contact
