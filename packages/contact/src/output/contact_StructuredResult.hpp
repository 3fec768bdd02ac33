#pragma once
// What a run of the structured model problems (Problem = poisson | elasticity) produced: every
// figure its summary.json reports, as values, and the JSON writers that turn them into
// summary.json. Study = single: StructuredRunResult; Study = scalability: the reference paper's
// table, StructuredScalabilityResult (contact_StructuredRun.hpp runs both).
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "contact_ContactResult.hpp"
#include "contact_Json.hpp"
#include "tfeti_FetiSolver.hpp"

namespace contact {

// Study = single.
struct StructuredRunResult {
  std::string problem;  // poisson | elasticity
  int ranks = 0, dimension = 0, subdomains = 0;
  long long elements = 0;
  FetiDimensions feti;      // the solver's dimensions and counters after the solve
  tfeti::DualResult solve;  // PCPG: method, convergence, iterations, residual history
  // Per phase: the start, the assembly, the solver's own phases and the output.
  tfeti::MemoryLog memory;
  double tolerance = 0.0;  // FETI/PCPG/Relative tolerance
  unsigned long long preconditionerFactorBytes = 0;
  tfeti::FetiTimings timings;
  // Output/Time dual operator: the time of one F apply and the bandwidth it achieves.
  std::optional<double> dualApplySeconds, dualApplyBandwidthGbS;
  // With it: the other parts of an iteration (FetiSolver::timeIterationParts).
  tfeti::FetiSolver::IterationParts iterationParts;
  double peakRssMb = 0.0;
  double solutionNorm2 = 0.0;  // over all subdomain copies
  double maxAbsU = 0.0;
  // Prescribed displacements (when the input has some): their rows, the equality residual and
  // the record per entry (boundary, component, value, reaction) as prescribedSummary writes it.
  std::optional<Json> prescribed;
  long long prescribedRows = 0;
  double equalityResidual = 0.0;
  std::optional<double> errorVsDirect;  // Output/Compare with direct solve
  std::string vtu;                      // the VTU file written (empty: none)
};

// A row of the scalability table: one mesh (1/H, H/h) of one problem, solved by FETI and TFETI
// with every preconditioner.
struct StructuredTableRow {
  std::string problem;
  int hInverse = 0, hOverh = 0;  // 1/H and H/h: h = 1 / (hInverse * hOverh)
  int dimension = 0, subdomains = 0;
  long long primal = 0, dualFeti = 0, dualTfeti = 0;
  // Iterations per preconditioner, in the order solved (none: not converged), of FETI and TFETI.
  std::vector<std::pair<std::string, std::optional<int>>> feti, tfeti;
};

// Study = scalability.
struct StructuredScalabilityResult {
  int ranks = 0;
  double tolerance = 0.0;
  std::string localSolver;
  bool allConverged = true;
  std::vector<StructuredTableRow> table;
};

// summary.json of the run, without "parameters" (writeSummary adds them).
Json summaryJson(const StructuredRunResult& result);
Json summaryJson(const StructuredScalabilityResult& result);

}  // namespace contact
