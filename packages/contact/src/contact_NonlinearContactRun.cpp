#include "contact_NonlinearContactRun.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "contact_ContactOutput.hpp"
#include "contact_DriverCommon.hpp"
#include "contact_ElasticContactRun.hpp"
#include "contact_LoadStepControl.hpp"
#include "contact_Materials.hpp"
#include "contact_NonlinearIteration.hpp"
#include "contact_NonlinearModel.hpp"
#include "contact_NonlinearOptions.hpp"
#include "contact_NonlinearStepOutput.hpp"
#include "contact_PrescribedDisplacement.hpp"

namespace contact {

using Teuchos::ParameterList;

ElasticContactSpec nonlinearContactSpec(const ParameterList& params) {
  // The same bodies, loads and contact pair as elastic_contact, 2D or 3D as the mesh is.
  return elasticContactSpec(params);
}

NonlinearHistory readRestart(const std::string& restartDir, const ElasticContactProblem& problem,
                             std::vector<SubdomainRestart>& subdomains) {
  NonlinearHistory history = readRestartState(restartDir);
  const std::string stepDir = restartStepDirectory(restartDir, history.step);
  subdomains.clear();
  for (const auto& local : problem.local) {
    subdomains.push_back(readSubdomainRestart(stepDir, local.mesh.id));
    const SubdomainRestart& s = subdomains.back();
    if (s.displacement.size() != local.f.size())
      throw std::runtime_error(stepDir + ": subdomain " + std::to_string(s.id) + " has " +
                               std::to_string(s.displacement.size()) +
                               " displacement values, the mesh " + std::to_string(local.f.size()) +
                               " (restart with the same mesh and subdomains)");
  }
  return history;
}

double requireLoad(const tfeti::Comm& comm, const std::vector<tfeti::SubdomainData>& local) {
  Field f;
  for (const auto& s : local) f.push_back(s.f);
  const double norm = globalNorm(comm, f);
  if (!(norm > 0.0)) throw std::invalid_argument("Contact problem: no load is applied");
  return norm;
}

double requireLoadOrMotion(const tfeti::Comm& comm, const std::vector<tfeti::SubdomainData>& local,
                           const NonlinearOptions& options, bool prescribedMotion) {
  if (options.obstacleDisplacement.empty() && !prescribedMotion) return requireLoad(comm, local);
  Field f;
  for (const auto& s : local) f.push_back(s.f);
  return globalNorm(comm, f);
}

namespace {

// The resultant of the multiplier forces B^T lambda of the last solve on the nodes of the Fixed
// boundaries, along `direction` (dim entries): the support's reaction. Gluing rows cancel in the
// sum over a node's copies, so it is the Dirichlet rows' force; in equilibrium it balances the
// applied load plus the force a rigid obstacle exerts.
double supportForce(const tfeti::Comm& comm, const tfeti::FetiSolver& solver,
                    const ElasticContactProblem& problem, const double direction[]) {
  const int dim = problem.dim();
  const Field btl = solver.multiplierForces();
  double local = 0.0, global = 0.0;
  for (std::size_t i = 0; i < btl.size(); ++i)
    for (int n : problem.local[i].mesh.dirichletNodes)
      for (int c = 0; c < dim; ++c) local += direction[c] * btl[i][dim * n + c];
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &local, &global);
  return global;
}

}  // namespace

