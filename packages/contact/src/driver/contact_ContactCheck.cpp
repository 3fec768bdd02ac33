#include "contact_ContactCheck.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <optional>
#include <sstream>
#include <vector>

#include "contact_ContactOutput.hpp"
#include "contact_ContactParameters.hpp"
#include "contact_DryRun.hpp"
#include "contact_ElasticContactProblem.hpp"
#include "contact_Friction.hpp"
#include "contact_FrictionHistory.hpp"
#include "contact_GmshMesh.hpp"
#include "contact_NonlinearHistory.hpp"
#include "contact_NonlinearIteration.hpp"
#include "contact_NonlinearOptions.hpp"
#include "contact_NonlinearSetup.hpp"
#include "contact_PrescribedDisplacement.hpp"
#include "tfeti_FetiSolver.hpp"

namespace contact {

namespace {

using Teuchos::ParameterList;

// A nonlinear Restart's step, read as the run reads it (-1: no restart).
int checkRestart(const ParameterList& params, const ElasticContactSpec& spec,
                 const ElasticContactProblem& problem, const std::string& outputDirectory) {
  if (!params.sublist("Nonlinear").get<bool>("Restart")) return -1;
  std::vector<SubdomainRestart> saved;
  FrictionHistory friction;
  const bool frictional = modelFriction(params, spec.pairs).active();
  return readRestart(outputDirectory + "/restart", problem, saved, frictional ? &friction : nullptr)
      .step;
}

// "problem: ...": the kind, the nonlinear run's load steps, kinematics, material and stiffness
// (and restart), the dual solver.
std::string problemLine(const ParameterList& params, const ElasticContactSpec& spec, bool nonlinear,
                        int restartStep, const std::string& outputDirectory,
                        const std::string& solver) {
  std::ostringstream s;
  s << "problem: " << params.get<std::string>("Problem");
  if (nonlinear) {
    const auto& nl = params.sublist("Nonlinear");
    double yield = 0.0;
    for (const auto& b : spec.bodies) yield = std::max(yield, b.yieldStress);
    s << " (" << nl.get<int>("Load steps") << " load steps, "
      << (nl.get<bool>("Geometrically nonlinear") ? "total Lagrangian" : "small strain") << ", "
      << (yield > 0.0 ? "J2 plastic" : "elastic") << ", stiffness "
      << nl.get<std::string>("Stiffness") << ")";
    if (restartStep >= 0)
      s << "; restart from step " << restartStep << " in " << outputDirectory << "/restart";
  }
  s << "; dual solver " << solver;
  return s.str();
}

// The mesh and a line per body: elements, parts, subdomains and material.
void addBodyLines(const ElasticContactSpec& spec, const ElasticContactProblem& problem,
                  bool nonlinear, std::vector<std::string>& lines) {
  std::ostringstream s;
  s << "mesh: " << problem.mesh.source << ": " << problem.mesh.numNodes() << " nodes";
  lines.push_back(s.str());
  for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
    const GmshBody& gb = problem.mesh.body(spec.bodies[b].name);
    s.str("");
    s << "body \"" << gb.name << "\": " << gb.numElements() << " " << elementTypeName(gb.type)
      << " elements, " << spec.bodies[b].subdomains << " METIS parts, "
      << std::count(problem.bodyOfSubdomain.begin(), problem.bodyOfSubdomain.end(),
                    static_cast<int>(b))
      << " subdomains; E = " << spec.bodies[b].law.E << ", nu = " << spec.bodies[b].law.nu;
    if (nonlinear && spec.bodies[b].yieldStress > 0.0)
      s << ", yield stress " << spec.bodies[b].yieldStress << ", H = " << spec.bodies[b].hardening;
    lines.push_back(s.str());
  }
}

// The first n values of v as {a, b, c}.
template <class Values>
std::string braced(const Values& v, std::size_t n) {
  std::ostringstream b;
  b << "{";
  for (std::size_t c = 0; c < n; ++c) b << (c ? ", " : "") << v[c];
  b << "}";
  return b.str();
}

// A line per boundary with a condition (and the prescribed and coupling rows), then the contact
// pair.
void addBoundaryLines(const tfeti::Comm& comm, const ElasticContactSpec& spec,
                      const ElasticContactProblem& problem, long long rows,
                      std::vector<std::string>& lines) {
  const auto boundary = [&](const std::string& role, const std::string& name) {
    std::ostringstream s;
    s << "boundary \"" << name << "\" (" << role << "): " << problem.mesh.boundary(name).numEdges()
      << (problem.mesh.dim == 3 ? " faces" : " edges");
    lines.push_back(s.str());
  };
  for (const auto& name : spec.fixed) boundary("fixed", name);
  for (const auto& [name, comp] : spec.symmetry)
    boundary(std::string("symmetry, u_") + "xyz"[comp % 3] + " = 0", name);
  for (const auto& p : spec.prescribed)
    boundary("prescribed " + describePrescribed(p, problem.mesh.dim) + " m", p.boundary);
  if (!spec.prescribed.empty()) {
    long long mine =
                  static_cast<long long>(problem.equalities.size() - problem.couplingRows.size()),
              all = 0;
    Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &mine, &all);
    lines.push_back("prescribed rows: " + std::to_string(all) +
                    " (one per subdomain copy of a prescribed node and component)");
  }
  for (const auto& k : spec.couplings)
    boundary(std::string("coupled u_") + "xyz"[k.component % 3] + ": one common value", k.boundary);
  if (!spec.couplings.empty())
    lines.push_back("coupling rows: " + std::to_string(problem.couplingRowCount) +
                    " (one per coupled node and component but the first of its boundary)");
  const std::size_t dim = static_cast<std::size_t>(problem.mesh.dim);
  for (const auto& [name, t] : spec.tractions) boundary("traction " + braced(t, t.size()), name);
  for (std::size_t k = 0; k < problem.pairs.size(); ++k) {
    const auto& pair = problem.pairs[k];
    const ContactPairSpec& ps = pair.spec;
    boundary("contact slave", ps.slave);
    if (!ps.obstacle) boundary("contact master", ps.master);
    const long long pairRows =
        problem.pairs.size() == 1
            ? rows
            : std::count(problem.rowPair.begin(), problem.rowPair.end(), static_cast<int>(k));
    std::ostringstream s;
    s << (ps.name.empty() ? std::string("contact pair") : "contact pair \"" + ps.name + "\"")
      << ": " << pair.slaveNodes.size() << " slave nodes of \"" << ps.slave << "\" against "
      << (ps.obstacle ? std::string("the rigid obstacle")
                      : (dim == 3 ? "the faces of \"" : "the segments of \"") + ps.master + "\"")
      << ": " << pairRows << " within the search radius " << pair.searchRadius << "; applied force "
      << braced(problem.appliedForce, dim);
    lines.push_back(s.str());
  }
}

