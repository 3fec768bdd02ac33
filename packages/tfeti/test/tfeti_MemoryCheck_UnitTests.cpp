// The memory checks of the set-up (tfeti_NodeMemory.hpp), on 1, 2 and 3 ranks of one node:
//  - a node's need is its ranks' needs summed, against the least MemAvailable its ranks read;
//  - the subdomain factors' bytes, told by their symbolic analyses, are checked before any
//    factorization: a node without room for them stops the set-up with an error on every rank,
//    naming FETI "Memory check"; with room to the KiB the set-up goes on; "Memory check" = false
//    goes on regardless and checks nothing (nor the explicit F_s); a local solver that cannot
//    tell its bytes (KLU2) is not checked;
//  - the Dirichlet preconditioner's interior factors likewise, after the subdomain
//    factorizations, at the set-up's peak (K kept or freed one by one);
//  - the dry run's forecast (FetiSolver::forecastSetupMemory) counts, before anything is
//    factorized, exactly the needs these checks then find (Tacho's workspace within a column);
//  - the explicit F_s' check's need covers what an assembly takes on the heap.
// The explicit F_s' own check: tfeti_ExplicitDual_UnitTests.cpp.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "tfeti_ExplicitDualOperator.hpp"
#include "tfeti_FakeNodeMemory.hpp"
#include "tfeti_FetiSolver.hpp"
#include "tfeti_HeapTally.hpp"
#include "tfeti_NodeMemory.hpp"
#include "tfeti_Test3d.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

Teuchos::ParameterList parameters(const std::string& dualOperator, bool memoryCheck = true,
                                  const std::string& localSolver = "cholmod") {
  Teuchos::ParameterList params = tfeti_test::tightFetiParameters("dirichlet", dualOperator);
  params.set("Memory check", memoryCheck);
  params.set("Local solver", localSolver);
  return params;
}

// 3D elasticity, 2 x 2 x 1 subdomains of 2 x 2 x 2 Hex8 elements under gravity.
const tfeti_test::Box3d& box() {
  static const tfeti_test::Box3d b(2, 2, 1, 2, 2, 2, false);
  return b;
}

std::vector<tfeti::SubdomainData> localSubdomains() {
  tfeti_test::Material3d mat;
  mat.dofsPerNode = 3;
  return tfeti_test::localBoxSubdomains(box(), mat, {0.0, 0.0, -1.0}, *Tpetra::getDefaultComm());
}

tfeti::FetiSolver make(const Teuchos::ParameterList& params) {
  return tfeti::FetiSolver(Tpetra::getDefaultComm(), box().numSubdomains(), localSubdomains(),
                           params);
}

// max |u - v| / max |v| over every subdomain of every rank.
double solutionDifference(const tfeti::FetiSolver& u, const tfeti::FetiSolver& v) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < v.data().size(); ++i)
    for (std::size_t k = 0; k < v.solution(i).size(); ++k) {
      diff = std::max(diff, std::abs(u.solution(i)[k] - v.solution(i)[k]));
      scale = std::max(scale, std::abs(v.solution(i)[k]));
    }
  const tfeti::Comm& comm = *Tpetra::getDefaultComm();
  return tfeti_test::globalMax(comm, diff) / tfeti_test::globalMax(comm, scale);
}

}  // namespace

