// FetiSolver's results after solve(): the multipliers gathered or spread by row, the
// multipliers' forces on the subdomains, the constraint report, the primal solution on the
// caller's map, and the measurements (F's time, the factors' bytes).
#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_Gather.hpp"
#include "tfeti_PhaseTimer.hpp"
#include "tfeti_TpetraInterface.hpp"

namespace tfeti {

std::vector<std::vector<double>> FetiSolver::multiplierForces() const {
  if (lambda_.is_null())
    throw std::logic_error("FetiSolver::multiplierForces: no solution (call solve() first)");
  MultiVector btl(tearing_.primalMap, 1);
  tearing_.B->apply(*lambda_, btl, Teuchos::TRANS);
  auto v = btl.getData(0);
  std::vector<std::vector<double>> out;
  std::size_t offset = 0;
  for (const auto& s : subdomains_) {
    out.emplace_back(v.getRawPtr() + offset, v.getRawPtr() + offset + s->numDofs());
    offset += s->numDofs();
  }
  return out;
}

ConstraintReport FetiSolver::constraintReport() const {
  ConstraintReport r;
  r.inequalityRows = tearing_.numInequalityRows;
  if (u_vec_.is_null()) return r;
  Vector bu(tearing_.multiplierMap);
  tearing_.B->apply(*u_vec_, bu);
  bu.update(-1.0, *tearing_.rhs, 1.0);  // B u - c
  auto v = bu.getData();
  auto l = lambda_->getData();
  const auto& map = *tearing_.multiplierMap;
  double mx[4] = {-std::numeric_limits<double>::infinity(), 0.0, 0.0,
                  -std::numeric_limits<double>::infinity()};  // penetration, compl, eq, -min l
  double sums[2] = {0.0, 0.0};                                // force, active rows
  double fr[4] = {0.0, 0.0, 0.0, 0.0};  // friction: bound excess, slip residual, rows, stick rows
  const bool tied = inequalitiesTied(params_);
  // Stick or slip as the primal fit has it (after the penalty's equality projection, MPRGP's).
  Vector holding(tearing_.multiplierMap);
  rowsHoldingWithEquality(holding);
  auto holds = holding.getData();
  for (std::size_t i = 0; i < map.getNodeNumElements(); ++i) {
    const GO row = map.getGlobalElement(static_cast<LO>(i));
    if (tearing_.isInequality(row) &&
        !tearing_.inequalityRows[row - tearing_.firstInequalityRow].isNonPenetration()) {
      // A friction row: not one of the contact conditions above but its own: |lambda| within
      // the box, B u = c where inside (stick), B u - c of lambda's sign at a bound (slip).
      if (tied) mx[2] = std::max(mx[2], std::abs(v[i]));
      const InequalityRow& r = tearing_.inequalityRows[row - tearing_.firstInequalityRow];
      if (r.disc == 2) continue;  // with its first row
      if (r.disc == 1) {
        // A disc pair (rows i, i + 1): |lambda| <= g, the slip s = B u - c zero inside (stick),
        // along lambda at the circle (slip).
        const double lt = std::hypot(l[i], l[i + 1]), g = r.upperBound;
        fr[0] = std::max(fr[0], lt - g);
        const bool slips = holds[i] == 0.0;
        if (g > 0.0)
          fr[1] = std::max(fr[1], slips ? std::max(std::abs(v[i] * l[i + 1] - v[i + 1] * l[i]) / lt,
                                                   -(v[i] * l[i] + v[i + 1] * l[i + 1]) / lt)
                                        : std::hypot(v[i], v[i + 1]));
        fr[2] += 2.0;
        fr[3] += slips ? 0.0 : 2.0;
        continue;
      }
      // At a bound where the row does not hold: the bound lambda is at, or nearest to.
      int side = r.boundActive(l[i]);
      if (holds[i] != 0.0)
        side = 0;
      else if (side == 0)
        side = l[i] - r.lowerBound < r.upperBound - l[i] ? -1 : 1;
      fr[0] = std::max({fr[0], r.lowerBound - l[i], l[i] - r.upperBound});
      // A degenerate box (l = u: an open node's zero Coulomb bound) holds lambda at both bounds
      // at once: any slip is admissible there.
      if (r.lowerBound != r.upperBound)
        fr[1] = std::max(fr[1], side == 0 ? std::abs(v[i]) : std::max(0.0, -side * v[i]));
      fr[2] += 1.0;
      fr[3] += side == 0 ? 1.0 : 0.0;
    } else if (tearing_.isInequality(row)) {
      if (tied) mx[2] = std::max(mx[2], std::abs(v[i]));
      mx[0] = std::max(mx[0], v[i]);
      mx[1] = std::max(mx[1], std::abs(l[i] * v[i]));
      mx[3] = std::max(mx[3], -l[i]);
      sums[0] += l[i];
      sums[1] += l[i] > 0.0 ? 1.0 : 0.0;
    } else {
      mx[2] = std::max(mx[2], std::abs(v[i]));
    }
  }
  double gmx[4], gsums[2];
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 4, mx, gmx);
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 2, sums, gsums);
  double gfr[2], gcount[2], counts[2] = {fr[2], fr[3]};
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 2, fr, gfr);
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 2, counts, gcount);
  r.frictionRows = static_cast<GO>(gcount[0]);
  r.stickRows = static_cast<GO>(gcount[1]);
  r.maxFrictionBoundExcess = gfr[0];
  r.maxFrictionSlipResidual = gfr[1];
  if (r.inequalityRows > 0) {
    r.maxPenetration = gmx[0];
    r.maxComplementarity = gmx[1];
    r.minMultiplier = -gmx[3];
  }
  r.equalityResidual = gmx[2];
  r.force = gsums[0];
  r.activeRows = static_cast<GO>(gsums[1]);
  return r;
}

