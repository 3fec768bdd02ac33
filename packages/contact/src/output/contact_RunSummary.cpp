#include "contact_RunSummary.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

namespace contact {

Json timingsJson(const tfeti::FetiTimings& t, int iterations) {
  Json j = Json::object();
  j["factorization_s"] = t.factorization;
  j["tearing_s"] = t.tearing;
  j["coarse_s"] = t.coarse;
  j["preconditioner_s"] = t.preconditioner;
  j["dual_rhs_s"] = t.dualRhs;
  j["dual_operator_s"] = t.dualOperator;
  j["explicit_memory_check_s"] = t.explicitMemoryCheck;
  j["setup_s"] = t.setup();
  j["solve_s"] = t.solve;
  j["recovery_s"] = t.recovery;
  j["per_iteration_s"] = iterations > 0 ? t.solve / iterations : 0.0;
  j["subdomain_factorizations"] = t.factorizations;
  j["subdomain_factorizations_reused"] = t.factorizationsReused;
  j["tearings"] = t.tearings;
  j["tearings_reused"] = t.tearingsReused;
  j["symbolic_analyses"] = t.symbolicAnalyses;
  j["symbolic_analyses_shared"] = t.symbolicAnalysesShared;
  return j;
}

namespace {

template <class T>
Json arrayJson(const Teuchos::Array<T>& values) {
  Json a = Json::array();
  for (const T& v : values) a.push(Json(v));
  return a;
}

}  // namespace

Json parametersJson(const Teuchos::ParameterList& params) {
  Json j = Json::object();
  for (auto it = params.begin(); it != params.end(); ++it) {
    const std::string& name = params.name(it);
    const auto& any = params.entry(it).getAny(false);
    if (params.isSublist(name))
      j[name] = parametersJson(params.sublist(name));
    else if (any.type() == typeid(bool))
      j[name] = Teuchos::any_cast<bool>(any);
    else if (any.type() == typeid(int))
      j[name] = Teuchos::any_cast<int>(any);
    else if (any.type() == typeid(double))
      j[name] = Teuchos::any_cast<double>(any);
    else if (any.type() == typeid(std::string))
      j[name] = Teuchos::any_cast<std::string>(any);
    else if (any.type() == typeid(Teuchos::Array<int>))
      j[name] = arrayJson(Teuchos::any_cast<Teuchos::Array<int>>(any));
    else if (any.type() == typeid(Teuchos::Array<double>))
      j[name] = arrayJson(Teuchos::any_cast<Teuchos::Array<double>>(any));
    else if (any.type() == typeid(Teuchos::Array<std::string>))
      j[name] = arrayJson(Teuchos::any_cast<Teuchos::Array<std::string>>(any));
    else
      j[name] = Teuchos::toString(any);  // a type no parameter uses today: its text
  }
  return j;
}

void writeSummary(const tfeti::Comm& comm, const std::string& dir, const Json& summary,
                  const Teuchos::ParameterList& params) {
  if (comm.getRank() != 0) return;
  const std::string path = dir + "/summary.json";
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  Json s = summary;
  s["parameters"] = parametersJson(params);  // what was solved, defaults filled in
  out << s.dump();
}

// Largest resident set size over the ranks, in MiB.
double peakRssMb(const tfeti::Comm& comm) {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  double mine = usage.ru_maxrss / 1024.0, all = 0.0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &mine, &all);
  return all;
}

Json memoryJson(const tfeti::MemoryLog& log, long long unknowns) {
  Json j = Json::object();
  Json phases = Json::array();
  double peakMax = 0.0, peakSum = 0.0;
  for (const auto& p : log.phases()) {
    Json q = Json::object();
    q["phase"] = p.phase;
    q["rss_mib_max"] = p.maxOverRanks.rssMib;
    q["peak_mib_max"] = p.maxOverRanks.peakMib;
    q["rss_mib_sum"] = p.sumOverRanks.rssMib;
    q["peak_mib_sum"] = p.sumOverRanks.peakMib;
    phases.push(std::move(q));
    peakMax = std::max(peakMax, p.maxOverRanks.peakMib);
    peakSum = std::max(peakSum, p.sumOverRanks.peakMib);
  }
  j["phases"] = std::move(phases);
  j["peak_mib_per_rank"] = peakMax;
  j["peak_mib_all_ranks"] = peakSum;
  j["bytes_per_unknown"] = unknowns > 0 ? peakSum * 1048576.0 / static_cast<double>(unknowns) : 0.0;
  return j;
}

