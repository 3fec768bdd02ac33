#include "tfeti_FetiSolver.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <chrono>

namespace tfeti {

namespace {
// Wall time of a phase, measured between barriers so that it is the slowest rank's time.
class PhaseTimer {
 public:
  PhaseTimer(const Comm& comm, double& into) : comm_(comm), into_(into) {
    comm_.barrier();
    start_ = std::chrono::steady_clock::now();
  }
  ~PhaseTimer() {
    comm_.barrier();
    into_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  const Comm& comm_;
  double& into_;
  std::chrono::steady_clock::time_point start_;
};

Teuchos::RCP<Teuchos::StringToIntegralParameterEntryValidator<int>> choice(
    const std::vector<std::string>& names) {
  return Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
      Teuchos::Array<std::string>(names.begin(), names.end()), names.front()));
}
}  // namespace

Formulation parseFormulation(const std::string& name) {
  return name == "FETI" ? Formulation::FETI : Formulation::TFETI;
}

PreconditionerType parsePreconditioner(const std::string& name) {
  if (name == "lumped") return PreconditionerType::Lumped;
  if (name == "dirichlet") return PreconditionerType::Dirichlet;
  return PreconditionerType::None;
}

Teuchos::RCP<const Teuchos::ParameterList> FetiSolver::validParameters() {
  static Teuchos::RCP<Teuchos::ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::rcp(new Teuchos::ParameterList("FETI"));
    pl->set("Formulation", "TFETI",
            "TFETI: Dirichlet conditions as multipliers, every subdomain floats; FETI: Dirichlet "
            "dofs eliminated in K",
            choice({"TFETI", "FETI"}));
    pl->set("Gluing", "nonredundant",
            "nonredundant: m-1 rows at a node shared by m subdomains; redundant: m(m-1)/2",
            choice({"nonredundant", "redundant"}));
    pl->set("Gluing at Dirichlet nodes", true,
            "keep gluing rows at interface nodes on the Dirichlet boundary (the paper's count; "
            "in TFETI they duplicate the Dirichlet rows)");
    pl->set("Preconditioner", "dirichlet", "dual preconditioner",
            choice({"dirichlet", "lumped", "none"}));
    std::vector<std::string> solvers = localSolverTypes();
    pl->set("Local solver", "cholmod", "sparse direct solver of the subdomain problems",
            choice(solvers));
    pl->sublist("PCPG").setParameters(*Pcpg::validParameters());
  }
  return pl;
}

FetiSolver::FetiSolver(const Teuchos::RCP<const Comm>& comm, int numSubdomains,
                       std::vector<SubdomainData> local, const Teuchos::ParameterList& params)
    : comm_(comm), params_(params), data_(std::move(local)) {
  params_.validateParametersAndSetDefaults(*validParameters());
  const Formulation formulation = parseFormulation(params_.get<std::string>("Formulation"));
  const PreconditionerType precType =
      parsePreconditioner(params_.get<std::string>("Preconditioner"));
  const std::string solver = params_.get<std::string>("Local solver");
  // A rank may hold no subdomain; every rank must still agree on the dofs per node.
  int localDpn = data_.empty() ? 0 : data_.front().dofsPerNode, dpn = 0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 1, &localDpn, &dpn);

  {
    PhaseTimer t(*comm_, timings_.factorization);
    for (auto& sd : data_) {
      std::vector<int> dirichletDofs;
      for (int n : sd.mesh.dirichletNodes)
        for (int c = 0; c < sd.dofsPerNode; ++c) dirichletDofs.push_back(n * sd.dofsPerNode + c);
      subdomains_.push_back(std::make_shared<Subdomain>(sd.mesh.id, sd.dofsPerNode, sd.mesh.coords,
                                                        sd.K, sd.f, dirichletDofs, formulation,
                                                        solver));
      // The subdomain keeps its own (possibly modified) copy of K.
      sd.K = CsrMatrix();
    }
  }
  {
    PhaseTimer t(*comm_, timings_.tearing);
    TearingOptions opts;
    opts.formulation = formulation;
    opts.gluing = params_.get<std::string>("Gluing") == "redundant" ? Gluing::Redundant
                                                                    : Gluing::NonRedundant;
    opts.gluingAtDirichletNodes = params_.get<bool>("Gluing at Dirichlet nodes");
    std::vector<TearingInput> input;
    for (const auto& sd : data_) {
      TearingInput in;
      in.id = sd.mesh.id;
      in.numDofs = sd.mesh.numNodes() * sd.dofsPerNode;
      in.boundaryNodes = sd.mesh.boundaryNodes();
      std::vector<char> dir(sd.mesh.numNodes(), 0);
      for (int n : sd.mesh.dirichletNodes) dir[n] = 1;
      for (int n : in.boundaryNodes) {
        in.boundaryGlobal.push_back(sd.mesh.globalNode[n]);
        in.boundaryDirichlet.push_back(dir[n]);
      }
      input.push_back(std::move(in));
    }
    tearing_ = buildTearing(comm_, numSubdomains, input, dpn, opts);
  }
  {
    PhaseTimer t(*comm_, timings_.coarse);
    coarse_ = std::make_unique<CoarseSpace>(tearing_, subdomains_, solver);
  }
  {
    PhaseTimer t(*comm_, timings_.preconditioner);
    for (std::size_t i = 0; i < subdomains_.size(); ++i) {
      std::vector<int> dofs;
      for (const auto& e : tearing_.subdomainRows[i]) dofs.push_back(e.dof);
      std::sort(dofs.begin(), dofs.end());
      dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
      subdomains_[i]->setupPreconditioner(dofs, precType, solver);
    }
    if (precType != PreconditionerType::None)
      M_ = Teuchos::rcp(new DualPreconditioner(tearing_, subdomains_));
  }
  {
    PhaseTimer t(*comm_, timings_.dualRhs);
    Kplus_ = Teuchos::rcp(new PseudoInverseOperator(tearing_.primalMap, subdomains_));
    F_ = Teuchos::rcp(new DualOperator(tearing_.B, Kplus_));
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
    d_ = Teuchos::rcp(new Vector(tearing_.multiplierMap));
    tearing_.B->apply(Kf, *d_);
    lambda0_ = Teuchos::rcp(new Vector(tearing_.multiplierMap));
    if (coarse_->dimension() > 0) {
      Vector e(coarse_->coarseMap());
      coarse_->applyKernelTranspose(*f_, e);
      coarse_->particularSolution(e, *lambda0_);
    }
  }
}

