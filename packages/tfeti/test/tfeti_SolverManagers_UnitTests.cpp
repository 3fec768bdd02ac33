// Belos conventions of the iterative solvers (issue 17) on 1, 2 and 3 ranks:
//  - Belos's parameter names ("Convergence Tolerance", "Maximum Iterations") as aliases of the
//    package's, with the same results; both names with different values an error naming both;
//  - the SolverManager-like interface of MprgpSolMgr and SmalbeSolMgr: setProblem,
//    setParameters (only the parameters given change), getCurrentParameters, reset,
//    achievedTol, getNumIters; a solve after reset repeats the first one exactly;
//  - "Verbosity" as a Belos::MsgType mask (each type prints its kind of line and only it) and as
//    the package's levels 1 and 2, to a FancyOStream, never changing std::cout's format state;
//  - the Teuchos::TimeMonitor timers: "tfeti: Hessian apply" is called exactly once per counted
//    multiplication, the solve timers once per solve.
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_FancyOStream.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_MprgpSolMgr_decl.hpp"
#include "tfeti_SmalbeSolMgr_decl.hpp"
#include "tfeti_SolverConventions.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

using Teuchos::RCP;
using Teuchos::rcp;
using tfeti::GO;
using tfeti::LO;
using tfeti::MultiVector;
using tfeti::Operator;
using tfeti::Vector;
using tfeti_test::contains;
using tfeti_test::messageOf;
using Qp = tfeti::BoundConstrainedQp<double, MultiVector, Operator>;
using Mprgp = tfeti::MprgpSolMgr<double, MultiVector, Operator>;
using Smalbe = tfeti::SmalbeSolMgr<double, MultiVector, Operator>;

// An obstacle problem: A = tridiag(-1, 2 + 0.01 i, -1) (SPD), b_i = sin(0.3 i), x >= -0.4 + 0.1
// cos(i) (about a third of the bounds active at the solution), x = 0 initially.
struct ObstacleQp {
  RCP<tfeti::CrsMatrix> A;
  RCP<Vector> b, lower;
  Qp fresh() const {
    Qp qp;
    qp.A = A;
    qp.b = b;
    qp.lower = lower;
    qp.x = rcp(new Vector(b->getMap()));
    return qp;
  }
};

ObstacleQp obstacleQp(GO n) {
  ObstacleQp p;
  auto map =
      rcp(new tfeti::Map(static_cast<Tpetra::global_size_t>(n), 0, Tpetra::getDefaultComm()));
  p.A = rcp(new tfeti::CrsMatrix(map, 3));
  p.b = rcp(new Vector(map));
  p.lower = rcp(new Vector(map));
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l) {
    const GO i = map->getGlobalElement(l);
    std::vector<GO> cols{i};
    std::vector<double> vals{2.0 + 0.01 * i};
    if (i > 0) cols.push_back(i - 1), vals.push_back(-1.0);
    if (i + 1 < n) cols.push_back(i + 1), vals.push_back(-1.0);
    p.A->insertGlobalValues(i, Teuchos::arrayViewFromVector(cols),
                            Teuchos::arrayViewFromVector(vals));
    p.b->replaceLocalValue(l, std::sin(0.3 * i));
    p.lower->replaceLocalValue(l, -0.4 + 0.1 * std::cos(double(i)));
  }
  p.A->fillComplete();
  return p;
}

// Q: the orthogonal projector onto span{1} (Q x = 0: the entries of x sum to zero).
class MeanProjector : public Operator {
 public:
  explicit MeanProjector(RCP<const tfeti::Map> map) : map_(std::move(map)) {}
  RCP<const tfeti::Map> getDomainMap() const override { return map_; }
  RCP<const tfeti::Map> getRangeMap() const override { return map_; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp = Teuchos::NO_TRANS,
             double alpha = 1.0, double beta = 0.0) const override {
    const double n = double(map_->getGlobalNumElements());
    for (std::size_t c = 0; c < X.getNumVectors(); ++c) {
      Vector ones(map_);
      ones.putScalar(1.0);
      const double mean = ones.dot(*X.getVector(c)) / n;
      Y.getVectorNonConst(c)->update(alpha * mean, ones, beta);
    }
  }