namespace {
// The VTK type of a linear element of the FETI mesh: triangles and quadrilaterals in 2D,
// tetrahedra and hexahedra in 3D (corners in VTK's order, as the structured mesh lists them).
int vtkLinearCell(int dim, int nodes) {
  if (dim == 2 && (nodes == 3 || nodes == 4)) return nodes == 3 ? kVtkTriangle : kVtkQuad;
  if (dim == 3 && (nodes == 4 || nodes == 8)) return nodes == 4 ? kVtkTetra : kVtkHexahedron;
  throw std::invalid_argument("VTU output: no linear " + std::to_string(dim) + "D cell of " +
                              std::to_string(nodes) + " nodes");
}
}  // namespace

VtuPiece vtuPiece(const tfeti::FetiSolver& solver) {
  VtuPiece piece;
  VtuField u{"u", 1, {}}, sub{"subdomain", 1, {}};
  if (!solver.data().empty()) piece.dim = solver.data().front().mesh.dim;
  // One value per node (Poisson) or dim components (elasticity), written with 3 components.
  const bool vec = !solver.data().empty() && solver.data().front().dofsPerNode > 1;
  if (vec) u = VtuField{"displacement", 3, {}};
  for (std::size_t i = 0; i < solver.data().size(); ++i) {
    const auto& data = solver.data()[i];
    const auto& mesh = data.mesh;
    const int base = static_cast<int>(piece.points.size() / piece.dim);
    piece.points.insert(piece.points.end(), mesh.coords.begin(), mesh.coords.end());
    const auto& el = mesh.elements;
    for (int e = 0; e < el.size(); ++e) {
      piece.cellTypes.push_back(vtkLinearCell(mesh.dim, el.offsets[e + 1] - el.offsets[e]));
      for (int k = el.offsets[e]; k < el.offsets[e + 1]; ++k)
        piece.cellPoints.push_back(base + el.nodes[k]);
    }
    const auto& us = solver.solution(i);
    const int dpn = data.dofsPerNode;
    for (int n = 0; n < mesh.numNodes(); ++n) {
      if (vec)
        for (int c = 0; c < 3; ++c) u.values.push_back(c < dpn ? us[dpn * n + c] : 0.0);
      else
        u.values.push_back(us[n]);
    }
    sub.values.insert(sub.values.end(), el.size(), static_cast<double>(mesh.id));
  }
  piece.pointData.push_back(std::move(u));
  piece.cellData.push_back(std::move(sub));
  return piece;
}

FetiDimensions fetiDimensions(const tfeti::FetiSolver& solver, const Teuchos::ParameterList& feti) {
  FetiDimensions d;
  d.formulation = feti.get<std::string>("Formulation");
  d.preconditioner = feti.get<std::string>("Preconditioner");
  d.localSolver = feti.get<std::string>("Local solver");
  d.primal = solver.primalDimension();
  d.dual = solver.dualDimension();
  d.gluingRows = solver.gluingRows();
  d.dirichletRows = solver.dirichletRows();
  d.contactRows = solver.inequalityRows();
  d.coarse = solver.coarseDimension();
  d.largestScalingGroup = solver.largestScalingGroup();
  d.dualOperatorApplies = solver.dualOperatorApplies();
  d.factorBytes = static_cast<unsigned long long>(solver.globalFactorBytes());
  d.factorMemory = solver.factorMemoryCheck();
  d.preconditionerMemory = solver.preconditionerMemoryCheck();
  d.dualOperator = solver.dualOperatorKind();
  const auto bytes = solver.explicitDualBytes();
  d.explicitDualBytes = bytes.total;
  d.explicitDualBytesMaxRank = bytes.maxPerRank;
  d.explicitDevice = solver.explicitDeviceWork();
  d.explicitAssembly = solver.explicitAssembly();
  d.dualChoice = solver.dualOperatorChoice();
  return d;
}

