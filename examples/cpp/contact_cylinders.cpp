// Guide program 2 (docs/cpp_guide.md): a contact problem configured in C++.
//
// The reference paper's two cylinders (a steel cylinder of radius 1 m pressed onto a block by a
// line load of 4e7 N/m, symmetric half model, coarse mesh) set up by a ParameterList built in
// code, solved by contact::ContactSolver, and its results read from the ContactResult: p_max,
// the half-width, the contact force, the pressure per slave node and the QP counters. Hertz's
// line contact is computed here from the same data; the program exits non-zero when the run
// misses it by more than the mesh allows (3 % in p_max, 5 % in the half-width) or the contact
// force does not balance the load.
//
// Usage: contact_cylinders GEO_FILE   (the package's examples/two_cylinders.geo)
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <iostream>

#include "contact_ContactSolver.hpp"

namespace {
// A Teuchos::Array parameter value (Array's own brace constructor would read {4, 4} as
// "4 copies of 4").
template <class T>
Teuchos::Array<T> array(std::initializer_list<T> values) {
  return Teuchos::Array<T>(values.begin(), values.end());
}

// The same list as tests/inputs/two_cylinders_coarse.xml, in code.
Teuchos::ParameterList cylinderParameters(const std::string& geo, double E, double nu,
                                          double lineLoad) {
  Teuchos::ParameterList p("tfeti_contact");
  p.set("Problem", "elastic_contact");
  p.sublist("Material").set("Young's modulus", E).set("Poisson's ratio", nu);
  Teuchos::ParameterList& cp = p.sublist("Contact problem");
  cp.set("Mesh file", geo);
  cp.set("Element order", 1);
  cp.set("Mesh size factor", 2.0);  // coarse: 4 mm elements at the contact point
  cp.set("Bodies", array<std::string>({"cylinder", "block"}));
  cp.set("Subdomains per body", array({4, 4}));
  cp.set("Fixed boundaries", array<std::string>({"fixed"}));
  cp.set("Symmetry boundaries", array<std::string>({"cylinder_symmetry", "block_symmetry"}));
  cp.set("Symmetry components", array({0, 0}));
  cp.set("Traction boundaries", array<std::string>({"load"}));
  // The half model carries half the line load on its loaded edge of length 1 m.
  cp.set("Tractions", array({0.0, -lineLoad / 2}));
  cp.set("Slave", "cylinder_contact");
  cp.set("Master", "block_contact");
  cp.set("Search radius", 0.1);
  Teuchos::ParameterList& feti = p.sublist("FETI");
  feti.set("Dual solver", "SMALBE");
  // Tight enough for the contact force to balance the load to 1e-6.
  feti.sublist("SMALBE").set("Relative tolerance", 1e-7).set("Equality tolerance", 1e-9);
  return p;
}
}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  const bool root = comm->getRank() == 0;
  if (argc < 2) {
    if (root) std::cerr << "usage: contact_cylinders GEO_FILE (examples/two_cylinders.geo)\n";
    return 1;
  }
  const double E = 2.0e11, nu = 0.3, lineLoad = 4.0e7, radius = 1.0;

  contact::ContactSolver solver(comm);
  solver.setParameters(cylinderParameters(argv[1], E, nu, lineLoad));
  const contact::ContactResult r = solver.solve();  // sets up first: mesh, partition, factorize
  if (!r.converged) {
    if (root) std::cerr << "contact_cylinders: not converged: " << r.message << "\n";
    return r.exitCode;
  }

  // Hertz's line contact of a cylinder on a flat body of the same material (plane strain).
  const double pi = std::acos(-1.0);
  const double eStar = E / (2 * (1 - nu * nu));
  const double a = std::sqrt(4 * lineLoad * radius / (pi * eStar));
  const double p0 = 2 * lineLoad / (pi * a);

  const contact::ContactMeasures& c = r.contact;
  const double pMaxError = std::abs(c.pMax - p0) / p0;
  const double widthError = std::abs(c.extent - a) / a;
  // The per-node pressures: p_max is their largest, and no node pulls (pressure >= 0).
  double largest = 0.0, smallest = 0.0;
  int touching = 0;
  for (const contact::ContactNode& node : r.contactNodes) {
    largest = std::max(largest, node.pressure);
    smallest = std::min(smallest, node.pressure);
    if (node.lambda > 0) ++touching;
  }
  const tfeti::QpCounters& qp = r.qp.qp;

  if (root) {
    std::cout << "contact_cylinders: " << r.ranks << " ranks, " << r.subdomains << " subdomains, "
              << r.nodes << " nodes, " << r.contactNodes.size() << " slave nodes (" << touching
              << " in contact)\n"
              << "  p_max " << c.pMax / 1e6 << " MPa (Hertz " << p0 / 1e6 << ", error "
              << 100 * pMaxError << " %), half-width " << 1e3 * c.extent << " mm (Hertz " << 1e3 * a
              << ", error " << 100 * widthError << " %)\n"
              << "  contact force " << c.force << " N/m for " << c.appliedForce
              << " applied (relative error " << c.forceRelativeError << ")\n"
              << "  " << r.qp.method << ": " << qp.outerIterations << " outer iterations, "
              << qp.hessianMultiplications << " Hessian multiplications, " << qp.cgSteps << " CG, "
              << qp.expansionSteps << " expansion, " << qp.proportioningSteps
              << " proportioning steps\n";
  }
  const bool ok = pMaxError < 0.03 && widthError < 0.05 && c.forceRelativeError < 1e-6 &&
                  std::abs(largest - c.pMax) <= 1e-9 * c.pMax && smallest >= 0.0 && touching > 2 &&
                  qp.converged && qp.hessianMultiplications > 0;
  if (!ok && root) std::cerr << "contact_cylinders: WRONG ANSWER\n";
  return ok ? 0 : 1;
}
