#include "tfeti_LocalSolver.hpp"

#include <stdexcept>

namespace tfeti {

std::unique_ptr<LocalSolver> createCholmodSolver();
std::unique_ptr<LocalSolver> createAmesos2Solver(const std::string& type);

const std::vector<std::string>& localSolverTypes() {
  static const std::vector<std::string> types{"cholmod", "klu2", "tacho"};
  return types;
}

std::unique_ptr<LocalSolver> createLocalSolver(const std::string& type) {
  if (type == "cholmod") return createCholmodSolver();
  if (type == "klu2" || type == "tacho") return createAmesos2Solver(type);
  std::string valid;
  for (const auto& t : localSolverTypes()) valid += (valid.empty() ? "" : ", ") + t;
  throw std::invalid_argument("unknown local solver \"" + type + "\"; valid: " + valid);
}

}  // namespace tfeti
