#!/usr/bin/env python3
"""Checks a tfeti_contact summary.json against what the method must deliver.

  check_summary.py scalability DIR        dimensions equal the reference paper's table exactly,
                                          numerical scalability of Dirichlet-preconditioned TFETI
  check_summary.py single DIR [--max-error E]
                                          converged, error against the direct solve below E
  check_summary.py same DIR1 DIR2 ...     identical iteration counts, residual histories and
                                          solution norms to rounding (different rank counts)
  check_summary.py diverged DIR           the run reported non-convergence (converged = false)
"""
import json
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
        return json.load(f)


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def scalability(d):
    s = load(d)
    if not s.get("all_converged"):
        fail("not every solve converged")
    rows = [r for r in s["table"] if r["problem"] == "poisson"]
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
    by_ratio = {}
    for r in rows:
        by_ratio.setdefault(r["h_inverse"] // r["H_inverse"], {})[r["H_inverse"]] = \
            r["iterations"]["tfeti"]["dirichlet"]
    for ratio, its in sorted(by_ratio.items()):
        if 4 not in its:
            continue
        bound = GROWTH * its[4]
        worst = max(its.values())
        print(f"H/h={ratio}: TFETI+Dirichlet iterations {dict(sorted(its.items()))}, bound {bound}")
        if worst > bound:
            fail(f"H/h={ratio}: {worst} iterations exceed {bound} (1.5 x the count at H=1/4)")
    print("OK: all dimensions equal the paper's; iterations bounded")


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


if __name__ == "__main__":
    mode, args = sys.argv[1], sys.argv[2:]
    if mode == "scalability":
        scalability(args[0])
    elif mode == "single":
        err = 1e-6
        if "--max-error" in args:
            err = float(args[args.index("--max-error") + 1])
        single(args[0], err)
    elif mode == "same":
        same(args)
    elif mode == "diverged":
        diverged(args[0])
    else:
        fail("unknown mode " + mode)
