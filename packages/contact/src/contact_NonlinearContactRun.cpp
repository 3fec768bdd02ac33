#include "contact_NonlinearContactRun.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "contact_ContactOutput.hpp"
#include "contact_DriverCommon.hpp"
#include "contact_ElasticContactProblem.hpp"
#include "contact_ElasticContactRun.hpp"
#include "contact_NonlinearHistory.hpp"
#include "plasticity_J2Plasticity.hpp"
#include "plasticity_TotalLagrangian.hpp"
#include "tfeti_Gather.hpp"
#include "tfeti_StrictParameters.hpp"

namespace contact {

namespace {

using Teuchos::Array;
using Teuchos::ParameterList;
using Field = std::vector<std::vector<double>>;  // one vector per local subdomain

struct Options {
  plasticity::Kinematics kinematics = plasticity::Kinematics::TotalLagrangian;
  int steps = 1, maxIterations = 50, maxCutbacks = 4, stopAfter = 0;
  double eta1 = 1e-6, eta2 = 1e-6;
  std::string stiffness = "initial";  // initial | step | iteration
  bool restart = false, vtuEveryStep = true;
  ContactExtentRule rule;
};

Options optionsFrom(const ParameterList& params) {
  const auto& nl = params.sublist("Nonlinear");
  Options o;
  o.kinematics = nl.get<bool>("Geometrically nonlinear") ? plasticity::Kinematics::TotalLagrangian
                                                         : plasticity::Kinematics::SmallStrain;
  o.steps = nl.get<int>("Load steps");
  o.maxIterations = nl.get<int>("Maximum iterations");
  o.maxCutbacks = nl.get<int>("Maximum cutbacks");
  o.stopAfter = nl.get<int>("Stop after step");
  o.eta1 = nl.get<double>("Eta 1");
  o.eta2 = nl.get<double>("Eta 2");
  o.stiffness = nl.get<std::string>("Stiffness");
  o.restart = nl.get<bool>("Restart");
  o.vtuEveryStep = nl.get<bool>("VTU every step");
  const auto& ex = nl.sublist("Contact extent");
  o.rule.angle = ex.get<std::string>("Measure") == "angle";
  const auto c = ex.get<Array<double>>("Centre"), d = ex.get<Array<double>>("Direction");
  if (c.size() != 2 || d.size() != 2 || !(std::hypot(d[0], d[1]) > 0.0))
    throw std::invalid_argument(
        "Nonlinear/Contact extent: \"Centre\" and \"Direction\" need 2 values each, the "
        "direction non-zero");
  const double dn = std::hypot(d[0], d[1]);
  o.rule.centre[0] = c[0], o.rule.centre[1] = c[1];
  o.rule.direction[0] = d[0] / dn, o.rule.direction[1] = d[1] / dn;
  if (o.steps < 1) throw std::invalid_argument("Nonlinear: \"Load steps\" must be >= 1");
  if (o.maxIterations < 1)
    throw std::invalid_argument("Nonlinear: \"Maximum iterations\" must be >= 1");
  if (o.maxCutbacks < 0)
    throw std::invalid_argument("Nonlinear: \"Maximum cutbacks\" must be >= 0");
  if (!(o.eta1 > 0.0) || !(o.eta2 > 0.0))
    throw std::invalid_argument("Nonlinear: \"Eta 1\" and \"Eta 2\" must be positive");
  return o;
}

double globalNorm(const tfeti::Comm& comm, const Field& v) {
  double local = 0.0, global = 0.0;
  for (const auto& x : v)
    for (double y : x) local += y * y;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &local, &global);
  return std::sqrt(global);
}

double globalMax(const tfeti::Comm& comm, double local) {
  double global = 0.0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &local, &global);
  return global;
}

// Every rank's subdomains, their material and the state of the run.
struct Model {
  ElasticContactProblem problem;
  std::vector<std::unique_ptr<plasticity::MaterialLaw>> laws;  // per local subdomain
  std::vector<plasticity::J2PlasticMaterial*> plastic;         // null for elastic bodies
  Field externalLoad;                                          // at load factor 1
  Field u;                                                     // converged total displacement

