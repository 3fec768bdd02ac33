#pragma once
// Checks the contact tests share: convergence on every rank and the error of a torn solution
// against a reference indexed by untorn dof.
#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "tfeti_FetiSolver.hpp"

namespace contact_test {

inline bool convergedEverywhere(const tfeti::Comm& comm, bool converged) {
  int mine = converged ? 1 : 0, all = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MIN, 1, &mine, &all);
  return all == 1;
}

// max over every copy of every node of |u - reference| (reference[dpn * untorn node + c]),
// relative to max |reference|.
inline double tornSolutionError(const tfeti::Comm& comm, const tfeti::FetiSolver& solver,
                                const std::vector<double>& reference, int dofsPerNode) {
  double err = 0.0, scale = 0.0;
  for (double v : reference) scale = std::max(scale, std::abs(v));
  for (std::size_t i = 0; i < solver.data().size(); ++i) {
    const auto& mesh = solver.data()[i].mesh;
    const auto& u = solver.solution(i);
    for (int k = 0; k < mesh.numNodes(); ++k)
      for (int d = 0; d < dofsPerNode; ++d)
        err = std::max(err, std::abs(u[dofsPerNode * k + d] -
                                     reference.at(dofsPerNode * mesh.globalNode[k] + d)));
  }
  double global = 0.0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &err, &global);
  return scale > 0.0 ? global / scale : global;
}

}  // namespace contact_test
