// FetiSolver's set-up: the subdomains and their factorizations, the tearing, the coarse space,
// the preconditioner and the dual right-hand side, built by the constructor and rebuilt by
// update() and updateStiffness().
#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_InputChecks.hpp"
#include "tfeti_NodeMemory.hpp"
#include "tfeti_PhaseTimer.hpp"
#include "tfeti_TpetraInterface.hpp"

namespace tfeti {

namespace {
TearingOptions tearingOptions(const Teuchos::ParameterList& params) {
  TearingOptions opts;
  opts.formulation = parseFormulation(params.get<std::string>("Formulation"));
  const std::string gluing = params.get<std::string>("Gluing");
  opts.gluing = gluing == "redundant" ? Gluing::Redundant
                : gluing == "none"    ? Gluing::None
                                      : Gluing::NonRedundant;
  opts.gluingAtDirichletNodes = params.get<bool>("Gluing at Dirichlet nodes");
  opts.inequalityScaling = params.get<std::string>("Inequality row scaling") == "separate"
                               ? TearingOptions::InequalityScaling::Separate
                               : TearingOptions::InequalityScaling::Joined;
  return opts;
}

// What the tearing needs of each local subdomain: its size and its boundary nodes.
std::vector<TearingInput> tearingInput(const std::vector<SubdomainData>& data) {
  std::vector<TearingInput> input;
  for (const auto& sd : data) {
    TearingInput in;
    in.id = sd.mesh.id;
    in.numDofs = sd.mesh.numNodes() * sd.dofsPerNode;
    in.boundaryNodes = sd.mesh.boundaryNodes();
    const std::vector<int> dir = sd.mesh.dirichletMasks(sd.dofsPerNode);
    for (int n : in.boundaryNodes) {
      in.boundaryGlobal.push_back(sd.mesh.globalNode[n]);
      in.boundaryDirichlet.push_back(dir[n]);
    }
    input.push_back(std::move(in));
  }
  return input;
}

// Subdomain sd as the set-up builds it, with its kernel and fixing dofs, not factorized: from K
// and f moved in (the set-up) or copied (the forecast, which needs the fixing dofs).
std::shared_ptr<Subdomain> unfactorizedSubdomain(const SubdomainData& sd,
                                                 const std::vector<double>& coords, CsrMatrix K,
                                                 std::vector<double> f,
                                                 const Teuchos::ParameterList& params) {
  KernelOptions kernel;
  kernel.dim = sd.mesh.dim;
  kernel.elements = sd.mesh.connectivity();
  kernel.kernel = sd.kernel;
  kernel.residualTolerance = params.get<double>("Kernel tolerance");
  return std::make_shared<Subdomain>(sd.mesh.id, sd.dofsPerNode, coords, kernel, std::move(K),
                                     std::move(f), sd.mesh.dirichletDofs(sd.dofsPerNode),
                                     parseFormulation(params.get<std::string>("Formulation")),
                                     params.get<std::string>("Local solver"),
                                     Factorization::Deferred);
}
}  // namespace

namespace {
// The forecast as it adds up subdomain by subdomain, in the order of the run's set-up.
class SetupTally {
 public:
  explicit SetupTally(const Teuchos::ParameterList& valid)
      : solver_(valid.get<std::string>("Local solver")),
        dirichlet_(parsePreconditioner(valid.get<std::string>("Preconditioner")) ==
                   PreconditionerType::Dirichlet),
        storage_(parseDenseStorage(valid.get<std::string>("Explicit storage"))),
        release_(!valid.get<bool>("Keep subdomain matrices")),
        // As buildConstraints frees K: after each preconditioner, unless the Schur assembly of
        // an explicit operator needs it (auto counted as explicit: K kept longer, an upper bound).
        schur_(parseBlockAssembly(valid.get<std::string>("Explicit assembly")) ==
               BlockAssembly::Schur),
        schurNeedsK_(valid.get<std::string>("Dual operator") != "implicit" && schur_) {}

