// The solvers as a library (issue 17) on 1, 2 and 3 ranks:
//  - "Verbosity" 2 of PCPG, MPRGP and SMALBE never changes std::cout's format state, and the
//    progress lines go to the caller's Teuchos::FancyOStream when one is given (nothing to
//    std::cout then);
//  - "Preconditioning in face" is one parameter of the FETI list: switched off or on it gives the
//    same contact solution, and the spelling in the MPRGP sublists is an error saying where it
//    belongs.
// The problem: the unit square of plane-strain elasticity (2 x 2 subdomains of 4 x 4 elements)
// clamped at x = 0 and sagging under its weight onto an obstacle below its right half.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

using tfeti_test::contains;

tfeti::StructuredRectangle square() {
  return tfeti::StructuredRectangle(0, 1, 0, 1, 2, 2, 4, 4);
}

// -u_y <= gap at the nodes of y = 0 with x >= 0.5 (rank 0 contributes every row).
std::vector<tfeti::InequalityRow> obstacle(const tfeti::Comm& comm, double gap) {
  std::vector<tfeti::InequalityRow> rows;
  if (comm.getRank() != 0) return rows;
  const auto rect = square();
  for (int s = 0; s < rect.numSubdomains(); ++s) {
    const tfeti::SubdomainMesh m = rect.subdomain(s);
    for (int n = 0; n < m.numNodes(); ++n)
      if (m.coords[2 * n + 1] == 0.0 && m.coords[2 * n] >= 0.5)
        rows.push_back({{{s, 2 * n + 1, -1.0}}, gap});
  }
  return rows;
}

Teuchos::ParameterList contactParameters(const std::string& method, bool inFace) {
  Teuchos::ParameterList p;
  p.set("Dual solver", method);
  p.set("Preconditioning in face", inFace);
  p.sublist("SMALBE").set("Relative tolerance", 1e-10);
  p.sublist("SMALBE").set("Equality tolerance", 1e-10);
  p.sublist("MPRGP").set("Relative tolerance", 1e-10);
  return p;
}

// All local subdomain solutions, concatenated.
std::vector<double> solution(const tfeti::FetiSolver& solver) {
  std::vector<double> u;
  for (std::size_t i = 0; i < solver.data().size(); ++i)
    u.insert(u.end(), solver.solution(i).begin(), solver.solution(i).end());
  return u;
}

// The gap that lets the right half of the bottom edge touch: 30 % of its free sag.
double halfSagGap(const tfeti::Comm& comm) {
  auto rcomm = Tpetra::getDefaultComm();
  const auto rect = square();
  Teuchos::ParameterList p;
  tfeti::FetiSolver unconstrained(rcomm, rect.numSubdomains(),
                                  tfeti_test::localSubdomains(rect, comm, tfeti_test::elasticity()),
                                  p);
  unconstrained.solve();
  double sag = 0.0;
  for (std::size_t i = 0; i < unconstrained.data().size(); ++i) {
    const auto& m = unconstrained.data()[i].mesh;
    for (int n = 0; n < m.numNodes(); ++n)
      if (m.coords[2 * n + 1] == 0.0) sag = std::max(sag, -unconstrained.solution(i)[2 * n + 1]);
  }
  return 0.3 * tfeti_test::globalMax(comm, sag);
}

struct FormatState {
  std::streamsize precision, width;
  std::ios_base::fmtflags flags;
  explicit FormatState(const std::ostream& os)
      : precision(os.precision()), width(os.width()), flags(os.flags()) {}
  bool operator==(const FormatState& o) const {
    return precision == o.precision && width == o.width && flags == o.flags;
  }
};

// Runs f with std::cout writing into a buffer; returns what was written.
std::string capturingCout(const std::function<void()>& f) {
  std::ostringstream captured;
  std::streambuf* old = std::cout.rdbuf(captured.rdbuf());
  try {
    f();
  } catch (...) {
    std::cout.rdbuf(old);
    throw;
  }
  std::cout.rdbuf(old);
  return captured.str();
}

}  // namespace