TEUCHOS_UNIT_TEST(MemoryCheck, NodeMemoryAddsTheNeedsOfANodesRanks) {
  auto comm = Tpetra::getDefaultComm();
  const int P = comm->getSize(), rank = comm->getRank();
  {
    tfeti_test::MeminfoFile good(
        "MemTotal:       100 kB\nMemAvailable:    4096 kB\nBuffers: 1 kB\n");
    TEST_EQUALITY(tfeti::availableBytesIn(good.path()), 4096.0 * 1024.0);
  }
  {
    tfeti_test::MeminfoFile none("MemTotal:       100 kB\nMemFree:    4096 kB\n");
    TEST_COMPARE(tfeti::availableBytesIn(none.path()), <, 0.0);
  }
  TEST_COMPARE(tfeti::availableBytesIn("/nonexistent/meminfo"), <, 0.0);
  // A file named by TFETI_MEMINFO must give the line: else the check would check nothing.
  setenv("TFETI_MEMINFO", "/nonexistent/meminfo", 1);
  const std::string msg = tfeti_test::messageOf([&] { tfeti::nodeMemory(*comm, 1.0); });
  unsetenv("TFETI_MEMINFO");
  out << msg << "\n";
  TEST_ASSERT(tfeti_test::contains(msg, "TFETI_MEMINFO=/nonexistent/meminfo"));
  TEST_ASSERT(tfeti_test::contains(msg, "MemAvailable"));
  // Every rank of this test runs on one machine: one node, whose available memory is the least
  // its ranks read, and whose need is the sum of theirs.
  tfeti_test::FakeNodeMemory fake(1000 + rank);
  for (const double perRank : {100000.0, 400000.0}) {
    const tfeti::NodeMemory m = tfeti::nodeMemory(*comm, perRank * (rank + 1));
    const double need = perRank * P * (P + 1) / 2;
    out << P << " ranks, " << perRank << " bytes per rank: " << tfeti::describe(m) << "\n";
    TEST_ASSERT(m.known);
    TEST_EQUALITY(m.ranks, P);
    TEST_EQUALITY(m.firstRank, 0);
    TEST_EQUALITY(m.needBytes, need);
    TEST_EQUALITY(m.availableBytes, 1000.0 * 1024.0);
    TEST_EQUALITY(m.fits, need <= 1000.0 * 1024.0);
  }
  TEST_EQUALITY(tfeti::bytesText(1536.0), std::string("1.5 KiB"));
  TEST_EQUALITY(tfeti::bytesText(3.0 * 1024 * 1024 * 1024), std::string("3.00 GiB"));
}

TEUCHOS_UNIT_TEST(MemoryCheck, FactorsBeyondTheNodesMemory) {
  auto comm = Tpetra::getDefaultComm();
  const int P = comm->getSize();
  tfeti::FetiSolver roomy = make(parameters("implicit"));
  const tfeti::NodeMemory& m = roomy.factorMemoryCheck();
  out << "this machine: " << tfeti::describe(m) << "; the factors stream "
      << roomy.globalFactorBytes() << " bytes\n";
  TEST_ASSERT(m.known && m.fits);
  TEST_EQUALITY(m.ranks, P);
  TEST_EQUALITY(m.firstRank, 0);
  // The need is what the factors then hold (CHOLMOD's supernodal values unpacked, the index
  // arrays: at least what a solve streams), and on each rank the last factorization's transient
  // at most: the decoupled copy of K and CHOLMOD's (two copies of K's triangle at most, and an
  // update matrix no larger than the factor).
  double held = 0.0, transient = 0.0;
  for (const auto& s : roomy.subdomains()) {
    held += static_cast<double>(s->factorMemory());
    transient =
        std::max(transient, static_cast<double>(2 * s->stiffness().bytes() + s->factorMemory()));
  }
  held = tfeti_test::globalSum(*comm, held);
  out << "held " << held << ", need beyond " << m.needBytes - held << "\n";
  TEST_COMPARE(m.needBytes, >, held);
  TEST_COMPARE(m.needBytes - held, <=, tfeti_test::globalSum(*comm, transient));
  TEST_COMPARE(held, >=, static_cast<double>(roomy.globalFactorBytes()));
  TEST_COMPARE(m.availableBytes, >, m.needBytes);
  const tfeti::DualResult reference = roomy.solve();
  TEST_ASSERT(reference.converged);
  const long long kib = tfeti_test::kibAtLeast(m.needBytes);
  {
    // One KiB short: every rank stops with the error, before anything is factorized.
    tfeti_test::FakeNodeMemory fake(kib - 1);
    const std::string msg = tfeti_test::messageOf([&] { make(parameters("implicit")); });
    out << msg << "\n";
    TEST_ASSERT(
        tfeti_test::contains(msg, "the subdomain factors (\"Local solver\" = cholmod) do not fit"));
    TEST_ASSERT(
        tfeti_test::contains(msg, tfeti::bytesText(1024.0 * (kib - 1)) +
                                      " available (MemAvailable) before the factorizations"));
    TEST_ASSERT(tfeti_test::contains(msg, "\"Memory check\" = false"));
    TEST_ASSERT(tfeti_test::contains(
        msg, "the " + std::to_string(P) + (P == 1 ? " rank" : " ranks") +
                 " on the node of rank 0 need " + tfeti::bytesText(m.needBytes)));
  }
  {
    // Room to the KiB: it goes on, and solves as before.
    tfeti_test::FakeNodeMemory fake(kib);
    tfeti::FetiSolver tight = make(parameters("implicit"));
    TEST_ASSERT(tight.factorMemoryCheck().fits);
    TEST_EQUALITY(tight.factorMemoryCheck().needBytes, m.needBytes);
    const tfeti::DualResult r = tight.solve();
    TEST_EQUALITY(r.iterations, reference.iterations);
    TEST_EQUALITY(solutionDifference(tight, roomy), 0.0);
  }
  {
    // "Memory check" = false: no check at all, the explicit F_s' neither.
    tfeti_test::FakeNodeMemory fake(1);
    for (const std::string kind : {"implicit", "explicit"}) {
      tfeti::FetiSolver unchecked = make(parameters(kind, false));
      TEST_ASSERT(!unchecked.factorMemoryCheck().known);
      TEST_EQUALITY(unchecked.dualOperatorKind(), kind);
      TEST_ASSERT(unchecked.dualOperatorChoice().fitsMemory);
      TEST_EQUALITY(unchecked.dualOperatorChoice().nodeAvailableBytes, -1.0);
      const tfeti::DualResult r = unchecked.solve();
      TEST_EQUALITY(r.iterations, reference.iterations);
      TEST_COMPARE(solutionDifference(unchecked, roomy), <, 1e-10);
    }
    // KLU2 cannot tell its factor's bytes before it factorizes: nothing is checked.
    tfeti::FetiSolver klu2 = make(parameters("implicit", true, "klu2"));
    TEST_ASSERT(!klu2.factorMemoryCheck().known);
    TEST_ASSERT(klu2.solve().converged);
  }
}

