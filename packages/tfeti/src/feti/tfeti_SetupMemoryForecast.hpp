#pragma once
// What a FetiSolver set-up will allocate, told before anything is factorized
// (FetiSolver::forecastSetupMemory, for tfeti_contact --check): the same quantities its memory
// checks (FETI "Memory check") compare with the nodes' MemAvailable, from the same symbolic
// analyses, so that a dry run says what the run's checks will find.
#include <vector>

namespace tfeti {

// One rank's figures, in bytes.
struct SetupMemoryForecast {
  // m_s: the rows of B touching each local subdomain (the explicit F_s is m_s x m_s).
  std::vector<long long> dualRows;
  // The subdomain factors (Subdomain::predictFactorMemory): what they hold once made, and the
  // peak while they are made one by one (the factors so far, the next one's transient): the need
  // of the run's factor check, exactly (the kernels and fixing dofs found as the run finds them).
  // factorsKnown = false where the local solver cannot tell (KLU2, Tacho): the run does not check
  // them, and both are 0.
  double factors = 0.0, factorPeak = 0.0;
  bool factorsKnown = true;
  // The Dirichlet preconditioner (0 with the other preconditioners: its blocks K_bb and K_bi and
  // its interior factors): the set-up's peak as it goes subdomain by subdomain, with each
  // factorization's transient, K freed after each where the run frees it (the need of the run's
  // preconditioner check, exactly); and what the set-up leaves beyond the factors: the
  // preconditioner less the K it freed (negative where it frees K and makes no factor).
  double interiorPeak = 0.0, preconditionerLeaves = 0.0;
  bool interiorKnown = true;
  // The explicit F_s ("Explicit storage"): the blocks' bytes, and the assembly's largest
  // transient (explicitSchurTransient from the analysis with the dofs B_s touches last, the
  // fixing dofs among them left out as the run leaves them; explicitSolvesTransient for the
  // solves). With the K that the Schur assembly frees, this is the run's explicit check's need,
  // exactly (Tacho: see explicitSolverKeeps).
  double explicitBlocks = 0.0, explicitTransient = 0.0, stiffnessFreedByAssembly = 0.0;
  // What the assembly's solves leave with the local solvers as long as their factors live
  // (LocalSolver::solveKeeps: Tacho's workspace, n x min(128, m_s) per subdomain; 0 otherwise),
  // part of the explicit check's need. The run's check counts what the workspace grows by, from
  // the column its earlier solves made: the forecast is above it by at most n doubles a
  // subdomain. (The solves' transient bound, explicitSolvesTransient, counts the local solver's
  // solve vectors as three arrays of the width, which for Tacho may hold the same workspace:
  // counted twice for the largest block at most, on the safe side.)
  double explicitSolverKeeps = 0.0;

  // The run's explicit check's need on this rank (after the factors and the preconditioner are
  // made): the blocks, what the solves leave with the local solvers and the assembly's largest
  // transient, less the K the Schur assembly frees. The dry run's explicit line and the tests
  // take it from here, so that what is printed is what is tested.
  double explicitNeed() const {
    return explicitBlocks + explicitSolverKeeps + explicitTransient - stiffnessFreedByAssembly;
  }
};

}  // namespace tfeti