 private:
  RCP<const tfeti::Map> map_;
};

std::vector<double> local(const Vector& v) {
  auto d = v.getData();
  return std::vector<double>(d.begin(), d.end());
}

double calls(const std::string& timer) {
  auto t = Teuchos::TimeMonitor::lookupCounter(timer);
  return t.is_null() ? 0.0 : double(t->numCalls());
}

bool root() {
  return Tpetra::getDefaultComm()->getRank() == 0;
}

// ------------------------------------------------------------------------------------------

TEUCHOS_UNIT_TEST(SolverManagers, BelosNamesAreAliases) {
  const auto p = obstacleQp(60);
  Teuchos::ParameterList own;
  own.set("Relative tolerance", 1e-9);
  own.set("Maximum iterations", 500);
  Teuchos::ParameterList belos;
  belos.set("Convergence Tolerance", 1e-9);
  belos.set("Maximum Iterations", 500);
  const Qp q1 = p.fresh(), q2 = p.fresh();
  Mprgp a(q1, own), b(q2, belos);
  // One name per setting in the parameters in use.
  TEST_EQUALITY(b.getCurrentParameters().get<double>("Relative tolerance"), 1e-9);
  TEST_EQUALITY(b.getCurrentParameters().get<int>("Maximum iterations"), 500);
  TEST_ASSERT(!b.getCurrentParameters().isParameter("Convergence Tolerance"));
  TEST_ASSERT(!b.getCurrentParameters().isParameter("Maximum Iterations"));
  const Belos::ReturnType ra = a.solve();
  const Belos::ReturnType rb = b.solve();
  TEST_EQUALITY(ra, Belos::Converged);
  TEST_EQUALITY(rb, Belos::Converged);
  TEST_ASSERT(a.counters().history == b.counters().history);
  TEST_ASSERT(local(*q1.x->getVector(0)) == local(*q2.x->getVector(0)));

  // The limit takes effect under its Belos name.
  Teuchos::ParameterList few;
  few.set("Maximum Iterations", 3);
  Mprgp limited(p.fresh(), few);
  const Belos::ReturnType rl = limited.solve();
  TEST_EQUALITY(rl, Belos::Unconverged);
  TEST_EQUALITY(limited.getNumIters(), 3);

  // Both names: equal values are accepted, different ones are an error naming both.
  Teuchos::ParameterList same = own;
  same.set("Convergence Tolerance", 1e-9);
  Mprgp ok(p.fresh(), same);
  TEST_EQUALITY(ok.getCurrentParameters().get<double>("Relative tolerance"), 1e-9);
  Teuchos::ParameterList both = own;
  both.set("Convergence Tolerance", 1e-7);
  const std::string m = messageOf([&] { Mprgp s(p.fresh(), both); });
  out << m << "\n";
  TEST_ASSERT(contains(m, "\"Convergence Tolerance\" = 1e-07"));
  TEST_ASSERT(contains(m, "\"Relative tolerance\" = 1e-09"));
  Teuchos::ParameterList badType;
  badType.set("Maximum Iterations", 2.5);
  TEST_ASSERT(contains(messageOf([&] { Mprgp s(p.fresh(), badType); }), "must be an int"));

  // SMALBE: "Maximum Iterations" is its outer limit, and the inner sublist takes aliases too.
  auto Q = rcp(new MeanProjector(p.b->getMap()));
  Teuchos::ParameterList sp;
  sp.set("Convergence Tolerance", 1e-8);
  sp.set("Maximum Iterations", 40);
  sp.sublist("MPRGP").set("Maximum Iterations", 77);
  Smalbe smalbe(p.fresh(), Q, sp);
  const auto& cur = smalbe.getCurrentParameters();
  TEST_EQUALITY(cur.get<double>("Relative tolerance"), 1e-8);
  TEST_EQUALITY(cur.get<int>("Maximum outer iterations"), 40);
  TEST_EQUALITY(cur.sublist("MPRGP").get<int>("Maximum iterations"), 77);
  Teuchos::ParameterList sBoth = sp;
  sBoth.set("Maximum outer iterations", 41);
  const std::string ms = messageOf([&] { Smalbe s(p.fresh(), Q, sBoth); });
  TEST_ASSERT(contains(ms, "SMALBE") && contains(ms, "\"Maximum outer iterations\" = 41"));

  // The FETI list: the solvers' sublists, before validation.
  Teuchos::ParameterList feti;
  feti.sublist("PCPG").set("Convergence Tolerance", 1e-10);
  feti.sublist("SMALBE").sublist("MPRGP").set("Maximum Iterations", 12);
  tfeti::FetiSolver::applySolverAliases(feti);
  TEST_EQUALITY(feti.sublist("PCPG").get<double>("Relative tolerance"), 1e-10);
  TEST_EQUALITY(feti.sublist("SMALBE").sublist("MPRGP").get<int>("Maximum iterations"), 12);
  feti.validateParameters(*tfeti::FetiSolver::validParameters());
}

