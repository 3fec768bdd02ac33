// The mesh-file checks Gmsh's reader does not make: a node or element tag defined twice (ASCII
// formats 2.2 and 4.1, which lay out their sections differently) and two nodes of one body at
// one point. Each error must name the file and the tags; valid files must pass unchanged.
#include <Teuchos_UnitTestHarness.hpp>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact_GmshMesh.hpp"
#include "contact_MeshIntegrity.hpp"

namespace {

// Two triangles of the unit square in format 4.1: one surface entity in the physical group
// "body". The node and element sections are parameters so that tests can damage them.
std::string msh41(const std::string& nodeTags, const std::string& elements) {
  return "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
         "$PhysicalNames\n1\n2 1 \"body\"\n$EndPhysicalNames\n"
         "$Entities\n0 0 1 0\n1 0 0 0 1 1 0 1 1 0\n$EndEntities\n"
         "$Nodes\n1 4 1 4\n2 1 0 4\n" +
         nodeTags + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n$EndNodes\n$Elements\n1 2 1 2\n2 1 2 2\n" +
         elements + "$EndElements\n";
}

std::string msh22(const std::string& nodes, const std::string& elements) {
  return "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
         "$PhysicalNames\n1\n2 1 \"body\"\n$EndPhysicalNames\n$Nodes\n4\n" +
         nodes + "$EndNodes\n$Elements\n2\n" + elements + "$EndElements\n";
}

std::string write(const std::string& name, const std::string& text) {
  const std::string path = std::string(P_tmpdir) + "/contact_MeshIntegrity_" + name + ".msh";
  std::ofstream(path) << text;
  return path;
}

std::string errorOf(const std::string& path) {
  try {
    contact::checkUniqueMshTags(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

const std::string kTags = "1\n2\n3\n4\n";
const std::string kTris41 = "1 1 2 3\n2 1 3 4\n";
const std::string kNodes22 = "1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n";
const std::string kTris22 = "1 2 2 1 1 1 2 3\n2 2 2 1 1 1 3 4\n";

TEUCHOS_UNIT_TEST(MeshIntegrity, ValidFilesPassAndLoad) {
  for (const std::string& path :
       {write("ok41", msh41(kTags, kTris41)), write("ok22", msh22(kNodes22, kTris22))}) {
    TEST_EQUALITY(errorOf(path), "");
    const contact::GmshMesh mesh = contact::loadMesh(path);  // Gmsh agrees the file is valid
    TEST_EQUALITY(mesh.bodies.size(), 1u);
    TEST_EQUALITY(mesh.bodies[0].numElements(), 2);
    TEST_EQUALITY(mesh.coords.size(), 8u);
    std::remove(path.c_str());
  }
}

TEUCHOS_UNIT_TEST(MeshIntegrity, NodeTagDefinedTwice) {
  const std::string p41 = write("node41", msh41("1\n2\n3\n2\n", kTris41));
  const std::string e41 = errorOf(p41);
  out << e41 << "\n";
  TEST_ASSERT(contains(e41, p41) && contains(e41, "node tag 2 is defined twice") &&
              contains(e41, "lines 16 and 18"));
  const std::string p22 = write("node22", msh22("1 0 0 0\n2 1 0 0\n3 1 1 0\n2 0 1 0\n", kTris22));
  const std::string e22 = errorOf(p22);
  out << e22 << "\n";
  TEST_ASSERT(contains(e22, p22) && contains(e22, "node tag 2 is defined twice") &&
              contains(e22, "lines 11 and 13"));
  // Through the reader, as a run meets it.
  TEST_THROW(contact::loadMesh(p22), std::runtime_error);
  std::remove(p41.c_str());
  std::remove(p22.c_str());
}

TEUCHOS_UNIT_TEST(MeshIntegrity, ElementTagDefinedTwice) {
  const std::string p41 = write("elem41", msh41(kTags, "1 1 2 3\n1 1 3 4\n"));
  const std::string e41 = errorOf(p41);
  out << e41 << "\n";
  TEST_ASSERT(contains(e41, "element tag 1 is defined twice") && contains(e41, "lines 27 and 28"));
  const std::string p22 = write("elem22", msh22(kNodes22, "5 2 2 1 1 1 2 3\n5 2 2 1 1 1 3 4\n"));
  TEST_ASSERT(contains(errorOf(p22), "element tag 5 is defined twice"));
  std::remove(p41.c_str());
  std::remove(p22.c_str());
}

TEUCHOS_UNIT_TEST(MeshIntegrity, CoincidentNodesOfABodyAreACrack) {
  // Nodes 0..3 of the unit square and node 4 a copy of node 2 (tags 10, 20, ..., 50).
  const std::vector<double> xy = {0, 0, 1, 0, 1, 1, 0, 1, 1, 1};
  const std::vector<std::size_t> tags = {10, 20, 30, 40, 50};
  std::string e;
  try {
    contact::checkNoCoincidentNodes("m.msh", "body", 2, xy, {0, 1, 2, 3, 4}, tags);
  } catch (const std::runtime_error& err) {
    e = err.what();
  }
  out << e << "\n";
  TEST_ASSERT(contains(e, "m.msh") && contains(e, "\"body\"") && contains(e, "30 and 50"));
  // A body that uses only one of the two copies is fine (the other belongs to another body).
  TEST_NOTHROW(contact::checkNoCoincidentNodes("m.msh", "body", 2, xy, {0, 1, 2, 3}, tags));
  // Close but distinct nodes (a graded mesh) are not coincident.
  const std::vector<double> close = {0, 0, 1, 0, 1, 1, 0, 1, 1, 1 + 1e-9};
  TEST_NOTHROW(contact::checkNoCoincidentNodes("m.msh", "body", 2, close, {0, 1, 2, 3, 4}, tags));
}

}  // namespace
