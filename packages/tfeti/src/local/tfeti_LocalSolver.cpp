#include "tfeti_LocalSolver.hpp"

#include <stdexcept>

#include "tfeti_Amesos2Solver.hpp"
#include "tfeti_CholmodSolver.hpp"

namespace tfeti {

const std::vector<std::string>& localSolverTypes() {
  static const std::vector<std::string> types{"cholmod", "cholmod-simplicial", "cholmod-supernodal",
                                              "klu2", "tacho"};
  return types;
}

LocalAnalysisCounts localAnalysisCounts() {
  return cholmodAnalysisCounts();
}

std::size_t localSolverMemoryInUse() {
  return cholmodMemoryInUse();
}

std::size_t localSolverMemoryPeak(bool reset) {
  return cholmodMemoryPeak(reset);
}

std::unique_ptr<LocalSolver> createLocalSolver(const std::string& type) {
  if (type == "cholmod") return createCholmodSolver("auto");
  if (type == "cholmod-simplicial") return createCholmodSolver("simplicial");
  if (type == "cholmod-supernodal") return createCholmodSolver("supernodal");
  if (type == "klu2" || type == "tacho") return createAmesos2Solver(type);
  std::string valid;
  for (const auto& t : localSolverTypes()) valid += (valid.empty() ? "" : ", ") + t;
  throw std::invalid_argument("unknown local solver \"" + type + "\"; valid: " + valid);
}

}  // namespace tfeti