TEUCHOS_UNIT_TEST(SolverManagers, PcpgAliasesAndTimers) {
  auto comm = Tpetra::getDefaultComm();
  const tfeti::StructuredRectangle rect(0, 1, 0, 1, 2, 2, 4, 4);
  auto solveWith = [&](const Teuchos::ParameterList& pcpg) {
    Teuchos::ParameterList p;
    p.sublist("PCPG") = pcpg;
    tfeti::FetiSolver s(comm, rect.numSubdomains(),
                        tfeti_test::localSubdomains(rect, *comm, tfeti_test::poisson()), p);
    const double solves = calls("tfeti: PCPG solve"), applies = calls("tfeti: Hessian apply");
    const tfeti::DualResult r = s.solve();
    // One application of F for the initial gradient, one per iteration.
    TEST_EQUALITY(calls("tfeti: PCPG solve"), solves + 1);
    TEST_EQUALITY(calls("tfeti: Hessian apply"), applies + r.iterations + 1);
    return r;
  };
  Teuchos::ParameterList own, belos;
  own.set("Relative tolerance", 1e-10);
  belos.set("Convergence Tolerance", 1e-10);
  const tfeti::DualResult a = solveWith(own), b = solveWith(belos);
  TEST_ASSERT(a.converged && b.converged);
  TEST_EQUALITY(a.iterations, b.iterations);
  TEST_ASSERT(a.history == b.history);
  TEST_COMPARE(a.relativeResidual, <=, 1e-10);
}

