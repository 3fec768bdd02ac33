// FetiSolver's parameters: the valid list with the FETI defaults of the QP solvers, the checks
// and aliases applied before validation, and the choices read from a validated list.
#include <Teuchos_StandardParameterEntryValidators.hpp>

#include "tfeti_FetiSolver.hpp"
#include "tfeti_LocalSolver.hpp"
#include "tfeti_MprgpSolMgr_decl.hpp"
#include "tfeti_SmalbeSolMgr_decl.hpp"
#include "tfeti_SolverConventions.hpp"
#include "tfeti_StrictParameters.hpp"

namespace tfeti {

namespace {
using strict::choice;

// The method's choices: formulation, gluing, scaling, preconditioner, the local and coarse
// solvers, the dual solver and the meaning of the inequality rows.
void addMethodChoices(Teuchos::ParameterList& pl) {
  pl.set("Formulation", "TFETI",
         "TFETI: Dirichlet conditions as multipliers, every subdomain floats; FETI: Dirichlet "
         "dofs eliminated in K",
         choice({"TFETI", "FETI"}));
  pl.set("Kernel tolerance", 1e-8,
         "largest ||K R|| / ||K|| accepted for the kernel R of a subdomain matrix K (rigid "
         "modes of its pieces, or the kernel supplied); above it the subdomain is an error");
  pl.set("Gluing", "nonredundant",
         "nonredundant: m-1 rows at a node shared by m subdomains; redundant: m(m-1)/2; "
         "none: no gluing rows (the caller's equality rows join the subdomains)",
         choice({"nonredundant", "redundant", "none"}));
  pl.set("Gluing at Dirichlet nodes", true,
         "keep gluing rows at interface nodes on the Dirichlet boundary (the paper's count; "
         "in TFETI they duplicate the Dirichlet rows)");
  pl.set("Inequality row scaling", "joined",
         "the preconditioner's scaling (B B^T)^+ of the inequality rows: joined: each joins "
         "the scaling group of the rows it shares dofs with (a tied or contact row on a node "
         "a cut shares joins the node's gluing rows); separate: each row its own group",
         choice({"joined", "separate"}));
  pl.set("Preconditioner", "dirichlet", "dual preconditioner",
         choice({"dirichlet", "lumped", "none"}));
  std::vector<std::string> solvers = localSolverTypes();
  // "cholmod-simplicial" took 23-28 % less CPU time than "cholmod" (CHOLMOD's own choice,
  // supernodal) on the 3D subdomain matrices with this machine's reference BLAS; with OpenBLAS
  // the supernodal choice was faster still (docs/benchmarks.md, "3D setup profile"), so the
  // better default depends on the BLAS installed and stays until measured on every case. G G^T is
  // one larger matrix with large dense fronts: its own parameter, so that forcing the subdomains'
  // kind does not force the coarse one.
  pl.set("Local solver", "cholmod", "sparse direct solver of the subdomain problems",
         choice(solvers));
  pl.set("Coarse solver", "cholmod",
         "sparse direct solver of the coarse problem G G^T (replicated on every rank)",
         choice(solvers));
  pl.set("Dual solver", "auto",
         "auto: PCPG without inequality rows, SMALBE with them; PCPG: projected CG "
         "(equality constraints only); SMALBE: augmented Lagrangian with MPRGP inner solves; "
         "penalty: MPRGP on P F P + rho Q (the reference paper's choice)",
         choice({"auto", "PCPG", "SMALBE", "penalty"}));
  pl.set("Dual operator", "implicit",
         "how F = B K+ B^T is applied: implicit: B^T, the subdomain factors' triangular solves, "
         "B; explicit: every subdomain's F_s = B_s K_s+ B_s^T assembled once as a dense "
         "matrix and applied by BLAS-2; auto: explicit with Explicit device = gpu, and on the "
         "host when the dual problem is a QP (inequality rows) and the F_s take fewer bytes "
         "than the subdomain factors, implicit otherwise (docs/dual_operator.md)",
         choice({"implicit", "explicit", "auto"}));
  pl.set("Explicit storage", "packed",
         "Dual operator = explicit: the dense F_s as the packed upper triangle (half the "
         "bytes) or the full square; with Explicit device = gpu, packed is the upper triangle "
         "by 32 x 32 tiles on the device (docs/dual_operator.md)",
         choice({"packed", "full"}));
  pl.set("Explicit assembly", "schur",
         "Dual operator = explicit: how each F_s is assembled: schur: from the inverse of the "
         "Schur complement of K_reg onto the dofs B_s touches (a factorization with those dofs "
         "last, then dense LAPACK); solves: K+ applied to the columns of B_s^T. Local solvers "
         "other than CHOLMOD, and K released, take the solves (docs/dual_operator.md)",
         choice({"schur", "solves"}));
  pl.set("Explicit device", "host",
         "Dual operator = explicit: where the F_s are applied: host (BLAS-2 per subdomain) or "
         "gpu (kept on a CUDA device, one batched product per apply; a TFETI_ENABLE_CUDA build, "
         "docs/dual_operator.md)",
         choice({"host", "gpu"}));
  pl.set("Explicit export file", "",
         "Dual operator = explicit: when not empty, every rank writes its F_s to "
         "<value>.rank<r>.bin after each assembly (the format of gpu/README.md)");
  pl.set("Inequality rows", "inequalities",
         "inequalities: B_I u <= c_I with lambda_I >= 0 (frictionless contact); equalities: "
         "B_I u = c_I with lambda_I free (the pair tied: bonded bodies, the gap closed), a "
         "linear problem that \"Dual solver\" = auto solves by PCPG",
         choice({"inequalities", "equalities"}));
}

// MPRGP's fixed expansion step 1.9 / ||P F P + rho Q|| = 1.9 / rho hardly moves the iterate
// when rho >> ||P F P||; the projected CG step is set by the curvature along the
// (preconditioned) direction instead (docs/qp_solvers.md: penalty method, 8192 subdomains,
// 1066 -> 281 multiplications).
void setProjectedCgExpansion(Teuchos::ParameterList& mprgp) {
  auto& entry = mprgp.getEntry("Expansion step");
  entry.setValue<std::string>("projected CG", false,
                              "FETI default: projected CG (the component's: fixed)",
                              entry.validator());
}

// SMALBE's parameters with the FETI defaults.
void setSmalbeDefaults(Teuchos::ParameterList& smalbe) {
  smalbe.setParameters(*SmalbeSolMgr<Scalar, MultiVector, Operator>::getValidParameters());
  // Measured (docs/qp_solvers.md): rho = ||P F P|| needs up to 100 outer iterations on the
  // two-membrane problem; with the projected CG expansion rho = 10 ||P F P|| gives the fewest
  // multiplications (8192 subdomains: 117 against 157 at 100 ||P F P||; 101k-unknown
  // two-cylinder case: 306 against 587), at the price of more, cheap, outer iterations.
  smalbe.set("Penalty", 10.0,
             "rho = value * ||P F P|| (FETI default 10; the component's default is 1)",
             strict::positive());
  setProjectedCgExpansion(smalbe.sublist("MPRGP"));
  // The contact rows' gaps order the face of smooth convex bodies: the level search finds it in
  // about log2(rows) loose face solves where MPRGP's expansion steps open a row or two each
  // (docs/qp_solvers.md: two cylinders at 1M unknowns, 765 -> 143 multiplications). Used only
  // with "Face solve" = pcpg, and only for frictionless contact without a warm start.
  // Once the active set settles, the face PCPG replaces the tail of SMALBE's outer iterations
  // (docs/qp_solvers.md: two cylinders 101k-4M unknowns, 112-232 multiplications with the
  // level search against 223-1421 for SMALBE alone); the result is accepted only by SMALBE's
  // final test, so SMALBE alone remains the fallback.
  {
    auto& entry = smalbe.getEntry("Face solve");
    entry.setValue<std::string>("pcpg", false, "FETI default: pcpg (the component's: none)",
                                entry.validator());
  }
  // With the loose verdicts a face tried after every outer iteration is cheap, and its
  // active-set steps settle the face faster than the outer iterations do (two membranes,
  // 8192 subdomains, H/h = 32: 11 -> 1 outer iteration, 111 -> 67 multiplications).
  smalbe.set("Face settle iterations", 0,
             "FETI default 0: a face solve after every outer iteration (the component's: 1)",
             strict::count(0));
  {
    auto& entry = smalbe.getEntry("Initial face");
    entry.setValue<std::string>("levels", false,
                                "FETI default: levels, the contact rows' gaps, for a cold start; "
                                "a warm start (the Newton loop's previous QP) starts from the "
                                "previous solution's active set (start), except with 2D "
                                "friction's boxes; none: neither (the component's default)",
                                entry.validator());
  }
  // At rho = 10 ||P F P|| the outer iterations grow with the subdomains per side (25 at 64 x 64
  // per membrane, 35 at 88 x 88; 3-6 multiplications each): the component's limit of 100
  // would be reached near 250 x 250.
  smalbe.set("Maximum outer iterations", 1000,
             "limit on multiplier updates (FETI default 1000; the component's default is 100)",
             strict::count());
}

void addPenaltyParameters(Teuchos::ParameterList& pen) {
  pen.set("Penalty", 1e4,
          "rho relative to the estimate of ||P F P||; the constraint error G lambda falls like "
          "1/rho (about 1e-5 relative at the default)",
          strict::positive());
  pen.set("Power iterations", 20, "power iterations for the estimate of ||P F P||",
          strict::count());
  pen.set("Equality projection", true,
          "true: the penalty solution is projected onto G lambda = e (mu <- P mu), so every "
          "subdomain's rigid-mode balance holds to rounding and a Newton loop's residual can fall "
          "below the penalty's ~1/rho; the bounds are then off by at most the ||Q mu|| removed "
          "(summary: equality_projection_norm). false: the reference paper's plain penalty");
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

void FetiSolver::rejectMisplacedParameters(const Teuchos::ParameterList& feti) {
  const auto misplaced = [&](const Teuchos::ParameterList& list, const std::string& path) {
    if (list.isParameter(kPreconditioningInFace))
      throw std::invalid_argument(
          "FETI: \"" + std::string(kPreconditioningInFace) + "\" is set in the " + path +
          " sublist; it belongs to the FETI list itself (one switch for MPRGP alone and inside "
          "SMALBE): move it there");
  };
  if (feti.isSublist("MPRGP")) misplaced(feti.sublist("MPRGP"), "\"MPRGP\"");
  if (feti.isSublist("SMALBE") && feti.sublist("SMALBE").isSublist("MPRGP"))
    misplaced(feti.sublist("SMALBE").sublist("MPRGP"), "\"SMALBE\" / \"MPRGP\"");
}

void FetiSolver::applySolverAliases(Teuchos::ParameterList& feti) {
  const auto apply = [&](const std::vector<std::string>& path, const std::string& maxIterations) {
    Teuchos::ParameterList* list = &feti;
    std::string name;
    for (const std::string& p : path) {
      if (!list->isSublist(p)) return;
      list = &list->sublist(p);
      name += (name.empty() ? "" : "/") + p;
    }
    applyParameterAliases(*list, "FETI/" + name, belosAliases(maxIterations));
  };
  apply({"PCPG"}, "Maximum iterations");
  apply({"MPRGP"}, "Maximum iterations");
  apply({"SMALBE"}, "Maximum outer iterations");
  apply({"SMALBE", "MPRGP"}, "Maximum iterations");
}

Teuchos::RCP<const Teuchos::ParameterList> FetiSolver::validParameters() {
  static Teuchos::RCP<Teuchos::ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::rcp(new Teuchos::ParameterList("FETI"));
    addMethodChoices(*pl);
    pl->sublist("PCPG").setParameters(*Pcpg::validParameters());
    pl->sublist("MPRGP").setParameters(
        *MprgpSolMgr<Scalar, MultiVector, Operator>::getValidParameters());
    setProjectedCgExpansion(pl->sublist("MPRGP"));
    auto& smalbe = pl->sublist("SMALBE");
    setSmalbeDefaults(smalbe);
    // One switch for MPRGP's preconditioner, alone or inside SMALBE: the FETI list's own
    // "Preconditioning in face" below (the sublists would only contradict it).
    pl->sublist("MPRGP").remove(kPreconditioningInFace);
    smalbe.sublist("MPRGP").remove(kPreconditioningInFace);
    addPenaltyParameters(pl->sublist("Penalty", false, "Dual solver = penalty"));
    pl->set(
        kPreconditioningInFace, true,
        "SMALBE / penalty: precondition MPRGP's conjugate gradient steps by P M P + Q / rho (M the "
        "chosen dual preconditioner) restricted to the free set");
    pl->set("Initial equality multiplier", "gap",
            "SMALBE's first multiplier of G lambda = e (unless warm-started): zero, or gap: Q c_I, "
            "the multiplier at which lambda = 0 is the solution when no load acts (c_I the gaps "
            "of the inequality rows; at the solution it is Q (c - B u), the gaps left open)",
            choice({"gap", "zero"}));
    pl->set("Keep subdomain matrices", true,
            "false: free each subdomain matrix K once its preconditioner is set up (a linear "
            "solve needs it no more; about 200 bytes per unknown in 2D); update() then cannot "
            "rebuild a preconditioner whose interface dofs changed");
    pl->set("Memory check", true,
            "before the subdomain factorizations and before the explicit F_s are allocated, "
            "compare what the ranks of each node (host) need with its MemAvailable "
            "(/proc/meminfo) and stop with an error where some node falls short (auto: implicit "
            "instead of explicit), rather than be killed by the kernel's OOM killer; false: go "
            "on regardless (swap, or memory the kernel will free that it does not count as "
            "available)");
    pl->set("Warm power iterations", 0,
            "after a refactorization (a Newton method's new tangent) estimate ||P F P|| by this "
            "many power iterations from the last estimate's vector, when the dual dimension is "
            "unchanged, instead of SMALBE's / Penalty's \"Power iterations\" from a fixed "
            "start; 0: always from the fixed start",
            strict::count(0));
    pl->set("Inexact face relative tolerance", 0.01,
            "SMALBE in an inexact Newton QP (a tolerance factor above 1, setToleranceFactor): "
            "the face CG stops at ||P_F g|| <= max(value, SMALBE's \"Face relative tolerance\") "
            "* tol * ||b||; the gluing residual it leaves is closed by the next increment, and "
            "the step's last QP (factor 1) keeps the face relative tolerance. 0.3 saves a third "
            "of the multiplications on step-42's indentation but costs Newton iterations on the "
            "force-driven plastic Hertz sphere (docs/nonlinear_contact.md), hence the default "
            "0.01: as in an exact QP",
            strict::between(0.0, 1.0, true, false));
    pl->set("Warm start", true,
            "SMALBE / penalty after update(): start from the multipliers of the previous solve "
            "(projected onto G lambda = e and the bounds) when the dual dimension is unchanged");
  }
  return pl;
}

bool FetiSolver::inequalitiesTied(const Teuchos::ParameterList& feti) {
  return feti.isParameter("Inequality rows") &&
         feti.get<std::string>("Inequality rows") == "equalities";
}

std::string FetiSolver::dualSolverFor(const Teuchos::ParameterList& feti, GO inequalityRows) {
  // Tied inequality rows are equality rows: no bound constrains their multipliers.
  if (inequalitiesTied(feti)) inequalityRows = 0;
  std::string method = feti.get<std::string>("Dual solver");
  if (method == "auto") method = inequalityRows > 0 ? "SMALBE" : "PCPG";
  if (method == "PCPG" && inequalityRows > 0)
    throw std::invalid_argument(
        "FETI: \"Dual solver\" = PCPG handles equality constraints only, but the problem has " +
        std::to_string(inequalityRows) + " inequality (contact) rows: choose SMALBE or penalty");
  return method;
}
}  // namespace tfeti