  // The displacement of the contact surfaces' nodes (2 per mesh node, zero elsewhere), from
  // the subdomain holding each node's first copy.
  std::vector<double> surfaceDisplacement(const tfeti::Comm& comm, const Field& disp) const {
    std::vector<char> onSurface(problem.mesh.numNodes(), 0);
    for (int n : problem.surfaceNodes) onSurface[n] = 1;
    std::vector<double> mine;
    for (std::size_t i = 0; i < problem.local.size(); ++i) {
      const auto& mesh = problem.local[i].mesh;
      for (int n = 0; n < mesh.numNodes(); ++n) {
        const int g = static_cast<int>(mesh.globalNode[n]);
        if (onSurface[g] && problem.copyOf[g].first == mesh.id)
          mine.insert(mine.end(), {static_cast<double>(g), disp[i][2 * n], disp[i][2 * n + 1]});
      }
    }
    const std::vector<double> all = tfeti::allGather(comm, mine);
    std::vector<double> out(2 * static_cast<std::size_t>(problem.mesh.numNodes()), 0.0);
    for (std::size_t k = 0; k + 2 < all.size(); k += 3) {
      const auto g = static_cast<std::size_t>(all[k]);
      out[2 * g] = all[k + 1];
      out[2 * g + 1] = all[k + 2];
    }
    return out;
  }

  Field internalForce(const Field& disp, plasticity::Kinematics kin) const {
    Field f;
    for (std::size_t i = 0; i < laws.size(); ++i)
      f.push_back(plasticity::internalForce(problem.localElements[i], *laws[i], disp[i], kin));
    return f;
  }

  void commit() {
    for (auto* p : plastic)
      if (p) p->commit();
  }
  void revert() {
    for (auto* p : plastic)
      if (p) p->revert();
  }
};

// Equivalent plastic strain: the largest at any Gauss point, and a nodal field (the mean over
// the elements at a node of each element's Gauss point mean) for output.
double plasticStrain(const plasticity::J2PlasticMaterial* law, const plasticity::ElementMesh& em,
                     std::vector<double>& nodal) {
  nodal.assign(em.numNodes(), 0.0);
  if (!law) return 0.0;
  std::vector<int> count(em.numNodes(), 0);
  const int npe = plasticity::nodesPerElement(em.type), ngp = law->gaussPointsPerElement();
  double mx = 0.0;
  for (int e = 0; e < em.numElements(); ++e) {
    double mean = 0.0;
    for (int q = 0; q < ngp; ++q) {
      const double a = law->trialEquivalentPlasticStrain({e, q});
      mx = std::max(mx, a);
      mean += a / ngp;
    }
    for (int k = 0; k < npe; ++k) {
      const int n = em.connectivity[static_cast<std::size_t>(e) * npe + k];
      nodal[n] += mean;
      ++count[n];
    }
  }
  for (int n = 0; n < em.numNodes(); ++n)
    if (count[n] > 0) nodal[n] /= count[n];
  return mx;
}

// step_NNNN: the files of a converged load step.
std::string stepBaseName(int step) {
  std::ostringstream base;
  base << "step_" << std::setw(4) << std::setfill('0') << step;
  return base.str();
}
// The ParaView collection of the converged steps' VTU files, the load factor as time (a
// restarted run's history holds the steps of the run it continues).
std::vector<PvdEntry> stepCollection(const NonlinearHistory& history) {
  std::vector<PvdEntry> entries;
  for (const auto& s : history.steps)
    entries.push_back({s.loadFactor, stepBaseName(s.step) + ".pvtu"});
  return entries;
}

struct StepOutcome {
  bool converged = false;
  std::string reason;  // why not
  Field u;             // the trial displacement at the end
  std::vector<IterationRecord> iterations;
};

}  // namespace