std::vector<double> FetiSolver::multipliersOfRows(GO first, GO count, const Vector* source) const {
  std::vector<double> mine;  // (row - first, lambda) pairs
  if (source == nullptr) source = lambda_.get();
  if (source != nullptr) {
    auto l = source->getData();
    const auto& map = *tearing_.multiplierMap;
    for (std::size_t i = 0; i < map.getNodeNumElements(); ++i) {
      const GO row = map.getGlobalElement(static_cast<LO>(i));
      if (row >= first && row < first + count)
        mine.insert(mine.end(), {static_cast<double>(row - first), l[i]});
    }
  }
  const std::vector<double> all = allGather(*comm_, mine);
  std::vector<double> out(count, 0.0);
  for (std::size_t k = 0; k + 1 < all.size(); k += 2)
    out[static_cast<std::size_t>(all[k])] = all[k + 1];
  return out;
}

std::vector<double> FetiSolver::inequalityMultipliers() const {
  return multipliersOfRows(tearing_.firstInequalityRow, tearing_.numInequalityRows);
}

std::vector<double> FetiSolver::inequalityRowsHolding() const {
  if (lambda_.is_null()) return std::vector<double>(tearing_.numInequalityRows, 0.0);
  Vector mask(tearing_.multiplierMap);
  rowsHoldingWithEquality(mask);
  return multipliersOfRows(tearing_.firstInequalityRow, tearing_.numInequalityRows, &mask);
}

std::vector<double> FetiSolver::userEqualityMultipliers() const {
  return multipliersOfRows(tearing_.firstUserEqualityRow, tearing_.numUserEqualityRows);
}

std::vector<std::vector<FetiSolver::InequalityOnDof>>
FetiSolver::inequalityMultipliersOnSubdomains() const {
  std::vector<std::vector<InequalityOnDof>> out(subdomains_.size());
  if (lambda_.is_null() || tearing_.numInequalityRows == 0) return out;
  // The rows touching a local subdomain may be owned elsewhere: bring them here.
  std::vector<GO> rows;
  for (const auto& list : tearing_.subdomainRows)
    for (const auto& e : list)
      if (tearing_.isInequality(e.row)) rows.push_back(e.row);
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  auto here = Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                   Teuchos::ArrayView<const GO>(rows), 0, comm_));
  Vector local(here);
  local.doImport(*lambda_, Tpetra::Import<LO, GO, Node>(tearing_.multiplierMap, here),
                 Tpetra::INSERT);
  auto lv = local.getData();
  for (std::size_t i = 0; i < subdomains_.size(); ++i)
    for (const auto& e : tearing_.subdomainRows[i])
      if (tearing_.isInequality(e.row))
        out[i].push_back({e.dof, e.coef, lv[here->getLocalElement(e.row)]});
  return out;
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