  // Subdomain K, touched by `rows` rows of B on the dofs `dofs`, with the fixing dofs the
  // run will choose (none for a FETI subdomain held by its Dirichlet conditions).
  void add(const CsrMatrix& K, const std::vector<int>& dofs, long long rows,
           const std::vector<int>& fixing) {
    LocalSolver& solver = solverFor();
    const MemoryPrediction factor = predictPseudoInverseMemory(K, !fixing.empty(), solver);
    f_.factorsKnown = f_.factorsKnown && factor.known();
    if (factor.known())
      factors_.make(static_cast<double>(factor.held), static_cast<double>(factor.transient));
    f_.dualRows.push_back(rows);
    f_.explicitBlocks += static_cast<double>(explicitBlockBytes(storage_, rows));
    // The block assembled anew: from the Schur complement (the run leaves the fixing dofs out
    // of the dofs B_s touches), else by solves.
    const std::size_t m = static_cast<std::size_t>(rows);
    const std::ptrdiff_t schurPeak =
        schur_ && m > 0 ? predictPseudoInverseBlockMemory(K, dofs, fixing, solver) : -1;
    f_.explicitTransient = std::max(
        f_.explicitTransient,
        schurPeak >= 0 ? explicitSchurTransient(static_cast<double>(schurPeak), dofs.size(), m, 0)
                       : explicitSolvesTransient(K.rows, m, m, 0));
    if (schurPeak < 0 && m > 0)
      f_.explicitSolverKeeps += static_cast<double>(
          solver.solveKeeps(static_cast<std::size_t>(K.rows), explicitSolveWidth(m)));
    if (dirichlet_) {
      const MemoryPrediction p = predictDirichletMemory(K, dofs, solverFor());
      f_.interiorKnown = f_.interiorKnown && p.known();
      if (p.known())
        preconditioner_.make(static_cast<double>(p.held), static_cast<double>(p.transient));
    }
    const double kBytes = static_cast<double>(K.bytes());
    if (release_ && !schurNeedsK_) preconditioner_.release(kBytes);
    if (release_ && schurNeedsK_) f_.stiffnessFreedByAssembly += kBytes;
  }

  SetupMemoryForecast result() const {
    SetupMemoryForecast f = f_;
    if (f.factorsKnown) {
      f.factors = factors_.running;
      f.factorPeak = factors_.peak;
    }
    f.interiorPeak = preconditioner_.peak;
    f.preconditionerLeaves = preconditioner_.running;
    return f;
  }

 private:
  // Every solver is kept to the end, as the run keeps its factors: equal patterns then share
  // one analysis, and the analyses made here are those the run would make.
  LocalSolver& solverFor() {
    solvers_.push_back(createLocalSolver(solver_));
    return *solvers_.back();
  }
  const std::string solver_;
  const bool dirichlet_;
  const DenseStorage storage_;
  const bool release_, schur_, schurNeedsK_;
  std::vector<std::unique_ptr<LocalSolver>> solvers_;
  SetupMemoryForecast f_;
  RunningPeak factors_, preconditioner_;
};
}  // namespace

Teuchos::ParameterList FetiSolver::validatedParameters(const Teuchos::ParameterList& feti) {
  Teuchos::ParameterList valid = feti;
  rejectMisplacedParameters(valid);
  applySolverAliases(valid);
  valid.validateParametersAndSetDefaults(*validParameters());
  // A device that the run cannot use is an input error: said before anything is factorized.
  checkExplicitDevice(valid.get<std::string>("Dual operator"),
                      parseExplicitDevice(valid.get<std::string>("Explicit device")));
  return valid;
}

SetupMemoryForecast FetiSolver::forecastSetupMemory(const Teuchos::RCP<const Comm>& comm,
                                                    int numSubdomains,
                                                    const std::vector<SubdomainData>& local,
                                                    const Teuchos::ParameterList& feti,
                                                    const std::vector<InequalityRow>& inequalities,
                                                    const std::vector<EqualityRow>& equalities) {
  const Teuchos::ParameterList valid = validatedParameters(feti);
  // The constructor's checks of the subdomains first: the forecast builds them as it does.
  checkSubdomainInput(*comm, numSubdomains, local);
  int localDpn = local.empty() ? 0 : local.front().dofsPerNode, dpn = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &localDpn, &dpn);
  const Tearing t = buildTearing(comm, numSubdomains, tearingInput(local), dpn,
                                 tearingOptions(valid), inequalities, equalities);
  const std::vector<long long> rows = subdomainRowCounts(t);
  SetupTally tally(valid);
  // An analysis that fails on one rank is reported on every rank (none left in a collective).
  collectively(*comm, [&] {
    for (std::size_t i = 0; i < local.size(); ++i) {
      // A K given as a Tpetra::CrsMatrix becomes CSR arrays, as the constructor makes it.
      const bool tpetra = !local[i].tpetraK.is_null();
      const CsrMatrix converted =
          tpetra ? csrFromTpetra(*local[i].tpetraK,
                                 "subdomain " + std::to_string(local[i].mesh.id) + ": tpetraK")
                 : CsrMatrix{};
      const CsrMatrix& K = tpetra ? converted : local[i].K;
      // The kernel and the fixing dofs as the run will find them (a copy of K and f while they
      // are found): whether the factor takes a decoupled copy of K, and which dofs the Schur
      // assembly leaves out.
      const std::vector<int> fixing =
          unfactorizedSubdomain(local[i], local[i].mesh.coords, K, local[i].f, valid)->fixingDofs();
      tally.add(K, subdomainDualDofs(t, i), rows[i], fixing);
    }
  });
  return tally.result();
}