namespace {

// Blocks assembled in the run, the columns solved for, and those that assembling each block anew
// would have solved: fewer where update() kept the unchanged rows' part; the blocks of those
// assembled from the Schur complement (their columns count as solved).
Json explicitAssemblyJson(const tfeti::FetiSolver::ExplicitAssembly& e) {
  Json a = Json::object();
  a["blocks"] = e.blocks;
  a["columns_solved"] = e.columnsSolved;
  a["columns_full"] = e.columnsFull;
  a["schur_blocks"] = e.schurBlocks;
  return a;
}

// The F_s against the nodes' memory before the last assembly from scratch: whether they fit, and
// for the node with the least room its need and available bytes (-1: unknown or not checked).
Json memoryCheckJson(const tfeti::FetiSolver::DualOperatorChoice& c) {
  Json a = Json::object();
  a["fits"] = c.fitsMemory;
  a["node_need_bytes"] = c.nodeNeedBytes;
  a["node_available_bytes"] = c.nodeAvailableBytes;
  return a;
}

// "Dual operator" = auto: the last set-up's choice and what it rested on.
Json dualChoiceJson(const tfeti::FetiSolver::DualOperatorChoice& c) {
  Json a = Json::object();
  a["chosen"] = c.chosen;
  a["qp"] = c.qp;
  a["explicit_bytes"] = c.explicitBytes;
  a["factor_bytes"] = c.factorBytes;
  a["explicit_fits_memory"] = c.fitsMemory;
  return a;
}

// The batched applies on the device: per apply, what the kernel streams and what crosses between
// host and device (all ranks), and the bandwidth of the slowest rank's kernels.
Json deviceWorkJson(const tfeti::FetiSolver::ExplicitDeviceWork& dev) {
  Json w = Json::object();
  w["applies"] = dev.applies;
  w["kernel_seconds"] = dev.kernelSeconds;
  w["apply_seconds"] = dev.applySeconds;
  w["kernel_bytes_per_apply"] = dev.kernelBytes;
  w["transfer_bytes_per_apply"] = dev.transferBytes;
  w["kernel_bandwidth_gb_per_s"] =
      dev.kernelSeconds > 0 ? dev.kernelBytes * dev.applies / dev.kernelSeconds / 1e9 : 0.0;
  return w;
}

}  // namespace

namespace {
// A memory check of the set-up (tfeti::NodeMemory): whether it was made, and then whether the
// node with the least room had it, what its ranks needed and what it had available.
Json nodeMemoryJson(const tfeti::NodeMemory& m) {
  Json check = Json::object();
  check["checked"] = m.known;
  if (m.known) {
    check["fits"] = m.fits;
    check["node_need_bytes"] = m.needBytes;
    check["node_available_bytes"] = m.availableBytes;
    check["node_ranks"] = m.ranks;
  }
  return check;
}
}  // namespace

void addFactorSummary(Json& s, const FetiDimensions& feti) {
  s["factor_bytes"] = feti.factorBytes;
  s["factor_memory_check"] = nodeMemoryJson(feti.factorMemory);
  // The need is the factorizations' peak; what the factors then hold on that node.
  if (feti.factorMemory.known)
    s["factor_memory_check"]["node_held_bytes"] = feti.factorMemory.heldBytes;
  s["preconditioner_memory_check"] = nodeMemoryJson(feti.preconditionerMemory);
}

