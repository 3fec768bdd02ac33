#include "contact_DriverCommon.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <sys/resource.h>

#include <cmath>
#include <fstream>
#include <stdexcept>

namespace contact {

Json timingsJson(const tfeti::FetiTimings& t, int iterations) {
  Json j = Json::object();
  j["factorization_s"] = t.factorization;
  j["tearing_s"] = t.tearing;
  j["coarse_s"] = t.coarse;
  j["preconditioner_s"] = t.preconditioner;
  j["dual_rhs_s"] = t.dualRhs;
  j["setup_s"] = t.setup();
  j["solve_s"] = t.solve;
  j["recovery_s"] = t.recovery;
  j["per_iteration_s"] = iterations > 0 ? t.solve / iterations : 0.0;
  return j;
}

void writeSummary(const tfeti::Comm& comm, const std::string& dir, const Json& summary) {
  if (comm.getRank() != 0) return;
  const std::string path = dir + "/summary.json";
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << summary.dump();
}

// Largest resident set size over the ranks, in MiB.
double peakRssMb(const tfeti::Comm& comm) {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  double mine = usage.ru_maxrss / 1024.0, all = 0.0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &mine, &all);
  return all;
}

VtuPiece vtuPiece(const tfeti::FetiSolver& solver) {
  VtuPiece piece;
  VtuField u{"u", 1, {}}, sub{"subdomain", 1, {}};
  const bool vec = !solver.data().empty() && solver.data().front().dofsPerNode == 2;
  if (vec) u = VtuField{"displacement", 3, {}};
  for (std::size_t i = 0; i < solver.data().size(); ++i) {
    const auto& mesh = solver.data()[i].mesh;
    const int base = static_cast<int>(piece.points.size() / 2);
    piece.points.insert(piece.points.end(), mesh.coords.begin(), mesh.coords.end());
    for (int q : mesh.quads) piece.quads.push_back(base + q);
    const auto& us = solver.solution(i);
    for (int n = 0; n < mesh.numNodes(); ++n) {
      if (vec)
        u.values.insert(u.values.end(), {us[2 * n], us[2 * n + 1], 0.0});
      else
        u.values.push_back(us[n]);
    }
    sub.values.insert(sub.values.end(), mesh.numElements(), static_cast<double>(mesh.id));
  }
  piece.pointData.push_back(std::move(u));
  piece.cellData.push_back(std::move(sub));
  return piece;
}

}  // namespace contact