FetiSolver::FetiSolver(const Teuchos::RCP<const Comm>& comm, int numSubdomains,
                       std::vector<SubdomainData> local, const Teuchos::ParameterList& params,
                       const std::vector<InequalityRow>& inequalities,
                       const std::vector<EqualityRow>& equalities)
    : comm_(comm),
      params_(validatedParameters(params)),
      numSubdomains_(numSubdomains),
      data_(std::move(local)),
      equalities_(equalities) {
  // Subdomain matrices given as Tpetra::CrsMatrix become CSR arrays (checked with the rest; one
  // given as both is left as it is, for checkSubdomainInput to say so).
  collectively(*comm_, [&] {
    for (auto& sd : data_) {
      if (sd.tpetraK.is_null() || sd.K.rows != 0 || !sd.K.rowPtr.empty()) continue;
      sd.K = csrFromTpetra(*sd.tpetraK, "subdomain " + std::to_string(sd.mesh.id) + ": tpetraK");
      sd.tpetraK = Teuchos::null;
    }
  });
  // Every size the solver indexes by, on every rank, before anything is built from it.
  checkSubdomainInput(*comm_, numSubdomains_, data_);
  // A rank may hold no subdomain; every rank must still agree on the dofs per node.
  int localDpn = data_.empty() ? 0 : data_.front().dofsPerNode;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 1, &localDpn, &dofsPerNode_);
  std::vector<std::vector<double>> coords;
  for (const auto& sd : data_) coords.push_back(sd.mesh.coords);
  buildSubdomains(coords);
  buildConstraints(inequalities, false);
  buildDualRhs();
}

void FetiSolver::buildSubdomains(const std::vector<std::vector<double>>& coords) {
  PhaseTimer t(*comm_, timings_.factorization, &memory_, "factorization");
  subdomains_.clear();
  kernelCoords_ = coords;
  // An error in one subdomain is reported on every rank (no rank left waiting in a collective).
  // The kernels first, then what the factors will take against the nodes' memory, then the
  // factorizations: a problem too large for its nodes stops before any factor is allocated.
  collectively(*comm_, [&] {
    for (std::size_t i = 0; i < data_.size(); ++i) {
      auto& sd = data_[i];
      // K and f move into the subdomain (data_ keeps the mesh, the kernel and the sizes).
      subdomains_.push_back(
          unfactorizedSubdomain(sd, coords[i], std::move(sd.K), std::move(sd.f), params_));
    }
  });
  checkFactorMemory();
  collectively(*comm_, [&] {
    for (auto& s : subdomains_) s->factorize();
  });
  stiffnessChanged_.assign(subdomains_.size(), 1);
  countFactorizations();
}