// The Dirichlet preconditioner's interior factors, checked after the subdomain factorizations:
// the need is what they hold at the set-up's peak (all of them with K kept; less with K freed one
// by one), each told by a symbolic analysis that the factorization then uses. A node whose memory
// runs out between the two checks (the available bytes' source gives plenty to the first, 1 KiB
// to the next) stops there with an error on every rank naming the preconditioner.
TEUCHOS_UNIT_TEST(MemoryCheck, PreconditionerBeyondTheNodesMemory) {
  auto comm = Tpetra::getDefaultComm();
  const int P = comm->getSize();
  const auto globalSum = [&](double x) {
    double sum = 0.0;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &x, &sum);
    return sum;
  };
  double held = 0.0, keptNeed = 0.0;
  {
    tfeti::FetiSolver roomy = make(parameters("implicit"));
    const tfeti::NodeMemory& m = roomy.preconditionerMemoryCheck();
    keptNeed = m.needBytes;
    out << "this machine: " << tfeti::describe(m) << "\n";
    TEST_ASSERT(m.known && m.fits);
    TEST_EQUALITY(m.ranks, P);
    // The need: what the preconditioners then hold (blocks and interior factors), and one
    // set-up's transient per rank beyond.
    double mine = 0.0, transient = 0.0;
    for (const auto& s : roomy.subdomains()) {
      mine += static_cast<double>(s->preconditionerMemory());
      transient = std::max(transient, static_cast<double>(2 * s->stiffness().bytes() +
                                                          s->preconditionerFactorMemory()));
    }
    held = globalSum(mine);
    TEST_COMPARE(held, >, 0.0);
    TEST_COMPARE(m.needBytes, >, held);
    TEST_COMPARE(m.needBytes - held, <=, globalSum(transient));
    // A prediction is the bytes a set-up then holds, and the set-up analyses nothing again; its
    // transient is the copy of K_ii and CHOLMOD's peak beyond (the old interior factor is freed
    // first, the new one takes as much).
    for (std::size_t i = 0; i < roomy.subdomains().size(); ++i) {
      tfeti::Subdomain& s = *roomy.subdomains()[i];
      const std::vector<int> dofs = s.interfaceDofs();
      const std::size_t before = s.preconditionerMemory();
      const tfeti::MemoryPrediction p =
          s.predictPreconditionerMemory(dofs, tfeti::PreconditionerType::Dirichlet, "cholmod");
      TEST_EQUALITY(p.held, static_cast<std::ptrdiff_t>(before));
      std::vector<char> onInterface(s.numDofs(), 0);
      for (int d : dofs) onInterface[d] = 1;
      const tfeti::CsrMatrix& K = s.stiffness();
      std::size_t ni = 0, nnz = 0;
      for (int r = 0; r < K.rows; ++r) {
        if (onInterface[r]) continue;
        ++ni;
        for (int k = K.rowPtr[r]; k < K.rowPtr[r + 1]; ++k) nnz += onInterface[K.colInd[k]] ? 0 : 1;
      }
      const std::ptrdiff_t copy = static_cast<std::ptrdiff_t>(sizeof(int) * (ni + 1) +
                                                              (sizeof(int) + sizeof(double)) * nnz);
      const tfeti::LocalAnalysisCounts counts = tfeti::localAnalysisCounts();
      const std::size_t inUse = tfeti::localSolverMemoryInUse();
      tfeti::localSolverMemoryPeak(true);
      s.setupPreconditioner(dofs, tfeti::PreconditionerType::Dirichlet, "cholmod");
      TEST_EQUALITY(static_cast<std::size_t>(p.transient - copy),
                    tfeti::localSolverMemoryPeak() - inUse);
      TEST_EQUALITY(tfeti::localAnalysisCounts().made, counts.made);
      TEST_EQUALITY(tfeti::localAnalysisCounts().shared, counts.shared);
      TEST_EQUALITY(s.preconditionerMemory(), before);
      const tfeti::MemoryPrediction lumped =
          s.predictPreconditionerMemory(dofs, tfeti::PreconditionerType::Lumped, "cholmod");
      TEST_EQUALITY(lumped.held, 0);
      TEST_EQUALITY(lumped.transient, 0);
    }
    TEST_ASSERT(roomy.solve().converged);
  }
  {
    // K freed after each interior factor: the peak is below the one with every K kept.
    Teuchos::ParameterList params = parameters("implicit");
    params.set("Keep subdomain matrices", false);
    tfeti::FetiSolver freeing = make(params);
    out << "K freed: " << tfeti::describe(freeing.preconditionerMemoryCheck()) << "\n";
    TEST_ASSERT(freeing.preconditionerMemoryCheck().known);
    TEST_COMPARE(freeing.preconditionerMemoryCheck().needBytes, <, keptNeed);
  }
  {
    // The lumped preconditioner makes no factor: nothing to check.
    Teuchos::ParameterList params = parameters("implicit");
    params.set("Preconditioner", "lumped");
    TEST_ASSERT(!make(params).preconditionerMemoryCheck().known);
  }
  int reads = 0;
  tfeti::setAvailableBytesSource([&reads] { return ++reads == 1 ? 1e15 : 1024.0; });
  const std::string msg = tfeti_test::messageOf([&] { make(parameters("implicit")); });
  tfeti::setAvailableBytesSource({});
  out << msg << "\n";
  TEST_EQUALITY(reads, 2);
  TEST_ASSERT(tfeti_test::contains(
      msg,
      "the Dirichlet preconditioner's interior factors (\"Local solver\" = cholmod) do not fit"));
  TEST_ASSERT(tfeti_test::contains(msg,
                                   "1.0 KiB available (MemAvailable) after the subdomain "
                                   "factorizations"));
  TEST_ASSERT(tfeti_test::contains(msg, "\"Preconditioner\" = lumped"));
  TEST_ASSERT(tfeti_test::contains(msg, "\"Memory check\" = false"));
}

