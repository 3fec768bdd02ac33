#include "contact_ContactResult.hpp"
#include "contact_Materials.hpp"

#include "contact_RunSummary.hpp"

namespace contact {

namespace {

bool nonlinearRun(const ContactResult& r) {
  return r.problem == "nonlinear_contact";
}

// The keys of the elastic run's "contact" object after the constraint report.
void addElasticContact(Json& c, const ContactMeasures& m) {
  c["p_max"] = m.pMax;
  c["p_max_recovered"] = m.pMaxRecovered;
  c[m.extentKey] = m.extent;
  c["force"] = m.force;
  c["applied_force"] = m.appliedForce;
  c["force_relative_error"] = m.forceRelativeError;
  if (m.slab) {
    c["line_length"] = m.slab->lineLength;
    c["force_per_unit_length"] = m.slab->forcePerUnitLength;
    c["node_planes"] = m.slab->nodePlanes;
    c["half_width_min"] = m.slab->halfWidthMin;
    c["half_width_max"] = m.slab->halfWidthMax;
  }
  if (m.hertz) addHertzComparison(c, *m.hertz);
}

void addNonlinearContact(Json& c, const ContactMeasures& m) {
  c["p_max"] = m.pMax;
  c["p_max_recovered"] = m.pMaxRecovered;
  c["extent_measure"] = m.extentKey;
  c["contact_extent"] = m.extent;
  if (m.extentKey != "angle") c[m.extentKey] = m.extent;
  c["force"] = m.force;
  c["applied_force"] = m.appliedForce;
  c["force_relative_error"] = m.forceRelativeError;
  c["support_force"] = m.supportForce;
  c["support_relative_error"] = m.supportRelativeError;
  if (m.hertz) addHertzComparison(c, *m.hertz);
  // The contact conditions of the last QP solve (rows B_I du <= g on the last geometry).
  Json last = constraintJson(m.constraints);
  last["max_abs_du"] = m.lastMaxAbsIncrement;
  c["last_solve"] = std::move(last);
}

// The prescribed entries (with their reactions) and the kinematic couplings.
void addConstraintRecords(Json& s, const ContactResult& r) {
  if (r.prescribed) {
    s["prescribed_rows"] = r.prescribedRows;
    s["prescribed"] = *r.prescribed;
  }
  if (r.couplings) {
    s["coupling_rows"] = r.couplingRows;
    s["couplings"] = *r.couplings;
  }
}

// The keys that open every contact summary, elastic or nonlinear, in the order readers expect.
Json runHeader(const ContactResult& r) {
  Json s = Json::object();
  s["study"] = "single";
  s["problem"] = r.problem;
  s["ranks"] = r.ranks;
  s["subdomains"] = r.subdomains;
  s["nodes"] = r.nodes;
  s["dimension"] = r.dimension;
  Json d = Json::object();
  d["partitioner"] = r.distribution.partitioner;
  d["dof_imbalance"] = r.distribution.dofImbalance;
  d["contact_imbalance"] = r.distribution.contactImbalance;
  d["edge_cut"] = r.distribution.edgeCut;
  s["subdomain_distribution"] = std::move(d);
  return s;
}

Json elasticSummary(const ContactResult& r) {
  Json s = runHeader(r);
  s["formulation"] = r.feti.formulation;
  s["preconditioner"] = r.feti.preconditioner;
  s["local_solver"] = r.feti.localSolver;
  s["dual_solver"] = r.qp.method;
  s["primal_dim"] = r.feti.primal;
  s["dual_dim"] = r.feti.dual;
  s["gluing_rows"] = r.feti.gluingRows;
  s["dirichlet_rows"] = r.feti.dirichletRows;
  s["contact_rows"] = r.feti.contactRows;
  s["coarse_dim"] = r.feti.coarse;
  s["largest_scaling_group"] = r.feti.largestScalingGroup;
  s["converged"] = r.converged;
  s["iterations"] = r.qp.iterations;
  s["relative_residual"] = r.qp.relativeResidual;
  Json history = Json::array();
  for (double h : r.qp.history) history.push(h);
  s["residual_history"] = std::move(history);
  s["dual_operator_applies"] = r.feti.dualOperatorApplies;
  addFactorSummary(s, r.feti);
  addDualOperatorSummary(s, r.feti);
  s["contact_type"] = r.contactType;
  s["contact_discretization"] = r.contactDiscretization;
  addMaterialSummary(s, r.materials);
  s["qp"] = qpJson(r.qp);
  s["contact"] = contactJson(r);
  s["max_von_mises"] = r.maxVonMises;
  s["max_von_mises_nodal"] = r.maxVonMisesNodal;
  s["max_abs_u"] = r.maxAbsU;
  addConstraintRecords(s, r);
  s["timings"] = timingsJson(r.timings, r.qp.iterations);
  s["peak_rss_mb"] = r.peakRssMb;
  if (!r.contactCsv.empty()) s["contact_csv"] = r.contactCsv;
  if (!r.vtu.empty()) s["vtu"] = r.vtu;
  return s;
}

Json nonlinearSummary(const ContactResult& r) {
  Json s = runHeader(r);
  s["primal_dim"] = r.feti.primal;
  s["dual_dim"] = r.feti.dual;
  s["contact_rows"] = r.feti.contactRows;
  addDualOperatorSummary(s, r.feti);  // the last solve's operator
  s["converged"] = r.converged;
  const NonlinearOutcome& o = r.nonlinear;
  addMaterialSummary(s, r.materials);
  const IterationTotals totals = iterationTotals(r.history);
  s["iterations"] = totals.iterations;
  Json nl = Json::object();
  nl["geometrically_nonlinear"] = o.geometricallyNonlinear;
  nl["stiffness"] = o.stiffness;
  nl["eta1"] = o.eta1;
  nl["eta2"] = o.eta2;
  nl["load_factor"] = r.history.loadFactor;
  nl["converged_steps"] = r.history.step;
  nl["stopped"] = o.stopped;
  nl["restarted"] = o.restarted;
  nl["total_iterations"] = totals.iterations;
  nl["rejected_iterations"] = totals.rejected;
  nl["total_mprgp_iterations"] = totals.mprgpIterations;
  nl["total_hessian_multiplications"] = totals.hessianMultiplications;
  if (r.exitCode == 3) nl["message"] = r.message;
  if (!r.fixedPoint.empty()) {
    Json fp = Json::array();
    for (const FixedPointStep& f : r.fixedPoint) {
      Json e = Json::object();
      e["step"] = f.step;
      e["iterations"] = f.iterations;
      e["relative_change"] = f.change;
      fp.push(std::move(e));
    }
    nl["fixed_point"] = std::move(fp);
    nl["fixed_point_tolerance"] = r.friction.fixedPointTolerance;
  }
  if (r.frictionLimit) {
    Json f = Json::object();
    f["load_factor"] = r.frictionLimit->loadFactor;
    f["motion"] = r.frictionLimit->motion;
    f["load"] = r.frictionLimit->load;
    f["capacity"] = r.frictionLimit->capacity;
    f["lifted_contact_rows"] = r.frictionLimit->liftedRows;
    nl["friction_limit"] = std::move(f);
  }
  s["nonlinear"] = std::move(nl);
  s["steps"] = stepsJson(r.history);
  if (r.haveContact) {
    s["contact"] = contactJson(r);
    s["max_von_mises"] = r.maxVonMises;
    s["max_von_mises_nodal"] = r.maxVonMisesNodal;
    s["max_plastic_strain"] = r.maxPlasticStrain;
  }
  s["max_abs_u"] = r.maxAbsU;
  addConstraintRecords(s, r);
  if (!r.contactCsv.empty()) s["contact_csv"] = r.contactCsv;
  if (!r.iterationsCsv.empty()) s["iterations_csv"] = r.iterationsCsv;
  if (!r.stepsCsv.empty()) s["steps_csv"] = r.stepsCsv;
  s["timings"] = timingsJson(r.timings, static_cast<int>(totals.iterations));
  s["wall_time"] = r.wallTime;
  s["peak_rss_mb"] = r.peakRssMb;
  return s;
}

}  // namespace

namespace {

// contact.pairs: per pair its name, force (the resultant's magnitude) and force_vector, and a
// pair with friction its friction record (nonlinear runs).
void addPairForces(Json& c, const std::vector<PairForce>& pairs, const ContactResult* frictional) {
  if (pairs.empty()) return;
  Json list = Json::array();
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const PairForce& p = pairs[k];
    Json j = Json::object();
    j["name"] = p.name;
    j["discretization"] = p.discretization;
    j["force"] = p.force;
    Json v = Json::array();
    for (double x : p.vector) v.push(x);
    j["force_vector"] = std::move(v);
    if (frictional)
      addPairFrictionJson(j, frictional->contactNodes, frictional->friction, static_cast<int>(k),
                          frictional->dimension);
    list.push(std::move(j));
  }
  c["pairs"] = std::move(list);
}

}  // namespace

Json contactJson(const ContactResult& r) {
  if (nonlinearRun(r)) {
    Json c = Json::object();
    addNonlinearContact(c, r.contact);
    if (r.friction.active()) addFrictionJson(c, r.contactNodes, r.friction, r.dimension);
    addPairForces(c, r.pairs, r.friction.active() ? &r : nullptr);
    return c;
  }
  Json c = constraintJson(r.contact.constraints);
  addElasticContact(c, r.contact);
  addPairForces(c, r.pairs, nullptr);
  return c;
}

Json summaryJson(const ContactResult& r) {
  return nonlinearRun(r) ? nonlinearSummary(r) : elasticSummary(r);
}

}  // namespace contact