TEUCHOS_UNIT_TEST(SolverManagers, SolverManagerInterface) {
  const auto p = obstacleQp(80);
  const Qp q1 = p.fresh();
  Teuchos::ParameterList params;
  params.set("Relative tolerance", 1e-10);
  Mprgp byConstructor(q1, params);
  const Belos::ReturnType r1 = byConstructor.solve();
  TEST_EQUALITY(r1, Belos::Converged);

  // Belos's order: construct, parameters, problem.
  Mprgp m;
  TEST_ASSERT(contains(messageOf([&] { m.solve(); }), "setProblem"));
  m.setParameters(rcp(new Teuchos::ParameterList(params)));
  const Qp q2 = p.fresh();
  m.setProblem(q2);
  const Belos::ReturnType r2 = m.solve();
  TEST_EQUALITY(r2, Belos::Converged);
  TEST_ASSERT(m.counters().history == byConstructor.counters().history);
  TEST_ASSERT(local(*q2.x->getVector(0)) == local(*q1.x->getVector(0)));
  TEST_EQUALITY(m.getNumIters(), byConstructor.getNumIters());
  TEST_COMPARE(m.getNumIters(), >, 0);
  // achievedTol: ||g^P|| / ||b|| of the solution, at most the tolerance.
  TEST_EQUALITY(m.achievedTol(), m.counters().projectedGradientNorm / p.b->norm2());
  TEST_COMPARE(m.achievedTol(), <=, 1e-10);
  TEST_COMPARE(m.achievedTol(), >, 0.0);

  // setParameters changes what it is given and keeps the rest.
  Teuchos::ParameterList gamma;
  gamma.set("Gamma", 2.0);
  m.setParameters(gamma);
  TEST_EQUALITY(m.getCurrentParameters().get<double>("Gamma"), 2.0);
  TEST_EQUALITY(m.getCurrentParameters().get<double>("Relative tolerance"), 1e-10);
  Teuchos::ParameterList back;
  back.set("Gamma", 1.0);
  back.set("Convergence Tolerance", 1e-10);  // replaces the package's name set earlier
  m.setParameters(back);

  // reset forgets the results; the same problem from the same start repeats the solve exactly.
  m.reset();
  TEST_EQUALITY(m.getNumIters(), 0);
  TEST_EQUALITY(m.achievedTol(), 0.0);
  TEST_EQUALITY(m.counters().hessianMultiplications, 0);
  TEST_ASSERT(m.getGradient().is_null());
  const Qp q3 = p.fresh();
  m.setProblem(q3);
  const Belos::ReturnType r3 = m.solve();
  TEST_EQUALITY(r3, Belos::Converged);
  TEST_ASSERT(m.counters().history == byConstructor.counters().history);
  TEST_EQUALITY(m.counters().hessianMultiplications,
                byConstructor.counters().hessianMultiplications);

  // SMALBE: the same interface; achievedTol and achievedEqualityTol within the tolerances.
  auto Q = rcp(new MeanProjector(p.b->getMap()));
  Teuchos::ParameterList sp;
  sp.set("Relative tolerance", 1e-9);
  sp.set("Equality tolerance", 1e-9);
  const Qp s1 = p.fresh();
  Smalbe direct(s1, Q, sp);
  const Belos::ReturnType rs1 = direct.solve();
  TEST_EQUALITY(rs1, Belos::Converged);
  Smalbe s;
  TEST_ASSERT(contains(messageOf([&] { s.solve(); }), "setProblem"));
  s.setParameters(sp);
  const Qp s2 = p.fresh();
  s.setProblem(s2, Q);
  const Belos::ReturnType rs2 = s.solve();
  TEST_EQUALITY(rs2, Belos::Converged);
  TEST_ASSERT(local(*s2.x->getVector(0)) == local(*s1.x->getVector(0)));
  TEST_EQUALITY(s.getNumIters(), s.counters().outerIterations);
  TEST_COMPARE(s.getNumIters(), >, 0);
  TEST_COMPARE(s.achievedTol(), <=, 1e-9);
  TEST_COMPARE(s.achievedEqualityTol(), <=, 1e-9);
  TEST_EQUALITY(s.achievedEqualityTol(),
                s.getNormOfA() * s.counters().equalityResidualNorm / p.b->norm2());
  s.reset();
  TEST_EQUALITY(s.getNumIters(), 0);
  TEST_ASSERT(s.getMultiplier().is_null());
  const Qp s3 = p.fresh();
  s.setProblem(s3, Q);
  const Belos::ReturnType rs3 = s.solve();
  TEST_EQUALITY(rs3, Belos::Converged);
  TEST_ASSERT(s.counters().history == direct.counters().history);
}