// The dry run's forecast against the run's checks, on the same subdomains: the factors' and the
// interior factors' needs equal to the byte (K kept, K freed one by one; both local solvers'
// kinds; TFETI and FETI), the F_s' blocks equal to what the operator holds, and the F_s' need
// the run's, by solves and from the Schur complement (the forecast finds the fixing dofs the run
// leaves out of B_s's). A local solver that cannot tell the factors (KLU2, Tacho) is reported as
// such; Tacho's workspace is counted.
TEUCHOS_UNIT_TEST(MemoryCheck, ForecastIsWhatTheChecksFind) {
  auto comm = Tpetra::getDefaultComm();
  const auto sum = [&](double x) { return tfeti_test::globalSum(*comm, x); };
  for (const std::string solver : {"cholmod", "cholmod-simplicial", "cholmod-supernodal"}) {
    for (const bool keep : {true, false}) {
      for (const std::string assembly : {"schur", "solves"}) {
        Teuchos::ParameterList params = parameters("explicit", true, solver);
        params.set("Keep subdomain matrices", keep);
        params.set("Explicit assembly", assembly);
        const tfeti::SetupMemoryForecast f = tfeti::FetiSolver::forecastSetupMemory(
            comm, box().numSubdomains(), localSubdomains(), params);
        tfeti::FetiSolver run = make(params);
        out << solver << ", K " << (keep ? "kept" : "freed") << ", " << assembly << ": factors "
            << sum(f.factors) << " (run " << run.factorMemoryCheck().needBytes << "), interiors "
            << sum(f.interiorPeak) << " (run " << run.preconditionerMemoryCheck().needBytes
            << ")\n";
        TEST_ASSERT(f.factorsKnown && f.interiorKnown);
        TEST_EQUALITY(f.dualRows.size(), run.subdomains().size());
        TEST_EQUALITY(sum(f.factorPeak), run.factorMemoryCheck().needBytes);
        double held = 0.0;
        for (const auto& s : run.subdomains()) held += static_cast<double>(s->factorMemory());
        TEST_EQUALITY(sum(f.factors), sum(held));
        TEST_EQUALITY(sum(f.interiorPeak), run.preconditionerMemoryCheck().needBytes);
        // The F_s: what the operator holds; the need the run's check's.
        TEST_EQUALITY(sum(f.explicitBlocks), static_cast<double>(run.explicitDualBytes().total));
        const double runNeed = run.dualOperatorChoice().nodeNeedBytes;
        const double forecastNeed = sum(f.explicitNeed());
        out << "  F_s' need " << forecastNeed << " (run " << runNeed << ")\n";
        // Exactly, from the Schur complement too: the forecast finds the kernels and the fixing
        // dofs that the run leaves out of a block's dofs (before 2026-12-07 it could not, and
        // was off by what they change). Here they are among the dual rows' dofs, so that matters.
        TEST_EQUALITY(forecastNeed, runNeed);
        double fixedOnInterface = 0.0;
        for (std::size_t i = 0; i < run.subdomains().size(); ++i) {
          const std::vector<int> dofs = tfeti::subdomainDualDofs(run.tearing(), i);
          for (int d : run.subdomains()[i]->fixingDofs())
            fixedOnInterface += std::count(dofs.begin(), dofs.end(), d);
        }
        TEST_COMPARE(sum(fixedOnInterface), >, 0.0);
        TEST_ASSERT(run.solve().converged);
      }
    }
  }
  // FETI: subdomains held by their Dirichlet conditions have no fixing dofs, and their factor
  // no decoupled copy of K (the forecast counted one for every subdomain before 2026-12-07).
  for (const std::string assembly : {"schur", "solves"}) {
    Teuchos::ParameterList params = parameters("explicit", true, "cholmod");
    params.set("Formulation", "FETI");
    params.set("Explicit assembly", assembly);
    const tfeti::SetupMemoryForecast f = tfeti::FetiSolver::forecastSetupMemory(
        comm, box().numSubdomains(), localSubdomains(), params);
    tfeti::FetiSolver run = make(params);
    int held = 0, floating = 0;
    for (const auto& s : run.subdomains()) (s->fixingDofs().empty() ? held : floating) += 1;
    out << "FETI, " << assembly << ": " << tfeti_test::globalSum(*comm, double(held))
        << " subdomains held, " << tfeti_test::globalSum(*comm, double(floating))
        << " floating; factors " << sum(f.factorPeak) << " (run "
        << run.factorMemoryCheck().needBytes << ")\n";
    TEST_COMPARE(tfeti_test::globalSum(*comm, double(held)), >, 0.0);
    TEST_COMPARE(tfeti_test::globalSum(*comm, double(floating)), >, 0.0);
    TEST_EQUALITY(sum(f.factorPeak), run.factorMemoryCheck().needBytes);
    TEST_EQUALITY(sum(f.explicitNeed()), run.dualOperatorChoice().nodeNeedBytes);
    TEST_ASSERT(run.solve().converged);
  }
  const tfeti::SetupMemoryForecast klu2 = tfeti::FetiSolver::forecastSetupMemory(
      comm, box().numSubdomains(), localSubdomains(), parameters("implicit", true, "klu2"));
  TEST_ASSERT(!klu2.factorsKnown && !klu2.interiorKnown);
  TEST_EQUALITY(klu2.factors, 0.0);
  // Amesos2's solvers assemble by solves. Tacho keeps its workspace of the widest solve with
  // every factor, n x min(128, m_s) doubles: counted by the forecast and the run's check alike,
  // except that the run's check counts what it grows by, and the set-up's one-column solves
  // (d = B K+ f) have already made it a column wide: at most n doubles per subdomain apart.
  for (const std::string solver : {"klu2", "tacho"}) {
    const Teuchos::ParameterList params = parameters("explicit", true, solver);
    const tfeti::SetupMemoryForecast f = tfeti::FetiSolver::forecastSetupMemory(
        comm, box().numSubdomains(), localSubdomains(), params);
    tfeti::FetiSolver run = make(params);
    double workspace = 0.0, column = 0.0;
    for (std::size_t i = 0; i < run.subdomains().size(); ++i) {
      workspace += 8.0 * run.subdomains()[i]->numDofs() *
                   std::min<double>(128.0, static_cast<double>(f.dualRows[i]));
      column += solver == "tacho" ? 8.0 * run.subdomains()[i]->numDofs() : 0.0;
    }
    const double forecastNeed = sum(f.explicitNeed());
    out << solver << ": F_s' need " << forecastNeed << " (run "
        << run.dualOperatorChoice().nodeNeedBytes << "), kept by the solves "
        << sum(f.explicitSolverKeeps) << "\n";
    TEST_EQUALITY(f.explicitSolverKeeps, solver == "tacho" ? workspace : 0.0);
    const double runNeed = run.dualOperatorChoice().nodeNeedBytes;
    TEST_COMPARE(forecastNeed, >=, runNeed);
    TEST_COMPARE(forecastNeed - runNeed, <=, sum(column));
    TEST_EQUALITY(run.explicitAssembly().schurBlocks, 0LL);
    TEST_ASSERT(run.solve().converged);
  }
}

