#pragma once
// Amesos2's KLU2 and Tacho behind the LocalSolver interface. Reached through createLocalSolver
// ("klu2", "tacho"); Amesos2's headers stay in the .cpp.
#include <memory>
#include <string>

#include "tfeti_LocalSolver.hpp"

namespace tfeti {

// type: "klu2" or "tacho".
std::unique_ptr<LocalSolver> createAmesos2Solver(const std::string& type);

}  // namespace tfeti
