#pragma once
// What a run of the two-membrane benchmark (Problem = two_membranes, contact_TwoMembranes.hpp)
// produced: every figure its summary.json reports, as values, and the JSON writers that turn them
// into summary.json. Study = single: TwoMembranesResult; Study = scalability: the table of the QP
// solvers' Hessian multiplications over H and H/h, TwoMembranesScalabilityResult
// (contact_TwoMembranesRun.hpp runs both).
#include <string>
#include <vector>

#include "contact_ContactResult.hpp"
#include "contact_Json.hpp"
#include "tfeti_FetiSolver.hpp"

namespace contact {

// Study = single.
struct TwoMembranesResult {
  int ranks = 0, subdomains = 0;
  long long elements = 0;  // of both membranes
  double H = 0.0, h = 0.0;
  FetiDimensions feti;      // the solver's dimensions and counters after the solve
  tfeti::DualResult solve;  // the QP solve: method, convergence, counters, residual history
  tfeti::MemoryLog memory;  // the solver's phases
  tfeti::ConstraintReport contact;
  double expectedContactForce = 0.0;
  tfeti::FetiTimings timings;
  double peakRssMb = 0.0;
  double solutionNorm2 = 0.0, maxAbsU = 0.0, minU = 0.0;  // over all subdomain copies
  std::string contactCsv, vtu;                            // the files written (vtu empty: none)
};

// One QP solver's solve of a table row.
struct TwoMembranesSolve {
  std::string method;  // SMALBE | penalty
  tfeti::DualResult result;
  tfeti::ConstraintReport contact;
  double expectedContactForce = 0.0;
  double setupSeconds = 0.0, solveSeconds = 0.0, maxAbsU = 0.0;
};

// A row of the table: one mesh (1/H, H/h) solved by every QP solver.
struct TwoMembranesTableRow {
  int hInverse = 0, hOverh = 0;  // 1/H and H/h: h = 1 / (hInverse * hOverh)
  int subdomains = 0;
  long long primal = 0, dual = 0;
  std::vector<TwoMembranesSolve> solvers;  // in the order solved
};

// Study = scalability.
struct TwoMembranesScalabilityResult {
  int ranks = 0;
  bool allConverged = true;
  std::vector<TwoMembranesTableRow> table;
};

// summary.json of the run, without "parameters" (writeSummary adds them).
Json summaryJson(const TwoMembranesResult& result);
Json summaryJson(const TwoMembranesScalabilityResult& result);

}  // namespace contact