void FetiSolver::countFactorizations() {
  long long local[2] = {0, 0}, global[2] = {0, 0};
  for (char changed : stiffnessChanged_) ++local[changed ? 0 : 1];
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 2, local, global);
  timings_.factorizations += global[0];
  timings_.factorizationsReused += global[1];
}

void FetiSolver::countAnalyses() {
  const LocalAnalysisCounts now = localAnalysisCounts();
  long long local[2] = {now.made - analysesCounted_.made, now.shared - analysesCounted_.shared};
  long long global[2] = {0, 0};
  analysesCounted_ = now;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 2, local, global);
  timings_.symbolicAnalyses += global[0];
  timings_.symbolicAnalysesShared += global[1];
}

void FetiSolver::refactorizeSubdomains() {
  PhaseTimer t(*comm_, timings_.factorization, &memory_, "factorization");
  stiffnessChanged_.assign(subdomains_.size(), 0);
  collectively(*comm_, [&] {
    for (std::size_t i = 0; i < data_.size(); ++i) {
      if (!keepsStiffness(data_[i].K))
        stiffnessChanged_[i] = subdomains_[i]->refactorize(std::move(data_[i].K),
                                                           params_.get<double>("Kernel tolerance"));
      subdomains_[i]->setLoad(std::move(data_[i].f));
      data_[i].K = CsrMatrix();
      data_[i].f.clear();
    }
  });
  countFactorizations();
}

bool FetiSolver::keepOrBuildTearing(const std::vector<InequalityRow>& inequalities,
                                    bool subdomainsKept) {
  PhaseTimer t(*comm_, timings_.tearing, &memory_, "tearing");
  // Rows with their entries unchanged (a Newton iteration against a height-function obstacle in
  // small strain moves only the gaps) over the same subdomains, hence the same kernels: B, the
  // maps, the scaling and G = R^T B^T are those already built, and only c changes.
  const bool kept =
      subdomainsKept && coarse_ && updateTearingValues(comm_, tearing_, inequalities, equalities_);
  if (!kept) {
    tearing_ = buildTearing(comm_, numSubdomains_, tearingInput(data_), dofsPerNode_,
                            tearingOptions(params_), inequalities, equalities_);
    if (parseFormulation(params_.get<std::string>("Formulation")) == Formulation::FETI)
      requireNoRowOnEliminatedDofs();
  }
  ++(kept ? timings_.tearingsReused : timings_.tearings);
  return kept;
}

void FetiSolver::buildConstraints(const std::vector<InequalityRow>& inequalities,
                                  bool subdomainsKept) {
  const PreconditionerType precType =
      parsePreconditioner(params_.get<std::string>("Preconditioner"));
  const bool kept = keepOrBuildTearing(inequalities, subdomainsKept);
  chooseDualOperator();
  // K is freed after the preconditioner's set-up, unless the explicit operator's Schur assembly
  // still needs it (it factorizes K_reg again with the dual rows' dofs last): then the operator
  // frees each subdomain's K once its F_s is assembled.
  const bool release = !params_.get<bool>("Keep subdomain matrices");
  const bool schurNeedsK =
      dualChoice_.chosen == "explicit" &&
      parseBlockAssembly(params_.get<std::string>("Explicit assembly")) == BlockAssembly::Schur;
  const bool releaseNow = release && !schurNeedsK;
  if (!kept) {
    PhaseTimer t(*comm_, timings_.coarse, &memory_, "coarse");
    coarse_ = std::make_unique<CoarseSpace>(tearing_, subdomains_,
                                            params_.get<std::string>("Coarse solver"));
  }
  {
    PhaseTimer t(*comm_, timings_.preconditioner, &memory_, "preconditioner");
    setupPreconditioners(precType, releaseNow);
  }
  Kplus_ = Teuchos::rcp(new PseudoInverseOperator(tearing_.primalMap, subdomains_));
  buildDualOperator(release && schurNeedsK);
  countAnalyses();
}

