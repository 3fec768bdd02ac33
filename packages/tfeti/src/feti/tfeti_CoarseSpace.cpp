#include "tfeti_CoarseSpace.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_RowMatrixTransposer.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "tfeti_CoarseGramian.hpp"
#include "tfeti_ComplementFactors.hpp"
#include "tfeti_Gather.hpp"

namespace tfeti {

std::unique_ptr<LocalSolver> CoarseSpace::factorizeGramian(const Vector* rowMask,
                                                           const std::string& localSolver,
                                                           CsrMatrix* keep) const {
  // G G^T assembled from its subdomain-pair blocks and replicated on every rank, which factorizes
  // it there: the coarse problem is small, and a replicated factor makes every coarse solve
  // communication-free after one Import.
  const std::vector<GO> offset =
      coarseBlockOffsets(*G_->getRowMap()->getComm(), coarseOffset_, dimension_);
  const double* mask = nullptr;
  Teuchos::ArrayRCP<const double> maskData;
  if (rowMask != nullptr) {
    if (!rowMask->getMap()->isSameAs(*Gt_->getRowMap()))
      throw std::logic_error("CoarseSpace: a row mask on another map than the multipliers'");
    maskData = rowMask->getData();
    mask = maskData.getRawPtr();
  }
  const CsrMatrix GGt = assembleGramianFromTranspose(*Gt_, offset, mask);
  auto factor = createLocalSolver(localSolver);
  factor->factorize(GGt);
  if (keep != nullptr) *keep = GGt;
  return factor;
}

void CoarseSpace::leastSquaresOnRows(const Vector& x, const Vector& rowMask, Vector& alpha,
                                     const std::string& localSolver) const {
  if (dimension_ == 0) return;
  // G_A = G diag(mask): the kernel coefficients that satisfy the selected rows best.
  std::unique_ptr<LocalSolver> factor;
  try {
    factor = factorizeGramian(&rowMask, localSolver);
  } catch (const std::exception& e) {
    throw std::runtime_error(
        std::string("the active constraints do not fix every rigid body mode (G_A G_A^T is "
                    "singular): a body held only by contact has no active contact, or only "
                    "friction rows at their bound (sliding) hold it along the surface (") +
        e.what() + ")");
  }
  Vector masked(x.getMap());
  masked.elementWiseMultiply(1.0, rowMask, x, 0.0);
  G_->apply(masked, *c_);
  solveReplicated(*factor, *c_, alpha);
}

CoarseSpace::CoarseSpace(const Tearing& tearing, const SubdomainList& subdomains,
                         const std::string& localSolver)
    : subdomains_(subdomains) {
  auto comm = tearing.multiplierMap->getComm();
  const int N = static_cast<int>(tearing.dofOffset.size()) - 1;

  // Coarse ids: subdomain by subdomain, kernelDim() each (0 for a non-floating subdomain).
  std::vector<long long> dims(N, 0), allDims(N, 0);
  for (const auto& s : subdomains) dims[s->id()] = s->kernelDim();
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, N, dims.data(), allDims.data());
  std::vector<GO> offset(N + 1, 0);
  for (int s = 0; s < N; ++s) offset[s + 1] = offset[s] + allDims[s];
  dimension_ = offset[N];
  std::vector<GO> mine;
  for (const auto& s : subdomains) {
    coarseOffset_.push_back(offset[s->id()]);
    for (int k = 0; k < s->kernelDim(); ++k) mine.push_back(offset[s->id()] + k);
  }
  coarseMap_ = Teuchos::rcp(new Map(static_cast<Tpetra::global_size_t>(dimension_),
                                    Teuchos::ArrayView<const GO>(mine), 0, comm));

