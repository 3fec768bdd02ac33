#!/usr/bin/env python3
"""The face solve ended the contact solve (FETI/SMALBE/Face solve = pcpg, issue 11).

    check_face_solve.py [--max-mults N] [--reference REF] DIR [DIR ...]

Each DIR's summary.json must report a converged SMALBE solve whose result is a face solve's
(SMALBE's message in qp.message: "(the last a face solve)", "face solve: N face solves, M face
CG steps, K active-set changes"), with at least one face solve and no more Hessian multiplications than
--max-mults (default: no limit). The same face solves and CG steps on every DIR (rank counts).
With --reference (the same input solved by SMALBE alone): the same contact solution, i.e.
p_max, the contact force and the pressure at every contact node (contact_pressure.csv) within
1e-4 of the reference's p_max and force (both solves stop at a relative tolerance of 1e-7 on
the dual gradient, which moves the pressures by a few 1e-6 relative).
"""
import csv
import json
import os
import re
import sys


def pressures(d):
    with open(os.path.join(d, "contact_pressure.csv")) as f:
        return [(float(r["x"]), float(r["y"]), float(r["pressure"])) for r in csv.DictReader(f)]


def same_solution(ref, d, tol=1e-4):
    out = []
    with open(os.path.join(ref, "summary.json")) as f:
        rc = json.load(f)["contact"]
    with open(os.path.join(d, "summary.json")) as f:
        dc = json.load(f)["contact"]
    for key in ("p_max", "force"):
        err = abs(dc[key] - rc[key]) / abs(rc[key])
        print(f"{d}: {key} {dc[key]:.9g} against {rc[key]:.9g} ({ref}): relative {err:.2e}")
        if not err <= tol:
            out.append(f"{d}: {key} differs from {ref} by {err:.2e} > {tol}")
    a, b = pressures(ref), pressures(d)
    if len(a) != len(b):
        return out + [f"{d}: {len(b)} contact nodes, {ref} has {len(a)}"]
    worst = max((abs(p - q[2]) for (_, _, p), q in zip(a, b)), default=0.0) / abs(rc["p_max"])
    print(f"{d}: largest pressure difference {worst:.2e} of p_max over {len(a)} nodes")
    if not worst <= tol:
        out.append(f"{d}: pressures differ from {ref} by {worst:.2e} of p_max > {tol}")
    return out


def main(argv):
    limit = None
    reference = None
    dirs = []
    it = iter(argv)
    for a in it:
        if a == "--max-mults":
            limit = int(next(it))
        elif a == "--reference":
            reference = next(it)
        else:
            dirs.append(a)
    if not dirs:
        print(__doc__)
        return 2
    failures = []
    seen = []
    for d in dirs:
        with open(os.path.join(d, "summary.json")) as f:
            s = json.load(f)
        q = s.get("qp", {})
        msg = q.get("message", "")
        m = re.search(r"face solve: (\d+) face solves, (\d+) face CG steps", msg)
        accepted = "(the last a face solve)" in msg
        row = (int(m.group(1)) if m else None, int(m.group(2)) if m else None,
               q.get("hessian_multiplications"))
        print(f"{d}: converged {s.get('converged')}, face solves {row[0]}, face CG steps {row[1]},"
              f" Hessian multiplications {row[2]}, accepted {accepted}")
        if not s.get("converged"):
            failures.append(f"{d}: not converged")
        if not accepted:
            failures.append(f"{d}: the result is not a face solve's")
        if not row[0] or row[0] < 1:
            failures.append(f"{d}: no face solve")
        if limit is not None and row[2] > limit:
            failures.append(f"{d}: {row[2]} Hessian multiplications > {limit}")
        seen.append(row)
        if reference is not None:
            failures += same_solution(reference, d)
    if any(r != seen[0] for r in seen[1:]):
        failures.append(f"the counts differ between the runs: {seen}")
    for f in failures:
        print("FAILED:", f)
    print("check passed" if not failures else "check FAILED")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