FetiSolver::IterationParts FetiSolver::timeIterationParts(int repeats) const {
  Vector x(tearing_.multiplierMap), y(tearing_.multiplierMap), z(tearing_.multiplierMap);
  x.randomize();
  z.randomize();
  IterationParts p;
  const auto mean = [&](double& into, const auto& f) {
    {
      PhaseTimer t(*comm_, into);
      for (int r = 0; r < repeats; ++r) f();
    }
    into /= repeats;
  };
  mean(p.projector, [&] { coarse_->project(x, y); });
  if (!M_.is_null()) mean(p.preconditioner, [&] { M_->apply(x, y); });
  double sink = 0.0;
  mean(p.vectorUpdates, [&] {
    sink += x.dot(z) + y.dot(z);
    y.update(1e-3, x, 1.0);
    z.update(-1e-3, y, 1.0);
    x.update(1e-3, z, 1.0);
  });
  return p;
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

FetiSolver::ExplicitDualBytes FetiSolver::explicitDualBytes() const {
  const auto& ex = F_->explicitPart();
  const unsigned long long mine = ex ? ex->bytes() : 0;
  ExplicitDualBytes b;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 1, &mine, &b.total);
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 1, &mine, &b.maxPerRank);
  return b;
}

FetiSolver::ExplicitDeviceWork FetiSolver::explicitDeviceWork() const {
  ExplicitDeviceWork all;
  all.device = params_.get<std::string>("Explicit device");
  ExplicitDualOperator::DeviceWork mine = deviceWorkDone_;
  if (const auto& ex = F_->explicitPart()) mine.add(ex->deviceWork());
  // The slowest rank's counts and seconds, all ranks' bytes: two reductions.
  const double most[3] = {static_cast<double>(mine.applies), mine.kernelSeconds, mine.applySeconds};
  const double sum[2] = {mine.kernelBytes, mine.transferBytes};
  double mostAll[3], sumAll[2];
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 3, most, mostAll);
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 2, sum, sumAll);
  all.applies = static_cast<long long>(mostAll[0]);
  all.kernelSeconds = mostAll[1];
  all.applySeconds = mostAll[2];
  all.kernelBytes = sumAll[0];
  all.transferBytes = sumAll[1];
  return all;
}

FetiSolver::ExplicitAssembly FetiSolver::explicitAssembly() const {
  long long mine[4] = {explicitAssemblyDone_.blocks, explicitAssemblyDone_.columnsSolved,
                       explicitAssemblyDone_.columnsFull, explicitAssemblyDone_.schurBlocks};
  if (const auto& ex = F_->explicitPart()) {
    mine[0] += ex->assemblies();
    mine[1] += ex->assembledColumns();
    mine[2] += ex->assembledRows();
    mine[3] += ex->schurAssemblies();
  }
  long long all[4] = {0, 0, 0, 0};
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 4, mine, all);
  return {all[0], all[1], all[2], all[3]};
}

std::string FetiSolver::dualOperatorKind() const {
  return F_->explicitPart() ? "explicit" : "implicit";
}

Teuchos::RCP<MultiVector> FetiSolver::solution(const Teuchos::RCP<const Map>& untornMap) const {
  TEUCHOS_TEST_FOR_EXCEPTION(u_.size() != data_.size(), std::logic_error,
                             "FetiSolver::solution: no solution yet (call solve() first)");
  std::vector<std::vector<GO>> nodes;
  for (const auto& sd : data_) nodes.push_back(sd.mesh.globalNode);
  return untornVector(untornMap, nodes, dofsPerNode_, u_);
}
}  // namespace tfeti
