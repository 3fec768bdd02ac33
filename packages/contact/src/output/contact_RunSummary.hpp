#pragma once
// The pieces of summary.json every run shares (the contact runs, the structured problems, the two
// membranes): timings, memory, the FETI dimensions and the dual solve, the QP counters, the
// constraint report, the validated parameters and the file itself; and the VTU piece of a solved
// FETI problem.
#include <string>

#include "contact_ContactResult.hpp"
#include "contact_Json.hpp"
#include "contact_VtuWriter.hpp"
#include "tfeti_FetiSolver.hpp"

namespace contact {

Json timingsJson(const tfeti::FetiTimings& t, int iterations);
// The validated parameter list (defaults filled in) as JSON: sublists as objects, arrays as
// arrays.
Json parametersJson(const Teuchos::ParameterList& params);
// DIR/summary.json (rank 0): the summary plus "parameters", the list the run solved.
void writeSummary(const tfeti::Comm& comm, const std::string& dir, const Json& summary,
                  const Teuchos::ParameterList& params);
// Largest resident set size over the ranks, in MiB.
double peakRssMb(const tfeti::Comm& comm);
// The "memory" object of a summary: per phase (in the order run) the resident size after it and
// the peak so far, the largest over the ranks and the sum over them (MiB); the peak per rank and
// over all ranks, and the peak over all ranks in bytes per unknown.
Json memoryJson(const tfeti::MemoryLog& log, long long unknowns);
// The solved subdomains of this rank (2D or 3D, their elements as cells): u (or displacement)
// per node, subdomain id per cell.
VtuPiece vtuPiece(const tfeti::FetiSolver& solver);

// The solver's dimensions and counters after a solve; feti: its FETI parameters (formulation,
// preconditioner, local solver).
FetiDimensions fetiDimensions(const tfeti::FetiSolver& solver, const Teuchos::ParameterList& feti);
// "factor_bytes" (the subdomain factors of all ranks) and "factor_memory_check": checked (false:
// "Memory check" = false, a local solver that cannot tell its bytes before it factorizes, or no
// /proc/meminfo), and then fits, node_need_bytes (the factorizations' peak: the factors made so
// far and the next one's transient), node_available_bytes, node_ranks of the node with the least
// room and node_held_bytes (what the factors then hold there); "preconditioner_memory_check" the
// same (without node_held_bytes) for the Dirichlet preconditioner (its blocks and interior
// factors, a factorization's transient) at the last set-up that made some (checked false
// without any).
void addFactorSummary(Json& summary, const FetiDimensions& feti);
// "dual_operator" (implicit | explicit), "explicit_dual_bytes" (the dense local F_s on all ranks)
// and "explicit_dual_bytes_max_rank" (the largest rank's): 0 when implicit; when explicit,
// "explicit_dual_assembly" (blocks, columns_solved, columns_full, schur_blocks); with "Dual
// operator" = auto, "dual_operator_auto" (chosen, qp, explicit_bytes, factor_bytes);
// "explicit_device" (host | gpu) and, with gpu, "explicit_device_work" (applies, kernel_seconds,
// apply_seconds, kernel_bytes_per_apply, transfer_bytes_per_apply, kernel_bandwidth_gb_per_s).
void addDualOperatorSummary(Json& summary, const FetiDimensions& feti);
// The keys every single-run summary of a structured problem or the two membranes shares:
// formulation, preconditioner, local and dual solver, dimensions, convergence, iterations,
// residual history, F applications, factor bytes and the memory per phase.
void addSolverSummary(Json& summary, const FetiDimensions& feti, const tfeti::DualResult& result,
                      const tfeti::MemoryLog& memory);
// The QP solver's counters ("qp" object).
Json qpJson(const tfeti::DualResult& result);
// How well the recovered solution meets the contact rows (part of the "contact" object).
Json constraintJson(const tfeti::ConstraintReport& report);
// max |u| over every subdomain copy on every rank.
double maxAbsSolution(const tfeti::Comm& comm, const tfeti::FetiSolver& solver);

}  // namespace contact
