#!/usr/bin/env python3
"""The face solve ended the contact solve (FETI/SMALBE/Face solve = pcpg, issue 11).

    check_face_solve.py DIR [DIR ...]

Each DIR's summary.json must report a converged SMALBE solve whose result is a face solve's
(SMALBE's message in qp.message: "(the last a face solve)", "face solve: N face solves, M face
CG steps, K active-set changes"), with at least one face solve and no more Hessian multiplications than
--max-mults (default: no limit). The same face solves and CG steps on every DIR (rank counts).
"""
import json
import os
import re
import sys


def main(argv):
    limit = None
    dirs = []
    it = iter(argv)
    for a in it:
        if a == "--max-mults":
            limit = int(next(it))
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
    if any(r != seen[0] for r in seen[1:]):
        failures.append(f"the counts differ between the runs: {seen}")
    for f in failures:
        print("FAILED:", f)
    print("check passed" if not failures else "check FAILED")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
