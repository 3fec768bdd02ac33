#include "contact_VtuWriter.hpp"

#include <charconv>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "plasticity_ElementTypes.hpp"

namespace contact {

namespace {
// Numbers as text, `perLine` to a line, formatted by std::to_chars into a buffer written in
// blocks: the same characters as the stream's own formatting (10 significant digits as %.10g,
// integers in full) in a third of its time (docs/benchmarks.md, "Packed supernodal solves").
template <class T>
void writeNumbers(std::ofstream& out, const std::vector<T>& values, std::size_t perLine) {
  std::string text;
  text.reserve(1 << 16);
  char number[32];
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::to_chars_result r;
    if constexpr (std::is_floating_point_v<T>)
      r = std::to_chars(number, number + sizeof(number), values[i], std::chars_format::general, 10);
    else
      r = std::to_chars(number, number + sizeof(number), values[i]);
    text.append(number, r.ptr);
    text.push_back((i + 1) % perLine ? ' ' : '\n');
    if (text.size() > (1 << 16) - 64) out.write(text.data(), text.size()), text.clear();
  }
  out.write(text.data(), text.size());
}

void writeArray(std::ofstream& out, const VtuField& f) {
  out << "        <DataArray type=\"Float64\" Name=\"" << f.name << "\" NumberOfComponents=\""
      << f.components << "\" format=\"ascii\">\n";
  writeNumbers(out, f.values, 12);
  out << "\n        </DataArray>\n";
}

void declareArrays(std::ofstream& out, const std::vector<VtuField>& fields) {
  for (const auto& f : fields)
    out << "      <PDataArray type=\"Float64\" Name=\"" << f.name << "\" NumberOfComponents=\""
        << f.components << "\"/>\n";
}
}  // namespace

int vtkCellSize(int vtkType) {
  plasticity::ElementType type = plasticity::ElementType::Tri3;
  if (!plasticity::elementTypeOfVtk(vtkType, type))
    throw std::invalid_argument("VTU output: unsupported VTK cell type " + std::to_string(vtkType));
  return plasticity::nodesPerElement(type);
}

std::string writeVtu(const tfeti::Comm& comm, const std::string& directory,
                     const std::string& basename, const VtuPiece& piece) {
  const int rank = comm.getRank();
  const std::string pieceName = basename + "_" + std::to_string(rank) + ".vtu";
  const std::string path = directory + "/" + pieceName;
  {
    std::ofstream out(path);
    if (!out) throw std::runtime_error("cannot write " + path);
    std::size_t generalPoints = 0;
    for (int t : piece.cellTypes) generalPoints += vtkCellSize(t);
    if (generalPoints != piece.cellPoints.size())
      throw std::invalid_argument("VTU output: " + std::to_string(piece.cellPoints.size()) +
                                  " cell points for cells needing " +
                                  std::to_string(generalPoints));
    if (piece.dim != 2 && piece.dim != 3)
      throw std::invalid_argument("VTU output: points of dimension " + std::to_string(piece.dim));
    const std::size_t np = piece.points.size() / piece.dim,
                      nc = piece.quads.size() / 4 + piece.cellTypes.size();
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
           "byte_order=\"LittleEndian\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\""
        << np << "\" NumberOfCells=\"" << nc << "\">\n      <Points>\n";
    VtuField xyz{"Points", 3, {}};
    xyz.values.reserve(3 * np);
    for (std::size_t p = 0; p < np; ++p)
      for (int c = 0; c < 3; ++c)
        xyz.values.push_back(c < piece.dim ? piece.points[piece.dim * p + c] : 0.0);
    writeArray(out, xyz);
    out << "      </Points>\n      <Cells>\n"
        << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    std::vector<int> types(piece.quads.size() / 4, kVtkQuad);
    types.insert(types.end(), piece.cellTypes.begin(), piece.cellTypes.end());
    std::vector<int> points = piece.quads;
    points.insert(points.end(), piece.cellPoints.begin(), piece.cellPoints.end());
    writeNumbers(out, points, 16);
    out << "\n        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" "
           "format=\"ascii\">\n";
    std::vector<std::size_t> offsets(nc);
    for (std::size_t c = 0, offset = 0; c < nc; ++c) offsets[c] = offset += vtkCellSize(types[c]);
    writeNumbers(out, offsets, 16);
    out << "\n        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" "
           "format=\"ascii\">\n";
    writeNumbers(out, types, 32);
    out << "\n        </DataArray>\n      </Cells>\n      <PointData>\n";
    for (const auto& f : piece.pointData) writeArray(out, f);
    out << "      </PointData>\n      <CellData>\n";
    for (const auto& f : piece.cellData) writeArray(out, f);
    out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
    if (!out) throw std::runtime_error("error while writing " + path);
  }
  const std::string index = directory + "/" + basename + ".pvtu";
  if (rank == 0) {
    std::ofstream out(index);
    if (!out) throw std::runtime_error("cannot write " + index);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" "
           "byte_order=\"LittleEndian\">\n  <PUnstructuredGrid GhostLevel=\"0\">\n"
           "    <PPoints>\n      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n"
           "    </PPoints>\n    <PPointData>\n";
    declareArrays(out, piece.pointData);
    out << "    </PPointData>\n    <PCellData>\n";
    declareArrays(out, piece.cellData);
    out << "    </PCellData>\n";
    for (int r = 0; r < comm.getSize(); ++r)
      out << "    <Piece Source=\"" << basename << "_" << r << ".vtu\"/>\n";
    out << "  </PUnstructuredGrid>\n</VTKFile>\n";
  }
  comm.barrier();
  return index;
}

void writePvd(const std::string& path, const std::vector<PvdEntry>& datasets) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error("cannot write " + tmp);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" "
           "byte_order=\"LittleEndian\">\n  <Collection>\n"
        << std::setprecision(17);
    for (const auto& d : datasets)
      out << "    <DataSet timestep=\"" << d.time << "\" group=\"\" part=\"0\" file=\"" << d.file
          << "\"/>\n";
    out << "  </Collection>\n</VTKFile>\n";
    if (!out) throw std::runtime_error("error while writing " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace contact
