#include "tfeti_Pcpg.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>

#include "tfeti_SolverConventions.hpp"
#include "tfeti_StrictParameters.hpp"
#include "tfeti_TimedOperator.hpp"

namespace tfeti {

Teuchos::RCP<const Teuchos::ParameterList> Pcpg::validParameters() {
  static Teuchos::RCP<Teuchos::ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::rcp(new Teuchos::ParameterList("PCPG"));
    pl->set("Relative tolerance", 1e-6, "stop when ||P(F l - d)|| <= tolerance * ||P d||",
            strict::positive());
    pl->set("Maximum iterations", 1000, "iteration limit; reaching it is a failure",
            strict::count());
    pl->set("Verbosity", 0,
            "0 silent, 1 summary, 2 every iteration (rank 0), or a sum of Belos::MsgType "
            "values (Warnings 1, IterationDetails 2, FinalSummary 8, TimingDetails 16)",
            strict::intBetween(0, kAllMsgTypes));
  }
  return pl;
}

Pcpg::Pcpg(Teuchos::RCP<const Operator> F, const CoarseSpace& coarse,
           Teuchos::RCP<const Operator> preconditioner, const Teuchos::ParameterList& params)
    : F_(std::move(F)), coarse_(coarse), M_(std::move(preconditioner)) {
  params_ = params;
  applyParameterAliases(params_, "PCPG", belosAliases("Maximum iterations"));
  params_.validateParametersAndSetDefaults(*validParameters());
  tol_ = params_.get<double>("Relative tolerance");
  maxIter_ = params_.get<int>("Maximum iterations");
  out_.setMask(verbosityMask(params_.get<int>("Verbosity"), "PCPG"));
  F_ = TimedOperator<Scalar, MultiVector, Operator>::wrap(F_, solverTimer("tfeti: Hessian apply"));
}

PcpgResult Pcpg::solve(const Vector& d, Vector& lambda, Vector& g) {
  Teuchos::TimeMonitor monitor(*solverTimer("tfeti: PCPG solve"));
  const auto start = std::chrono::steady_clock::now();
  const auto map = lambda.getMap();
  const bool root = map->getComm()->getRank() == 0;
  Vector w(map), z(map), p(map), q(map);
  PcpgResult res;

  coarse_.project(d, w);
  const double pdNorm = w.norm2();
  const double scale = pdNorm > 0.0 ? pdNorm : 1.0;

  F_->apply(lambda, g);
  g.update(-1.0, d, 1.0);  // g = F l - d
  coarse_.project(g, w);
  double wNorm = w.norm2();
  res.history.push_back(wNorm / scale);
  auto precondition = [&](const Vector& in, Vector& out) {
    if (M_.is_null()) {
      Tpetra::deep_copy(out, in);
      return;
    }
    M_->apply(in, out);
    coarse_.project(out, out);
  };
  precondition(w, z);
  Tpetra::deep_copy(p, z);
  double wz = w.dot(z);

  int it = 0;
  while (wNorm > tol_ * scale && it < maxIter_) {
    F_->apply(p, q);
    const double pq = p.dot(q);
    if (!(pq > 0.0)) break;  // F not positive definite on ker G, or breakdown: report failure
    // p is built from the gradient g = F l - d, so the step goes against it.
    const double alpha = wz / pq;
    lambda.update(-alpha, p, 1.0);
    g.update(-alpha, q, 1.0);
    coarse_.project(g, w);
    wNorm = w.norm2();
    ++it;
    res.history.push_back(wNorm / scale);
    if (out_.wants(Belos::IterationDetails) && root) {
      auto line = SolverOutput::line();
      line << "  PCPG " << std::setw(4) << it << "  ||Pg||/||Pd|| = " << std::scientific
           << std::setprecision(3) << wNorm / scale << "\n";
      out_.write(line);
    }
    if (wNorm <= tol_ * scale) break;
    precondition(w, z);
    const double wzNew = w.dot(z);
    p.update(1.0, z, wzNew / wz);
    wz = wzNew;
  }
  res.iterations = it;
  res.projectedGradientNorm = wNorm;
  res.relativeResidual = wNorm / scale;
  res.converged = wNorm <= tol_ * scale;
  if ((out_.wants(Belos::FinalSummary) || (!res.converged && out_.wants(Belos::Warnings))) &&
      root) {
    auto line = SolverOutput::line();
    line << "PCPG: " << (res.converged ? "converged" : "NOT converged") << " in " << it
         << " iterations, ||Pg||/||Pd|| = " << res.relativeResidual << "\n";
    out_.write(line);
  }
  if (out_.wants(Belos::TimingDetails) && root) {
    auto line = SolverOutput::line();
    line << "PCPG: solve " << std::scientific << std::setprecision(3)
         << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
         << " s\n";
    out_.write(line);
  }
  last_ = res;
  return res;
}

}  // namespace tfeti