void addNonlinearContactParameters(ParameterList& pl) {
  auto& mat = pl.sublist("Material");
  mat.set("Yield stress", 0.0,
          "nonlinear_contact: initial uniaxial yield stress of J2 plasticity; 0: elastic",
          tfeti::strict::nonNegative());
  mat.set("Hardening modulus", 0.0,
          "nonlinear_contact: linear isotropic hardening modulus H (0: perfect plasticity)",
          tfeti::strict::nonNegative());
  auto& nl = pl.sublist("Nonlinear", false, "Problem = nonlinear_contact: load steps, iterations");
  nl.set("Geometrically nonlinear", true,
         "total Lagrangian kinematics (Green-Lagrange strain); false: small strain");
  nl.set("Load steps", 1, "equal load increments up to the full load", tfeti::strict::count());
  nl.set("Maximum iterations", 50, "iterations per load step before it is cut back",
         tfeti::strict::count());
  nl.set("Eta 1", 1e-6, "stop when ||du|| / ||u|| < Eta 1 ...", tfeti::strict::positive());
  nl.set("Eta 2", 1e-6, "... and ||f - B^T lambda - f_int|| / ||f|| < Eta 2",
         tfeti::strict::positive());
  nl.set("Maximum cutbacks", 4,
         "consecutive halvings of a load increment that does not converge before the run stops",
         tfeti::strict::count(0));
  nl.set("Stiffness", "initial",
         "initial: K of the undeformed elastic body, factorized once (the paper's algorithm); "
         "step: the material tangent at the start of every load step; iteration: at every "
         "iteration (both refactorize)",
         Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
             Teuchos::tuple<std::string>("initial", "step", "iteration"), "Stiffness")));
  nl.set("Restart", false,
         "continue from the last converged load step saved in the output directory's restart/");
  nl.set("Stop after step", 0,
         "stop (successfully) once this load step has converged, to be continued with Restart; "
         "0: run to the full load",
         tfeti::strict::count(0));
  nl.set("VTU every step", true, "write step_NNNN.pvtu at every converged step");
  auto& ex = nl.sublist("Contact extent", false, "how contact_extent is measured");
  ex.set("Measure", "half_width",
         "half_width: half the contact width along x (metres); angle: the half-angle (degrees) "
         "seen from Centre, from Direction",
         Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
             Teuchos::tuple<std::string>("half_width", "angle"), "Measure")));
  ex.set("Centre", Array<double>(std::vector<double>{0.0, 0.0}), "{x, y} (angle)",
         tfeti::strict::doubles(2));
  ex.set("Direction", Array<double>(std::vector<double>{0.0, -1.0}),
         "{dx, dy}: where the angle is zero (angle)", tfeti::strict::doubles(2));
}

void checkNonlinearParameters(const ParameterList& params) {
  optionsFrom(params);
  elasticContactSpec(params);
  const auto& mat = params.sublist("Material");
  if (mat.get<double>("Yield stress") < 0.0 || mat.get<double>("Hardening modulus") < 0.0)
    throw std::invalid_argument(
        "Material: \"Yield stress\" and \"Hardening modulus\" must be >= 0");
}