TEUCHOS_UNIT_TEST(SolverOutput, VerboseSolvesLeaveStdCoutAsTheCallerSetIt) {
  auto comm = Tpetra::getDefaultComm();
  const auto rect = square();
  const double gap = halfSagGap(*comm);
  const bool root = comm->getRank() == 0;
  std::cout << std::setprecision(11) << std::fixed << std::showpos;
  const FormatState before(std::cout);
  for (const std::string method : {"PCPG", "SMALBE", "penalty"})
    for (bool userStream : {false, true}) {
      Teuchos::ParameterList p = contactParameters(method, true);
      p.sublist("PCPG").set("Verbosity", 2);
      p.sublist("SMALBE").set("Verbosity", 2);
      p.sublist("SMALBE").sublist("MPRGP").set("Verbosity", 2);
      p.sublist("MPRGP").set("Verbosity", 2);
      tfeti::FetiSolver solver(
          comm, rect.numSubdomains(),
          tfeti_test::localSubdomains(rect, *comm, tfeti_test::elasticity()), p,
          method == "PCPG" ? std::vector<tfeti::InequalityRow>{} : obstacle(*comm, gap));
      std::ostringstream mine;
      if (userStream) solver.setOutputStream(Teuchos::fancyOStream(Teuchos::rcpFromRef(mine)));
      bool converged = false;
      const std::string onCout = capturingCout([&] { converged = solver.solve().converged; });
      TEST_ASSERT(converged);
      TEST_ASSERT(FormatState(std::cout) == before);
      const std::string& printed = userStream ? mine.str() : onCout;
      const std::string tag = method == "PCPG"     ? "  PCPG "
                              : method == "SMALBE" ? "SMALBE "
                                                   : "  MPRGP ";
      out << method << (userStream ? " to the user's stream" : " to std::cout") << ": "
          << printed.size() << " characters\n";
      TEST_EQUALITY(contains(printed, tag), root);  // progress lines on rank 0 only
      if (userStream) TEST_EQUALITY(onCout, "");
      // The lines are in the solvers' own format (3 significant digits in scientific notation),
      // not in the caller's fixed notation with 11 digits.
      if (root) TEST_ASSERT(contains(printed, "e-"));
    }
  std::cout << std::setprecision(6) << std::defaultfloat << std::noshowpos;
}

TEUCHOS_UNIT_TEST(SolverOutput, PreconditioningInFaceIsOneParameter) {
  auto comm = Tpetra::getDefaultComm();
  const auto rect = square();
  const double gap = halfSagGap(*comm);
  const auto rows = obstacle(*comm, gap);
  for (const std::string method : {"SMALBE", "penalty"}) {
    std::vector<double> u[2];
    long long active[2] = {0, 0};
    int steps[2] = {0, 0};
    for (bool inFace : {false, true}) {
      tfeti::FetiSolver solver(comm, rect.numSubdomains(),
                               tfeti_test::localSubdomains(rect, *comm, tfeti_test::elasticity()),
                               contactParameters(method, inFace), rows);
      const tfeti::DualResult r = solver.solve();
      TEST_ASSERT(r.converged);
      u[inFace] = solution(solver);
      const tfeti::ConstraintReport c = solver.constraintReport();
      active[inFace] = c.activeRows;
      steps[inFace] = r.iterations;
      out << method << ", in face " << inFace << ": " << r.iterations << " MPRGP steps, "
          << c.activeRows << " of " << c.inequalityRows << " rows active, penetration "
          << c.maxPenetration << "\n";
      TEST_COMPARE(c.activeRows, >, 0);
      TEST_COMPARE(c.activeRows, <, c.inequalityRows);
      // SMALBE meets G lambda = e to its tolerance; the penalty method to about 1e-5 relative
      // at its default rho.
      TEST_COMPARE(c.maxPenetration, <=, (method == "SMALBE" ? 1e-6 : 1e-3) * gap);
    }
    // The preconditioner changes the path, not the solution.
    double diff = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < u[0].size(); ++i) {
      diff = std::max(diff, std::abs(u[0][i] - u[1][i]));
      scale = std::max(scale, std::abs(u[1][i]));
    }
    TEST_COMPARE(tfeti_test::globalMax(*comm, diff), <=,
                 1e-6 * tfeti_test::globalMax(*comm, scale));
    TEST_EQUALITY(active[0], active[1]);
    // ... and the switch does switch: the paths differ.
    TEST_INEQUALITY(steps[0], steps[1]);
  }
  // The old nested spellings are errors that say where the parameter belongs.
  for (bool value : {false, true})
    for (bool inSmalbe : {false, true}) {
      Teuchos::ParameterList p = contactParameters("SMALBE", !value);
      (inSmalbe ? p.sublist("SMALBE").sublist("MPRGP") : p.sublist("MPRGP"))
          .set("Preconditioning in face", value);
      const std::string m = tfeti_test::messageOf([&] {
        tfeti::FetiSolver solver(comm, rect.numSubdomains(),
                                 tfeti_test::localSubdomains(rect, *comm, tfeti_test::elasticity()),
                                 p, rows);
      });
      out << m << "\n";
      TEST_ASSERT(contains(m, inSmalbe ? "is set in the \"SMALBE\" / \"MPRGP\" sublist"
                                       : "is set in the \"MPRGP\" sublist"));
      TEST_ASSERT(contains(m, "it belongs to the FETI list itself"));
    }
  // The FETI list documents one parameter.
  const auto valid = tfeti::FetiSolver::validParameters();
  TEST_ASSERT(valid->isParameter("Preconditioning in face"));
  TEST_ASSERT(!valid->sublist("MPRGP").isParameter("Preconditioning in face"));
  TEST_ASSERT(!valid->sublist("SMALBE").sublist("MPRGP").isParameter("Preconditioning in face"));
}