void FetiSolver::setupPreconditioners(PreconditionerType type, bool releaseStiffness) {
  // Contact rows that move between iterations of a nonlinear solve mostly keep the same dofs,
  // and most subdomains of a plastic body keep their K: the interior factorization is redone
  // only when either changes.
  std::vector<std::vector<int>> dofs(subdomains_.size());
  std::vector<char> rebuild(subdomains_.size(), 0);
  for (std::size_t i = 0; i < subdomains_.size(); ++i) {
    dofs[i] = subdomainDualDofs(tearing_, i);
    rebuild[i] = stiffnessChanged_[i] || dofs[i] != subdomains_[i]->interfaceDofs();
  }
  checkPreconditionerMemory(dofs, rebuild, type, releaseStiffness);
  const std::string solver = params_.get<std::string>("Local solver");
  collectively(*comm_, [&] {
    for (std::size_t i = 0; i < subdomains_.size(); ++i) {
      if (rebuild[i]) subdomains_[i]->setupPreconditioner(dofs[i], type, solver);
      // Freed one by one, so that K and the preconditioner's factors never coexist in full.
      if (releaseStiffness) subdomains_[i]->releaseStiffness();
    }
  });
  stiffnessChanged_.assign(subdomains_.size(), 0);
  if (type != PreconditionerType::None)
    M_ = Teuchos::rcp(new DualPreconditioner(tearing_, subdomains_));
}

void FetiSolver::chooseDualOperator() {
  DualOperatorChoice c;
  // The last memory check stands until the next assembly of new blocks checks again.
  c.fitsMemory = dualChoice_.fitsMemory;
  c.nodeNeedBytes = dualChoice_.nodeNeedBytes;
  c.nodeAvailableBytes = dualChoice_.nodeAvailableBytes;
  c.chosen = params_.get<std::string>("Dual operator");
  c.automatic = c.chosen == "auto";
  if (c.automatic) {
    c.qp = dualSolverFor(params_, tearing_.numInequalityRows) != "PCPG";
    const DenseStorage storage = parseDenseStorage(params_.get<std::string>("Explicit storage"));
    const std::vector<long long> rows = subdomainRowCounts(tearing_);
    double mine[2] = {0.0, 0.0}, all[2] = {0.0, 0.0};
    for (std::size_t i = 0; i < subdomains_.size(); ++i) {
      mine[0] += static_cast<double>(explicitBlockBytes(storage, rows[i]));
      mine[1] += static_cast<double>(subdomains_[i]->factorBytes());
    }
    Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 2, mine, all);
    c.explicitBytes = all[0];
    c.factorBytes = all[1];
    const bool device =
        parseExplicitDevice(params_.get<std::string>("Explicit device")) == ExplicitDevice::Gpu;
    c.chosen = device || (c.qp && c.explicitBytes < c.factorBytes) ? "explicit" : "implicit";
  }
  dualChoice_ = c;
}

void FetiSolver::buildDualOperator(bool releaseStiffness) {
  const ExplicitDevice device = parseExplicitDevice(params_.get<std::string>("Explicit device"));
  if (!F_.is_null() && F_->explicitPart()) {
    const auto& ex = F_->explicitPart();
    deviceWorkDone_.add(ex->deviceWork());
    explicitAssemblyDone_.blocks += ex->assemblies();
    explicitAssemblyDone_.columnsSolved += ex->assembledColumns();
    explicitAssemblyDone_.columnsFull += ex->assembledRows();
    explicitAssemblyDone_.schurBlocks += ex->schurAssemblies();
  }
  if (dualChoice_.chosen != "explicit") {
    F_ = Teuchos::rcp(new DualOperator(tearing_.B, Kplus_));
    return;
  }
  // The blocks of the operator being replaced whose factor and rows are unchanged are taken
  // over (update() with new contact rows); a refactorized subdomain's block is assembled anew.
  std::shared_ptr<const ExplicitDualOperator> previous;
  if (!F_.is_null()) previous = F_->explicitPart();
  // After updateStiffness() no block can be taken over: free the old ones (and the old F) before
  // the new ones are assembled, so that both never take memory at once.
  const auto reusable = [&] {
    for (const auto& b : previous->blocks())
      for (const auto& sub : subdomains_)
        if (sub->id() == b.subdomainId && sub->factorVersion() == b.version) return true;
    return false;
  };
  if (previous && !reusable()) {
    previous.reset();
    F_ = Teuchos::null;
  }
  const DenseStorage storage = parseDenseStorage(params_.get<std::string>("Explicit storage"));
  bool doesNotFit = false;
  {
    PhaseTimer t(*comm_, timings_.explicitMemoryCheck);
    doesNotFit = explicitDoesNotFit(storage, previous.get(), releaseStiffness);
  }
  if (doesNotFit) {
    F_ = Teuchos::rcp(new DualOperator(tearing_.B, Kplus_));
    return;
  }
  std::shared_ptr<const ExplicitDualOperator> ex;
  {
    PhaseTimer t(*comm_, timings_.dualOperator, &memory_, "dual_operator");
    collectively(*comm_, [&] {
      ex = std::make_shared<const ExplicitDualOperator>(
          tearing_, subdomains_, storage, previous.get(), device,
          parseBlockAssembly(params_.get<std::string>("Explicit assembly")), releaseStiffness);
    });
  }
  previous.reset();
  F_ = Teuchos::null;
  F_ = Teuchos::rcp(new DualOperator(tearing_.B, Kplus_, ex));
  const std::string file = params_.get<std::string>("Explicit export file");
  if (!file.empty())
    collectively(*comm_, [&] {
      ex->exportBlocks(file + ".rank" + std::to_string(comm_->getRank()) + ".bin");
    });
}