// The explicit check's need against what an assembly takes: an operator assembled again on the
// run's factors and tearing, its peak on the heap (C++'s and CHOLMOD's allocations, HeapTally)
// summed over the ranks of the node, within the need the run's check counted, from the Schur
// complement and by solves, and above the blocks' bytes. (Kokkos allocates the operator's
// Tpetra vectors with malloc, which HeapTally does not see: they are vectors of the multipliers,
// not counted by the check either. CHOLMOD's solve vectors, shared by the process, were made by
// the run's own assembly: the solves' bound counts them, this assembly does not make them.)
TEUCHOS_UNIT_TEST(MemoryCheck, ExplicitAssemblyWithinTheCheckedNeed) {
  auto comm = Tpetra::getDefaultComm();
  const auto sum = [&](double x) { return tfeti_test::globalSum(*comm, x); };
  const tfeti_test::Box3d larger(2, 2, 1, 4, 4, 4, false);
  tfeti_test::Material3d mat;
  mat.dofsPerNode = 3;
  for (const std::string assembly : {"schur", "solves"}) {
    Teuchos::ParameterList params = parameters("explicit", true, "cholmod");
    params.set("Explicit assembly", assembly);
    params.set("Keep subdomain matrices", true);
    tfeti::FetiSolver run(comm, larger.numSubdomains(),
                          tfeti_test::localBoxSubdomains(larger, mat, {0.0, 0.0, -1.0}, *comm),
                          params);
    const double need = run.dualOperatorChoice().nodeNeedBytes;
    const double blocks = static_cast<double>(run.explicitDualBytes().total);
    const std::size_t before = tfeti_test::HeapTally::inUse();
    tfeti_test::HeapTally::reset();
    double peak = 0.0;
    {
      const tfeti::ExplicitDualOperator again(
          run.tearing(), run.subdomains(), tfeti::DenseStorage::Packed, nullptr,
          tfeti::ExplicitDevice::Host,
          assembly == "schur" ? tfeti::BlockAssembly::Schur : tfeti::BlockAssembly::Solves);
      peak = static_cast<double>(tfeti_test::HeapTally::peak() - before);
    }
    out << assembly << ": the assembly's peak " << sum(peak) << " bytes, the check's need " << need
        << ", the blocks " << blocks << "\n";
    TEST_COMPARE(sum(peak), <=, need);
    TEST_COMPARE(sum(peak), >=, blocks);
  }
}
