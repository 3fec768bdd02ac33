// VTU output of mixed plane cells: what ParaView reads back (cell count, offsets, types, point
// data) must match what was handed over, and inconsistent input is an error.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "contact_VtuWriter.hpp"

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The whitespace-separated values of the DataArray named `name`.
std::vector<long long> dataArray(const std::string& xml, const std::string& name) {
  const auto start = xml.find("Name=\"" + name + "\"");
  const auto open = xml.find('>', start) + 1;
  const auto close = xml.find("</DataArray>", open);
  std::istringstream in(xml.substr(open, close - open));
  std::vector<long long> v;
  for (long long x; in >> x;) v.push_back(x);
  return v;
}

// A quad, a 3-node triangle and a 9-node quad on 15 points.
contact::VtuPiece mixedPiece() {
  contact::VtuPiece p;
  for (int i = 0; i < 15; ++i) p.points.insert(p.points.end(), {0.1 * i, 0.2 * (i % 3)});
  p.quads = {0, 1, 2, 3};
  p.cellTypes = {contact::kVtkTriangle, contact::kVtkBiquadraticQuad};
  p.cellPoints = {3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14};
  contact::VtuField u{"u", 1, {}};
  for (int i = 0; i < 15; ++i) u.values.push_back(i);
  p.pointData.push_back(u);
  p.cellData.push_back({"subdomain", 1, {0, 1, 2}});
  return p;
}

TEUCHOS_UNIT_TEST(VtuWriter, MixedCellsAreWrittenAsVtkReadsThem) {
  auto comm = Tpetra::getDefaultComm();
  const std::string dir = std::filesystem::temp_directory_path() / "contact_vtu_test";
  std::filesystem::create_directories(dir);
  const std::string index = contact::writeVtu(*comm, dir, "mixed", mixedPiece());
  TEST_ASSERT(std::filesystem::exists(index));
  const std::string xml = slurp(dir + "/mixed_0.vtu");
  TEST_ASSERT(xml.find("NumberOfPoints=\"15\" NumberOfCells=\"3\"") != std::string::npos);
  TEST_COMPARE_ARRAYS(dataArray(xml, "offsets"), std::vector<long long>({4, 7, 16}));
  TEST_COMPARE_ARRAYS(dataArray(xml, "types"), std::vector<long long>({9, 5, 28}));
  const auto conn = dataArray(xml, "connectivity");
  TEST_EQUALITY(conn.size(), std::size_t(16));
  TEST_EQUALITY(conn.back(), 14LL);
  TEST_COMPARE_ARRAYS(dataArray(xml, "subdomain"), std::vector<long long>({0, 1, 2}));
  const std::string pvtu = slurp(index);
  TEST_ASSERT(pvtu.find("Name=\"u\"") != std::string::npos);
  TEST_ASSERT(pvtu.find("mixed_0.vtu") != std::string::npos);
}

TEUCHOS_UNIT_TEST(VtuWriter, InconsistentCellsAreAnError) {
  auto comm = Tpetra::getDefaultComm();
  const std::string dir = std::filesystem::temp_directory_path() / "contact_vtu_test";
  std::filesystem::create_directories(dir);
  contact::VtuPiece p = mixedPiece();
  p.cellPoints.pop_back();  // the 9-node quad now has 8 points
  TEST_THROW(contact::writeVtu(*comm, dir, "bad", p), std::invalid_argument);
  p = mixedPiece();
  p.cellTypes[0] = 23;  // VTK_QUADRATIC_QUAD: not a cell this code writes
  TEST_THROW(contact::writeVtu(*comm, dir, "bad", p), std::invalid_argument);
}

// The FETI driver lists its quadrilaterals as general cells (one code path with the hexahedra of
// 3D): the file is the one the quads list gives.
TEUCHOS_UNIT_TEST(VtuWriter, QuadsAsGeneralCellsWriteTheSameFile) {
  auto comm = Tpetra::getDefaultComm();
  const std::string dir = std::filesystem::temp_directory_path() / "contact_vtu_test";
  std::filesystem::create_directories(dir);
  contact::VtuPiece quads;
  for (int i = 0; i < 6; ++i)
    quads.points.insert(quads.points.end(), {0.5 * (i % 3), 0.5 * (i / 3)});
  quads.quads = {0, 1, 4, 3, 1, 2, 5, 4};
  quads.pointData.push_back({"displacement", 3, std::vector<double>(18, 0.25)});
  quads.cellData.push_back({"subdomain", 1, {0, 1}});
  contact::VtuPiece general = quads;
  general.quads.clear();
  general.cellTypes = {contact::kVtkQuad, contact::kVtkQuad};
  general.cellPoints = quads.quads;
  contact::writeVtu(*comm, dir, "as_quads", quads);
  contact::writeVtu(*comm, dir, "as_cells", general);
  const std::string a = slurp(dir + "/as_quads_0.vtu"), b = slurp(dir + "/as_cells_0.vtu");
  TEST_ASSERT(!a.empty());
  TEST_ASSERT(a == b);
}

}  // namespace
