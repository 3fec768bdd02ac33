// elastic_contact as the load-step loop's one-step case: small strain, linear laws, one
// increment from u = 0 at load factor 1 on the reference geometry, which solves the linear
// problem exactly with the loads and contact rows the FETI solver is built with. A QP that did
// not converge is reported (exit code 2) with the state it left, not retried; nothing is written
// per step, and the figures are the elastic problem's (stresses recovered from the linear laws,
// the contact force as the sum of the multipliers, the 3D slab's line contact).
#include <algorithm>
#include <cmath>
#include <iostream>

#include "contact_ContactParameters.hpp"
#include "contact_ContactRun.hpp"
#include "contact_RecoveredFields.hpp"
#include "contact_RunPolicy.hpp"
#include "contact_VtuWriter.hpp"

namespace contact {

namespace {

// A 3D line contact (a plane-strain slab): the length of the contact line (the slave nodes'
// extent along z), the force per unit of it (to compare with a 2D run's force per unit
// thickness) and the half-width on each node plane, whose spread shows how far the solution is
// from independent of z.
SlabContact slabContact(const std::vector<ContactNode>& nodes, double force) {
  const std::vector<PlaneHalfWidth> planes = halfWidthPerPlane(nodes);
  SlabContact s;
  s.lineLength = planes.empty() ? 0.0 : planes.back().z - planes.front().z;
  s.forcePerUnitLength = s.lineLength > 0.0 ? force / s.lineLength : 0.0;
  s.nodePlanes = static_cast<int>(planes.size());
  for (std::size_t k = 0; k < planes.size(); ++k) {
    s.halfWidthMin = k ? std::min(s.halfWidthMin, planes[k].halfWidth) : planes[k].halfWidth;
    s.halfWidthMax = k ? std::max(s.halfWidthMax, planes[k].halfWidth) : planes[k].halfWidth;
  }
  return s;
}

class ElasticContactPolicy final : public RunPolicy {
 public:
  std::string name() const override { return "elastic_contact"; }

  ElasticContactSpec readParameters(const Teuchos::ParameterList& params,
                                    NonlinearOptions&) const override {
    return elasticContactSpec(params);
  }

  // Small strain, one increment at load factor 1 solved as built, no cut-back; the contact zone
  // measured as "Contact zone" says.
  void fitOptions(const Teuchos::ParameterList& params, int dim, int,
                  NonlinearOptions& options) const override {
    NonlinearOptions o;
    o.kinematics = plasticity::Kinematics::SmallStrain;
    o.steps = 1;
    o.maxIterations = 1;
    o.maxCutbacks = 0;
    o.stiffness = "initial";
    o.vtuEveryStep = false;
    o.solveAsBuilt = true;
    o.singleIncrement = true;
    o.rule.line = lineContact(params, dim);
    options = o;
  }

  // An unloaded problem is valid: its solution is u = 0.
  double loadNorm(const tfeti::Comm& comm, const ElasticContactProblem& problem,
                  const NonlinearOptions&) const override {
    Field f;
    for (const auto& s : problem.local) f.push_back(s.f);
    return globalNorm(comm, f);
  }

  // The rows of the mesh's search: the only increment is solved as built.
  void initialContact(const tfeti::Comm&, NonlinearModel&, const NonlinearOptions&,
                      double) const override {}

  // The prescribed rows at their full value: the only increment is solved as built.
  std::vector<tfeti::EqualityRow> initialEqualityRows(const ElasticContactProblem& problem, double,
                                                      const Field&) const override {
    return problem.equalities;
  }

  // The one iteration's line would repeat the run's last line.
  bool printsIterations() const override { return false; }
  bool keepsUnconvergedStep() const override { return true; }
  bool savesSteps() const override { return false; }

