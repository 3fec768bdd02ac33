#!/usr/bin/env python3
"""Checks a tfeti_contact summary.json against what the method must deliver.

  check_summary.py scalability DIR [--reference-H 4] [--check tfeti:dirichlet,feti:lumped,...]
                                          dimensions equal their closed forms (any dimension)
                                          and, for 2D Poisson, the reference paper's table
                                          exactly; numerical scalability: at fixed H/h the
                                          iterations of each checked formulation:preconditioner
                                          stay within GROWTH times the count at H = 1/reference
  check_summary.py single DIR [--max-error E]
                                          converged, error against the direct solve below E
  check_summary.py same DIR1 DIR2 ...     identical iteration counts, residual histories and
                                          solution norms to rounding (different rank counts)
  check_summary.py diverged DIR           the run reported non-convergence (converged = false)
  check_summary.py same_dual_operator IMPLICIT EXPLICIT [EXPLICIT2 ...] [--tol T] [--device D]
                                     [--partial] [--mult-tol F] [--assembly schur|solves]
                                          FETI "Dual operator" = explicit against implicit:
                                          dual_operator and the F_s bytes reported (0 when
                                          implicit; total >= largest rank's > 0 when explicit),
                                          the same iterations (PCPG), outer iterations and
                                          Hessian multiplications (QP) or nonlinear iterations
                                          and multiplications to 1 % (nonlinear_contact), the
                                          same contact force, solution norm,
                                          max |u|, contact.csv and contact_pressure.csv (when
                                          written) to T (1e-10) relative to their scale;
                                          explicit_device is D (host; with gpu every F apply
                                          on the device and explicit_device_work reported);
                                          a QP's multiplications to F (0.01); schur_blocks
                                          in (0, blocks] (schur) or 0 (solves)
  check_summary.py dual_operator_auto DIR --chosen implicit|explicit [--fits-memory true|false]
                                          FETI "Dual operator" = auto: converged with that
                                          operator, which the rule gives from the reported
                                          dual_operator_auto (QP, F_s and factor bytes) and
                                          explicit_memory_check (the F_s within the nodes'
                                          memory: --fits-memory, default true)
  check_summary.py factor_memory DIR --checked true|false [--write-meminfo FILE]
                   [--write-meminfo-edges PREFIX]
                                          factor_memory_check: made or not as expected; where
                                          made, the subdomain factors' held bytes at least the
                                          bytes they stream (factor_bytes), and fits exactly when
                                          the need is within the available bytes; the same of
                                          preconditioner_memory_check where made; FILE: a
                                          meminfo whose MemAvailable is that need to the KiB
                                          above (a node with room for the factors alone);
                                          PREFIX_factors_short: one KiB below it;
                                          PREFIX_with_preconditioner(_short): what the factors
                                          hold (node_held_bytes) and the preconditioner's need
                                          summed, to the KiB above (below)
  check_summary.py explicit_export DIR FILE [FILE ...]
                                          the F_s blocks a run exported (FETI "Explicit
                                          export file"), read as gpu/ reads them: header, one
                                          block per subdomain, symmetric, diagonal >= 0,
                                          their packed bytes equal to explicit_dual_bytes
  check_summary.py prescribed DIR (--reaction R | --contact-force) [--tol T] [--residual E]
                                          prescribed displacements: converged, B_E u = c_E to
                                          E (1e-8) of max |u|, the first prescribed entry's reaction
                                          equals R (or minus the contact force) to T (1e-8)
  check_summary.py contact DIR [--force-tol T]
                                          converged; the contact conditions of the recovered
                                          solution (no penetration, lambda >= 0,
                                          complementarity, gluing) to 1e-6 of the solution's
                                          scale; the contact force balances the load to T
  check_summary.py patch DIR [DIR2 ...] --pressure P [--tol T]
                                          the contact patch test: converged, the contact
                                          conditions (contact), and every row's pressure and
                                          recovered pressure in contact_pressure.csv equal to P
                                          to T (1e-8) relative,
                                          in every DIR (other rank counts)
  check_summary.py same_contact [--solution-only] DIR1 DIR2 ...
                                          the same outer iterations and Hessian multiplications
                                          to 10 % (unless --solution-only) and the same solution
                                          along the contact side (contact.csv)
  check_summary.py hertz DIR [DIR2 ...] [--p-tol T] [--extent-tol T] [--estar E] [--force-tol F]
                    [--vm-tol T] [--recovered]
                                          elastic contact against Hertz: p_max within 3 % (T),
                                          the half-width (2D) or contact radius (3D) within 5 %
                                          (T), the force balances the load to F (1e-6), the contact
                                          conditions hold; further DIRs (other rank counts) give
                                          the same p_max and extent; with --vm-tol, the
                                          max von Mises within T of Hertz's; with --estar, the
                                          summary's Hertz line contact is the closed form with
                                          that combined modulus E* (1e-9 relative); with
                                          --recovered, the recovered p_max and the nodal max von
                                          Mises take the place of the raw ones (and agree across
                                          DIRs to 1e-5)
  check_summary.py plane_strain DIR_2D DIR_3D [DIR_3D ...] [--tol T] [--u-tol U]
                                          a 3D slab (the 2D mesh extruded, symmetry planes on
                                          its end faces, Contact zone line) against the 2D run:
                                          the same contact keys; p_max and the half-width (the
                                          mean and every node plane's) within T of the 2D ones;
                                          the same applied force per unit length (1e-9); the
                                          solution independent of z: |u_z| and the in-plane
                                          displacement's difference from the 2D one at the same
                                          (x, y) of the same body below U max|u| (solution_*.vtu)
  check_summary.py membranes_scaling DIR [DIR2 ...]
                                          all converged; for each H/h the Hessian
                                          multiplications of SMALBE stay below MEMBRANE_GROWTH
                                          times their count at the coarsest level; the contact
                                          force balances the load (SMALBE to 1e-5, the penalty
                                          method, whose error falls like 1/rho, to 1e-4);
                                          every row meets the contact conditions; further
                                          DIRs (other rank counts) have the same counts
  check_summary.py nonlinear DIR [--force-tol T] [--hertz-tol T]
                                          a nonlinear_contact run reached load factor 1; every
                                          step has the keys issue 5 names and its last
                                          iteration meets Eta 1 and Eta 2; the last QP solve
                                          meets the contact conditions; the resultant contact
                                          force balances the load and the fixed boundaries'
                                          reaction to T; with Hertz, p_max and
                                          the half-width within the given tolerance
  check_summary.py bounded_iterations --max N DIR1 [DIR2 ...]
                                          a tied run (Contact type = tied, PCPG): converged,
                                          B u = c on the gluing and tied rows to 1e-6 of
                                          max|u|, at most N iterations, and the same count and
                                          max|u| (1e-6) in every DIR (other rank counts)
  check_summary.py bounded_multiplications --max N DIR1 [DIR2 ...]
                                          a nonlinear run: converged, at most N Hessian
                                          multiplications over all its QPs, the same count in
                                          every DIR (other rank counts)
  check_summary.py tightened_qps DIR        a nonlinear run converged with some QPs solved tighter
                                          than configured (iterations.csv's
                                          qp_tolerance_factor below 1), its last one among them,
                                          none before the residual met Eta 2
  check_summary.py same_nonlinear DIR1 DIR2 ...
                                          the same load steps and, per step, p_max, contact
                                          extent and max von Mises to 1e-5, max plastic strain
                                          to 1e-3
                                          (other rank counts, or a run continued by restart)
                                          and, when DIR1 is frictional, the friction results:
                                          the resultant contact force, the largest accumulated
                                          and net slip, per node (final and per-step contact
                                          CSVs) the contact force's components, slip
                                          increment, accumulated and net slip to 1e-5 of the
                                          column's largest value, the same states
  check_summary.py friction_fields DIR    the accumulated slip step by step (per-step CSVs) and
                                          the VTU's friction point data against the CSV
  check_summary.py tresca_bonded TRESCA BONDED [--tol T]
                                          Tresca with a huge slip bound against the pair
                                          bonded: both closed and sticking everywhere, the
                                          reactions, tangential force and displacements to T
  check_summary.py nonlinear_vs_elastic NONLINEAR ELASTIC [--tol T] [--force-tol F]
                                          a one-step nonlinear run of a linear elastic material
                                          against the elastic contact run: p_max and the contact
                                          extent within T, the force within F (1e-6)
  check_summary.py newton NEWTON REFERENCE [--tol T]
                                          the same problem with the tangent refactorized
                                          (Stiffness iteration or step) and with the paper's
                                          initial stiffness: both reach load factor 1 with the
                                          same steps; the final p_max, contact extent, force
                                          and von Mises agree to T (1e-4), the plastic strain
                                          to 100 T; the tangent needs fewer iterations
  check_summary.py penalty_vs_smalbe PENALTY_DIR SMALBE_DIR [--tol T]
  check_summary.py same_indentation DIR1 DIR2 [--tol T]
                                          two runs of one indentation (e.g. gaps along the
                                          normal and along a fixed direction): both reached
                                          load factor 1; contact force and extent agree to T
  check_summary.py plastic DIR            plastic strain > 0, von Mises within 1 % of the yield
                                          surface sigma_Y + H alpha at every step
  check_summary.py plastic_vs_elastic PLASTIC ELASTIC
                                          the same overload: the elastic run exceeds yield, the
                                          plastic one yields (plastic strain > 0), caps von
                                          Mises near sigma_Y and has a lower p_max
  check_summary.py arc_grows DIR_0.9 DIR_0.99
                                          pin-hole: the contact half-angle of the conforming
                                          pin is larger
"""
import csv
import json
import math
import os
import sys

# The reference paper, "Numerical experiments: Scalability": (1/H, 1/h) -> primal, FETI, TFETI.
PAPER = {
    (2, 4): (36, 11, 17), (4, 8): (144, 63, 75), (8, 16): (576, 287, 311),
    (16, 32): (2304, 1215, 1263), (2, 8): (100, 19, 29), (4, 16): (400, 111, 131),
    (8, 32): (1600, 511, 551), (16, 64): (6400, 2175, 2255), (2, 16): (324, 35, 53),
    (4, 32): (1296, 207, 243), (8, 64): (5184, 959, 1031), (16, 128): (20736, 4095, 4239),
}
# Theory: for fixed H/h the condition number of Dirichlet-preconditioned (T)FETI is bounded by
# C (1 + log(H/h))^2 independently of the number of subdomains, so iteration counts must not
# grow with it. Allowed: at most 1.5 times the count at 16 subdomains (H = 1/4).
GROWTH = 1.5


def load(d):
    with open(d + "/summary.json") as f:
        s = json.load(f)
    # Every summary echoes the validated parameter list, defaults filled in, and the study it
    # ran is the one the parameters name.
    p = s.get("parameters")
    if not isinstance(p, dict) or not {"Study", "Problem", "FETI", "Output"} <= set(p):
        fail(d + ": summary.json does not echo the validated parameters")
    if p["Study"] != s.get("study", p["Study"]):
        fail(d + ": echoed Study %s, ran %s" % (p["Study"], s.get("study")))
    if "problem" in s and p["Study"] == "single" and p["Problem"] != s["problem"]:
        fail(d + ": echoed Problem %s, ran %s" % (p["Problem"], s["problem"]))
    return s


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def expected_dimensions(r):
    """Closed forms for a row of the structured table (any dimension dim, c dofs per node, S
    subdomains per side of n elements): every subdomain has (n + 1)^dim nodes; a node's copies
    are the product over the axes of 2 (on an interior subdomain boundary) or 1, so that the
    copies of all nodes number (S (n + 1))^dim against (S n + 1)^dim nodes. Non-redundant
    gluing (FETI) adds copies - 1 rows per node and component; TFETI adds a Dirichlet row on
    every copy of a node of the face x = 0, (S (n + 1))^(dim - 1) of them."""
    dim = r.get("dimension", 2)
    c = 1 if r["problem"] == "poisson" else dim
    S = r["H_inverse"]
    n = r["h_inverse"] // S
    copies = (S * (n + 1)) ** dim
    feti = c * (copies - (S * n + 1) ** dim)
    return c * copies, feti, feti + c * (S * (n + 1)) ** (dim - 1)


