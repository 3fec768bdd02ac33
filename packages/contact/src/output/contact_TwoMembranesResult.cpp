#include "contact_TwoMembranesResult.hpp"

#include "contact_RunSummary.hpp"

namespace contact {

namespace {

// The "contact" object: the contact rows' conditions, the contact force and the one expected.
Json membraneContactJson(const tfeti::ConstraintReport& c, double expectedForce) {
  Json j = constraintJson(c);
  j["force"] = c.force;
  j["expected_force"] = expectedForce;
  return j;
}

Json solveJson(const TwoMembranesSolve& m) {
  Json j = qpJson(m.result);
  j["contact"] = membraneContactJson(m.contact, m.expectedContactForce);
  j["setup_s"] = m.setupSeconds;
  j["solve_s"] = m.solveSeconds;
  j["max_abs_u"] = m.maxAbsU;
  return j;
}

Json rowJson(const TwoMembranesTableRow& r) {
  Json row = Json::object();
  row["problem"] = "two_membranes";
  row["H_inverse"] = r.hInverse;
  row["h_inverse"] = r.hInverse * r.hOverh;
  row["H_over_h"] = r.hOverh;
  row["subdomains"] = r.subdomains;
  row["primal_dim"] = r.primal;
  row["dual_dim"] = r.dual;
  Json bySolver = Json::object();
  for (const auto& m : r.solvers) bySolver[m.method] = solveJson(m);
  row["solvers"] = std::move(bySolver);
  return row;
}

}  // namespace

Json summaryJson(const TwoMembranesResult& r) {
  Json s = Json::object();
  s["study"] = "single";
  s["problem"] = "two_membranes";
  s["ranks"] = r.ranks;
  s["subdomains"] = r.subdomains;
  s["elements"] = r.elements;
  s["H"] = r.H;
  s["h"] = r.h;
  addSolverSummary(s, r.feti, r.solve, r.memory);
  s["qp"] = qpJson(r.solve);
  s["contact"] = membraneContactJson(r.contact, r.expectedContactForce);
  Json timings = timingsJson(r.timings, r.solve.iterations);
  const long long multiplications = r.solve.qp.hessianMultiplications;
  timings["per_multiplication_s"] =
      multiplications > 0 ? r.timings.solve / static_cast<double>(multiplications) : 0.0;
  s["timings"] = std::move(timings);
  s["peak_rss_mb"] = r.peakRssMb;
  s["solution_norm2"] = r.solutionNorm2;
  s["max_abs_u"] = r.maxAbsU;
  s["min_u"] = r.minU;
  s["contact_csv"] = r.contactCsv;
  if (!r.vtu.empty()) s["vtu"] = r.vtu;
  return s;
}

Json summaryJson(const TwoMembranesScalabilityResult& r) {
  Json s = Json::object();
  s["study"] = "scalability";
  s["problem"] = "two_membranes";
  s["ranks"] = r.ranks;
  s["all_converged"] = r.allConverged;
  Json table = Json::array();
  for (const auto& row : r.table) table.push(rowJson(row));
  s["table"] = std::move(table);
  return s;
}

}  // namespace contact