  // The stresses of the linear laws and the contact nodes on the reference geometry, as the
  // elastic problem reports them.
  void evaluateStep(ContactRun& r, LoadSteps&, const Field& u, StepRecord& rec) const override {
    const tfeti::Comm& comm = *r.comm;
    const NonlinearModel& model = *r.model;
    const ElasticContactProblem& problem = model.problem;
    const tfeti::FetiSolver& solver = *r.solver;
    Field solution;
    for (std::size_t i = 0; i < problem.local.size(); ++i) solution.push_back(solver.solution(i));
    r.nodes = contactNodes(problem, solver, r.options.rule, {},
                           model.surfaceDisplacement(comm, solution));
    recoverContactPressures(r.nodes, problem);
    double vm = 0.0;
    r.stresses.clear();
    for (std::size_t i = 0; i < problem.local.size(); ++i) {
      r.stresses.push_back(
          plasticity::recoverStresses(problem.localElements[i], *model.laws[i], u[i]));
      const auto& st = r.stresses.back();
      for (int e = 0; e < problem.localElements[i].numElements(); ++e)
        for (int q = 0; q < st.gaussPointsPerElement; ++q)
          vm = std::max(vm, st.atGaussPoint(e, q, plasticity::kVonMises));
    }
    r.maxVonMisesNodal = maxNodalVonMises(comm, problem, r.stresses);
    r.evaluated = true;
    rec.pMax = maxPressure(r.nodes);
    rec.contactExtent = contactExtent(r.nodes, r.options.rule, problem.dim());
    rec.maxVonMises = globalMax(comm, vm);
    // The sum of the multipliers (forces along each row's normal), the figure the elastic
    // problem's summary has always reported.
    rec.contactForce = 0.0;
    for (const auto& n : r.nodes) rec.contactForce += n.lambda;
  }

  // The only step, kept whether or not its QP converged, is the final state.
  void evaluateFinalState(ContactRun&, LoadSteps&) const override {}

  double appliedForce(const ContactRun& r) const override {
    const double* F = r.model->problem.appliedForce;
    return std::hypot(F[0], F[1], F[2]);
  }

  void addContactMeasures(ContactMeasures& c, const ContactRun& r) const override {
    if (r.model->problem.dim() == 3 && r.options.rule.line) c.slab = slabContact(r.nodes, c.force);
  }

  void writeFinalState(ContactResult& res, const ContactRun& r, const LoadSteps&,
                       const std::string& dir) const override {
    const ElasticContactProblem& problem = r.model->problem;
    writeContactCsv(*r.comm, res.contactCsv, res.contactNodes, problem.dim());
    if (!r.vtu) return;
    std::vector<SubdomainFields> fields;
    for (std::size_t i = 0; i < problem.local.size(); ++i) {
      fields.push_back({&problem.localElements[i],
                        problem.local[i].mesh.id,
                        &r.model->u[i],
                        &r.stresses[i],
                        {}});
      if (problem.namedPairs)
        fields.back().extra.push_back(
            contactPairField(res.contactNodes, problem.local[i].mesh.globalNode));
    }
    const std::vector<std::string> names =
        problem.namedPairs ? std::vector<std::string>{"contact_pair"} : std::vector<std::string>{};
    res.vtu = writeVtu(*r.comm, dir, "solution", stressPiece(fields, names));
  }

  void report(const ContactResult& res, const ContactRun& r, const LoadSteps&) const override {
    const ContactMeasures& c = res.contact;
    std::cout << "elastic_contact: " << r.model->problem.numSubdomains() << " subdomains, primal "
              << res.feti.primal << ", dual " << res.feti.dual << " (" << res.feti.contactRows
              << " contact rows), " << res.qp.method << ": " << res.qp.qp.hessianMultiplications
              << " Hessian multiplications (" << (res.converged ? "converged" : "NOT CONVERGED")
              << "); p_max " << c.pMax << " (recovered " << c.pMaxRecovered << ")"
              << (r.options.rule.line ? ", half-width " : ", contact radius ") << c.extent
              << ", force " << c.force << " (applied " << c.appliedForce << "), max von Mises "
              << res.maxVonMises << "\n";
  }
};

}  // namespace

std::unique_ptr<const RunPolicy> elasticContactPolicy() {
  return std::make_unique<ElasticContactPolicy>();
}

}  // namespace contact