void FetiSolver::buildDualRhs() {
  PhaseTimer t(*comm_, timings_.dualRhs, &memory_, "dual_rhs");
  f_ = Teuchos::rcp(new MultiVector(tearing_.primalMap, 1));
  {
    auto f = f_->getDataNonConst(0);
    std::size_t offset = 0;
    for (const auto& s : subdomains_) {
      for (int i = 0; i < s->numDofs(); ++i) f[offset + i] = s->load()[i];
      offset += s->numDofs();
    }
  }
  MultiVector Kf(tearing_.primalMap, 1);
  Kplus_->apply(*f_, Kf);
  shiftOwnRowsByOrigin();
  d_ = Teuchos::rcp(new Vector(tearing_.multiplierMap));
  tearing_.B->apply(Kf, *d_);
  d_->update(-1.0, *tearing_.rhs, 1.0);  // d = B K+ f - c
  lambda0_ = Teuchos::rcp(new Vector(tearing_.multiplierMap));
  if (coarse_->dimension() > 0) {
    Vector e(coarse_->coarseMap());
    coarse_->applyKernelTranspose(*f_, e);
    coarse_->particularSolution(e, *lambda0_);
  }
}

void FetiSolver::setToleranceFactor(double factor) {
  if (!(factor > 0.0) || !std::isfinite(factor))
    throw std::invalid_argument(
        "FetiSolver::setToleranceFactor: the factor must be positive and finite, got " +
        std::to_string(factor));
  toleranceFactor_ = factor;
}

void FetiSolver::setIncrementOrigin(std::vector<std::vector<double>> u) {
  collectively(*comm_, [&] {
    if (u.empty()) return;
    if (u.size() != data_.size())
      throw std::invalid_argument("FetiSolver::setIncrementOrigin: " + std::to_string(u.size()) +
                                  " displacement vectors for " + std::to_string(data_.size()) +
                                  " local subdomains");
    for (std::size_t i = 0; i < u.size(); ++i) {
      const int n = subdomains_[i]->numDofs();
      if (static_cast<int>(u[i].size()) != n)
        throw std::invalid_argument("FetiSolver::setIncrementOrigin: subdomain " +
                                    std::to_string(data_[i].mesh.id) + " has " + std::to_string(n) +
                                    " dofs, the displacement " + std::to_string(u[i].size()));
    }
  });
  incrementOrigin_ = std::move(u);
}