// The run's check that every rigid motion is held, on the rows of its first solve: the rigid
// obstacle where the first increment moves it, and the friction rows with a bound from the start
// (Tresca; Coulomb sticking where friction alone holds a body, which it says). It returns what
// addInitialFrictionRows found: that, and the load factor beyond which the contact and friction
// rows cannot hold the load (an error where it is 0). A restart starts from its saved state, which
// the dry run does not read: its run checks.
InitialFriction checkRigidMotions(const tfeti::Comm& comm, const ParameterList& params,
                                  const ElasticContactSpec& spec, ElasticContactProblem& problem,
                                  const NonlinearOptions* options) {
  // The report is of the reference configuration: a moved obstacle's rows only for this check.
  struct Saved {
    ElasticContactProblem& p;
    NodeToSegmentResult contact;
    std::vector<int> rowPair;
    std::vector<tfeti::InequalityRow> inequalities;
    std::vector<ElasticContactProblem::Pair> pairs;
    explicit Saved(ElasticContactProblem& q)
        : p(q),
          contact(q.contact),
          rowPair(q.rowPair),
          inequalities(q.inequalities),
          pairs(q.pairs) {}
    ~Saved() {
      p.contact = std::move(contact);
      p.rowPair = std::move(rowPair);
      p.inequalities = std::move(inequalities);
      p.pairs = std::move(pairs);
    }
  };
  std::optional<Saved> saved;
  if (options != nullptr && !options->obstacleDisplacement.empty()) {
    saved.emplace(problem);
    searchContactAtReference(problem, *options, std::min(1.0, 1.0 / options->steps),
                             comm.getRank());
  }
  std::vector<tfeti::InequalityRow> rows = problem.inequalities;
  InitialFriction friction =
      addInitialFrictionRows(spec, problem, modelFriction(params, spec.pairs), {}, rows, comm);
  requireLoadHeld(friction.limit);
  return friction;
}

}  // namespace

void checkContactProblem(const Teuchos::RCP<const tfeti::Comm>& comm, ParameterList& params,
                         const std::string& outputDirectory, std::ostream& out) {
  // The full runs' set-up, in their order, up to the FETI solver.
  const bool nonlinear = params.get<std::string>("Problem") == "nonlinear_contact";
  if (nonlinear) checkNonlinearParameters(params);
  const ElasticContactSpec spec =
      nonlinear ? nonlinearContactSpec(params) : elasticContactSpec(params);
  ElasticContactProblem problem = buildElasticContactProblem(spec, *comm);
  NonlinearOptions options;
  if (nonlinear) {
    options = nonlinearOptionsFrom(params);
    checkNonlinearOptionsFor(options, problem.dim(),
                             static_cast<int>(std::count_if(
                                 spec.pairs.begin(), spec.pairs.end(),
                                 [](const ContactPairSpec& p) { return p.obstacle.has_value(); })));
    requireLoadOrMotion(*comm, problem.local, options, !problem.prescribed.empty());
  }
  checkHertzInput(params, problem.dim(), contactBodyLaws(spec, problem));
  const int restartStep = nonlinear ? checkRestart(params, spec, problem, outputDirectory) : -1;
  const InitialFriction friction =
      restartStep < 0
          ? checkRigidMotions(*comm, params, spec, problem, nonlinear ? &options : nullptr)
          : InitialFriction();
  const auto rows = static_cast<long long>(problem.contact.rows.size());
  const std::string solver = tfeti::FetiSolver::dualSolverFor(fetiParameters(params, spec), rows);

  std::vector<std::string> lines{
      problemLine(params, spec, nonlinear, restartStep, outputDirectory, solver)};
  addBodyLines(spec, problem, nonlinear, lines);
  addBoundaryLines(*comm, spec, problem, rows, lines);
  if (friction.sticks)
    lines.push_back(
        "friction: Coulomb friction alone holds a body along the contact surface: "
        "every load step starts sticking, then takes mu lambda_N");
  if (friction.limit && friction.limit->loadFactor < 1.0)
    lines.push_back("friction: " + frictionLimitText(*friction.limit));
  printDryRunReport(comm, problem.numSubdomains(), lines, problem.local, rows,
                    fetiParameters(params, spec), out, problem.inequalities, problem.equalities);
}

}  // namespace contact
