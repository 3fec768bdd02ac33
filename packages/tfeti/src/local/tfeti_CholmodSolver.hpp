#pragma once
// CHOLMOD (SuiteSparse) sparse Cholesky behind the LocalSolver interface. Reached through
// createLocalSolver ("cholmod", "cholmod-simplicial", "cholmod-supernodal"); cholmod.h stays in
// the .cpp, so this header needs no SuiteSparse headers.
#include <cstddef>
#include <memory>
#include <string>

#include "tfeti_LocalSolver.hpp"

namespace tfeti {

// kind: "simplicial" or "supernodal" forces CHOLMOD's factorization kind; anything else lets
// CHOLMOD choose per matrix.
std::unique_ptr<LocalSolver> createCholmodSolver(const std::string& kind);

// The symbolic analyses the CHOLMOD factors of this process made, and the factorizations that
// shared the analysis of a live factor of the same pattern and kind instead.
LocalAnalysisCounts cholmodAnalysisCounts();

// CHOLMOD's own count of the bytes it holds for this process (Common->memory_inuse).
std::size_t cholmodMemoryInUse();
// CHOLMOD's peak of that count (Common->memory_usage); reset: the peak restarts from now.
std::size_t cholmodMemoryPeak(bool reset);

}  // namespace tfeti