void FetiSolver::shiftOwnRowsByOrigin() {
  int any = 0, local = incrementOrigin_.empty() ? 0 : 1;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 1, &local, &any);
  if (any == 0) return;
  MultiVector u(tearing_.primalMap, 1);
  {
    auto v = u.getDataNonConst(0);
    std::size_t offset = 0;
    for (std::size_t s = 0; s < subdomains_.size(); ++s) {
      const int n = subdomains_[s]->numDofs();
      for (int i = 0; i < n && !incrementOrigin_.empty(); ++i)
        v[offset + i] = incrementOrigin_[s][i];
      offset += n;
    }
  }
  Vector Bu(tearing_.multiplierMap);
  tearing_.B->apply(u, Bu);
  auto c = tearing_.rhs->getDataNonConst();
  auto bu = Bu.getData();
  const auto map = tearing_.multiplierMap;
  for (std::size_t i = 0; i < map->getNodeNumElements(); ++i)
    if (map->getGlobalElement(static_cast<LO>(i)) < tearing_.firstUserEqualityRow) c[i] -= bu[i];
}

void FetiSolver::update(const std::vector<std::vector<double>>& loads,
                        const std::vector<InequalityRow>& inequalities,
                        const std::vector<EqualityRow>& equalities) {
  equalities_ = equalities;
  update(loads, inequalities);
}

void FetiSolver::updateStiffness(std::vector<CsrMatrix> K,
                                 const std::vector<std::vector<double>>& coords,
                                 const std::vector<std::vector<double>>& loads,
                                 const std::vector<InequalityRow>& inequalities,
                                 const std::vector<EqualityRow>& equalities) {
  equalities_ = equalities;
  updateStiffness(std::move(K), coords, loads, inequalities);
}

void FetiSolver::update(const std::vector<std::vector<double>>& loads,
                        const std::vector<InequalityRow>& inequalities) {
  collectively(*comm_, [&] {
    if (loads.size() != subdomains_.size())
      throw std::invalid_argument("FetiSolver::update: " + std::to_string(loads.size()) +
                                  " load vectors for " + std::to_string(subdomains_.size()) +
                                  " local subdomains");
    for (std::size_t i = 0; i < subdomains_.size(); ++i) subdomains_[i]->setLoad(loads[i]);
  });
  previousLambda_ = lambda_;
  previousEqualityMultiplier_ = equalityMultiplier_;
  previousPenaltyOffset_ = penaltyOffset_;
  previousNorm_ = normEstimate_;
  const RowIdentities before = rowIdentities(tearing_);
  const auto radii = discRadii();
  buildConstraints(inequalities, true);
  carryWarmStartOver(before, radii);
  buildDualRhs();
  u_vec_ = Teuchos::null;
  lambda_ = Teuchos::null;
  u_.clear();
}

bool FetiSolver::sameKernelPositions(const std::vector<std::vector<double>>& coords) const {
  // The same kernel positions (a small-strain tangent: the reference ones): the subdomains keep
  // their rigid modes and fixing dofs and refactorize in place, the symbolic analysis reused.
  int sameLocal = coords == kernelCoords_ && subdomains_.size() == data_.size() ? 1 : 0;
  for (const auto& sd : data_) sameLocal = sd.kernel.empty() ? sameLocal : 0;
  int same = 0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MIN, 1, &sameLocal, &same);
  return same == 1;
}

void FetiSolver::checkStiffnessUpdate(const std::vector<CsrMatrix>& K,
                                      const std::vector<std::vector<double>>& coords,
                                      const std::vector<std::vector<double>>& loads,
                                      bool inPlace) const {
  collectively(*comm_, [&] {
    for (std::size_t i = 0; i < data_.size(); ++i) {
      // An empty K keeps the subdomain's own, which must still be there (the preconditioner is
      // set up from it when the rows move) and stay valid (the same kernel positions).
      const bool keep = keepsStiffness(K[i]);
      const std::string name =
          "FetiSolver::updateStiffness: subdomain " + std::to_string(data_[i].mesh.id);
      if (keep && !inPlace)
        throw std::invalid_argument(name +
                                    ": an empty K keeps the current one, but new kernel positions "
                                    "(or a supplied kernel) rebuild every subdomain; pass K");
      if (keep && !subdomains_[i]->hasStiffness())
        throw std::invalid_argument(name +
                                    ": an empty K keeps the current one, which \"Keep subdomain "
                                    "matrices\" = false has freed; pass K");
      const std::string error = subdomainDataError(data_[i].mesh, coords[i], data_[i].dofsPerNode,
                                                   keep ? subdomains_[i]->stiffness() : K[i],
                                                   loads[i], {}, numSubdomains_);
      if (!error.empty()) throw std::invalid_argument("FetiSolver::updateStiffness: " + error);
    }
  });
}