// The text one solve writes to a FancyOStream with this "Verbosity" (rank 0; others: empty).
std::string outputOf(const ObstacleQp& p, int verbosity, int maxIterations = 10000) {
  std::ostringstream text;
  Teuchos::ParameterList params;
  params.set("Verbosity", verbosity);
  params.set("Maximum iterations", maxIterations);
  Mprgp m(p.fresh(), params);
  m.setOutputStream(Teuchos::fancyOStream(Teuchos::rcpFromRef(text)));
  m.solve();
  return text.str();
}

TEUCHOS_UNIT_TEST(SolverManagers, VerbosityAsBelosMask) {
  const auto p = obstacleQp(50);
  const std::string summary = outputOf(p, Belos::FinalSummary);
  const std::string steps = outputOf(p, Belos::IterationDetails | Belos::OrthoDetails);
  const std::string warnings = outputOf(p, Belos::Warnings | Belos::OrthoDetails, 2);
  const std::string quiet = outputOf(p, Belos::Warnings | Belos::OrthoDetails);
  const std::string timing = outputOf(p, Belos::TimingDetails);
  const std::string tests = outputOf(p, Belos::StatusTestDetails);
  const std::string level1 = outputOf(p, 1), level2 = outputOf(p, 2);
  out << summary << steps << warnings << timing << tests;
  if (root()) {
    TEST_ASSERT(contains(summary, "MPRGP: converged after"));
    TEST_ASSERT(!contains(summary, "  MPRGP "));
    TEST_ASSERT(contains(steps, "  MPRGP     1"));
    TEST_ASSERT(!contains(steps, "MPRGP: converged"));
    TEST_ASSERT(contains(warnings, "MPRGP: warning: not converged"));
    TEST_EQUALITY(quiet, "");  // converged: no warning
    TEST_ASSERT(contains(timing, "MPRGP: solve ") && contains(timing, "multiplications by A"));
    TEST_ASSERT(!contains(timing, "converged"));
    TEST_ASSERT(contains(tests, "MPRGP: status tests at the end") && contains(tests, "Passed"));
    // The package's levels: 1 the summary, 2 also every step.
    TEST_EQUALITY(level1, summary);
    TEST_ASSERT(contains(level2, "  MPRGP     1") && contains(level2, "MPRGP: converged after"));
  } else {
    TEST_EQUALITY(summary + steps + warnings + timing + tests + level1 + level2, "");
  }
  // Unknown bits and negative values: an error naming the parameter.
  Teuchos::ParameterList bad;
  bad.set("Verbosity", 128);
  const std::string m = messageOf([&] { Mprgp s(p.fresh(), bad); });
  TEST_ASSERT(contains(m, "Verbosity"));
  bad.set("Verbosity", -1);
  TEST_ASSERT(contains(messageOf([&] { Mprgp s(p.fresh(), bad); }), "Verbosity"));

  // Errors: written (when any output is asked for) and thrown.
  ObstacleQp nan = p;
  nan.b = rcp(new Vector(*p.b, Teuchos::Copy));
  nan.b->putScalar(std::numeric_limits<double>::quiet_NaN());
  std::ostringstream text;
  Teuchos::ParameterList params;
  params.set("Verbosity", int(Belos::FinalSummary));
  Mprgp s(nan.fresh(), params);
  s.setOutputStream(Teuchos::fancyOStream(Teuchos::rcpFromRef(text)));
  TEST_THROW(s.solve(), std::runtime_error);
  if (root()) TEST_ASSERT(contains(text.str(), "MPRGP: error: "));

  // SMALBE's types: a line per outer iteration, the summary, the final test.
  auto Q = rcp(new MeanProjector(p.b->getMap()));
  std::ostringstream st;
  Teuchos::ParameterList sp;
  sp.set("Verbosity", int(Belos::IterationDetails | Belos::StatusTestDetails));
  Smalbe sm(p.fresh(), Q, sp);
  sm.setOutputStream(Teuchos::fancyOStream(Teuchos::rcpFromRef(st)));
  sm.solve();
  if (root()) {
    TEST_ASSERT(contains(st.str(), "SMALBE    1"));
    TEST_ASSERT(contains(st.str(), "SMALBE: final test") && contains(st.str(), "Passed"));
    TEST_ASSERT(!contains(st.str(), "SMALBE: converged"));
  }
}