ElasticContactSpec nonlinearContactSpec(const ParameterList& params) {
  ElasticContactSpec spec = elasticContactSpec(params);
  spec.meshOptions.dimension = 2;
  return spec;
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
  const Options opt = optionsFrom(params);
  const ElasticContactSpec spec = nonlinearContactSpec(params);
  const auto& mat = params.sublist("Material");
  const double yield = mat.get<double>("Yield stress"),
               hardening = mat.get<double>("Hardening modulus");

  Model model;
  model.problem = buildElasticContactProblem(spec, *comm);
  ElasticContactProblem& problem = model.problem;
  for (std::size_t i = 0; i < problem.local.size(); ++i) {
    const auto& law = spec.bodies[problem.localBody[i]].law;
    const auto& em = problem.localElements[i];
    if (yield > 0.0) {
      auto j2 = std::make_unique<plasticity::J2PlasticMaterial>(
          law.E, law.nu, yield, hardening, em.numElements(), plasticity::numGaussPoints(em.type));
      model.plastic.push_back(j2.get());
      model.laws.push_back(std::move(j2));
    } else {
      model.plastic.push_back(nullptr);
      model.laws.push_back(std::make_unique<plasticity::LinearElasticMaterial>(law));
    }
    model.externalLoad.push_back(problem.local[i].f);
    model.u.emplace_back(problem.local[i].f.size(), 0.0);
  }
  const double appliedForce = std::hypot(problem.appliedForce[0], problem.appliedForce[1]);
  const double loadDirection[2] = {
      appliedForce > 0.0 ? problem.appliedForce[0] / appliedForce : 0.0,
      appliedForce > 0.0 ? problem.appliedForce[1] / appliedForce : 0.0};
  const double fNorm = requireLoad(*comm, problem.local);

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
  tfeti::FetiSolver solver(comm, problem.numSubdomains(), problem.local, params.sublist("FETI"),
                           problem.inequalities);
  for (auto& sd : problem.local) sd.K = tfeti::CsrMatrix();  // the solver holds its own copy
  const auto coordsOf = [&](const Field& disp) {
    Field x;
    for (std::size_t i = 0; i < disp.size(); ++i) {
      x.push_back(problem.localElements[i].coords);
      for (std::size_t k = 0; k < x[i].size(); ++k) x[i][k] += disp[i][k];
    }
    return x;
  };

  // One attempt at load factor t from the converged state.
  const auto attemptStep = [&](int step, double t) {
    StepOutcome out;
    out.u = model.u;
    Field& u = out.u;
    try {
      Field fint = model.internalForce(u, opt.kinematics);
      for (int it = 1; it <= opt.maxIterations; ++it) {
        updateContact(problem, model.surfaceDisplacement(*comm, u), comm->getRank(), spec.slave,
                      spec.master);
        Field rhs(u.size());
        for (std::size_t i = 0; i < u.size(); ++i) {
          rhs[i].resize(fint[i].size());
          for (std::size_t k = 0; k < rhs[i].size(); ++k)
            rhs[i][k] = t * model.externalLoad[i][k] - fint[i][k];
        }
        const bool refactor = opt.stiffness == "iteration" || (opt.stiffness == "step" && it == 1);
        if (refactor) {
          std::vector<tfeti::CsrMatrix> K;
          for (std::size_t i = 0; i < u.size(); ++i)
            K.push_back(plasticity::tangentStiffness(problem.localElements[i], *model.laws[i], u[i],
                                                     opt.kinematics, false));
          solver.updateStiffness(std::move(K), coordsOf(u), rhs, problem.inequalities);
        } else {
          solver.update(rhs, problem.inequalities);
        }
        const tfeti::DualResult qp = solver.solve();
        IterationRecord rec;
        rec.step = step;
        rec.loadFactor = t;
        rec.iteration = it;
        rec.mprgpIterations = qp.iterations;
        rec.hessianMultiplications = qp.qp.hessianMultiplications;
        if (!qp.converged) {
          out.iterations.push_back(rec);
          out.reason = "the contact QP did not converge in iteration " + std::to_string(it) + " (" +
                       qp.qp.message + ")";
          return out;
        }
        Field du(u.size());
        for (std::size_t i = 0; i < u.size(); ++i) {
          du[i] = solver.solution(i);
          for (std::size_t k = 0; k < u[i].size(); ++k) u[i][k] += du[i][k];
        }
        fint = model.internalForce(u, opt.kinematics);
        const Field btl = solver.multiplierForces();
        Field res(u.size());
        for (std::size_t i = 0; i < u.size(); ++i) {
          res[i].resize(u[i].size());
          for (std::size_t k = 0; k < u[i].size(); ++k)
            res[i][k] = t * model.externalLoad[i][k] - btl[i][k] - fint[i][k];
        }
        rec.solutionNorm = globalNorm(*comm, u);
        rec.relativeIncrement =
            rec.solutionNorm > 0.0 ? globalNorm(*comm, du) / rec.solutionNorm : 0.0;
        rec.relativeResidual = globalNorm(*comm, res) / (t * fNorm);
        out.iterations.push_back(rec);
        if (root && verbosity > 1)
          std::cout << "  step " << step << " (t = " << t << ") iteration " << it
                    << ": ||res||/||f|| = " << rec.relativeResidual
                    << ", ||du||/||u|| = " << rec.relativeIncrement << ", "
                    << rec.hessianMultiplications << " Hessian multiplications [" << elapsed()
                    << "]\n";
        if (rec.relativeIncrement < opt.eta1 && rec.relativeResidual < opt.eta2) {
          out.converged = true;
          return out;
        }
      }
      out.reason = "no convergence in " + std::to_string(opt.maxIterations) + " iterations";
    } catch (const plasticity::InvertedDeformationError& e) {
      out.reason = e.what();
    }
    return out;
  };

  // What a converged step reports, writes and saves.
  std::vector<plasticity::StressField> stresses;
  std::vector<std::vector<double>> plasticNodal;
  std::vector<ContactNode> nodes;
  double maxVm = 0.0, maxEp = 0.0;
  const auto evaluateOutputs = [&](const Field& u) {
    stresses.clear();
    plasticNodal.assign(u.size(), {});
    double vm = 0.0, ep = 0.0;
    for (std::size_t i = 0; i < u.size(); ++i) {
      const auto& em = problem.localElements[i];
      stresses.push_back(plasticity::cauchyStress(em, *model.laws[i], u[i], opt.kinematics));
      const auto& st = stresses.back();
      for (int e = 0; e < em.numElements(); ++e)
        for (int q = 0; q < st.gaussPointsPerElement; ++q)
          vm = std::max(vm, st.atGaussPoint(e, q, plasticity::kVonMises));
      ep = std::max(ep, plasticStrain(model.plastic[i], em, plasticNodal[i]));
    }
    maxVm = globalMax(*comm, vm);
    maxEp = globalMax(*comm, ep);
    nodes = contactNodes(problem, solver, opt.rule, model.surfaceDisplacement(*comm, u));
  };
  const auto writeVtuFor = [&](const std::string& base, const Field& u) {
    std::vector<SubdomainFields> fields;
    for (std::size_t i = 0; i < u.size(); ++i)
      fields.push_back({&problem.localElements[i],
                        problem.local[i].mesh.id,
                        &u[i],
                        &stresses[i],
                        {plasticNodal[i]}});
    return writeVtu(*comm, dir, base, stressPiece(fields, {"plastic_strain"}));
  };
  const auto saveRestart = [&]() {
    const std::string stepDir = restartStepDirectory(restartDir, history.step);
    if (root) std::filesystem::create_directories(stepDir);
    comm->barrier();
    for (std::size_t i = 0; i < model.u.size(); ++i) {
      SubdomainRestart s;
      s.id = problem.local[i].mesh.id;
      s.displacement = model.u[i];
      if (model.plastic[i]) s.history = model.plastic[i]->committedHistory();
      writeSubdomainRestart(stepDir, s);
    }
    comm->barrier();
    if (root) {
      writeRestartState(restartDir, history);
      // Older steps are no longer named by state.txt.
      for (const auto& entry : std::filesystem::directory_iterator(restartDir))
        if (entry.is_directory() && entry.path().string() != stepDir)
          std::filesystem::remove_all(entry.path());
    }
    comm->barrier();
  };
  const auto writeTables = [&]() {
    if (!root) return;
    writeIterationsCsv(dir + "/iterations.csv", history);
    writeStepsCsv(dir + "/steps.csv", history);
  };

  // The load steps.
  const double nominal = 1.0 / opt.steps;
  int cutbacks = 0;
  bool failed = false, stopped = false;
  std::string failure;
  while (history.loadFactor < 1.0 - 1e-12) {
    if (opt.stopAfter > 0 && history.step >= opt.stopAfter) {
      stopped = true;
      break;
    }
    const double t = std::min(1.0, history.loadFactor + history.stepSize);
    const int step = history.step + 1;
    StepOutcome out = attemptStep(step, t);
    for (auto& r : out.iterations) r.accepted = out.converged;
    history.iterations.insert(history.iterations.end(), out.iterations.begin(),
                              out.iterations.end());
    if (!out.converged) {
      model.revert();
      if (root && verbosity > 0)
        std::cout << "nonlinear_contact: step " << step << " at load factor " << t
                  << " rejected: " << out.reason << " [" << elapsed() << "]\n";
      if (cutbacks >= opt.maxCutbacks) {
        failed = true;
        std::ostringstream s;
        s << "load step " << step << " (load factor " << t << ") did not converge after "
          << cutbacks << " cut-backs: " << out.reason;
        failure = s.str();
        break;
      }
      ++cutbacks;
      history.stepSize *= 0.5;
      writeTables();
      continue;
    }
    evaluateOutputs(out.u);
    model.commit();
    model.u = std::move(out.u);
    StepRecord rec;
    rec.step = step;
    rec.loadFactor = t;
    rec.outerIterations = static_cast<int>(out.iterations.size());
    rec.cutbacks = cutbacks;
    for (const auto& r : out.iterations) {
      rec.mprgpIterations += r.mprgpIterations;
      rec.hessianMultiplications += r.hessianMultiplications;
      rec.residuals.push_back(r.relativeResidual);
      rec.increments.push_back(r.relativeIncrement);
    }
    rec.pMax = maxPressure(nodes);
    rec.contactExtent = contactExtent(nodes, opt.rule);
    rec.maxVonMises = maxVm;
    rec.maxPlasticStrain = maxEp;
    rec.contactForce = resultantForce(nodes, loadDirection);
    history.steps.push_back(rec);
    history.step = step;
    history.loadFactor = t;
    // After a cut-back, grow the increment again towards the nominal one.
    history.stepSize = std::min(nominal, 2.0 * history.stepSize);
    cutbacks = 0;
    const std::string base = stepBaseName(step);
    if (opt.vtuEveryStep) {
      writeVtuFor(base, model.u);
      if (root) writePvd(dir + "/steps.pvd", stepCollection(history));
    }
    writeContactCsv(*comm, dir + "/contact_pressure_" + base + ".csv", nodes);
    writeTables();
    saveRestart();
    if (root && verbosity > 0)
      std::cout << "nonlinear_contact: step " << step << " converged at load factor " << t << " in "
                << rec.outerIterations << " iterations (" << rec.hessianMultiplications
                << " Hessian multiplications); p_max " << rec.pMax << ", contact extent "
                << rec.contactExtent << ", max von Mises " << rec.maxVonMises
                << ", max plastic strain " << rec.maxPlasticStrain << " [" << elapsed() << "]\n";
  }

  // The final state: the last converged step (outputs re-evaluated when this run converged no
  // step, e.g. a restart that stops at once or fails at its first step).
  const bool haveStep = !history.steps.empty();
  if (haveStep && nodes.empty()) {
    // Contact rows and multipliers of the saved state need one solve at its load factor.
    const StepOutcome again = attemptStep(history.step, history.loadFactor);
    model.revert();
    if (again.converged) evaluateOutputs(again.u);
  }
  if (haveStep && !nodes.empty()) {
    writeContactCsv(*comm, dir + "/contact_pressure.csv", nodes);
    if (params.sublist("Output").get<bool>("VTU")) writeVtuFor("solution", model.u);
  }

  Json s = Json::object();
  s["study"] = "single";
  s["problem"] = "nonlinear_contact";
  s["ranks"] = comm->getSize();
  s["subdomains"] = problem.numSubdomains();
  s["nodes"] = problem.mesh.numNodes();
  s["primal_dim"] = static_cast<long long>(solver.primalDimension());
  s["dual_dim"] = static_cast<long long>(solver.dualDimension());
  s["contact_rows"] = static_cast<long long>(solver.inequalityRows());
  const bool converged = !failed && !stopped;
  s["converged"] = converged;
  Json m = Json::object();
  m["youngs_modulus"] = mat.get<double>("Young's modulus");
  m["poissons_ratio"] = mat.get<double>("Poisson's ratio");
  if (yield > 0.0) {
    m["yield_stress"] = yield;
    m["hardening_modulus"] = hardening;
  }
  s["material"] = std::move(m);
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
    c["extent_measure"] = opt.rule.angle ? "angle" : "half_width";
    c["contact_extent"] = last.contactExtent;
    if (!opt.rule.angle) c["half_width"] = last.contactExtent;
    c["force"] = last.contactForce;
    const double applied = history.loadFactor * appliedForce;
    c["applied_force"] = applied;
    c["force_relative_error"] =
        applied > 0.0 ? std::abs(last.contactForce - applied) / applied : 0.0;
    if (history.loadFactor > 1.0 - 1e-12)
      addHertzComparison(c, params, last.pMax, last.contactExtent);
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
