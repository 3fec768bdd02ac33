#!/usr/bin/env python3
"""The two membranes (the cases of `run_benchmarks.py --sets membranes`) solved by SMALBE alone and
with `SMALBE/Face solve = pcpg` in the same run (issue 11; docs/qp_solvers.md, "Face solve").
Prints one Markdown row per case: outer iterations, Hessian multiplications and solve time of
each, the face solves, and the face run's contact force error.

    python3 bench/membranes_face.py [--build build] [--out bench-out/membranes_face] [--max-dofs 4.5e6]
                                    [--cases 32x64]
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_benchmarks as rb  # noqa: E402

CASES = [(8, n) for n in (4, 8, 16, 32, 64)] + [(16, n) for n in (4, 8, 16, 32, 64, 88)] + \
        [(32, n) for n in (2, 4, 8, 16, 32, 44, 64)]


def solve(o, m, n, face):
    d = os.path.join(o.out, f"membranes_{n}x{n}_{m}_{face}")
    os.makedirs(d, exist_ok=True)
    xml = rb.MEMBRANES.format(n=n, m=m, method="SMALBE")
    # Always given: the default is pcpg (it was none).
    xml = rb.set_parameter(xml, "SMALBE/Face solve", face)
    path = os.path.join(d, "input.xml")
    with open(path, "w") as f:
        f.write(xml)
    rb.mpirun([o.build + "/bin/tfeti_contact", "--input=" + path, "--output=" + d], o.ranks)
    with open(os.path.join(d, "summary.json")) as f:
        return json.load(f)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--build", default="build")
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--out", default="bench-out/membranes_face")
    p.add_argument("--max-dofs", type=float, default=4.5e6)
    p.add_argument("--cases", default="", metavar="HxN,...",
                   help="only these cases (H/h x subdomains per side), e.g. 32x64")
    o = p.parse_args()
    only = {tuple(int(v) for v in c.split("x")) for c in o.cases.split(",") if c}
    print("| H/h | 1/H | unknowns | subdomains | SMALBE alone: outer / mults / solve s | "
          "face solve: outer / mults / solve s / face solves | force error (face) |\n"
          "|---|---|---|---|---|---|---|")
    for m, n in CASES:
        if 2 * (n * m + 1) ** 2 > o.max_dofs or (only and (m, n) not in only):
            continue
        a, b = solve(o, m, n, "none"), solve(o, m, n, "pcpg")
        msg = b["qp"]["message"]
        faces = msg.split("face solve: ")[1].split(" face solves")[0] if "face solve: " in msg else "0"
        c = b["contact"]
        err = abs(c["force"] - c["expected_force"]) / c["expected_force"]
        print(f"| {m} | {n} | {a['primal_dim']:,} | {a['subdomains']} | "
              f"{a['qp']['outer_iterations']} / {a['qp']['hessian_multiplications']} / "
              f"{a['timings']['solve_s']:.2f} | {b['qp']['outer_iterations']} / "
              f"{b['qp']['hessian_multiplications']} / {b['timings']['solve_s']:.2f} / {faces} | "
              f"{err:.1e} |", flush=True)


if __name__ == "__main__":
    main()