TEUCHOS_UNIT_TEST(SolverManagers, StdCoutStateNeverChanges) {
  const auto p = obstacleQp(40);
  auto Q = rcp(new MeanProjector(p.b->getMap()));
  const int all = tfeti::kAllMsgTypes;
  // std::cout as the caller left it, its text caught to keep the test log readable.
  std::ostringstream caught;
  std::streambuf* saved = std::cout.rdbuf(caught.rdbuf());
  std::cout << std::setprecision(13) << std::hex << std::showpos << std::left << std::setfill('#');
  const auto flags = std::cout.flags();
  Teuchos::ParameterList params;
  params.set("Verbosity", all);
  Mprgp(p.fresh(), params).solve();
  params.set("Maximum iterations", 2);
  Mprgp(p.fresh(), params).solve();
  Teuchos::ParameterList sp;
  sp.set("Verbosity", all);
  sp.sublist("MPRGP").set("Verbosity", all);
  Smalbe(p.fresh(), Q, sp).solve();
  const auto precision = std::cout.precision();
  const auto flagsAfter = std::cout.flags();
  const char fill = std::cout.fill();
  std::cout.flags(std::ios_base::fmtflags{});
  std::cout.rdbuf(saved);
  TEST_EQUALITY(precision, 13);
  TEST_ASSERT(flagsAfter == flags);
  TEST_EQUALITY(fill, '#');
  if (root()) {
    TEST_ASSERT(contains(caught.str(), "MPRGP: solve "));
    TEST_ASSERT(contains(caught.str(), "SMALBE: converged"));
  }
  std::cout << std::dec << std::noshowpos << std::right << std::setfill(' ')
            << std::setprecision(6);
}

TEUCHOS_UNIT_TEST(SolverManagers, TimersCountEveryMultiplication) {
  const auto p = obstacleQp(70);
  const double mprgp0 = calls("tfeti: MPRGP solve"), hess0 = calls("tfeti: Hessian apply");
  Mprgp m(p.fresh(), Teuchos::ParameterList());
  m.solve();
  TEST_EQUALITY(calls("tfeti: MPRGP solve"), mprgp0 + 1);
  TEST_EQUALITY(calls("tfeti: Hessian apply"), hess0 + double(m.counters().hessianMultiplications));

  // b = 0: the multiplication for the scale is counted and timed too.
  ObstacleQp zero = p;
  zero.b = rcp(new Vector(p.b->getMap()));
  Mprgp mz(zero.fresh(), Teuchos::ParameterList());
  const double hz = calls("tfeti: Hessian apply");
  mz.solve();
  TEST_EQUALITY(calls("tfeti: Hessian apply"), hz + double(mz.counters().hessianMultiplications));

  auto Q = rcp(new MeanProjector(p.b->getMap()));
  const double smalbe0 = calls("tfeti: SMALBE solve"), mprgp1 = calls("tfeti: MPRGP solve"),
               hess1 = calls("tfeti: Hessian apply");
  Smalbe s(p.fresh(), Q, Teuchos::ParameterList());
  s.solve();
  TEST_EQUALITY(calls("tfeti: SMALBE solve"), smalbe0 + 1);
  TEST_EQUALITY(calls("tfeti: MPRGP solve"), mprgp1 + s.counters().outerIterations);
  TEST_EQUALITY(calls("tfeti: Hessian apply"), hess1 + double(s.counters().hessianMultiplications));
  std::ostringstream summary;
  Teuchos::TimeMonitor::summarize(summary);
  if (root()) TEST_ASSERT(contains(summary.str(), "tfeti: Hessian apply"));  // rank 0 prints
}

}  // namespace