int runNonlinearContact(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                        const std::string& dir) {
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&]() {
    std::ostringstream s;
    s << std::fixed << std::setprecision(1)
      << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s";
    return s.str();
  };
  const bool root = comm->getRank() == 0;
  const int verbosity = params.sublist("Output").get<int>("Verbosity");
  checkNonlinearParameters(params);
  const NonlinearOptions opt = nonlinearOptionsFrom(params);
  const ElasticContactSpec spec = nonlinearContactSpec(params);
  // The bodies, their laws and the state; the dimension is the mesh's.
  NonlinearModel model = makeNonlinearModel(buildElasticContactProblem(spec, *comm), spec.bodies);
  ElasticContactProblem& problem = model.problem;
  const int dim = problem.dim();
  checkNonlinearOptionsFor(opt, dim, spec.obstacle.has_value());
  const double loadNorm =
      requireLoadOrMotion(*comm, problem.local, opt, !problem.prescribed.empty());
  const double* F = problem.appliedForce;
  const double appliedForce = dim == 3 ? std::hypot(F[0], F[1], F[2]) : std::hypot(F[0], F[1]);
  // The contact force is reported along the applied load, or along the obstacle's motion.
  double loadDirection[3] = {0.0, 0.0, 0.0};
  if (appliedForce > 0.0) {
    for (int c = 0; c < dim; ++c) loadDirection[c] = F[c] / appliedForce;
  } else if (!opt.obstacleDisplacement.empty()) {
    double n = 0.0;
    for (double v : opt.obstacleDisplacement) n += v * v;
    for (int c = 0; c < dim; ++c) loadDirection[c] = opt.obstacleDisplacement[c] / std::sqrt(n);
  } else if (!spec.prescribed.empty()) {
    // Driven by prescribed boundary displacements: the force along their direction (the sum of
    // the prescribed vectors), as a load in that direction would be reported.
    double n = 0.0;
    for (const PrescribedDisplacement& p : spec.prescribed) loadDirection[p.component] += p.value;
    for (int c = 0; c < dim; ++c) n += loadDirection[c] * loadDirection[c];
    for (int c = 0; c < dim && n > 0.0; ++c) loadDirection[c] /= std::sqrt(n);
  }

  const std::string restartDir = dir + "/restart";
  NonlinearHistory history;
  history.stepSize = 1.0 / opt.steps;
  if (opt.restart) {
    std::vector<SubdomainRestart> saved;
    history = readRestart(restartDir, problem, saved);
    for (std::size_t i = 0; i < problem.local.size(); ++i) {
      model.u[i] = saved[i].displacement;
      if (model.plastic[i]) model.plastic[i]->setCommittedHistory(saved[i].history);
    }
    if (root && verbosity > 0)
      std::cout << "nonlinear_contact: restart from step " << history.step << " (load factor "
                << history.loadFactor << ")\n";
  }
  if (root) std::filesystem::create_directories(restartDir);

  // K of the undeformed elastic bodies, factorized once; loads and rows change per iteration.
  // The prescribed displacements' rows are set per increment (LoadStepIteration); here at the
  // state the run starts from, so that they exist from the start.
  tfeti::FetiSolver solver(
      comm, problem.numSubdomains(), problem.local, params.sublist("FETI"), problem.inequalities,
      prescribedDisplacementRows(problem.local, problem.prescribed, history.loadFactor, model.u));
  for (auto& sd : problem.local) sd.K = tfeti::CsrMatrix();  // the solver holds its own copy

  LoadStepIteration iteration(comm, model, solver, opt, spec.slave, spec.master,
                              spec.obstacle ? &*spec.obstacle : nullptr, loadNorm);
  if (root && verbosity > 1)
    iteration.onIteration = [&](const IterationRecord& r) {
      std::cout << "  step " << r.step << " (t = " << r.loadFactor << ") iteration " << r.iteration
                << ": ||res||/||f|| = " << r.relativeResidual
                << ", ||du||/||u|| = " << r.relativeIncrement << ", " << r.hessianMultiplications
                << " Hessian multiplications [" << elapsed() << "]\n";
    };
  NonlinearStepOutput output(comm, model, solver, opt, dir);
  const auto writeTables = [&]() {
    if (!root) return;
    writeIterationsCsv(dir + "/iterations.csv", history);
    writeStepsCsv(dir + "/steps.csv", history);
  };

  // The load steps: attempt, then accept (commit, report, save) or cut back.
  LoadStepControl control(history, opt.steps, opt.maxCutbacks, opt.stopAfter);
  bool failed = false, stopped = false;
  std::string failure;
  while (!control.finished()) {
    if (control.stopRequested()) {
      stopped = true;
      break;
    }
    const double t = control.nextLoadFactor();
    const int step = control.nextStep();
    StepOutcome out = iteration.attempt(step, t);
    for (auto& r : out.iterations) r.accepted = out.converged;
    history.iterations.insert(history.iterations.end(), out.iterations.begin(),
                              out.iterations.end());
    if (!out.converged) {
      model.revert();
      if (root && verbosity > 0)
        std::cout << "nonlinear_contact: step " << step << " at load factor " << t
                  << " rejected: " << out.reason << " [" << elapsed() << "]\n";
      const int cutbacks = control.cutbacks();
      if (!control.reject()) {
        failed = true;
        std::ostringstream s;
        s << "load step " << step << " (load factor " << t << ") did not converge after "
          << cutbacks << " cut-backs: " << out.reason;
        failure = s.str();
        break;
      }
      writeTables();
      continue;
    }
    output.evaluate(out.u);
    model.commit();
    model.u = std::move(out.u);
    StepRecord rec;
    rec.step = step;
    rec.loadFactor = t;
    rec.outerIterations = static_cast<int>(out.iterations.size());
    rec.cutbacks = control.cutbacks();
    for (const auto& r : out.iterations) {
      rec.mprgpIterations += r.mprgpIterations;
      rec.hessianMultiplications += r.hessianMultiplications;
      rec.residuals.push_back(r.relativeResidual);
      rec.increments.push_back(r.relativeIncrement);
    }
    output.fill(rec, loadDirection);
    history.steps.push_back(rec);
    control.accept();
    const std::string base = stepBaseName(step);
    if (opt.vtuEveryStep) {
      output.writeVtu(base, model.u);
      if (root) writePvd(dir + "/steps.pvd", stepCollection(history));
    }
    output.writeContactCsv(dir + "/contact_pressure_" + base + ".csv");
    writeTables();
    saveRestart(*comm, restartDir, history, model);
    if (root && verbosity > 0)
      std::cout << "nonlinear_contact: step " << step << " converged at load factor " << t << " in "
                << rec.outerIterations << " iterations (" << rec.hessianMultiplications
                << " Hessian multiplications); p_max " << rec.pMax << ", contact extent "
                << rec.contactExtent << ", max von Mises " << rec.maxVonMises
                << ", max plastic strain " << rec.maxPlasticStrain << ", contact force "
                << rec.contactForce << " [" << elapsed() << "]\n";
  }

  // The final state: the last converged step (outputs re-evaluated when this run converged no
  // step, e.g. a restart that stops at once or fails at its first step).
  const bool haveStep = !history.steps.empty();
  if (haveStep && !output.evaluated()) {
    // Contact rows and multipliers of the saved state need one solve at its load factor.
    const StepOutcome again = iteration.attempt(history.step, history.loadFactor);
    model.revert();
    if (again.converged) output.evaluate(again.u);
  }
  if (haveStep && output.evaluated()) {
    output.writeContactCsv(dir + "/contact_pressure.csv");
    if (params.sublist("Output").get<bool>("VTU")) output.writeVtu("solution", model.u);
  }

  Json s = Json::object();
  s["study"] = "single";
  s["problem"] = "nonlinear_contact";
  s["ranks"] = comm->getSize();
  s["subdomains"] = problem.numSubdomains();
  s["nodes"] = problem.mesh.numNodes();
  s["dimension"] = dim;
  s["primal_dim"] = static_cast<long long>(solver.primalDimension());
  s["dual_dim"] = static_cast<long long>(solver.dualDimension());
  s["contact_rows"] = static_cast<long long>(solver.inequalityRows());
  const bool converged = !failed && !stopped;
  s["converged"] = converged;
  addMaterialSummary(s, spec.bodies);
  Json nl = Json::object();
  nl["geometrically_nonlinear"] = opt.kinematics == plasticity::Kinematics::TotalLagrangian;
  nl["stiffness"] = opt.stiffness;
  nl["eta1"] = opt.eta1;
  nl["eta2"] = opt.eta2;
  nl["load_factor"] = history.loadFactor;
  nl["converged_steps"] = history.step;
  nl["stopped"] = stopped;
  nl["restarted"] = opt.restart;
  const IterationTotals totals = iterationTotals(history);
  const long long its = totals.iterations, mults = totals.hessianMultiplications;
  nl["total_iterations"] = its;
  s["iterations"] = its;
  nl["rejected_iterations"] = totals.rejected;
  nl["total_mprgp_iterations"] = totals.mprgpIterations;
  nl["total_hessian_multiplications"] = mults;
  if (failed) nl["message"] = failure;
  s["nonlinear"] = std::move(nl);
  s["steps"] = stepsJson(history);
  if (haveStep) {
    const StepRecord& last = history.steps.back();
    Json c = Json::object();
    c["p_max"] = last.pMax;
    c["extent_measure"] = dim == 3 ? "contact_radius" : opt.rule.angle ? "angle" : "half_width";
    c["contact_extent"] = last.contactExtent;
    if (dim == 3)
      c["contact_radius"] = last.contactExtent;
    else if (!opt.rule.angle)
      c["half_width"] = last.contactExtent;
    c["force"] = last.contactForce;
    const double applied = history.loadFactor * appliedForce;
    c["applied_force"] = applied;
    c["force_relative_error"] =
        applied > 0.0 ? std::abs(last.contactForce - applied) / applied : 0.0;
    // The reaction of the fixed boundaries balances the contact force (and the load).
    const double support = supportForce(*comm, solver, problem, loadDirection);
    c["support_force"] = support;
    c["support_relative_error"] =
        last.contactForce != 0.0 ? std::abs(support - last.contactForce) / last.contactForce : 0.0;
    if (history.loadFactor > 1.0 - 1e-12)
      addHertzComparison(c, params, last.pMax, last.contactExtent, dim,
                         contactBodyLaws(spec, problem));
    // The contact conditions of the last QP solve (rows B_I du <= g on the last geometry).
    c["last_solve"] = constraintJson(solver.constraintReport());
    c["last_solve"]["max_abs_du"] = maxAbsSolution(*comm, solver);
    s["contact"] = std::move(c);
    s["max_von_mises"] = last.maxVonMises;
    s["max_plastic_strain"] = last.maxPlasticStrain;
  }
  {
    double mx = 0.0;
    for (const auto& x : model.u)
      for (double v : x) mx = std::max(mx, std::abs(v));
    s["max_abs_u"] = globalMax(*comm, mx);
  }
  s["contact_csv"] = dir + "/contact_pressure.csv";
  s["iterations_csv"] = dir + "/iterations.csv";
  s["steps_csv"] = dir + "/steps.csv";
  s["timings"] = timingsJson(solver.timings(), static_cast<int>(its));
  s["wall_time"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  s["peak_rss_mb"] = peakRssMb(*comm);
  writeTables();
  writeSummary(*comm, dir, s, params);
  if (failed) {
    if (root)
      std::cerr << "tfeti_contact: " << failure << "; results up to the last converged step ("
                << history.step << ", load factor " << history.loadFactor << ") are in " << dir
                << "\n";
    return 3;
  }
  if (root && verbosity > 0)
    std::cout << "nonlinear_contact: " << (stopped ? "stopped after" : "finished") << " step "
              << history.step << " at load factor " << history.loadFactor << ", " << its
              << " iterations, " << mults << " Hessian multiplications [" << elapsed() << "]\n";
  return 0;
}

}  // namespace contact