def scalability(d, reference_h, checked):
    s = load(d)
    if not s.get("all_converged"):
        fail("not every solve converged")
    for r in s["table"]:
        got = (r["primal_dim"], r["dual_dim_feti"], r["dual_dim_tfeti"])
        want = expected_dimensions(r)
        if got != want:
            fail(f"{r['problem']} H=1/{r['H_inverse']} h=1/{r['h_inverse']}: dimensions {got}, "
                 f"closed forms {want}")
        if r["subdomains"] != r["H_inverse"] ** r.get("dimension", 2):
            fail(f"{r['problem']} H=1/{r['H_inverse']}: {r['subdomains']} subdomains")
    rows = [r for r in s["table"] if r["problem"] == "poisson" and r.get("dimension", 2) == 2]
    if rows:
        seen = 0
        for r in rows:
            key = (r["H_inverse"], r["h_inverse"])
            if key in PAPER:
                got = (r["primal_dim"], r["dual_dim_feti"], r["dual_dim_tfeti"])
                if got != PAPER[key]:
                    fail(f"H=1/{key[0]} h=1/{key[1]}: dimensions {got}, paper {PAPER[key]}")
                seen += 1
        if seen != len(PAPER):
            fail(f"only {seen} of the paper's {len(PAPER)} rows present")
    # Iterations at fixed H/h against the count at H = 1/reference_h.
    for problem in sorted({r["problem"] for r in s["table"]}):
        for form, prec in checked:
            by_ratio = {}
            for r in s["table"]:
                if r["problem"] == problem:
                    by_ratio.setdefault(r["h_inverse"] // r["H_inverse"], {})[r["H_inverse"]] = \
                        r["iterations"][form][prec]
            for ratio, its in sorted(by_ratio.items()):
                if reference_h not in its:
                    fail(f"{problem} H/h={ratio}: no row at H=1/{reference_h}")
                bound = GROWTH * its[reference_h]
                worst = max(its.values())
                print(f"{problem} H/h={ratio}: {form.upper()}+{prec} iterations "
                      f"{dict(sorted(its.items()))}, bound {bound}")
                if worst > bound:
                    fail(f"{problem} H/h={ratio}: {form} {prec} {worst} iterations exceed {bound} "
                         f"({GROWTH} x the count at H=1/{reference_h})")
    print("OK: all dimensions equal their closed forms" + (" and the paper's" if rows else "") +
          "; iterations bounded")


def single(d, max_error):
    s = load(d)
    if not s["converged"]:
        fail("did not converge")
    err = s.get("error_vs_direct")
    if err is None or err > max_error:
        fail(f"error against the direct solve {err} > {max_error}")
    print(f"OK: {s['iterations']} iterations, error against direct solve {err:.3e}")


def same(dirs):
    sums = [load(d) for d in dirs]
    ref = sums[0]
    for d, s in zip(dirs[1:], sums[1:]):
        if s["iterations"] != ref["iterations"]:
            fail(f"{d}: {s['iterations']} iterations on {s['ranks']} ranks, "
                 f"{ref['iterations']} on {ref['ranks']}")
        rel = abs(s["solution_norm2"] - ref["solution_norm2"]) / ref["solution_norm2"]
        if rel > 1e-10:
            fail(f"{d}: solution norm differs by {rel:.2e} (relative) from {ref['ranks']} ranks")
        for k, (a, b) in enumerate(zip(ref["residual_history"], s["residual_history"])):
            # CG rounding grows relative to the current residual as it falls; the initial
            # residual is the natural scale of the differences between summation orders.
            if abs(a - b) > 1e-6 * ref["residual_history"][0]:
                fail(f"{d}: residual at iteration {k} is {b:.6e} on {s['ranks']} ranks, "
                     f"{a:.6e} on {ref['ranks']}")
        for key in ("primal_dim", "dual_dim", "coarse_dim"):
            if s[key] != ref[key]:
                fail(f"{d}: {key} {s[key]} != {ref[key]}")
    print(f"OK: {ref['iterations']} iterations and the same solution on ranks",
          [s["ranks"] for s in sums])


def diverged(d):
    s = load(d)
    if s["converged"]:
        fail("expected a non-converged run")
    print(f"OK: non-convergence reported after {s['iterations']} iterations")


def prescribed(d, reaction, against_contact, tol, residual_tol):
    s = load(d)
    if not s["converged"]:
        fail("did not converge")
    residual = s["contact"]["equality_residual"] if "contact" in s else s["equality_residual"]
    if residual > residual_tol * s["max_abs_u"]:
        fail(f"max |B_E u - c_E| = {residual:.3e} > {residual_tol} max |u|")
    got = s["prescribed"][0]["reaction"]
    expected = -s["contact"]["force"] if against_contact else reaction
    err = abs(got - expected) / abs(expected)
    if err > tol:
        fail(f"reaction {got:.10e} against {expected:.10e}: {err:.1e} > {tol:.1e}")
    print(f"OK: {s['prescribed_rows']} prescribed rows, reaction {got:.10e} (expected "
          f"{expected:.10e}, {err:.1e} relative), max |B_E u - c_E| {residual:.1e}")


# Contact conditions hold to this fraction of the solution's scale (max |u|, the load).
KKT_TOL = 1e-6


def patch(dirs, pressure, tol):
    for d in dirs:
        s = load(d)
        if not s["converged"]:
            fail(f"{d}: did not converge")
        c = s["contact"]
        if c["max_penetration"] > KKT_TOL * s["max_abs_u"]:
            fail(f"{d}: penetration {c['max_penetration']:.3e}")
        if c["min_multiplier"] < -KKT_TOL * c["force"]:
            fail(f"{d}: negative multiplier {c['min_multiplier']:.3e}")
        if c["force_relative_error"] > tol:
            fail(f"{d}: the force misses the load by {c['force_relative_error']:.3e}")
        with open(os.path.join(d, "contact_pressure.csv")) as f:
            rows = list(csv.DictReader(f))
        if not rows:
            fail(f"{d}: contact_pressure.csv has no rows")
        # The recovered pressure reproduces a uniform one as well (a linear fit).
        worst = max(abs(float(r[k]) / pressure - 1.0) for r in rows
                    for k in ("pressure", "pressure_recovered"))
        if worst > tol:
            fail(f"{d}: a row's pressure or recovered pressure is {worst:.3e} away from "
                 f"{pressure:g} (> {tol:.1e})")
        print(f"OK: {d}: {len(rows)} rows, every pressure and recovered pressure {pressure:g} "
              f"to {worst:.1e}")


def contact(d, force_tol):
    s = load(d)
    if not s["converged"]:
        fail("did not converge: " + s["qp"].get("message", ""))
    c, q = s["contact"], s["qp"]
    scale_u = s["max_abs_u"]
    force = c["expected_force"]
    checks = [
        ("penetration max(B_I u - c_I)", c["max_penetration"], KKT_TOL * scale_u),
        ("negative multiplier -min(lambda_I)", -c["min_multiplier"], KKT_TOL * force),
        ("complementarity max|lambda (B_I u - c)|", c["max_complementarity"],
         KKT_TOL * scale_u * force),
        ("gluing/Dirichlet residual max|B_E u - c_E|", c["equality_residual"], KKT_TOL * scale_u),
        ("force balance |sum lambda_I - load| / load", abs(c["force"] - force) / force, force_tol),
    ]
    for name, value, tol in checks:
        if value > tol:
            fail(f"{name} = {value:.3e} > {tol:.3e}")
    for key in ("outer_iterations", "hessian_multiplications", "cg_steps", "expansion_steps",
                "proportioning_steps", "projected_gradient_norm", "equality_residual_norm"):
        if key not in q:
            fail(f"qp.{key} missing from summary.json")
    if q["method"] == "penalty" and s["parameters"]["FETI"].get("Penalty", {}).get(
            "Equality projection", True):
        # The penalty's Q mu (about ||PFP|| / rho of mu) removed: G lambda = e to rounding.
        if "equality_projection_norm" not in q:
            fail("qp.equality_projection_norm missing from summary.json (penalty)")
        if not q["equality_residual_norm"] <= 1e-8 * q["equality_projection_norm"]:
            fail(f"penalty: ||Q mu|| {q['equality_residual_norm']:.3e} after the equality "
                 f"projection, {q['equality_projection_norm']:.3e} before")
    steps = q["cg_steps"] + q["expansion_steps"] + q["proportioning_steps"]
    if q["hessian_multiplications"] < steps:
        fail(f"{q['hessian_multiplications']} Hessian multiplications < {steps} MPRGP steps")
    print(f"OK: {q['method']}: {q['outer_iterations']} outer iterations, "
          f"{q['hessian_multiplications']} Hessian multiplications; {c['active_rows']} of "
          f"{c['rows']} contact rows active, force {c['force']:.10f}; " +
          ", ".join(f"{n} {v:.1e}" for n, v, _ in checks))


def same_dual_operator(dirs, tol, device="host", partial=False, mult_tol=0.01, assembly="schur"):
    ref = load(dirs[0])
    if ref.get("dual_operator") != "implicit" or ref.get("explicit_dual_bytes") != 0:
        fail(f"{dirs[0]}: dual_operator {ref.get('dual_operator')}, explicit_dual_bytes "
             f"{ref.get('explicit_dual_bytes')}: expected implicit, 0")

    def counts(s):
        if "nonlinear" in s:
            n = s["nonlinear"]
            return (n["total_iterations"], n["total_hessian_multiplications"])
        q = s.get("qp")
        return (q["outer_iterations"], q["hessian_multiplications"]) if q else (s["iterations"],)

    def close(a, b, scale):
        return abs(a - b) <= tol * max(scale, 1e-300)

    tables = [name for name in ("contact.csv", "contact_pressure.csv")
              if os.path.exists(f"{dirs[0]}/{name}")]
    ref_tables = {name: contact_rows(dirs[0], name) for name in tables}
    for d in dirs[1:]:
        s = load(d)
        total, most = s.get("explicit_dual_bytes", 0), s.get("explicit_dual_bytes_max_rank", 0)
        if s.get("dual_operator") != "explicit" or not 0 < most <= total:
            fail(f"{d}: dual_operator {s.get('dual_operator')}, F_s bytes {total} (largest rank "
                 f"{most}): expected explicit with 0 < largest rank <= total")
        if s.get("explicit_device", "host") != device:
            fail(f"{d}: explicit_device {s.get('explicit_device')}, expected {device}")
        # The assemblies: at least one block, never more columns solved than assembling every
        # assembled block anew would take; with partial, fewer (update() on the same factors
        # kept the unchanged rows' part of the blocks).
        a = s.get("explicit_dual_assembly", {})
        solved, whole = a.get("columns_solved", -1), a.get("columns_full", -1)
        if not (a.get("blocks", 0) > 0 and 0 < solved <= whole) or \
                (partial and not solved < whole):
            fail(f"{d}: explicit_dual_assembly {a}: expected blocks > 0 and 0 < columns_solved "
                 f"{'< ' if partial else '<= '}columns_full")
        # schur: blocks assembled anew come from the Schur complement (the partial ones by
        # solves); solves: none does.
        schur = a.get("schur_blocks", -1)
        if not (0 < schur <= a["blocks"] if assembly == "schur" else schur == 0):
            fail(f"{d}: explicit_dual_assembly {a}: Explicit assembly = {assembly} expects "
                 f"{'0 < schur_blocks <= blocks' if assembly == 'schur' else 'schur_blocks 0'}")
        if device == "gpu":
            w = s.get("explicit_device_work", {})
            if not w.get("applies", 0) >= s.get("dual_operator_applies", 1) or \
                    not w.get("kernel_bytes_per_apply", 0) >= total or \
                    not w.get("kernel_bandwidth_gb_per_s", 0) > 0:
                fail(f"{d}: explicit_device_work {w}: expected every F apply on the device "
                     f"({s.get('dual_operator_applies')}), streaming at least the F_s "
                     f"({total} bytes), at a bandwidth > 0")
        a, b = counts(s), counts(ref)
        # A QP's discrete choices (MPRGP's steps, where a face solve of the level search stops)
        # can flip with the rounding of F, and a nonlinear run solves a QP per iteration: the
        # same (outer) iterations, the multiplications to mult_tol (1 %). PCPG alone: the same
        # iterations.
        same = a == b if len(a) == 1 else \
            a[0] == b[0] and abs(a[1] - b[1]) <= mult_tol * b[1]
        if not s["converged"] or not same:
            fail(f"{d}: converged {s['converged']}, counts {a}; implicit {b}")
        if "contact" in ref and "force" in ref["contact"] and \
                not close(s["contact"]["force"], ref["contact"]["force"],
                          abs(ref["contact"]["force"])):
            fail(f"{d}: contact force {s['contact']['force']} vs {ref['contact']['force']}")
        for key in ("solution_norm2", "max_abs_u"):
            if key in ref and not close(s[key], ref[key], abs(ref[key])):
                fail(f"{d}: {key} {s[key]:.15e} vs {ref[key]:.15e} (implicit)")
        # Every column (coordinates, multipliers, pressures) relative to the column's largest.
        for name, ref_rows in ref_tables.items():
            rows = contact_rows(d, name)
            if len(rows) != len(ref_rows):
                fail(f"{d}: {len(rows)} rows in {name}, {len(ref_rows)} implicit")
            scale = [max(abs(r[k]) for r in ref_rows) for k in range(len(ref_rows[0]))] \
                if ref_rows else []
            for a, b in zip(ref_rows, rows):
                for k in range(len(a)):
                    if not close(a[k], b[k], scale[k]):
                        fail(f"{d}: {name} column {k}: {b[k]:.15e} vs {a[k]:.15e}")
        print(f"OK: {d}: explicit F_s {total} bytes ({most} on the largest rank), counts "
              f"{counts(s)} and the solution as implicit to {tol}")


def rule_without_memory(a):
    """auto's rule on the bytes: explicit for a QP whose F_s take fewer than the factors."""
    return "explicit" if a["qp"] and a["explicit_bytes"] < a["factor_bytes"] else "implicit"


def factor_memory(d, checked, meminfo=None, edges=None):
    """factor_memory_check: the subdomain factors against the nodes' memory before they were
    made (FETI "Memory check"), as expected; its figures consistent with factor_bytes."""
    s = load(d)
    m = s.get("factor_memory_check")
    if m is None or m.get("checked") != checked:
        fail(f"{d}: factor_memory_check {m}: expected checked {checked}")
    if checked:
        need, available = m["node_need_bytes"], m["node_available_bytes"]
        held = m.get("node_held_bytes", -1)
        if not need > held >= s["factor_bytes"] > 0:
            fail(f"{d}: factor_memory_check {m}: expected the need (the factorizations' peak) "
                 f"above node_held_bytes, and that at least the factors' bytes {s['factor_bytes']}"
                 " (every rank on one node)")
        if available < 0 or m["fits"] != (need <= available) or m["node_ranks"] < 1:
            fail(f"{d}: factor_memory_check {m}: fits must say whether the need is within the "
                 "available bytes")
    p = s.get("preconditioner_memory_check")
    if p is None or (not checked and p.get("checked")):
        fail(f"{d}: preconditioner_memory_check {p}: expected it, and unchecked where the factors "
             "were")
    if p["checked"] and not (p["node_need_bytes"] > 0 and p["node_ranks"] >= 1 and
                             p["fits"] == (p["node_need_bytes"] <= p["node_available_bytes"])):
        fail(f"{d}: preconditioner_memory_check {p}: fits must say whether the need is within "
             "the available bytes")
    written = []

    def write(path, need, short):
        kib = -(-int(need) // 1024) - (1 if short else 0)
        with open(path, "w") as f:
            f.write(f"MemTotal:       24000000 kB\nMemAvailable:   {kib} kB\n")
        written.append(path)

    if meminfo or edges:
        if not checked:
            fail("--write-meminfo and --write-meminfo-edges need a run whose factors were checked")
    if meminfo:
        write(meminfo, m["node_need_bytes"], False)
    if edges:
        if not p["checked"]:
            fail("--write-meminfo-edges needs a run whose interior factors were checked")
        # What a dry run adds for the preconditioner: its need on top of what the subdomain
        # factors hold once made.
        both = m["node_held_bytes"] + p["node_need_bytes"]
        write(edges + "_factors_short", m["node_need_bytes"], True)
        write(edges + "_with_preconditioner", both, False)
        write(edges + "_with_preconditioner_short", both, True)
    print(f"OK: {d}: factor_memory_check {m}, preconditioner_memory_check {p}" +
          (f"; written: {', '.join(written)}" if written else ""))


def dual_operator_auto(d, chosen, fits_memory=True):
    """FETI "Dual operator" = auto: the run converged with the expected operator, and the choice
    follows the rule from what summary.json says it rested on: explicit exactly when the dual
    problem is a QP, the F_s take fewer bytes than the subdomain factors (on the host) and they
    fit the nodes' available memory (explicit_fits_memory, as expected)."""
    s = load(d)
    a = s.get("dual_operator_auto")
    if not s.get("converged") or a is None:
        fail(f"{d}: converged {s.get('converged')}, dual_operator_auto {a}: expected a converged "
             "run with Dual operator = auto")
    fits = a["explicit_fits_memory"]
    mem = s.get("explicit_memory_check", {})
    if fits != fits_memory or mem.get("fits") != fits:
        fail(f"{d}: dual_operator_auto {a}, explicit_memory_check {mem}: expected fits "
             f"{fits_memory} in both")
    if not fits and not 0 <= mem["node_available_bytes"] < mem["node_need_bytes"]:
        fail(f"{d}: explicit_memory_check {mem}: F_s that do not fit need more than is "
             "available")
    if fits and rule_without_memory(a) == "explicit" and mem["node_available_bytes"] >= 0 and \
            not 0 < mem["node_need_bytes"] <= mem["node_available_bytes"]:
        fail(f"{d}: explicit_memory_check {mem}: explicit held, yet its need is not within the "
             "node's available memory")
    rule = rule_without_memory(a) if fits else "implicit"
    if a["chosen"] != chosen or s["dual_operator"] != chosen or rule != chosen:
        fail(f"{d}: dual_operator {s['dual_operator']}, dual_operator_auto {a} (the rule gives "
             f"{rule}): expected {chosen}")
    if "factor_bytes" in s and a["factor_bytes"] != s["factor_bytes"]:
        fail(f"{d}: dual_operator_auto factor_bytes {a['factor_bytes']} against factor_bytes "
             f"{s['factor_bytes']}")
    if chosen == "explicit" and a["explicit_bytes"] != s["explicit_dual_bytes"]:
        fail(f"{d}: dual_operator_auto explicit_bytes {a['explicit_bytes']} against the F_s "
             f"held, explicit_dual_bytes {s['explicit_dual_bytes']}")
    print(f"{d}: {chosen} (qp {a['qp']}, F_s {a['explicit_bytes']:.0f} bytes against factors "
          f"{a['factor_bytes']:.0f})")


def explicit_export(d, files):
    """The F_s blocks a run exported (FETI "Explicit export file"), read as gpu/ reads them:
    "TFETIF01", int64 count, per block int64 m and m*m float64 column-major."""
    import struct
    s = load(d)
    blocks = []
    for path in files:
        with open(path, "rb") as f:
            data = f.read()
        if data[:8] != b"TFETIF01":
            fail(f"{path}: no TFETIF01 header")
        (count,), pos = struct.unpack_from("<q", data, 8), 16
        for k in range(count):
            (m,) = struct.unpack_from("<q", data, pos)
            if not 0 < m <= 1 << 20 or pos + 8 + 8 * m * m > len(data):
                fail(f"{path}: block {k} of {count}: size {m} does not fit the file")
            blocks.append((m, struct.unpack_from(f"<{m * m}d", data, pos + 8)))
            pos += 8 + 8 * m * m
        if pos != len(data):
            fail(f"{path}: {len(data) - pos} bytes after the {count} blocks")
    if len(blocks) != s["subdomains"]:
        fail(f"{len(blocks)} blocks in {len(files)} files, {s['subdomains']} subdomains")
    packed = 8 * sum(m * (m + 1) // 2 for m, _ in blocks)
    if s.get("dual_operator") != "explicit" or s.get("explicit_dual_bytes") != packed:
        fail(f"{d}: explicit_dual_bytes {s.get('explicit_dual_bytes')}, the blocks' packed "
             f"triangles {packed} bytes")
    for k, (m, f) in enumerate(blocks):
        scale = max(abs(v) for v in f)
        for j in range(m):
            if not f[j * m + j] >= 0:  # 0 where a row acts on the dofs that fix the kernel
                fail(f"block {k}: diagonal {j} is {f[j * m + j]}, F_s is positive semidefinite")
            for i in range(j):
                if abs(f[j * m + i] - f[i * m + j]) > 1e-14 * scale:
                    fail(f"block {k}: F({i},{j}) = {f[j * m + i]}, F({j},{i}) = {f[i * m + j]}")
    sizes = sorted(m for m, _ in blocks)
    print(f"OK: {len(blocks)} blocks of {sizes[0]}..{sizes[-1]} rows in {len(files)} files, "
          f"symmetric, {packed} bytes packed as summary.json says")


def contact_rows(d, name="contact.csv"):
    with open(f"{d}/{name}") as f:
        return [tuple(float(x) for x in r) for r in list(csv.reader(f))[1:]]


def same_contact(dirs, solution_only):
    ref, ref_rows = load(dirs[0]), contact_rows(dirs[0])
    scale = max(max(abs(v) for v in r[2:]) for r in ref_rows)
    lscale = max(r[1] for r in ref_rows)
    for d in dirs[1:]:
        s, rows = load(d), contact_rows(d)
        if not solution_only:
            # Rounding in the reductions depends on the distribution and can flip one of
            # MPRGP's discrete choices near the end: allow a few multiplications of spread.
            a, b = s["qp"]["hessian_multiplications"], ref["qp"]["hessian_multiplications"]
            if abs(a - b) > max(2, 0.1 * b) or s["qp"]["outer_iterations"] != \
                    ref["qp"]["outer_iterations"]:
                fail(f"{d}: {s['qp']['outer_iterations']} outer iterations and {a} Hessian "
                     f"multiplications on {s['ranks']} ranks, "
                     f"{ref['qp']['outer_iterations']} and {b} on {ref['ranks']}")
        if len(rows) != len(ref_rows):
            fail(f"{d}: {len(rows)} contact rows, {len(ref_rows)} in {dirs[0]}")
        for a, b in zip(ref_rows, rows):
            if abs(a[0] - b[0]) > 1e-12:
                fail(f"{d}: contact node at y={b[0]}, expected y={a[0]}")
            if abs(a[1] - b[1]) > 1e-5 * lscale:
                fail(f"{d}: lambda at y={a[0]}: {b[1]:.8e} vs {a[1]:.8e}")
            for k in (2, 3):
                if abs(a[k] - b[k]) > 1e-6 * scale:
                    fail(f"{d}: u at y={a[0]}: {b[k]:.8e} vs {a[k]:.8e}")
    print("OK: the same contact solution in", dirs)


# For fixed H/h the Hessian multiplications of SMALBE-M with MPRGP are bounded independently of
# h (Dostál's optimality results for TFETI). Allowed growth from the coarsest decomposition
# (2x2 subdomains per membrane) to any finer one. The penalty method's counts are printed, not
# bounded: with ||P F P + rho Q|| = rho its expansion steps (length 1.9/rho) barely move, and
# its counts are erratic (docs/benchmarks.md).
MEMBRANE_GROWTH = 2.0
FORCE_TOL = {"SMALBE": 1e-5, "penalty": 1e-4}
# Allowed relative spread of the multiplication counts between rank counts.
COUNT_SPREAD = 0.35


def membranes_scaling(dirs):
    s = load(dirs[0])
    if not s.get("all_converged"):
        fail("not every solve converged")
    series = {}
    for r in s["table"]:
        for method, q in r["solvers"].items():
            c = q["contact"]
            where = f"H=1/{r['H_inverse']} h=1/{r['h_inverse']} {method}"
            if abs(c["force"] - c["expected_force"]) > FORCE_TOL[method] * c["expected_force"]:
                fail(f"{where}: contact force {c['force']}")
            u = q["max_abs_u"]
            tol = KKT_TOL if method == "SMALBE" else 100 * KKT_TOL
            for name, value, bound in (
                    ("penetration", c["max_penetration"], tol * u),
                    ("negative multiplier", -c["min_multiplier"], tol * c["expected_force"]),
                    ("complementarity", c["max_complementarity"], tol * u * c["expected_force"]),
                    ("gluing residual", c["equality_residual"], tol * u)):
                if value > bound:
                    fail(f"{where}: {name} {value:.3e} > {bound:.3e}")
            series.setdefault((r["H_over_h"], method), []).append(
                (r["H_inverse"], q["hessian_multiplications"]))
    for (ratio, method), pts in sorted(series.items()):
        pts.sort()
        bound = MEMBRANE_GROWTH * pts[0][1]
        worst = max(m for _, m in pts)
        print(f"H/h={ratio} {method}: Hessian multiplications by 1/H {pts}" +
              (f", bound {bound}" if method == "SMALBE" else ""))
        if method == "SMALBE" and worst > bound:
            fail(f"H/h={ratio} {method}: {worst} multiplications exceed {bound}")
    # Other rank counts: the same solution to the tolerance. The counts may differ a little:
    # MPRGP's discrete choices (CG or expansion step, proportioning) can flip on rounding
    # differences of the reductions, which depend on the data distribution.
    for d in dirs[1:]:
        other = load(d)
        for a, b in zip(s["table"], other["table"]):
            for method, q in a["solvers"].items():
                p = b["solvers"][method]
                where = f"{d}: H=1/{a['H_inverse']} h=1/{a['h_inverse']} {method}"
                m0, m1 = q["hessian_multiplications"], p["hessian_multiplications"]
                if abs(m0 - m1) > COUNT_SPREAD * max(m0, m1):
                    fail(f"{where}: {m1} multiplications on {other['ranks']} ranks, {m0} on "
                         f"{s['ranks']}")
                tol = KKT_TOL if method == "SMALBE" else 100 * KKT_TOL
                df = abs(q["contact"]["force"] - p["contact"]["force"])
                du = abs(q["max_abs_u"] - p["max_abs_u"])
                if df > tol * q["contact"]["expected_force"] or du > tol * q["max_abs_u"]:
                    fail(f"{where}: the solution differs between rank counts (force by {df:.2e}, "
                         f"max|u| by {du:.2e})")
    print("OK: Hessian multiplications bounded, contact conditions met" +
          (f", the same on ranks {[load(d)['ranks'] for d in dirs]}" if len(dirs) > 1 else ""))


HERTZ_TOL = {"p_max": 0.03, "extent": 0.05}


def hertz_line_reference(s, estar):
    """Hertz's line contact of the run's radii and line load with the combined modulus E*,
    computed here from the echoed parameters: (p_max, half_width)."""
    hz = s["parameters"]["Contact problem"]["Hertz"]
    r1, r2, load_ = hz["Radius 1"], hz["Radius 2"], hz["Line load"]
    r = r1 * r2 / (r1 + r2) if r2 > 0 else r1
    a = math.sqrt(4 * load_ * r / (math.pi * estar))
    return 2 * load_ / (math.pi * a), a


def hertz(dirs, p_tol=HERTZ_TOL["p_max"], extent_tol=HERTZ_TOL["extent"], estar=0.0,
          force_tol=1e-6, vm_tol=None, recovered=False):
    s = load(dirs[0])
    if not s["converged"]:
        fail("did not converge: " + s["qp"].get("message", ""))
    c = s["contact"]
    if estar > 0:
        p0, a = hertz_line_reference(s, estar)
        for key, want in (("p_max", p0), ("half_width", a)):
            if abs(c["hertz"][key] - want) > 1e-9 * want:
                fail(f"Hertz {key} {c['hertz'][key]:.9e} in summary.json is not the line "
                     f"contact's {want:.9e} with E* = {estar:.6e}")
    # The zone's extent: the half-width of a 2D (line) contact, the radius of a 3D (point) one.
    extent = "contact_radius" if "contact_radius" in c else "half_width"
    p_key = "p_max_recovered" if recovered else "p_max"
    for key, ref, tol in ((p_key, "p_max", p_tol), (extent, extent, extent_tol)):
        err = c["relative_error"][key]
        if abs(err - abs(c[key] / c["hertz"][ref] - 1)) > 1e-9:
            fail(f"relative_error.{key} {err} is not |{key} / Hertz's {ref} - 1|")
        if err > tol:
            fail(f"{key} {c[key]:.6e} differs from Hertz's by {100 * err:.2f} % > "
                 f"{100 * tol:.1f} %")
    vm_key = "max_von_mises_nodal" if recovered else "max_von_mises"
    if vm_tol is not None:
        vm, ref = s[vm_key], c["hertz"]["max_von_mises"]
        if abs(vm - ref) > vm_tol * ref:
            fail(f"{vm_key} {vm:.6e} differs from Hertz's {ref:.6e} by "
                 f"{100 * abs(vm / ref - 1):.2f} % > {100 * vm_tol:.1f} %")
    if c["force_relative_error"] > force_tol:
        fail(f"contact force {c['force']} against the applied {c['applied_force']}: "
             f"{c['force_relative_error']:.1e} relative")
    u = s["max_abs_u"]
    if c["max_penetration"] > KKT_TOL * u or c["equality_residual"] > KKT_TOL * u:
        fail(f"penetration {c['max_penetration']:.2e} or gluing residual "
             f"{c['equality_residual']:.2e} above {KKT_TOL} x max|u| = {KKT_TOL * u:.2e}")
    if c["min_multiplier"] < 0 or c["max_complementarity"] > KKT_TOL * u * c["force"]:
        fail(f"multiplier sign or complementarity: {c['min_multiplier']}, "
             f"{c['max_complementarity']:.2e}")
    for d in dirs[1:]:
        od = load(d)
        o = od["contact"]
        for key in ("p_max", extent) + (("p_max_recovered",) if recovered else ()):
            if abs(o[key] - c[key]) > 1e-5 * abs(c[key]):
                fail(f"{d}: {key} {o[key]} differs from {c[key]} ({dirs[0]})")
        if recovered and abs(od[vm_key] - s[vm_key]) > 1e-5 * s[vm_key]:
            fail(f"{d}: {vm_key} {od[vm_key]} differs from {s[vm_key]} ({dirs[0]})")
    print(f"OK: {p_key} {c[p_key]:.5e} (p_max {c['p_max']:.5e}, Hertz {c['hertz']['p_max']:.5e}, "
          f"{100 * abs(c[p_key] / c['hertz']['p_max'] - 1):.2f} %), {vm_key} {s[vm_key]:.5e} "
          f"(Hertz {c['hertz']['max_von_mises']:.5e}), {extent} {c[extent]:.5e} "
          f"(Hertz {c['hertz'][extent]:.5e}, {100 * c['relative_error'][extent]:.2f} %),"
          f" force error {c['force_relative_error']:.1e}")


def vtu_nodes(d):
    """(body, x, y, z, ux, uy, uz) of every point of the solution_*.vtu pieces; the body is the
    sign of y at the centroid of a cell using the point (the two cylinders: cylinder y > 0,
    block y < 0; their contact points coincide at the origin)."""
    import glob
    import re

    def array(xml, name):
        m = re.search(r'<DataArray[^>]*Name="%s"[^>]*>(.*?)</DataArray>' % name, xml, re.S)
        if not m:
            fail(f"{d}: no DataArray {name} in the VTU pieces")
        return [float(v) for v in m.group(1).split()]

    nodes = []
    paths = sorted(glob.glob(d + "/solution_*.vtu"))
    if not paths:
        fail(f"{d}: no solution_*.vtu")
    for path in paths:
        with open(path) as f:
            xml = f.read()
        pts, u = array(xml, "Points"), array(xml, "displacement")
        conn = [int(v) for v in array(xml, "connectivity")]
        ends = [int(v) for v in array(xml, "offsets")]
        body = [None] * (len(pts) // 3)
        for start, end in zip([0] + ends[:-1], ends):
            cell = conn[start:end]
            yc = sum(pts[3 * k + 1] for k in cell) / len(cell)
            for k in cell:
                body[k] = 1 if yc > 0 else -1
        nodes += [(body[k], *pts[3 * k:3 * k + 3], *u[3 * k:3 * k + 3])
                  for k in range(len(body)) if body[k] is not None]
    return nodes


def plane_strain(d2, dirs3, tol, u_tol):
    s2 = load(d2)
    c2 = s2["contact"]
    flat = {}
    for b, x, y, _, ux, uy, _ in vtu_nodes(d2):
        flat[(b, round(x, 12), round(y, 12))] = (ux, uy)
    scale = max(max(abs(v) for v in u) for u in flat.values())
    for d3 in dirs3:
        s3 = load(d3)
        if not (s2["converged"] and s3["converged"]):
            fail(f"{d2} or {d3} did not converge")
        if s2.get("dimension", 2) != 2 or s3.get("dimension") != 3:
            fail(f"{d2} must be a 2D run and {d3} a 3D one")
        c3 = s3["contact"]
        for key in ("p_max", "half_width", "force", "applied_force", "hertz", "relative_error"):
            if key not in c3:
                fail(f"{d3}: contact.{key} missing (the 2D run's keys)")
        checks = [("p_max", abs(c3["p_max"] - c2["p_max"]) / c2["p_max"], tol),
                  ("half_width", abs(c3["half_width"] - c2["half_width"]) / c2["half_width"], tol)]
        for key in ("half_width_min", "half_width_max"):
            checks.append((key, abs(c3[key] - c2["half_width"]) / c2["half_width"], tol))
        per_length = c3["applied_force"] / c3["line_length"]
        checks.append(("applied force per unit length",
                       abs(per_length - c2["applied_force"]) / c2["applied_force"], 1e-9))
        worst_z, worst_xy, missing = 0.0, 0.0, 0
        for b, x, y, _, ux, uy, uz in vtu_nodes(d3):
            ref = flat.get((b, round(x, 12), round(y, 12)))
            if ref is None:
                missing += 1
                continue
            worst_z = max(worst_z, abs(uz) / scale)
            worst_xy = max(worst_xy, max(abs(ux - ref[0]), abs(uy - ref[1])) / scale)
        if missing:
            fail(f"{d3}: {missing} points have no 2D node at their (x, y)")
        checks += [("max |u_z| / max|u|", worst_z, u_tol),
                   ("max |u_xy(3D) - u_xy(2D)| / max|u|", worst_xy, u_tol)]
        for name, value, t in checks:
            if value > t:
                fail(f"{d3}: {name} differs from the 2D run by {value:.3e} > {t:.1e}")
        print(f"OK: {d3} ({s3['ranks']} ranks, {c3['node_planes']} node planes) against 2D: " +
              ", ".join(f"{n} {v:.1e}" for n, v, _ in checks) +
              f"; p_max {c3['p_max']:.6e} (2D {c2['p_max']:.6e}), half-width "
              f"{c3['half_width']:.6e} (2D {c2['half_width']:.6e})")


def tied_equalities_hold(d, s):
    """A converged tied run (Contact type = tied) whose gluing and tied rows hold to KKT_TOL of
    max|u|: with a tied pair the contact rows are equality rows, which equality_residual covers.
    Returns its contact summary and max|u|."""
    c = s["contact"]
    if not s["converged"] or s.get("contact_type") != "tied":
        fail(f"{d}: converged {s['converged']}, contact type {s.get('contact_type')}")
    u = s["max_abs_u"]
    if c["equality_residual"] > KKT_TOL * u:
        fail(f"{d}: max|B u - c| over the gluing and tied rows = {c['equality_residual']:.3e}"
             f" > {KKT_TOL} x max|u| = {KKT_TOL * u:.3e}")
    return c, u


def tied(dirs):
    """A tied pair (Contact type = tied): B_I u = gap and the gluing rows to KKT_TOL of max|u|,
    the contact force balancing the load to 1e-6, and the same solution in every run (rank
    counts, PCPG and SMALBE without bounds)."""
    ref = load(dirs[0])
    for d in dirs:
        s = load(d)
        c, u = tied_equalities_hold(d, s)
        if c["force_relative_error"] > 1e-6:
            fail(f"{d}: contact force {c['force']} against the applied {c['applied_force']}: "
                 f"{c['force_relative_error']:.1e} relative")
        for key in ("force", "p_max"):
            if abs(c[key] - ref["contact"][key]) > 1e-6 * abs(ref["contact"][key]):
                fail(f"{d}: {key} {c[key]} differs from {ref['contact'][key]} ({dirs[0]})")
        if abs(u - ref["max_abs_u"]) > 1e-6 * ref["max_abs_u"]:
            fail(f"{d}: max|u| {u} differs from {ref['max_abs_u']} ({dirs[0]})")
        print(f"OK: {d}: {s['dual_solver']}, {s['qp']['hessian_multiplications']} "
              f"multiplications, max|B u - c| {c['equality_residual']:.1e} (max|u| {u:.3e}), "
              f"force error {c['force_relative_error']:.1e}")


def bounded_iterations(dirs, max_iterations):
    """Issue 13: the dual iterations of a tied problem stay below what the preconditioner's
    scaling must reach, independently of the rank count."""
    ref = load(dirs[0])
    for d in dirs:
        s = load(d)
        c, u = tied_equalities_hold(d, s)
        if s["iterations"] > max_iterations:
            fail(f"{d}: {s['iterations']} PCPG iterations > {max_iterations} "
                 f"({s['subdomains']} subdomains)")
        if s["iterations"] != ref["iterations"]:
            fail(f"{d}: {s['iterations']} iterations, {ref['iterations']} in {dirs[0]}")
        if abs(u - ref["max_abs_u"]) > 1e-6 * ref["max_abs_u"]:
            fail(f"{d}: max|u| {u} differs from {ref['max_abs_u']} ({dirs[0]})")
        print(f"OK: {d}: {s['subdomains']} subdomains, {s['ranks']} ranks: {s['iterations']} "
              f"iterations (at most {max_iterations}), max|B u - c| {c['equality_residual']:.1e}")


def bounded_multiplications(dirs, max_mults):
    """A nonlinear run's QPs together take at most max_mults Hessian multiplications, the same
    on every rank count (a face phase that falls back to SMALBE's outer iterations costs
    thousands: the Tresca block's second QP of step 2 took 9,034 before 2026-12-06)."""
    ref = load(dirs[0])
    for d in dirs:
        s = load(d)
        if not s["converged"]:
            fail(f"{d}: did not converge")
        n = s["nonlinear"]["total_hessian_multiplications"]
        per_step = [x["hessian_multiplications"] for x in s["steps"]]
        if n > max_mults:
            fail(f"{d}: {n} Hessian multiplications > {max_mults} (per step: {per_step})")
        if n != ref["nonlinear"]["total_hessian_multiplications"]:
            fail(f"{d}: {n} Hessian multiplications, "
                 f"{ref['nonlinear']['total_hessian_multiplications']} in {dirs[0]}")
        print(f"OK: {d}: {s['ranks']} ranks: {n} Hessian multiplications (at most {max_mults})")


def tightened_qps(d):
    """A Newton loop whose test stalled at the QPs' accuracy (LoadStepIteration::tightenQps): the
    run converged, some QPs were solved at a factor below 1 of the configured tolerances, among
    them the last one (whose multipliers are reported), and each only once an earlier iteration
    of its step had brought the residual below Eta 2."""
    s = load(d)
    if not s["converged"]:
        fail(f"{d}: did not converge")
    eta2 = s["parameters"]["Nonlinear"]["Eta 2"]
    with open(os.path.join(d, "iterations.csv")) as f:
        rows = list(csv.DictReader(f))
    tight = [r for r in rows if float(r["qp_tolerance_factor"]) < 1.0]
    if not tight:
        fail(f"{d}: no QP solved tighter than configured")
    if float(rows[-1]["qp_tolerance_factor"]) >= 1.0:
        fail(f"{d}: the last QP was not among the tightened ones")
    for r in tight:
        earlier = [q for q in rows if q["step"] == r["step"] and q["accepted"] == r["accepted"]
                   and int(q["iteration"]) < int(r["iteration"])]
        if not any(float(q["relative_residual"]) < eta2 for q in earlier):
            fail(f"{d}: step {r['step']} iteration {r['iteration']} tightened before the residual "
                 f"met Eta 2 = {eta2}")
    print(f"OK: {d}: {len(tight)} of {len(rows)} QPs at factor "
          f"{min(float(r['qp_tolerance_factor']) for r in tight)}, the last one among them")


def zero_load(dirs):
    """No load: the contact force, p_max and every displacement exactly zero."""
    for d in dirs:
        s = load(d)
        c = s["contact"]
        if not s["converged"]:
            fail(f"{d}: did not converge: " + s["qp"].get("message", ""))
        for name, value in (("contact force", c["force"]), ("p_max", c["p_max"]),
                            ("max|u|", s["max_abs_u"]), ("max von Mises", s["max_von_mises"])):
            if value != 0.0:
                fail(f"{d}: {name} = {value:.3e} without any load (must be exactly 0)")
        print(f"OK: {d}: exactly zero ({s['qp']['hessian_multiplications']} multiplications)")


def tiny_load(d, full_load):
    """A load tiny against the stiffness: the solution to absolute tolerances. The solver's
    tolerances are relative to ||b||, which the gaps dominate here, so they are absolute in the
    load: the KKT conditions to KKT_TOL x ||b|| (a displacement), the force balance to the
    absolute error allowed at the full load (1e-6 x full_load)."""
    s = load(d)
    c, q = s["contact"], s["qp"]
    if not s["converged"]:
        fail("did not converge: " + q.get("message", ""))
    scale_u = KKT_TOL * q["rhs_norm"]
    checks = [("penetration", c["max_penetration"], scale_u),
              ("gluing residual", c["equality_residual"], scale_u),
              ("negative multiplier", -c["min_multiplier"], 0.0),
              ("force error |sum lambda - load|", abs(c["force"] - c["applied_force"]),
               1e-6 * full_load)]
    for name, value, tol in checks:
        if value > tol:
            fail(f"{name} = {value:.3e} > {tol:.3e}")
    print(f"OK: force {c['force']:.6e} (applied {c['applied_force']:.6e}); " +
          ", ".join(f"{n} {v:.1e} <= {t:.1e}" for n, v, t in checks))


STEP_KEYS = ("step", "load_factor", "outer_iterations", "mprgp_iterations", "residuals",
             "p_max", "max_von_mises", "max_plastic_strain", "contact_extent")


def nonlinear(d, force_tol, hertz_tol):
    s = load(d)
    nl = s["nonlinear"]
    if not s["converged"] or abs(nl["load_factor"] - 1.0) > 1e-12:
        fail(f"{d}: did not reach load factor 1 ({nl['load_factor']}): {nl.get('message', '')}")
    steps = s["steps"]
    if not steps or len(steps) != nl["converged_steps"]:
        fail(f"{d}: {len(steps)} step records for {nl['converged_steps']} converged steps")
    for st in steps:
        missing = [k for k in STEP_KEYS if k not in st]
        if missing:
            fail(f"{d}: step {st.get('step')} lacks {missing}")
        if st["residuals"][-1] >= nl["eta2"] or st["increments"][-1] >= nl["eta1"]:
            fail(f"{d}: step {st['step']} ended at residual {st['residuals'][-1]:.2e}, "
                 f"increment {st['increments'][-1]:.2e} (Eta 2 {nl['eta2']}, Eta 1 {nl['eta1']})")
        if st["outer_iterations"] != len(st["residuals"]):
            fail(f"{d}: step {st['step']}: {st['outer_iterations']} iterations, "
                 f"{len(st['residuals'])} residuals")
    c = s["contact"]
    k = c["last_solve"]
    u = s["max_abs_u"]
    if k["max_penetration"] > KKT_TOL * u or k["equality_residual"] > KKT_TOL * u:
        fail(f"{d}: last solve: penetration {k['max_penetration']:.2e}, gluing residual "
             f"{k['equality_residual']:.2e}")
    if k["min_multiplier"] < 0:
        fail(f"{d}: negative contact multiplier {k['min_multiplier']}")
    if c["force_relative_error"] > force_tol:
        fail(f"{d}: resultant contact force {c['force']:.6e} against the load "
             f"{c['applied_force']:.6e}: {c['force_relative_error']:.1e} > {force_tol}")
    # The reaction of the fixed boundaries balances the contact force (and the load).
    if "support_relative_error" in c and c["support_relative_error"] > force_tol:
        fail(f"{d}: support reaction {c['support_force']:.6e} against the contact force "
             f"{c['force']:.6e}: {c['support_relative_error']:.1e} > {force_tol}")
    if k["max_complementarity"] > KKT_TOL * u * max(abs(c["force"]), 1e-300):
        fail(f"{d}: last solve: complementarity {k['max_complementarity']:.2e}")
    if hertz_tol > 0:
        extent = "contact_radius" if "contact_radius" in c else "half_width"
        for key in ("p_max", extent):
            if c["relative_error"][key] > hertz_tol:
                fail(f"{d}: {key} {c[key]:.5e} vs Hertz {c['hertz'][key]:.5e}: "
                     f"{100 * c['relative_error'][key]:.2f} % > {100 * hertz_tol:.0f} %")
    print(f"OK: {len(steps)} steps, {nl['total_iterations']} iterations, p_max {c['p_max']:.5e}, "
          f"extent {c['contact_extent']:.5e}, force error {c['force_relative_error']:.1e}")


# Compared across runs: what the solution determines. Not the split of a node's contact force
# into the multipliers lambda (normal) and tangential_force, nor their sums normal_force and
# tangential_force: a slave node that sits on a master node where the master kinks (the centre
# node of the symmetric Cattaneo mesh) takes either segment's frame as rounding decides, and its
# two multipliers rotate by the kink's angle (docs/friction.md). Its force vector (force_x, ...)
# and the resultant contact_force do not.
FRICTION_KEYS = ("max_accumulated_slip", "max_net_slip")
FRICTION_COLUMNS = ("slip_increment", "accumulated_slip", "net_slip")
FORCE_COLUMNS = ("force_x", "force_y", "force_z")


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def same_friction(d, ref_dir, tol):
    """Two frictional runs' friction results: the resultant contact force (to tol of its
    magnitude) and the contact keys FRICTION_KEYS (to tol relative); per node (matched by its
    id) in the final contact CSV and in every per-step CSV both have, the contact force's
    components to tol of the largest force's magnitude, the step's slip and the accumulated slip
    to tol of the column's largest value (the slips at least to KKT_TOL max|u|, the level at which a sticking node's slip is zero),
    and the same state (stick or slip; but at the transition, see at_bound). Returns the largest
    differences."""
    import glob
    import os
    a, b = load(ref_dir)["contact"], load(d)["contact"]
    fr = load(ref_dir)["parameters"]["Contact problem"]["Friction"]
    fa, fb = a["contact_force"], b["contact_force"]
    size = math.sqrt(sum(v * v for v in fa))
    if len(fa) != len(fb) or any(abs(x - y) > tol * size for x, y in zip(fa, fb)):
        fail(f"{d}: contact.contact_force {fb} differs from {fa} ({ref_dir})")
    for key in FRICTION_KEYS:
        if abs(a[key] - b[key]) > tol * max(abs(a[key]), 1e-300):
            fail(f"{d}: contact.{key} {b[key]} differs from {a[key]} ({ref_dir})")
    files = ["contact_pressure.csv"] + sorted(
        os.path.basename(p) for p in glob.glob(ref_dir + "/contact_pressure_step_*.csv")
        if os.path.exists(d + "/" + os.path.basename(p)))
    columns = FORCE_COLUMNS[:len(fa)] + FRICTION_COLUMNS
    # A sticking node's slip is zero to the QP's tolerance, which the friction checks hold to
    # KKT_TOL max|u|: below that two runs' slips need not agree (in a step where every node
    # sticks the column's largest value is such a zero).
    slip_floor = KKT_TOL * load(ref_dir)["max_abs_u"]
    worst = {c: 0.0 for c in columns}
    for name in files:
        ra = {r["node"]: r for r in read_rows(ref_dir + "/" + name)}
        rb = {r["node"]: r for r in read_rows(d + "/" + name)}
        if set(ra) != set(rb):
            fail(f"{d}/{name}: other slave nodes than {ref_dir}/{name}")
        # The force is a vector: its components to tol of its largest magnitude (in a step
        # loaded normally only, the x components are small beside the y ones).
        force_scale = max(math.sqrt(sum(float(r[c]) ** 2 for c in columns if c in FORCE_COLUMNS))
                          for r in ra.values())
        for col in columns:
            scale = (force_scale if col in FORCE_COLUMNS else
                     max(abs(float(r[col])) for r in ra.values()))
            for n, r in ra.items():
                diff = abs(float(r[col]) - float(rb[n][col]))
                allowed = tol * scale if col in FORCE_COLUMNS else max(tol * scale, slip_floor)
                worst[col] = max(worst[col], tol * diff / allowed if allowed > 0 else diff)
                if diff > allowed:
                    fail(f"{d}/{name}: node {n} {col} {rb[n][col]} differs from {r[col]} "
                         f"({ref_dir}; tolerance {allowed:.3e})")
        for n, r in ra.items():
            # A node exactly at the stick/slip transition (|lambda_T| at its bound to 1e-4 in
            # both runs) may be classified either way by rounding; any other must agree.
            if r["state"] != rb[n]["state"] and not (at_bound(r, fr) and at_bound(rb[n], fr)):
                fail(f"{d}/{name}: node {n} is {rb[n]['state']}, {r['state']} in {ref_dir}")
    return files, worst


def at_bound(row, friction):
    """|lambda_T| within 1e-4 of its bound (Coulomb: mu lambda_N; Tresca: the traction g)."""
    if friction["Friction law"] == "Coulomb":
        bound, value = friction["Friction coefficient"] * float(row["lambda"]), row["tangential_force"]
    else:
        bound, value = friction["Slip bound"], row["tangential_traction"]
    return bound > 0 and abs(abs(float(value)) - bound) <= 1e-4 * bound


def same_nonlinear(dirs):
    """Nonlinear runs of one problem (other rank counts, a restart): the same load steps and per
    step p_max, extent, von Mises and plastic strain; frictional runs also the friction results
    (same_friction)."""
    ref = load(dirs[0])["steps"]
    friction = "friction_law" in load(dirs[0]).get("contact", {})
    for d in dirs[1:]:
        if friction:
            files, worst = same_friction(d, dirs[0], 1e-5)
            print(f"OK: {d}: friction results of {len(files)} contact CSVs agree, largest "
                  "differences relative to the column's largest value (forces: the largest "
                  "force's magnitude; slips: at least KKT_TOL max|u| / tol): " +
                  ", ".join(f"{c} {v:.1e}" for c, v in worst.items()))
        other = load(d)["steps"]
        if [s["load_factor"] for s in other] != [s["load_factor"] for s in ref]:
            fail(f"{d}: load steps {[s['load_factor'] for s in other]} differ from "
                 f"{[s['load_factor'] for s in ref]} ({dirs[0]})")
        for a, b in zip(ref, other):
            # The plastic strain where yield begins is the most sensitive quantity: it moves
            # with the iterates at the level of the stopping tolerances (Eta 1, Eta 2).
            for key, tol in (("p_max", 1e-5), ("contact_extent", 1e-5), ("max_von_mises", 1e-5),
                             ("max_plastic_strain", 1e-3)):
                scale = max(abs(a[key]), 1e-300)
                if abs(a[key] - b[key]) > tol * scale:
                    fail(f"{d}: step {b['step']} {key} {b[key]} differs from {a[key]} ({dirs[0]})")
    print(f"OK: {len(dirs)} runs agree over {len(ref)} steps")


def nonlinear_vs_elastic(ndir, edir, tol, force_tol=1e-6):
    """A nonlinear run with a linear elastic material in one step against the elastic contact
    run: the same p_max and contact extent to tol (the loop puts the rows on the deformed
    geometry, the elastic run on the reference one) and the same force to force_tol."""
    n, e = load(ndir), load(edir)
    if not n["converged"] or not e["converged"]:
        fail("a run did not converge")
    if n["max_plastic_strain"] != 0:
        fail(f"{ndir}: plastic strain {n['max_plastic_strain']} in an elastic run")
    cn, ce = n["contact"], e["contact"]
    extent = "contact_radius" if "contact_radius" in ce else "half_width"
    for key, t in (("p_max", tol), (extent, tol), ("force", force_tol)):
        rel = abs(cn[key] - ce[key]) / abs(ce[key])
        if rel > t:
            fail(f"{key}: nonlinear {cn[key]:.8e}, elastic {ce[key]:.8e}: {rel:.1e} > {t:.0e}")
    print(f"OK: p_max {cn['p_max']:.6e} vs {ce['p_max']:.6e}, {extent} {cn[extent]:.6e} vs "
          f"{ce[extent]:.6e}, force {cn['force']:.8e} vs {ce['force']:.8e}")



def newton(ndir, rdir, tol):
    """A run whose tangent is refactorized (its kernel, the rigid modes of the reference positions
    in small strain and of the current ones in total Lagrangian, checked by the solver) against
    the paper's initial stiffness on the same problem: the same solution to the stopping
    tolerances, in fewer iterations."""
    n, r = load(ndir), load(rdir)
    for s, d in ((n, ndir), (r, rdir)):
        if not s["converged"] or s["nonlinear"]["load_factor"] != 1:
            fail(f"{d}: did not reach load factor 1")
    if n["nonlinear"]["stiffness"] == "initial" or r["nonlinear"]["stiffness"] != "initial":
        fail("the first run must refactorize its tangent, the second keep the initial stiffness")
    if [s["load_factor"] for s in n["steps"]] != [s["load_factor"] for s in r["steps"]]:
        fail("the runs took different load steps")
    extent = "contact_radius" if "contact_radius" in r["contact"] else "half_width"
    pairs = [(k, n["contact"][k], r["contact"][k], tol) for k in ("p_max", extent, "force")]
    pairs += [("max_von_mises", n["max_von_mises"], r["max_von_mises"], tol),
              ("max_plastic_strain", n["max_plastic_strain"], r["max_plastic_strain"], 100 * tol)]
    for key, a, b, t in pairs:
        if abs(a - b) > t * abs(b):
            fail(f"{key}: {a:.8e} ({ndir}) against {b:.8e} ({rdir}): more than {t:.0e} apart")
    ni, ri = n["nonlinear"]["total_iterations"], r["nonlinear"]["total_iterations"]
    if not ni < ri:
        fail(f"the tangent took {ni} iterations, the initial stiffness {ri}")
    print(f"OK: {n['nonlinear']['stiffness']}: {ni} iterations against {ri}; p_max "
          f"{n['contact']['p_max']:.6e} vs {r['contact']['p_max']:.6e}, force "
          f"{n['contact']['force']:.6e} vs {r['contact']['force']:.6e}")


def penalty_vs_smalbe(pdir, sdir, tol):
    """One nonlinear problem by the penalty method and by SMALBE: both converged to load factor 1,
    the penalty in at most 2 more Newton iterations, and the same p_max, contact force, largest
    von Mises stress and plastic strain to tol (the penalty's accuracy, about ||PFP|| / rho)."""
    p, q = load(pdir), load(sdir)
    for s, d in ((p, pdir), (q, sdir)):
        if not s["converged"] or s["nonlinear"]["load_factor"] != 1:
            fail(f"{d}: did not reach load factor 1")
    if p["parameters"]["FETI"]["Dual solver"] != "penalty":
        fail(f"{pdir}: not a penalty run")
    pi, si = p["nonlinear"]["total_iterations"], q["nonlinear"]["total_iterations"]
    if pi > si + 2:
        fail(f"the penalty took {pi} Newton iterations, SMALBE {si}")
    pairs = [("p_max", p["contact"]["p_max"], q["contact"]["p_max"]),
             ("force", p["contact"]["force"], q["contact"]["force"]),
             ("max_von_mises", p["max_von_mises"], q["max_von_mises"]),
             ("max_plastic_strain", p["max_plastic_strain"], q["max_plastic_strain"])]
    for key, a, b in pairs:
        if abs(a - b) > tol * max(abs(b), 1e-300):
            fail(f"{key}: penalty {a:.8e}, SMALBE {b:.8e}: more than {tol:.0e} apart")
    print(f"OK: penalty {pi} Newton iterations, SMALBE {si}; p_max {pairs[0][1]:.6e} vs "
          f"{pairs[0][2]:.6e}, force {pairs[1][1]:.6e} vs {pairs[1][2]:.6e}")


def same_indentation(d1, d2, tol):
    """Two formulations of one indentation by a prescribed obstacle motion: the same contact force
    and contact zone to tol (what separates them, e.g. the gap along the normal and along a fixed
    direction, is of the order of (a / R)^2)."""
    a, b = load(d1), load(d2)
    for s, d in ((a, d1), (b, d2)):
        if not s["converged"] or s["nonlinear"]["load_factor"] != 1:
            fail(f"{d}: did not reach load factor 1")
    extent = "contact_radius" if "contact_radius" in a["contact"] else "half_width"
    for key in ("force", extent):
        x, y = a["contact"][key], b["contact"][key]
        if abs(x - y) > tol * abs(y):
            fail(f"{key}: {x:.8e} ({d1}) against {y:.8e} ({d2}): more than {tol:.0e} apart")
    print(f"OK: force {a['contact']['force']:.6e} vs {b['contact']['force']:.6e}, {extent} "
          f"{a['contact'][extent]:.6e} vs {b['contact'][extent]:.6e}")

def reference_force(dirs, expected, tol):
    """Runs against a contact force another code computed on the same discrete problem (e.g.
    deal.II's step-42, tests/inputs/step42_16*.xml say how the value was obtained): each run's
    force within tol (relative) of it."""
    for d in dirs:
        s = load(d)
        if not s["converged"]:
            fail(f"{d}: did not converge")
        f = s["contact"]["force"]
        if abs(f - expected) > tol * abs(expected):
            fail(f"{d}: contact force {f:.8e} against the reference {expected:.8e}: more than "
                 f"{tol:.0e} apart ({abs(f - expected) / abs(expected):.2e})")
        print(f"OK: {d}: contact force {f:.8e}, reference {expected:.8e} "
              f"({abs(f - expected) / abs(expected):.1e} apart)")


def plastic(d):
    """A plastic run beyond yield: plastic strain > 0 and the von Mises stress within the yield
    surface sigma_Y + H alpha_max (1 % for the Cauchy stress of a law that acts on the second
    Piola-Kirchhoff stress, as in plastic_vs_elastic) at every converged step."""
    s = load(d)
    m = s["material"]
    sy, h = m["yield_stress"], m.get("hardening_modulus", 0.0)
    for st in s["steps"]:
        bound = 1.01 * (sy + h * st["max_plastic_strain"])
        if st["max_von_mises"] > bound:
            fail(f"{d}: step {st['step']}: von Mises {st['max_von_mises']:.4e} above the yield "
                 f"surface {bound:.4e}")
    if not s["max_plastic_strain"] > 0:
        fail(f"{d}: no plastic strain")
    print(f"OK: plastic strain {s['max_plastic_strain']:.3e}, von Mises {s['max_von_mises']:.4e} "
          f"(sigma_Y {sy:.2e}, H {h:.2e})")


def built_and_reused(dirs, built_key, reused_key, what, check):
    """The counters timings[built_key] and timings[reused_key] of every run: check(d, s, built,
    reused) fails on a run's own rule; the counts must be the same in every run (they must not
    depend on the rank count)."""
    counts = []
    for d in dirs:
        s = load(d)
        built, reused = s["timings"][built_key], s["timings"][reused_key]
        if not reused > 0:
            fail(f"{d}: no {what} reused ({built} built)")
        check(d, s, built, reused)
        counts.append((built, reused))
    if len(set(counts)) != 1:
        fail(f"the {what}s depend on the rank count: {counts} for {dirs}")
    print(f"OK: {counts[0][0]} {what}s built, {counts[0][1]} reused, in every run")


def factorizations_reused(dirs):
    """A small-strain plastic run with the tangent refactorized: the subdomains whose tangent
    stayed elastic keep their factor (timings subdomain_factorizations_reused > 0, fewer
    factorizations than subdomains times tangents), and which ones does not depend on the rank
    count (the same counts in every run)."""
    def whole(d, s, done, kept):
        if (done + kept) % s["subdomains"] != 0 or done < s["subdomains"]:
            fail(f"{d}: {done} computed and {kept} reused factorizations are not whole "
                 f"refactorizations of {s['subdomains']} subdomains")
    built_and_reused(dirs, "subdomain_factorizations", "subdomain_factorizations_reused",
                     "factorization", whole)


def analyses_shared(dirs):
    """Subdomains cut from a structured mesh repeat their sparsity patterns: the local factors
    share the symbolic analysis of a live factor of the same pattern (timings symbolic_analyses
    made, symbolic_analyses_shared > 0). The counts are per rank, so they depend on the rank
    count; the factorizations made from them do not."""
    for d in dirs:
        t = load(d)["timings"]
        made, shared = t["symbolic_analyses"], t["symbolic_analyses_shared"]
        if not made > 0 or not shared > 0:
            fail(f"{d}: {made} symbolic analyses made and {shared} shared: none shared")
        print(f"OK: {d}: {made} symbolic analyses made, {shared} shared")


def distribution_balance(dirs, contact_tol, dof_tol):
    """Subdomains to ranks with the contact zone shared: on more than one rank the graph method
    partitions with the contact rows as a second constraint (subdomain_distribution.partitioner
    metis_two_constraints), the largest rank's share of the initial contact rows within contact_tol
    of the mean and of the dofs within dof_tol; on one rank everything is balanced (1.0)."""
    for d in dirs:
        s = load(d)
        dist = s["subdomain_distribution"]
        if s["ranks"] == 1:
            if dist["partitioner"] != "single" or dist["contact_imbalance"] != 1.0:
                fail(f"{d}: one rank, but the distribution is {dist}")
        else:
            if dist["partitioner"] != "metis_two_constraints":
                fail(f"{d}: partitioner {dist['partitioner']}, expected metis_two_constraints "
                     "(the run has contact rows)")
            if dist["contact_imbalance"] > contact_tol:
                fail(f"{d}: contact imbalance {dist['contact_imbalance']:.4f} > {contact_tol}")
            if dist["dof_imbalance"] > dof_tol:
                fail(f"{d}: dof imbalance {dist['dof_imbalance']:.4f} > {dof_tol}")
        print(f"OK: {d}: {s['ranks']} rank(s), {dist['partitioner']}, dof imbalance "
              f"{dist['dof_imbalance']:.4f}, contact imbalance {dist['contact_imbalance']:.4f}, "
              f"cut {dist['edge_cut']:g}")


def tearings_reused(dirs, expected_built=None):
    """A Newton run against a height-function obstacle in small strain: the contact rows keep
    their entries from one iteration to the next (only the gaps move), so the solver keeps its
    tearing and coarse space (timings tearings_reused > 0); every iteration's QP either kept or
    built them (tearings + tearings_reused = the Newton iterations + the first set-up), and the
    counts do not depend on the rank count. With expected_built, exactly that many tearings are
    built (1: the solver is built with the first increment's rows, and a rigid obstacle's rows
    are kept through the step)."""
    def one_per_iteration(d, s, built, kept):
        iterations = s["nonlinear"]["total_iterations"]
        if built + kept != iterations + 1:
            fail(f"{d}: {built} tearings built and {kept} kept for {iterations} Newton "
                 f"iterations and the first set-up")
        if expected_built is not None and built != expected_built:
            fail(f"{d}: {built} tearings built, expected {expected_built}")
    built_and_reused(dirs, "tearings", "tearings_reused", "tearing", one_per_iteration)


def plastic_vs_elastic(pdir, edir):
    p, e = load(pdir), load(edir)
    for s, d in ((p, pdir), (e, edir)):
        if not s["converged"]:
            fail(f"{d}: did not converge")
    sy = p["material"]["yield_stress"]
    if e["max_von_mises"] <= sy:
        fail(f"the elastic run stays below yield ({e['max_von_mises']:.3e} <= {sy:.3e}): "
             f"no overload")
    if p["max_plastic_strain"] <= 0:
        fail("the overloaded plastic run has no plastic strain")
    if p["max_von_mises"] > 1.01 * sy:
        fail(f"von Mises {p['max_von_mises']:.4e} exceeds sigma_Y {sy:.4e} by more than 1 %")
    pp, pe = p["contact"]["p_max"], e["contact"]["p_max"]
    if not pp < 0.97 * pe:
        fail(f"plastic p_max {pp:.4e} is not below the elastic {pe:.4e} (by 3 %)")
    print(f"OK: p_max plastic {pp:.4e} < elastic {pe:.4e}; von Mises {p['max_von_mises']:.4e} "
          f"(sigma_Y {sy:.1e}); plastic strain {p['max_plastic_strain']:.3e}")


def arc_grows(d09, d099):
    a, b = load(d09), load(d099)
    for s, d in ((a, d09), (b, d099)):
        if not s["converged"] or s["contact"]["extent_measure"] != "angle":
            fail(f"{d}: not converged, or the extent is not an angle")
    t09, t099 = a["contact"]["contact_extent"], b["contact"]["contact_extent"]
    if not t099 > 1.5 * t09:
        fail(f"contact half-angle {t099:.2f} deg (0.99) is not well above {t09:.2f} deg (0.9)")
    print(f"OK: contact half-angle {t09:.2f} deg (R_pin/R_hole = 0.9) < {t099:.2f} deg (0.99)")


def friction(d, expect, force, mu, tol, resultant_tol=None, magnitudes=False, kkt_tol=None):
    """A frictional nonlinear run: the friction rows' conditions of the last solve (multipliers
    within their box, no slip where they stick, slip along the multiplier where it is at the
    bound), and per node in the contact CSV: expect = slide: every closed node slips and the
    tangential force is `force` (Tresca: -g times the closed length), or -mu times the normal
    force P = sum of the normal multipliers (Coulomb, mu > 0), to tol; expect = stick: every closed node sticks, its slip
    increment zero against the largest displacement. magnitudes (3D, --magnitudes): at full
    sliding the nodes' tangential forces point different ways, so `force` is compared with the
    sum of their magnitudes |lambda_T| (Tresca: g times the slave area), and every closed node
    has a non-zero slip increment. kkt_tol (--kkt-tol): the friction rows' conditions to this,
    the multipliers' excess over their bound relative to g (default 1e-10) and the slip where
    they stick relative to max |u| (default KKT_TOL); the penalty method meets them only to about
    ||PFP|| / rho."""
    resultant_tol = tol if resultant_tol is None else resultant_tol
    bound_tol = 1e-10 if kkt_tol is None else kkt_tol
    slip_tol = KKT_TOL if kkt_tol is None else kkt_tol
    s = load(d)
    if not s["converged"]:
        fail(f"{d}: did not converge")
    c = s["contact"]
    k = c["last_solve"]
    g = s["parameters"]["Contact problem"]["Friction"]["Slip bound"]
    if mu > 0:
        force = -mu * c["normal_force"]
        g = mu * c["p_max"]
    u = s["max_abs_u"]
    for key in ("tangential_force", "slip_nodes", "stick_nodes",
                "stick_radius" if magnitudes else "stick_half_width", "max_tangential_ratio",
                "friction_law"):
        if key not in c:
            fail(f"{d}: contact lacks {key}")
    if k["max_friction_bound_excess"] > bound_tol * g:
        fail(f"{d}: a tangential multiplier beyond its bound by {k['max_friction_bound_excess']}")
    if k["max_friction_slip_residual"] > slip_tol * u:
        fail(f"{d}: friction rows' slip residual {k['max_friction_slip_residual']:.2e} "
             f"(max |u| {u:.2e})")
    with open(s["contact_csv"]) as f:
        rows = list(csv.DictReader(f))
    closed = [r for r in rows if r["state"] != "open"]
    if not closed:
        fail(f"{d}: no closed node")
    if expect == "slide":
        if c["stick_nodes"] != 0 or c["slip_nodes"] != len(closed):
            fail(f"{d}: {c['stick_nodes']} stick, {c['slip_nodes']} slip of {len(closed)} closed")
        if magnitudes:
            lt = sum(abs(float(r["tangential_force"])) for r in closed)
            if abs(lt - abs(force)) > resultant_tol * abs(force):
                fail(f"{d}: sum |lambda_T| {lt:.10e}, expected {abs(force):.10e}")
            slip = min(abs(float(r["slip_increment"])) for r in closed)
            if not slip > KKT_TOL * u:
                fail(f"{d}: a sliding node's slip increment is {slip:.2e} (max |u| {u:.2e})")
        elif abs(c["tangential_force"] - force) > resultant_tol * abs(force):
            fail(f"{d}: tangential force {c['tangential_force']:.10e}, expected {force:.10e}")
        if mu > 0:
            # In the contact's own frame: the tangential multipliers sum to mu times the normal
            # ones (the x resultant differs from it where the rows' normals tilt on a curved or
            # deformed master: --resultant-tol).
            lt = sum(abs(float(r["tangential_force"])) for r in closed)
            ln = sum(float(r["lambda"]) for r in closed)
            if abs(lt - mu * ln) > tol * mu * ln:
                fail(f"{d}: sum |lambda_T| {lt:.10e} against mu sum lambda_N {mu * ln:.10e}")
        # Coulomb: the bounds in force are the last iterate's, mu lambda_N to the Fixed-point
        # tolerance in the 2-norm over the nodes, which lets one node's bound differ by more
        # (1.7e-6 seen for a 1e-6 tolerance): 10x the tolerance per node.
        ratio_tol = 1e-8 if mu == 0 else max(
            1e-8, 10 * s["parameters"]["Contact problem"]["Friction"]["Fixed-point tolerance"])
        if kkt_tol is not None:
            ratio_tol = max(ratio_tol, 10 * kkt_tol)
        if abs(c["max_tangential_ratio"] - 1.0) > ratio_tol:
            fail(f"{d}: max |lambda_T| / bound {c['max_tangential_ratio']} at full sliding")
    else:
        if c["slip_nodes"] != 0 or c["stick_nodes"] != len(closed):
            fail(f"{d}: {c['stick_nodes']} stick, {c['slip_nodes']} slip of {len(closed)} closed")
        slip = max(abs(float(r["slip_increment"])) for r in closed)
        if slip > KKT_TOL * u:
            fail(f"{d}: a sticking node slipped by {slip:.2e} (max |u| {u:.2e})")
        if not c["max_tangential_ratio"] < 1.0:
            fail(f"{d}: max |lambda_T| / bound {c['max_tangential_ratio']} while sticking")
    print(f"OK: {expect}: tangential force {c['tangential_force']:.8e}, {c['slip_nodes']} slip, "
          f"{c['stick_nodes']} stick, max ratio {c['max_tangential_ratio']:.6f}")


def friction_held(d, tol):
    """A body held along the surface by friction alone (no support): the run converged to load
    factor 1, the resultant contact force (normal and tangential) is the load in magnitude and
    along it (force_relative_error), the friction rows' conditions hold, and some node sticks
    (were all sliding, nothing would fix the body's sliding); with Tresca the summary's
    friction_limit beyond load factor 1, with Coulomb none."""
    s = load(d)
    if not s["converged"] or abs(s["nonlinear"]["load_factor"] - 1.0) > 1e-12:
        fail(f"{d}: did not reach load factor 1")
    c = s["contact"]
    k = c["last_solve"]
    u = s["max_abs_u"]
    resultant = math.sqrt(sum(f * f for f in c["contact_force"]))
    if abs(resultant - c["applied_force"]) > tol * c["applied_force"]:
        fail(f"{d}: |contact_force| {resultant:.10e} against the load {c['applied_force']:.10e}")
    if c["force_relative_error"] > tol:
        fail(f"{d}: force {c['force']:.10e} along the load, applied {c['applied_force']:.10e}")
    if k["max_friction_bound_excess"] > 1e-10 * c["applied_force"]:
        fail(f"{d}: a tangential multiplier beyond its bound by {k['max_friction_bound_excess']}")
    if c["max_tangential_ratio"] > 1.0 + 1e-5:
        fail(f"{d}: max |lambda_T| / bound {c['max_tangential_ratio']}")
    if k["max_friction_slip_residual"] > KKT_TOL * u or k["max_penetration"] > KKT_TOL * u:
        fail(f"{d}: slip residual {k['max_friction_slip_residual']:.2e}, penetration "
             f"{k['max_penetration']:.2e} (max |u| {u:.2e})")
    if c["stick_nodes"] < 1:
        fail(f"{d}: no node sticks")
    # Tresca's limit, known from the data, lies beyond load factor 1 (Coulomb's cones give none,
    # or 0, which is an error before the run).
    limit = s["nonlinear"].get("friction_limit")
    if c["friction_law"] == "Tresca" and (limit is None or not limit["load_factor"] > 1.0):
        fail(f"{d}: nonlinear.friction_limit {limit}: a Tresca body held to load factor 1")
    if c["friction_law"] != "Tresca" and limit is not None:
        fail(f"{d}: nonlinear.friction_limit {limit} without Tresca friction")
    print(f"OK: contact force {c['contact_force']} against the load {c['applied_force']:.6e}, "
          f"{c['stick_nodes']} stick, {c['slip_nodes']} slip")


def friction_beyond(d, limit):
    """A body held by friction alone, loaded beyond what friction can hold from the load factor
    `limit` on: the run stops with the step control's failure, its summary written, at the last
    converged load factor, below the limit and within 5 % of it; the summary's
    nonlinear.friction_limit (known from the data) is the limit to 1e-12."""
    s = load(d)
    nl = s["nonlinear"]
    if s["converged"]:
        fail(f"{d}: converged beyond the friction's limit")
    t = nl["load_factor"]
    if not (0.95 * limit < t <= limit):
        fail(f"{d}: last converged load factor {t}, expected just below {limit}")
    known = nl.get("friction_limit", {}).get("load_factor")
    if known is None or abs(known - limit) > 1e-12 * limit:
        fail(f"{d}: nonlinear.friction_limit.load_factor {known}, expected {limit}")
    print(f"OK: stopped at load factor {t:.6f} (limit {limit:.6f}): {nl.get('message', '')[:120]}")


def cattaneo(d, tol):
    """Cattaneo-Mindlin partial slip (a 2D Coulomb run loaded normally, then tangentially by a
    loading plate: a coupled and a prescribed component of one boundary): Q/(mu P) about 1/2,
    the stick half-width c within tol of a sqrt(1 - Q/(mu P)), stick and slip nodes both
    present, the friction rows' conditions of the last solve, the normal force equal to the
    applied load, the plate's prescribed reaction balancing Q, the resultant contact force
    balancing the plate's reaction and the load to 1e-6, the coupled boundary straight."""
    s = load(d)
    if not s["converged"]:
        fail(f"{d}: did not converge")
    c = s["contact"]
    cm = c.get("cattaneo_mindlin")
    if cm is None:
        fail(f"{d}: contact lacks cattaneo_mindlin")
    k = c["last_solve"]
    mu = c["friction_coefficient"]
    if k["max_friction_bound_excess"] > 1e-10 * mu * c["p_max"]:
        fail(f"{d}: a tangential multiplier beyond its bound by {k['max_friction_bound_excess']}")
    if k["max_friction_slip_residual"] > KKT_TOL * s["max_abs_u"]:
        fail(f"{d}: friction rows' slip residual {k['max_friction_slip_residual']:.2e}")
    q = cm["q_over_mu_p"]
    if not 0.3 < q < 0.7:
        fail(f"{d}: Q/(mu P) = {q:.4f}, not about 1/2")
    if c["stick_nodes"] == 0 or c["slip_nodes"] == 0:
        fail(f"{d}: {c['stick_nodes']} stick and {c['slip_nodes']} slip nodes: no partial slip")
    if cm["stick_ratio_error"] > tol:
        fail(f"{d}: c/a = {cm['stick_ratio']:.4f} against sqrt(1 - Q/(mu P)) = "
             f"{cm['stick_ratio_closed_form']:.4f}: {100 * cm['stick_ratio_error']:.2f} % > "
             f"{100 * tol:.0f} %")
    # The contact force along the load balances the applied load to the QP's tolerance.
    if c["force_relative_error"] > 1e-4:
        fail(f"{d}: contact force {c['force']} against the applied {c['applied_force']}")
    # The plate's reaction balances the x resultant of the contact forces; Q sums the tangential
    # multipliers only, and the rows on the deformed geometry tilt the normals by the surface's
    # slope (~1e-4 rad at P ~ 100 Q): they agree to 1 %.
    reaction = [e["reaction"] for e in s["prescribed"] if e["component"] == 0]
    Q = cm["tangential_force"]
    if len(reaction) != 1 or abs(abs(reaction[0]) - Q) > 1e-2 * Q:
        fail(f"{d}: the plate's reaction {reaction} does not balance Q = {Q}")
    # The cylinder's equilibrium (G lambda = e, to the QP's equality tolerance): the resultant
    # of the nodes' contact force vectors (normal and tangential, each in its node's frame) is
    # minus the plate's reaction along x and the applied line load along y.
    F = c["contact_force"]
    balance = max(abs(F[0] + reaction[0]), abs(F[1] - c["applied_force"]))
    if balance > 1e-6 * math.hypot(F[0], F[1]):
        fail(f"{d}: contact force {F} against (-{reaction[0]}, {c['applied_force']}): "
             f"{balance:.3e}")
    for e in s["couplings"]:
        if e["spread"] > 1e-8 * s["max_abs_u"]:
            fail(f"{d}: coupled {e['boundary']} spreads by {e['spread']:.2e}")
    print(f"OK: contact force ({F[0]:.8e}, {F[1]:.8e}) balances the plate and the load to "
          f"{balance / math.hypot(F[0], F[1]):.1e}")
    print(f"OK: P {cm['normal_force']:.6e}, Q {Q:.6e}, Q/(mu P) {q:.4f}; a "
          f"{cm['contact_half_width'] * 1e3:.3f} mm, c {cm['stick_half_width'] * 1e3:.3f} mm, "
          f"c/a {cm['stick_ratio']:.4f} against {cm['stick_ratio_closed_form']:.4f} "
          f"({100 * cm['stick_ratio_error']:.2f} %); {c['stick_nodes']} stick, "
          f"{c['slip_nodes']} slip; plate reaction {reaction[0]:.6e}")


def same_final(dirs):
    """Runs whose final states must agree (e.g. one load path and another that ends in full
    sliding): the contact figures of the last step and the friction forces to 1e-6."""
    ref = load(dirs[0])
    for d in dirs[1:]:
        other = load(d)
        for key in ("p_max", "contact_extent", "normal_force", "tangential_force"):
            a, b = ref["contact"][key], other["contact"][key]
            if abs(a - b) > 1e-6 * max(abs(a), 1e-300):
                fail(f"{d}: {key} {b} differs from {a} ({dirs[0]})")
        a, b = ref["max_von_mises"], other["max_von_mises"]
        if abs(a - b) > 1e-6 * abs(a):
            fail(f"{d}: max_von_mises {b} differs from {a} ({dirs[0]})")
    print(f"OK: {len(dirs)} runs end in the same state")


def vtu_point_data(path, names):
    """Points (x, y, z per point) and the named point-data arrays of one ASCII VTU piece."""
    import re
    with open(path) as f:
        xml = f.read()

    def array(name):
        m = re.search(r'<DataArray[^>]*Name="%s"[^>]*>(.*?)</DataArray>' % name, xml, re.S)
        if not m:
            fail(f"{path}: no DataArray {name}")
        return [float(v) for v in m.group(1).split()]
    return array("Points"), {n: array(n) for n in names}


STATE_CODES = {"open": 0, "stick": 1, "slip": 2}


def friction_fields(d):
    """The friction history and fields of a frictional nonlinear run with per-step contact CSVs
    and a final VTU: per node (its id), the accumulated slip of every step is the previous
    step's plus |slip increment| when the node is closed (the net slip: plus the signed
    increment), the path is at least |net| and positive at every node that slipped; the VTU's
    friction point data (contact_pressure, tangential_traction, slip_increment,
    accumulated_slip, net_slip, friction_state) at every point that is a slave node with a row
    equal the final contact CSV's at that node (position x + u to 1e-9 of the extent, values to
    1e-8 of the column's largest), -1 state and zeros elsewhere."""
    import glob
    s = load(d)
    steps = sorted(glob.glob(d + "/contact_pressure_step_*.csv"))
    if len(steps) < 2:
        fail(f"{d}: fewer than 2 per-step contact CSVs")
    acc = {}
    worst = 0.0
    for path in steps:
        rows = read_rows(path)
        scale = max(abs(float(r["slip_increment"])) for r in rows) or 1.0
        for r in rows:
            path0, net0 = acc.get(r["node"], (0.0, 0.0))
            ds = float(r["slip_increment"]) if r["state"] != "open" else 0.0
            expect = (path0 + abs(ds), net0 + ds)
            got = (float(r["accumulated_slip"]), float(r["net_slip"]))
            err = max(abs(e - g) for e, g in zip(expect, got)) / scale
            worst = max(worst, err)
            if err > 1e-9:
                fail(f"{path}: node {r['node']} accumulated slip {got} against the previous "
                     f"step's plus this step's {expect}")
            if got[0] < abs(got[1]) - 1e-12 * scale:
                fail(f"{path}: node {r['node']}: path {got[0]} below |net| {abs(got[1])}")
            acc[r["node"]] = got
    final = read_rows(d + "/contact_pressure.csv")
    slipped = [r for r in final if r["state"] == "slip"]
    if not slipped or min(float(r["accumulated_slip"]) for r in slipped) <= 0.0:
        fail(f"{d}: no slipping node, or one without accumulated slip")
    names = ("contact_pressure", "tangential_traction", "slip_increment", "accumulated_slip",
             "net_slip", "friction_state")
    columns = {"contact_pressure": "pressure", "tangential_traction": "tangential_traction",
               "slip_increment": "slip_increment", "accumulated_slip": "accumulated_slip",
               "net_slip": "net_slip"}
    pieces = sorted(glob.glob(d + "/solution_*.vtu"))
    if not pieces:
        fail(f"{d}: no solution_*.vtu")
    xs = [float(r["x"]) for r in final] + [float(r["y"]) for r in final]
    extent = max(xs) - min(xs)
    scales = {n: max(abs(float(r[c])) for r in final) or 1.0 for n, c in columns.items()}
    seen, points = set(), 0
    for path in pieces:
        pts, f = vtu_point_data(path, names + ("displacement",))
        u = f["displacement"]
        for k in range(len(pts) // 3):
            state = f["friction_state"][k]
            if state < 0:
                if state != -1 or any(f[n][k] != 0.0 for n in columns):
                    fail(f"{path}: point {k} without a contact row has friction values")
                continue
            x, y = pts[3 * k] + u[3 * k], pts[3 * k + 1] + u[3 * k + 1]
            match = [r for r in final if abs(float(r["x"]) - x) <= 1e-9 * extent and
                     abs(float(r["y"]) - y) <= 1e-9 * extent]
            if len(match) != 1:
                fail(f"{path}: point {k} at ({x}, {y}) matches {len(match)} contact CSV rows")
            r = match[0]
            if STATE_CODES[r["state"]] != state:
                fail(f"{path}: point {k} friction_state {state}, the CSV says {r['state']}")
            for n, c in columns.items():
                if abs(f[n][k] - float(r[c])) > 1e-8 * scales[n]:
                    fail(f"{path}: point {k} {n} {f[n][k]} against the CSV's {r[c]}")
            seen.add(r["node"])
            points += 1
    if seen != {r["node"] for r in final}:
        fail(f"{d}: {len(final) - len(seen)} contact CSV nodes missing from the VTU")
    print(f"OK: {d}: accumulated slip over {len(steps)} steps (worst {worst:.1e} of the step's "
          f"largest slip), largest path {s['contact']['max_accumulated_slip']:.4e} m, net "
          f"{s['contact']['max_net_slip']:.4e} m; VTU friction fields at {points} points "
          f"({len(seen)} slave nodes) equal the CSV")


def tresca_bonded(tdir, bdir, tol):
    """Tresca with a huge slip bound against the same plate bonded (Contact type = bonded): the
    bonded pair is closed everywhere (every normal multiplier > 0, so it is also a solution of
    the unilateral problem) and every Tresca node sticks; the prescribed entries' reactions (the
    top edge's normal and tangential forces), the Tresca tangential force against the bonded
    tangential reaction, and every displacement (VTU points by position) agree to tol (of
    max |u| for the displacements)."""
    t, b = load(tdir), load(bdir)
    for s, d in ((t, tdir), (b, bdir)):
        if not s["converged"]:
            fail(f"{d}: did not converge")
    if b.get("contact_type") != "bonded":
        fail(f"{bdir}: contact type {b.get('contact_type')}, not bonded")
    bonded = read_rows(b["contact_csv"])
    if min(float(r["lambda"]) for r in bonded) <= 0.0:
        fail(f"{bdir}: a bonded node pulls (lambda <= 0): the pair opens, no fair comparison")
    tres = read_rows(t["contact_csv"])
    if any(r["state"] != "stick" for r in tres) or len(tres) != len(bonded):
        fail(f"{tdir}: not every one of the {len(bonded)} nodes sticks")
    diffs = []
    rt = {(e["boundary"], e["component"]): e["reaction"] for e in t["prescribed"]}
    rb = {(e["boundary"], e["component"]): e["reaction"] for e in b["prescribed"]}
    for key, v in rb.items():
        diffs.append((f"reaction {key[0]} u_{'xyz'[key[1]]}", abs(rt[key] - v) / abs(v)))
    qb = [v for (name, c), v in rb.items() if c == 0][0]
    qt = t["contact"]["tangential_force"]
    diffs.append(("tangential force", abs(abs(qt) - abs(qb)) / abs(qb)))
    # Points by position (x, y, z: 2D has z = 0), every component (uz = 0 in 2D).
    ub = {}
    for _, x, y, z, ux, uy, uz in vtu_nodes(bdir):
        ub[(round(x, 9), round(y, 9), round(z, 9))] = (ux, uy, uz)
    scale = b["max_abs_u"]
    worst = 0.0
    for _, x, y, z, ux, uy, uz in vtu_nodes(tdir):
        ref = ub.get((round(x, 9), round(y, 9), round(z, 9)))
        if ref is None:
            fail(f"{tdir}: a point at ({x}, {y}, {z}) the bonded run does not have")
        worst = max(worst, *(abs(v - r) / scale for v, r in zip((ux, uy, uz), ref)))
    diffs.append(("max |u_Tresca - u_bonded| / max|u|", worst))
    for name, v in diffs:
        if v > tol:
            fail(f"{tdir}: {name} differs from the bonded run by {v:.2e} > {tol:.0e}")
    print(f"OK: Tresca g = {t['contact']['slip_bound']:.0e} against bonded: tangential force "
          f"{qt:.10e} (bonded reaction {qb:.10e}); " +
          ", ".join(f"{n} {v:.1e}" for n, v in diffs) +
          f"; max ratio {t['contact']['max_tangential_ratio']:.2e}, bonded lambda_N > 0 at all "
          f"{len(bonded)} nodes")


def option(args, name, default):
    return float(args[args.index(name) + 1]) if name in args else default


if __name__ == "__main__":
    mode, args = sys.argv[1], sys.argv[2:]
    if mode == "scalability":
        checked = [tuple(k.split(":")) for k in
                   (args[args.index("--check") + 1] if "--check" in args
                    else "tfeti:dirichlet").split(",")]
        scalability(args[0], int(option(args, "--reference-H", 4)), checked)
    elif mode == "single":
        single(args[0], option(args, "--max-error", 1e-6))
    elif mode == "same":
        same(args)
    elif mode == "same_dual_operator":
        flags = ("--tol", "--device", "--mult-tol", "--assembly")
        same_dual_operator([a for i, a in enumerate(args) if a not in flags + ("--partial",) and
                            (i == 0 or args[i - 1] not in flags)], option(args, "--tol", 1e-10),
                           args[args.index("--device") + 1] if "--device" in args else "host",
                           "--partial" in args, option(args, "--mult-tol", 0.01),
                           args[args.index("--assembly") + 1] if "--assembly" in args
                           else "schur")
    elif mode == "dual_operator_auto":
        fits = args[args.index("--fits-memory") + 1] if "--fits-memory" in args else "true"
        if fits not in ("true", "false"):
            fail(f"--fits-memory {fits}: expected true or false")
        dual_operator_auto(args[0], args[args.index("--chosen") + 1], fits == "true")
    elif mode == "factor_memory":
        checked = args[args.index("--checked") + 1] if "--checked" in args else None
        if checked not in ("true", "false"):
            fail(f"--checked {checked}: expected true or false")
        factor_memory(args[0], checked == "true",
                      args[args.index("--write-meminfo") + 1] if "--write-meminfo" in args
                      else None,
                      args[args.index("--write-meminfo-edges") + 1]
                      if "--write-meminfo-edges" in args else None)
    elif mode == "explicit_export":
        explicit_export(args[0], args[1:])
    elif mode == "factorizations_reused":
        factorizations_reused(args)
    elif mode == "analyses_shared":
        analyses_shared(args)
    elif mode == "tearings_reused":
        built = option(args, "--built", None)
        tearings_reused([a for i, a in enumerate(args) if a != "--built" and
                         (i == 0 or args[i - 1] != "--built")],
                        None if built is None else int(built))
    elif mode == "diverged":
        diverged(args[0])
    elif mode == "prescribed":
        prescribed(args[0], option(args, "--reaction", 0.0), "--contact-force" in args,
                   option(args, "--tol", 1e-8), option(args, "--residual", 1e-8))
    elif mode == "contact":
        contact(args[0], option(args, "--force-tol", 1e-6))
    elif mode == "patch":
        flags = {"--pressure", "--tol"}
        dirs = [a for i, a in enumerate(args) if a not in flags and (i == 0 or args[i - 1] not in flags)]
        patch(dirs, float(option(args, "--pressure", 0.0)), float(option(args, "--tol", 1e-8)))
    elif mode == "same_contact":
        only = "--solution-only" in args
        same_contact([a for a in args if a != "--solution-only"], only)
    elif mode == "hertz":
        tols = {"--p-tol", "--extent-tol", "--estar", "--force-tol", "--vm-tol"}
        dirs = [a for i, a in enumerate(args) if a not in tols and a != "--recovered" and
                (i == 0 or args[i - 1] not in tols)]
        hertz(dirs, option(args, "--p-tol", HERTZ_TOL["p_max"]),
              option(args, "--extent-tol", HERTZ_TOL["extent"]), option(args, "--estar", 0.0),
              option(args, "--force-tol", 1e-6), option(args, "--vm-tol", None),
              "--recovered" in args)
    elif mode == "plane_strain":
        tols = {"--tol", "--u-tol"}
        dirs = [a for i, a in enumerate(args) if a not in tols and
                (i == 0 or args[i - 1] not in tols)]
        plane_strain(dirs[0], dirs[1:], option(args, "--tol", 0.01), option(args, "--u-tol", 1e-5))
    elif mode == "zero_load":
        zero_load(args)
    elif mode == "tiny_load":
        tiny_load(args[0], option(args, "--full-load", 0.0))
    elif mode == "tied":
        tied(args)
    elif mode == "tightened_qps":
        tightened_qps(args[0])
    elif mode == "bounded_multiplications":
        bounded_multiplications([a for i, a in enumerate(args) if a != "--max" and
                                 (i == 0 or args[i - 1] != "--max")], int(option(args, "--max", 0)))
    elif mode == "bounded_iterations":
        bounded_iterations([a for i, a in enumerate(args) if a != "--max" and
                            (i == 0 or args[i - 1] != "--max")], int(option(args, "--max", 0)))
    elif mode == "membranes_scaling":
        membranes_scaling(args)
    elif mode == "nonlinear":
        nonlinear(args[0], option(args, "--force-tol", 1e-6), option(args, "--hertz-tol", 0.0))
    elif mode == "same_nonlinear":
        same_nonlinear(args)
    elif mode == "nonlinear_vs_elastic":
        nonlinear_vs_elastic(args[0], args[1], option(args, "--tol", 1e-3),
                             option(args, "--force-tol", 1e-6))
    elif mode == "newton":
        newton(args[0], args[1], float(option(args, "--tol", 1e-4)))
    elif mode == "penalty_vs_smalbe":
        penalty_vs_smalbe(args[0], args[1], float(option(args, "--tol", 1e-3)))
    elif mode == "same_indentation":
        same_indentation(args[0], args[1], float(option(args, "--tol", 1e-3)))
    elif mode == "reference_force":
        flags = {"--expected", "--tol"}
        reference_force([a for i, a in enumerate(args) if a not in flags and
                         (i == 0 or args[i - 1] not in flags)],
                        option(args, "--expected", float("nan")), option(args, "--tol", 1e-4))
    elif mode == "distribution_balance":
        flags = {"--contact-tol", "--dof-tol"}
        distribution_balance([a for i, a in enumerate(args) if a not in flags and
                              (i == 0 or args[i - 1] not in flags)],
                             option(args, "--contact-tol", 1.05), option(args, "--dof-tol", 1.10))
    elif mode == "plastic":
        plastic(args[0])
    elif mode == "plastic_vs_elastic":
        plastic_vs_elastic(args[0], args[1])
    elif mode == "cattaneo":
        cattaneo(args[0], option(args, "--tol", 0.05))
    elif mode == "same_final":
        same_final(args)
    elif mode == "friction":
        friction(args[0], args[1], option(args, "--force", 0.0), option(args, "--mu", 0.0),
                 option(args, "--tol", 1e-6), option(args, "--resultant-tol", None),
                 "--magnitudes" in args, option(args, "--kkt-tol", None))
    elif mode == "friction_held":
        friction_held(args[0], option(args, "--tol", 1e-6))
    elif mode == "friction_beyond":
        friction_beyond(args[0], option(args, "--limit", 1.0))
    elif mode == "friction_fields":
        friction_fields(args[0])
    elif mode == "tresca_bonded":
        tresca_bonded(args[0], args[1], option(args, "--tol", 1e-6))
    elif mode == "arc_grows":
        arc_grows(args[0], args[1])
    else:
        fail("unknown mode " + mode)
