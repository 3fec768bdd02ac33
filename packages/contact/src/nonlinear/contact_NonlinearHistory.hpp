#pragma once
// The record of a nonlinear contact run (every iteration of every load step, the converged
// steps' results) and the restart files that let a run continue from its last converged step.
//
// Layout of DIR/restart: state.txt (text: the last converged step, its load factor and step
// size, and the whole record) and step_<n>/subdomain_<id>.bin (binary: the subdomain's total
// displacement and committed material history). state.txt is written last and atomically
// (rename), after every subdomain file of its step, so it never names an incomplete step.
#include <string>
#include <vector>

#include "contact_Json.hpp"

namespace contact {

struct IterationRecord {
  int step = 0;  // the load step being attempted (1-based)
  double loadFactor = 0.0;
  int iteration = 0;
  double relativeResidual = 0.0;   // ||f - B^T lambda - f_int|| / ||f||
  double relativeIncrement = 0.0;  // ||du|| / ||u||
  double solutionNorm = 0.0;       // ||u||
  long long mprgpIterations = 0;   // MPRGP steps of this iteration's QP solve
  long long hessianMultiplications = 0;
  bool accepted = false;           // part of a converged step (not of a cut-back attempt)
  double qpToleranceFactor = 1.0;  // the QP stopped at this factor times its tolerances
  double lineSearchStep = 1.0;     // the fraction of the Newton step taken
};

struct StepRecord {
  int step = 0;
  double loadFactor = 0.0;
  int outerIterations = 0;
  long long mprgpIterations = 0, hessianMultiplications = 0;
  int cutbacks = 0;  // attempts of this step that were rejected before it converged
  std::vector<double> residuals, increments;
  double pMax = 0.0, maxVonMises = 0.0, maxPlasticStrain = 0.0, contactExtent = 0.0;
  double contactForce = 0.0;  // sum lambda n on the slave body, along the applied load
};

struct NonlinearHistory {
  int step = 0;             // converged steps so far
  double loadFactor = 0.0;  // of the last converged step
  double stepSize = 0.0;    // the load increment to try next
  std::vector<StepRecord> steps;
  std::vector<IterationRecord> iterations;
};

// summary.json's "steps": one object per converged step (the keys issue 5 names).
Json stepsJson(const NonlinearHistory& history);
struct IterationTotals {
  long long iterations = 0, rejected = 0, mprgpIterations = 0, hessianMultiplications = 0;
};
IterationTotals iterationTotals(const NonlinearHistory& history);

// Rank-0 files; each throws std::runtime_error naming the file.
void writeRestartState(const std::string& restartDir, const NonlinearHistory& history);
NonlinearHistory readRestartState(const std::string& restartDir);
void writeIterationsCsv(const std::string& path, const NonlinearHistory& history);
void writeStepsCsv(const std::string& path, const NonlinearHistory& history);

// One subdomain's state at a converged step (written by the rank that holds it).
struct SubdomainRestart {
  int id = -1;
  std::vector<double> displacement;
  std::vector<double> history;  // empty for an elastic body
};
std::string restartStepDirectory(const std::string& restartDir, int step);
void writeSubdomainRestart(const std::string& stepDir, const SubdomainRestart& state);
SubdomainRestart readSubdomainRestart(const std::string& stepDir, int id);

}  // namespace contact
