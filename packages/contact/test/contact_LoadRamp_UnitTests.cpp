// Per-entry load ramps: the scaling clamp((t - start) / (end - start), 0, 1) and the default
// window {0, 1} equal to t to the last bit; the parameter's checks (two values per entry,
// 0 <= start < end <= 1) with errors naming the parameter; prescribed rows and values scaled by
// their entry's ramp; conflicting ramps at a shared node. Serial code.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact_LoadRamp.hpp"
#include "contact_PrescribedDisplacement.hpp"
#include "contact_StructuredProblem.hpp"

namespace {

using contact::LoadRamp;

bool throwsNaming(const std::function<void()>& f, const std::string& what,
                  Teuchos::FancyOStream& out) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    out << "error: " << e.what() << "\n";
    return std::string(e.what()).find(what) != std::string::npos;
  }
  return false;
}

TEUCHOS_UNIT_TEST(LoadRamp, Scaling) {
  const LoadRamp normal{0.0, 0.5}, tangential{0.5, 1.0}, middle{0.25, 0.75};
  TEST_EQUALITY(normal.factor(0.0), 0.0);
  TEST_EQUALITY(normal.factor(0.25), 0.5);
  TEST_EQUALITY(normal.factor(0.5), 1.0);
  TEST_EQUALITY(normal.factor(1.0), 1.0);       // kept after its window
  TEST_EQUALITY(tangential.factor(0.25), 0.0);  // nothing before its window
  TEST_EQUALITY(tangential.factor(0.5), 0.0);
  TEST_EQUALITY(tangential.factor(0.75), 0.5);
  TEST_EQUALITY(tangential.factor(1.0), 1.0);
  TEST_EQUALITY(middle.factor(0.5), 0.5);
  TEST_EQUALITY(middle.factor(0.8), 1.0);
  // The default window is t itself, bit for bit, at any load factor a step control may reach.
  const LoadRamp all;
  TEST_ASSERT(all.isDefault());
  for (double t : {0.0, 0.1, 1.0 / 3.0, 0.7, 0.999999, 1.0}) TEST_EQUALITY(all.factor(t), t);
}

TEUCHOS_UNIT_TEST(LoadRamp, Parameters) {
  Teuchos::ParameterList list;
  contact::addLoadRampParameters(list);
  // Empty: {0, 1} for every entry.
  auto ramps = contact::loadRamps(list, "Prescribed ramps", 3, "Contact problem");
  TEST_EQUALITY(ramps.size(), 3u);
  for (const auto& r : ramps) TEST_ASSERT(r.isDefault());
  list.set("Prescribed ramps", Teuchos::Array<double>(std::vector<double>{0.0, 0.5, 0.5, 1.0}));
  ramps = contact::loadRamps(list, "Prescribed ramps", 2, "Contact problem");
  TEST_EQUALITY(ramps[0].end, 0.5);
  TEST_EQUALITY(ramps[1].start, 0.5);
  // Wrong length, reversed or empty window, outside [0, 1]: errors naming the parameter.
  TEST_ASSERT(
      throwsNaming([&] { contact::loadRamps(list, "Prescribed ramps", 3, "Contact problem"); },
                   "Contact problem/Prescribed ramps: 4 values; it needs {start, end} for "
                   "each of the 3 entries",
                   out));
  for (const auto& bad : {Teuchos::Array<double>(std::vector<double>{0.5, 0.5}),
                          Teuchos::Array<double>(std::vector<double>{0.8, 0.2}),
                          Teuchos::Array<double>(std::vector<double>{-0.1, 0.5}),
                          Teuchos::Array<double>(std::vector<double>{0.0, 1.5})}) {
    list.set("Traction ramps", bad);
    TEST_ASSERT(
        throwsNaming([&] { contact::loadRamps(list, "Traction ramps", 1, "Contact problem"); },
                     "Contact problem/Traction ramps: entry 1 has", out));
  }
}

TEUCHOS_UNIT_TEST(LoadRamp, PrescribedRows) {
  // u_x = 1e-3 on x1 from t = 0.5 on, u_y = -2e-3 on y1 until t = 0.5: the rows' right-hand
  // sides at t (from u = 0) are the values times their entry's ramp.
  contact::StructuredProblem p;
  p.field = "elasticity";
  p.subdomains = {2, 2};
  p.elements = {2, 2};
  p.fixed.clear();
  p.symmetry = {{"x0", 0}, {"y0", 1}};
  p.prescribed = {{"x1", 0, 1e-3, {0.5, 1.0}}, {"y1", 1, -2e-3, {0.0, 0.5}}};
  const contact::PrescribedValues values = p.prescribedValues();
  const auto comm = Tpetra::getDefaultComm();
  const auto local = contact::buildLocalSubdomains(p, *comm);
  for (double t : {0.25, 0.5, 0.75, 1.0}) {
    const double ux = 1e-3 * LoadRamp{0.5, 1.0}.factor(t);
    const double uy = -2e-3 * LoadRamp{0.0, 0.5}.factor(t);
    int nx = 0, ny = 0;
    for (const auto& row : contact::prescribedDisplacementRows(local, values, t)) {
      const bool x = row.entries[0].dof % 2 == 0;
      TEST_EQUALITY(row.rhs, x ? ux : uy);
      (x ? nx : ny) += 1;
    }
    out << "t = " << t << ": u_x rows " << nx << " at " << ux << ", u_y rows " << ny << " at " << uy
        << "\n";
    TEST_ASSERT(nx > 0 && ny > 0);
  }
  // The corner (x1, y1) carries two components, each with its own ramp: no conflict. The same
  // component of a shared node with one value and two ramps is one.
  p.symmetry.clear();  // only the two prescribed boundaries meet (at the corner (1, 1))
  p.prescribed = {{"x1", 0, 1e-3, {0.5, 1.0}}, {"y1", 0, 1e-3, {0.0, 0.5}}};
  TEST_ASSERT(throwsNaming([&] { p.prescribedValues(); },
                           "meet at a node with different ramps of the same component", out));
}

}  // namespace