PcpgResult FetiSolver::solve() {
  Vector lambda(tearing_.multiplierMap), g(tearing_.multiplierMap);
  PcpgResult result;
  {
    PhaseTimer t(*comm_, timings_.solve);
    Tpetra::deep_copy(lambda, *lambda0_);
    Pcpg pcpg(F_, *coarse_, M_, params_.sublist("PCPG"));
    result = pcpg.solve(*d_, lambda, g);
  }
  {
    PhaseTimer t(*comm_, timings_.recovery);
    // u = K+ (f - B^T lambda) + R alpha, alpha = (G G^T)^{-1} G (F lambda - d)
    MultiVector rhs(tearing_.primalMap, 1), u(tearing_.primalMap, 1);
    Tpetra::deep_copy(rhs, *f_);
    tearing_.B->apply(lambda, rhs, Teuchos::TRANS, -1.0, 1.0);
    Kplus_->apply(rhs, u);
    if (coarse_->dimension() > 0) {
      F_->apply(lambda, g);
      g.update(-1.0, *d_, 1.0);
      Vector alpha(coarse_->coarseMap());
      coarse_->leastSquaresCoefficients(g, alpha);
      coarse_->addKernelCombination(alpha, u);
    }
    auto uv = u.getData(0);
    u_.assign(subdomains_.size(), {});
    std::size_t offset = 0;
    for (std::size_t i = 0; i < subdomains_.size(); ++i) {
      const int n = subdomains_[i]->numDofs();
      u_[i].assign(uv.getRawPtr() + offset, uv.getRawPtr() + offset + n);
      offset += n;
    }
  }
  return result;
}

double FetiSolver::timeDualApply(int repeats) const {
  Vector x(tearing_.multiplierMap), y(tearing_.multiplierMap);
  x.randomize();
  double seconds = 0.0;
  {
    PhaseTimer t(*comm_, seconds);
    for (int r = 0; r < repeats; ++r) F_->apply(x, y);
  }
  return seconds / repeats;
}

std::size_t FetiSolver::globalFactorBytes() const {
  unsigned long long mine = 0, all = 0;
  for (const auto& s : subdomains_) mine += s->factorBytes();
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 1, &mine, &all);
  return all;
}

std::size_t FetiSolver::globalPreconditionerFactorBytes() const {
  unsigned long long mine = 0, all = 0;
  for (const auto& s : subdomains_) mine += s->preconditionerFactorBytes();
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 1, &mine, &all);
  return all;
}

}  // namespace tfeti