void addDualOperatorSummary(Json& s, const FetiDimensions& feti) {
  s["dual_operator"] = feti.dualOperator;
  s["explicit_dual_bytes"] = feti.explicitDualBytes;
  s["explicit_dual_bytes_max_rank"] = feti.explicitDualBytesMaxRank;
  if (feti.dualOperator == "explicit")
    s["explicit_dual_assembly"] = explicitAssemblyJson(feti.explicitAssembly);
  if (feti.dualChoice.automatic) s["dual_operator_auto"] = dualChoiceJson(feti.dualChoice);
  if (feti.dualOperator == "explicit" || feti.dualChoice.automatic)
    s["explicit_memory_check"] = memoryCheckJson(feti.dualChoice);
  s["explicit_device"] = feti.explicitDevice.device;
  if (feti.explicitDevice.device == "gpu")
    s["explicit_device_work"] = deviceWorkJson(feti.explicitDevice);
}

void addSolverSummary(Json& s, const FetiDimensions& feti, const tfeti::DualResult& result,
                      const tfeti::MemoryLog& memory) {
  s["formulation"] = feti.formulation;
  s["preconditioner"] = feti.preconditioner;
  s["local_solver"] = feti.localSolver;
  s["dual_solver"] = result.method;
  s["primal_dim"] = feti.primal;
  s["dual_dim"] = feti.dual;
  s["gluing_rows"] = feti.gluingRows;
  s["dirichlet_rows"] = feti.dirichletRows;
  s["contact_rows"] = feti.contactRows;
  s["coarse_dim"] = feti.coarse;
  s["largest_scaling_group"] = feti.largestScalingGroup;
  s["converged"] = result.converged;
  s["iterations"] = result.iterations;
  s["relative_residual"] = result.relativeResidual;
  Json history = Json::array();
  for (double h : result.history) history.push(h);
  s["residual_history"] = std::move(history);
  s["dual_operator_applies"] = feti.dualOperatorApplies;
  addFactorSummary(s, feti);
  addDualOperatorSummary(s, feti);
  s["memory"] = memoryJson(memory, feti.primal);
}

Json qpJson(const tfeti::DualResult& r) {
  Json q = Json::object();
  q["method"] = r.method;
  q["converged"] = r.converged;
  q["outer_iterations"] = r.qp.outerIterations;
  q["hessian_multiplications"] = r.qp.hessianMultiplications;
  q["cg_steps"] = r.qp.cgSteps;
  q["expansion_steps"] = r.qp.expansionSteps;
  q["proportioning_steps"] = r.qp.proportioningSteps;
  q["projected_gradient_norm"] = r.qp.projectedGradientNorm;
  q["equality_residual_norm"] = r.qp.equalityResidualNorm;
  if (r.method == "penalty") q["equality_projection_norm"] = r.qp.equalityProjectionNorm;
  q["rhs_norm"] = r.qp.rhsNorm;
  q["rho"] = r.rho;
  if (!r.qp.message.empty()) q["message"] = r.qp.message;
  return q;
}

Json constraintJson(const tfeti::ConstraintReport& c) {
  Json j = Json::object();
  j["rows"] = c.inequalityRows;
  j["active_rows"] = c.activeRows;
  j["min_multiplier"] = c.minMultiplier;
  j["max_penetration"] = c.maxPenetration;
  j["max_complementarity"] = c.maxComplementarity;
  j["equality_residual"] = c.equalityResidual;
  if (c.frictionRows > 0) {  // friction rows: their own conditions (ConstraintReport)
    j["friction_rows"] = c.frictionRows;
    j["stick_rows"] = c.stickRows;
    j["max_friction_bound_excess"] = c.maxFrictionBoundExcess;
    j["max_friction_slip_residual"] = c.maxFrictionSlipResidual;
  }
  return j;
}

double maxAbsSolution(const tfeti::Comm& comm, const tfeti::FetiSolver& solver) {
  double mine = 0.0, all = 0.0;
  for (std::size_t i = 0; i < solver.data().size(); ++i)
    for (double v : solver.solution(i)) mine = std::max(mine, std::abs(v));
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &mine, &all);
  return all;
}

}  // namespace contact