  // G = R^T B^T, one row per kernel vector, assembled where the subdomain lives: the rows of B
  // touching the subdomain (entries on one row summed), then one dot product per kernel vector.
  std::vector<std::vector<RowEntry>> entries(subdomains.size());
  std::vector<std::vector<GO>> cols(subdomains.size());
  Teuchos::Array<size_t> counts;
  for (std::size_t i = 0; i < subdomains.size(); ++i) {
    entries[i] = tearing.subdomainRows[i];
    std::stable_sort(entries[i].begin(), entries[i].end(),
                     [](const RowEntry& a, const RowEntry& b) { return a.row < b.row; });
    for (const auto& e : entries[i])
      if (cols[i].empty() || cols[i].back() != e.row) cols[i].push_back(e.row);
    counts.resize(counts.size() + subdomains[i]->kernelDim(), cols[i].size());
  }
  G_ = Teuchos::rcp(new CrsMatrix(coarseMap_, counts()));
  std::vector<double> vals;
  std::size_t gRow = 0;
  for (std::size_t i = 0; i < subdomains.size(); ++i) {
    const auto& s = *subdomains[i];
    const int n = s.numDofs();
    for (int k = 0; k < s.kernelDim(); ++k, ++gRow) {
      const double* R = s.kernel().data() + static_cast<std::size_t>(k) * n;
      vals.assign(cols[i].size(), 0.0);
      std::size_t c = 0;
      for (const auto& e : entries[i]) {
        while (cols[i][c] != e.row) ++c;
        vals[c] += e.coef * R[e.dof];
      }
      G_->insertGlobalValues(mine[gRow], Teuchos::ArrayView<const GO>(cols[i]),
                             Teuchos::ArrayView<const double>(vals));
    }
  }
  G_->fillComplete(tearing.multiplierMap, coarseMap_);
  if (dimension_ == 0) return;
  // G^T distributed by the multiplier map: every column of G whole on one rank.
  Gt_ = Tpetra::RowMatrixTransposer<Scalar, LO, GO, Node>(G_).createTranspose();

  try {
    // G G^T is kept for SMALBE's faces with more rows than G, which use it densely.
    factor_ = factorizeGramian(nullptr, localSolver,
                               dimension_ <= kDenseGramianMaxRows ? &gramian_ : nullptr);
  } catch (const std::exception& e) {
    throw std::runtime_error(
        std::string("coarse problem G G^T is singular: the constraints do not remove every "
                    "rigid body mode (") +
        e.what() + ")");
  }
  const int nc = static_cast<int>(dimension_);
  // Coarse right-hand sides reach every rank through an Import onto a replicated map.
  std::vector<GO> all(dimension_);
  for (GO g = 0; g < dimension_; ++g) all[g] = g;
  replicatedMap_ = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                        Teuchos::ArrayView<const GO>(all), 0, comm));
  replicate_ = Teuchos::rcp(new Tpetra::Import<LO, GO, Node>(coarseMap_, replicatedMap_));
  replicated_ = Teuchos::rcp(new Vector(replicatedMap_));
  c_ = Teuchos::rcp(new Vector(coarseMap_));
  alpha_ = Teuchos::rcp(new Vector(coarseMap_));
  rhs_.resize(nc);
  sol_.resize(nc);
}

void CoarseSpace::solveReplicated(LocalSolver& factor, const Vector& c, Vector& alpha) const {
  replicated_->doImport(c, *replicate_, Tpetra::INSERT);
  auto r = replicated_->getData();
  for (GO g = 0; g < dimension_; ++g) rhs_[g] = r[g];
  factor.solve(rhs_.data(), sol_.data());
  auto a = alpha.getDataNonConst();
  const auto& map = *coarseMap_;
  for (std::size_t l = 0; l < map.getNodeNumElements(); ++l) a[l] = sol_[map.getGlobalElement(l)];
}

void CoarseSpace::coarseSolve(const Vector& c, Vector& alpha) const {
  if (dimension_ == 0) return;
  solveReplicated(*factor_, c, alpha);
}

void CoarseSpace::leastSquaresCoefficients(const Vector& x, Vector& alpha) const {
  if (dimension_ == 0) return;
  G_->apply(x, *c_);
  coarseSolve(*c_, alpha);
}

void CoarseSpace::applyGEverywhere(const Vector& x, double* c) const {
  if (dimension_ == 0) return;
  G_->apply(x, *c_);
  replicated_->doImport(*c_, *replicate_, Tpetra::INSERT);
  auto r = replicated_->getData();
  for (GO g = 0; g < dimension_; ++g) c[g] = r[g];
}

void CoarseSpace::coefficientsEverywhere(const Vector& x, double* a) const {
  if (dimension_ == 0) return;
  applyGEverywhere(x, rhs_.data());
  factor_->solve(rhs_.data(), a);
}

std::vector<double> CoarseSpace::denseGramian() const {
  if (dimension_ > kDenseGramianMaxRows)
    throw std::logic_error("CoarseSpace::denseGramian: G G^T of dimension " +
                           std::to_string(dimension_) + " is not kept (at most " +
                           std::to_string(kDenseGramianMaxRows) + ")");
  const std::size_t n = static_cast<std::size_t>(dimension_);
  std::vector<double> dense(n * n, 0.0);
  for (int i = 0; i < gramian_.rows; ++i)
    for (int k = gramian_.rowPtr[i]; k < gramian_.rowPtr[i + 1]; ++k)
      dense[static_cast<std::size_t>(gramian_.colInd[k]) * n + i] = gramian_.values[k];
  return dense;
}

