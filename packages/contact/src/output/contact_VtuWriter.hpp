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

// Names for some VTK cell types (the element catalogue, plasticity_ElementTypes.hpp, holds each
// element type's VTK type and node order). The plane ones have Gmsh's node order (corners
// counter-clockwise, then the edge midpoints from edge 0-1, then the centre); quadratic
// tetrahedra and triquadratic hexahedra do not (plasticity::vtkNodeOrder permutes them).
enum VtkCellType {
  kVtkTriangle = 5,
  kVtkQuad = 9,
  kVtkTetra = 10,
  kVtkHexahedron = 12,
  kVtkQuadraticTriangle = 22,
  kVtkQuadraticTetra = 24,
  kVtkBiquadraticQuad = 28,
  kVtkTriquadraticHexahedron = 29
};
int vtkCellSize(int vtkType);  // points per cell (the catalogue's); throws for other types

struct VtuPiece {
  int dim = 2;                 // coordinates per point in `points`
  std::vector<double> points;  // x, y (z = 0) or x, y, z per point
  std::vector<int> quads;      // 4 point indices per cell (VTK_QUAD), written first
  // Any other cells, written after the quads: a VTK type per cell and its points.
  std::vector<int> cellTypes;
  std::vector<int> cellPoints;
  std::vector<VtuField> pointData;
  std::vector<VtuField> cellData;
};

// Writes the piece of this rank and the .pvtu index; returns the .pvtu path. Throws naming the
// file when it cannot be written.
std::string writeVtu(const tfeti::Comm& comm, const std::string& directory,
                     const std::string& basename, const VtuPiece& piece);

// One dataset of a ParaView collection: its time and its file (relative to the collection).
struct PvdEntry {
  double time = 0.0;
  std::string file;
};
// Writes the collection (.pvd) naming the datasets in the given order, so that ParaView plays
// them as a time series. Written to a temporary file and renamed: a reader never sees half of
// it. Throws naming the file when it cannot be written.
void writePvd(const std::string& path, const std::vector<PvdEntry>& datasets);

}  // namespace contact