void FetiSolver::updateStiffness(std::vector<CsrMatrix> K,
                                 const std::vector<std::vector<double>>& coords,
                                 const std::vector<std::vector<double>>& loads,
                                 const std::vector<InequalityRow>& inequalities) {
  collectively(*comm_, [&] {
    if (K.size() != data_.size() || coords.size() != data_.size() || loads.size() != data_.size())
      throw std::invalid_argument("FetiSolver::updateStiffness: expected " +
                                  std::to_string(data_.size()) +
                                  " matrices, coordinate sets and loads");
  });
  const bool inPlace = sameKernelPositions(coords);
  checkStiffnessUpdate(K, coords, loads, inPlace);
  for (std::size_t i = 0; i < data_.size(); ++i) {
    data_[i].K = std::move(K[i]);
    data_[i].f = loads[i];
  }
  previousLambda_ = lambda_;
  previousEqualityMultiplier_ = equalityMultiplier_;
  previousPenaltyOffset_ = penaltyOffset_;
  previousNorm_ = 0.0;  // a new K: estimate ||P F P|| again
  if (inPlace)
    refactorizeSubdomains();
  else
    buildSubdomains(coords);
  const RowIdentities before = rowIdentities(tearing_);
  const auto radii = discRadii();
  buildConstraints(inequalities, inPlace);
  carryWarmStartOver(before, radii);
  buildDualRhs();
  u_vec_ = Teuchos::null;
  lambda_ = Teuchos::null;
  u_.clear();
}

Teuchos::RCP<Vector> FetiSolver::discRadii() const {
  const auto map = tearing_.multiplierMap;
  auto radii = Teuchos::rcp(new Vector(map));
  auto r = radii->getDataNonConst();
  for (std::size_t i = 0; i < map->getNodeNumElements(); ++i) {
    const GO row = map->getGlobalElement(static_cast<LO>(i));
    r[i] = -1.0;
    if (!tearing_.isInequality(row)) continue;
    const InequalityRow& q = tearing_.inequalityRows[row - tearing_.firstInequalityRow];
    if (q.disc == 1 || frictionBox(q)) r[i] = q.upperBound;
    if (q.disc == 2) r[i] = r[i - 1];  // the first component, just before it on this rank
  }
  return radii;
}

void FetiSolver::carryWarmStartOver(const RowIdentities& before,
                                    const Teuchos::RCP<const Vector>& radiiBefore) {
  const RowCarryOver carryOver(before, rowIdentities(tearing_));
  const auto carry = [&](const Teuchos::RCP<const Vector>& v) -> Teuchos::RCP<Vector> {
    return v.is_null() ? Teuchos::null : carryOver.carry(*v);
  };
  previousLambda_ = carry(previousLambda_);
  previousEqualityMultiplier_ = carry(previousEqualityMultiplier_);
  previousPenaltyOffset_ = carry(previousPenaltyOffset_);
  normVector_ = carry(normVector_);
  previousDiscRadii_ = carry(radiiBefore);
}

void FetiSolver::requireNoRowOnEliminatedDofs() const {
  std::string error;
  for (std::size_t i = 0; i < data_.size() && error.empty(); ++i) {
    const std::vector<int> eliminated = data_[i].mesh.dirichletDofs(data_[i].dofsPerNode);
    for (const auto& e : tearing_.subdomainRows[i])
      if (tearing_.isUserEquality(e.row) &&
          std::binary_search(eliminated.begin(), eliminated.end(), e.dof)) {
        error = "FetiSolver: an equality row of the caller touches dof " + std::to_string(e.dof) +
                " of subdomain " + std::to_string(data_[i].mesh.id) +
                ", a Dirichlet dof that the FETI formulation eliminates (held at zero); use "
                "Formulation = TFETI or leave the node out of the mesh's Dirichlet nodes";
        break;
      }
  }
  throwIfAnyRankFailed(*comm_, error);
}
}  // namespace tfeti