void CoarseSpace::addTransposeEverywhere(const double* a, double scale, Vector& y) const {
  if (dimension_ == 0) return;
  auto local = alpha_->getDataNonConst();
  const auto& map = *coarseMap_;
  for (std::size_t l = 0; l < map.getNodeNumElements(); ++l) local[l] = a[map.getGlobalElement(l)];
  local = Teuchos::null;
  G_->apply(*alpha_, y, Teuchos::TRANS, scale, 1.0);
}

void CoarseSpace::project(const Vector& x, Vector& y) const {
  if (&x != &y) Tpetra::deep_copy(y, x);
  if (dimension_ == 0) return;
  leastSquaresCoefficients(x, *alpha_);
  G_->apply(*alpha_, y, Teuchos::TRANS, -1.0, 1.0);
}

std::vector<std::vector<std::pair<GO, double>>> CoarseSpace::columnsOfG(
    const std::vector<long long>& ids) const {
  std::unordered_map<GO, long long> position;
  for (std::size_t p = 0; p < ids.size(); ++p) position.emplace(static_cast<GO>(ids[p]), p);
  // Each entry of G lives in the row of one rank: gather (position, coarse id, value).
  std::vector<long long> at;
  std::vector<double> values;
  const auto& colMap = *G_->getColMap();
  for (std::size_t r = 0; r < G_->getNodeNumRows(); ++r) {
    Teuchos::ArrayView<const LO> cols;
    Teuchos::ArrayView<const double> v;
    G_->getLocalRowView(static_cast<LO>(r), cols, v);
    const GO row = G_->getRowMap()->getGlobalElement(static_cast<LO>(r));
    for (LO j = 0; j < cols.size(); ++j) {
      const auto it = position.find(colMap.getGlobalElement(cols[j]));
      if (it == position.end() || v[j] == 0.0) continue;
      at.push_back(it->second);
      at.push_back(static_cast<long long>(row));
      values.push_back(v[j]);
    }
  }
  const auto& comm = *G_->getRowMap()->getComm();
  const std::vector<long long> allAt = allGather(comm, at);
  const std::vector<double> allValues = allGather(comm, values);
  std::vector<std::vector<std::pair<GO, double>>> columns(ids.size());
  for (std::size_t e = 0; e < allValues.size(); ++e)
    columns[static_cast<std::size_t>(allAt[2 * e])].emplace_back(static_cast<GO>(allAt[2 * e + 1]),
                                                                 allValues[e]);
  for (auto& c : columns) std::sort(c.begin(), c.end());
  return columns;
}

void CoarseSpace::coarseSolveLocal(const double* b, double* x, int nrhs) const {
  if (dimension_ > 0 && nrhs > 0) factor_->solve(b, x, nrhs);
}

void CoarseSpace::particularSolution(const Vector& e, Vector& lambda) const {
  lambda.putScalar(0.0);
  if (dimension_ == 0) return;
  coarseSolve(e, *alpha_);
  G_->apply(*alpha_, lambda, Teuchos::TRANS);
}

void CoarseSpace::applyKernelTranspose(const MultiVector& primal, Vector& coarse) const {
  auto x = primal.getData(0);
  auto c = coarse.getDataNonConst();
  std::size_t offset = 0, cl = 0;
  for (const auto& s : subdomains_) {
    const int n = s->numDofs();
    for (int k = 0; k < s->kernelDim(); ++k) {
      double dot = 0.0;
      for (int i = 0; i < n; ++i)
        dot += s->kernel()[static_cast<std::size_t>(k) * n + i] * x[offset + i];
      c[cl++] = dot;
    }
    offset += n;
  }
}

void CoarseSpace::addKernelCombination(const Vector& alpha, MultiVector& primal) const {
  auto a = alpha.getData();
  auto u = primal.getDataNonConst(0);
  std::size_t offset = 0, cl = 0;
  for (const auto& s : subdomains_) {
    const int n = s->numDofs();
    for (int k = 0; k < s->kernelDim(); ++k, ++cl)
      for (int i = 0; i < n; ++i)
        u[offset + i] += a[cl] * s->kernel()[static_cast<std::size_t>(k) * n + i];
    offset += n;
  }
}

}  // namespace tfeti
