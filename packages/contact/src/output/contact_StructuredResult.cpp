#include "contact_StructuredResult.hpp"

#include "contact_RunSummary.hpp"

namespace contact {

namespace {

// The stopping rule of PCPG both studies report ("stopping_rule").
const char* const kPcpgStoppingRule =
    "relative norm of the projected gradient: ||P(F lambda - d)|| <= tol * ||P d||";

Json iterationsJson(const std::vector<std::pair<std::string, std::optional<int>>>& its) {
  Json j = Json::object();
  for (const auto& [preconditioner, n] : its) j[preconditioner] = n ? Json(*n) : Json();
  return j;
}

Json rowJson(const StructuredTableRow& r) {
  Json row = Json::object();
  row["problem"] = r.problem;
  row["H"] = 1.0 / r.hInverse;
  row["h"] = 1.0 / (r.hInverse * r.hOverh);
  row["H_inverse"] = r.hInverse;
  row["h_inverse"] = r.hInverse * r.hOverh;
  row["dimension"] = r.dimension;
  row["subdomains"] = r.subdomains;
  row["primal_dim"] = r.primal;
  row["dual_dim_feti"] = r.dualFeti;
  row["dual_dim_tfeti"] = r.dualTfeti;
  Json iterations = Json::object();
  iterations["feti"] = iterationsJson(r.feti);
  iterations["tfeti"] = iterationsJson(r.tfeti);
  row["iterations"] = std::move(iterations);
  return row;
}

}  // namespace

Json summaryJson(const StructuredRunResult& r) {
  Json s = Json::object();
  s["study"] = "single";
  s["problem"] = r.problem;
  s["ranks"] = r.ranks;
  s["dimension"] = r.dimension;
  s["subdomains"] = r.subdomains;
  s["elements"] = r.elements;
  addSolverSummary(s, r.feti, r.solve, r.memory);
  s["stopping_rule"] = kPcpgStoppingRule;
  s["tolerance"] = r.tolerance;
  s["preconditioner_factor_bytes"] = r.preconditionerFactorBytes;
  s["timings"] = timingsJson(r.timings, r.solve.iterations);
  if (r.dualApplySeconds) {
    s["timings"]["dual_apply_s"] = *r.dualApplySeconds;
    s["timings"]["projector_apply_s"] = r.iterationParts.projector;
    s["timings"]["preconditioner_apply_s"] = r.iterationParts.preconditioner;
    s["timings"]["vector_updates_s"] = r.iterationParts.vectorUpdates;
    s["dual_apply_bandwidth_gb_s"] = r.dualApplyBandwidthGbS.value_or(0.0);
  }
  s["peak_rss_mb"] = r.peakRssMb;
  s["solution_norm2"] = r.solutionNorm2;
  s["max_abs_u"] = r.maxAbsU;
  if (r.prescribed) {
    s["prescribed_rows"] = r.prescribedRows;
    s["equality_residual"] = r.equalityResidual;
    s["prescribed"] = *r.prescribed;
  }
  if (r.errorVsDirect) s["error_vs_direct"] = *r.errorVsDirect;
  if (!r.vtu.empty()) s["vtu"] = r.vtu;
  return s;
}

Json summaryJson(const StructuredScalabilityResult& r) {
  Json s = Json::object();
  s["study"] = "scalability";
  s["ranks"] = r.ranks;
  s["stopping_rule"] = kPcpgStoppingRule;
  s["tolerance"] = r.tolerance;
  s["local_solver"] = r.localSolver;
  s["all_converged"] = r.allConverged;
  Json table = Json::array();
  for (const auto& row : r.table) table.push(rowJson(row));
  s["table"] = std::move(table);
  return s;
}

}  // namespace contact
