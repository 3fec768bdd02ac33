#include "contact_VtuWriter.hpp"

#include <fstream>
#include <stdexcept>

namespace contact {

namespace {
void writeArray(std::ofstream& out, const VtuField& f) {
  out << "        <DataArray type=\"Float64\" Name=\"" << f.name << "\" NumberOfComponents=\""
      << f.components << "\" format=\"ascii\">\n";
  out.precision(10);
  for (std::size_t i = 0; i < f.values.size(); ++i)
    out << f.values[i] << ((i + 1) % 12 ? ' ' : '\n');
  out << "\n        </DataArray>\n";
}

void declareArrays(std::ofstream& out, const std::vector<VtuField>& fields) {
  for (const auto& f : fields)
    out << "      <PDataArray type=\"Float64\" Name=\"" << f.name << "\" NumberOfComponents=\""
        << f.components << "\"/>\n";
}
}  // namespace

std::string writeVtu(const tfeti::Comm& comm, const std::string& directory,
                     const std::string& basename, const VtuPiece& piece) {
  const int rank = comm.getRank();
  const std::string pieceName = basename + "_" + std::to_string(rank) + ".vtu";
  const std::string path = directory + "/" + pieceName;
  {
    std::ofstream out(path);
    if (!out) throw std::runtime_error("cannot write " + path);
    const std::size_t np = piece.points.size() / 2, nc = piece.quads.size() / 4;
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
           "byte_order=\"LittleEndian\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\""
        << np << "\" NumberOfCells=\"" << nc << "\">\n      <Points>\n";
    VtuField xyz{"Points", 3, {}};
    xyz.values.reserve(3 * np);
    for (std::size_t p = 0; p < np; ++p)
      xyz.values.insert(xyz.values.end(), {piece.points[2 * p], piece.points[2 * p + 1], 0.0});
    writeArray(out, xyz);
    out << "      </Points>\n      <Cells>\n"
        << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (std::size_t k = 0; k < piece.quads.size(); ++k)
      out << piece.quads[k] << ((k + 1) % 16 ? ' ' : '\n');
    out << "\n        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" "
           "format=\"ascii\">\n";
    for (std::size_t c = 0; c < nc; ++c) out << 4 * (c + 1) << ((c + 1) % 16 ? ' ' : '\n');
    out << "\n        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" "
           "format=\"ascii\">\n";
    for (std::size_t c = 0; c < nc; ++c) out << "9" << ((c + 1) % 32 ? ' ' : '\n');  // VTK_QUAD
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

}  // namespace contact
