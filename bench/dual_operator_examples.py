#!/usr/bin/env python3
"""FETI "Dual operator" = implicit, explicit and auto on the project's contact examples
(docs/dual_operator.md, "`Dual operator` = auto"): each example as shipped, with only the dual
operator set and the VTU output off, one run after the other on the same ranks. It shows what
auto chooses where nobody tuned the input, and what the other choice would have cost.

  python3 bench/dual_operator_examples.py [--build build] [--ranks 2] [--out bench-out/examples]
                                          [--examples a,b,...] [--modes implicit,explicit,auto]

Per run: wall time (the process, start-up included), set-up, assembly of the F_s, solve,
Hessian multiplications, peak memory (the largest rank), and for auto its choice and the
F_s / factor bytes it compared. Prints a markdown table; a run that fails or does not converge
is reported and makes the exit status non-zero.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLES = ["two_membranes", "two_cylinders_elastic", "dissimilar_cylinders", "pin_hole_0.9",
            "two_cylinders_plastic", "cattaneo_cylinders", "cattaneo_cylinders_sliding",
            "ball_between_plates", "sphere_indentation_rigid", "hertz_sphere_elastic",
            "hertz_sphere_tet", "hertz_sphere_plastic", "cylinders_3d", "cattaneo_sphere",
            "indentation_step42"]


def variant(example, mode):
    """The example's XML with the dual operator set, mesh paths absolute and no VTU output."""
    src = open(os.path.join(ROOT, "examples", example + ".xml")).read()
    src = re.sub(r'value="([^"/]+\.(?:geo|msh))"',
                 lambda m: 'value="%s"' % os.path.join(ROOT, "examples", m.group(1)), src)
    src = src.replace('<Parameter name="VTU" type="bool" value="true"/>',
                      '<Parameter name="VTU" type="bool" value="false"/>')
    feti = '<ParameterList name="FETI">'
    if feti not in src:
        raise SystemExit(f"{example}.xml has no FETI list to set the dual operator in")
    return src.replace(feti, feti + '\n    <Parameter name="Dual operator" type="string" '
                       f'value="{mode}"/>', 1)


def run(args, example, mode):
    os.makedirs(args.out, exist_ok=True)
    xml = os.path.join(args.out, f"{example}_{mode}.xml")
    out = os.path.join(args.out, f"{example}_{mode}")
    with open(xml, "w") as f:
        f.write(variant(example, mode))
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = ["mpiexec", "-n", str(args.ranks), os.path.join(args.build, "bin", "tfeti_contact"),
           f"--input={xml}", f"--output={out}"]
    start = time.time()
    r = subprocess.run(cmd, env=env, capture_output=True, text=True)
    wall = time.time() - start
    summary = os.path.join(out, "summary.json")
    if r.returncode != 0 or not os.path.exists(summary):
        print(f"{example} {mode}: exit {r.returncode}\n{r.stderr[-2000:]}", file=sys.stderr)
        return None
    s = json.load(open(summary))
    t = s.get("timings", {})
    auto = s.get("dual_operator_auto", {})
    row = {
        "example": example, "mode": mode, "converged": s.get("converged"), "wall": wall,
        "primal": s.get("primal_dim"), "dim": s.get("dimension"),
        "setup": t.get("setup_s", 0.0), "assembly": t.get("dual_operator_s", 0.0),
        "solve": t.get("solve_s", 0.0),
        # A linear solve's count, or the nonlinear loop's total over every QP.
        "mults": s.get("dual_operator_applies",
                       s.get("nonlinear", {}).get("total_hessian_multiplications")),
        "rss": s.get("peak_rss_mb"), "chosen": auto.get("chosen", ""),
        "ratio": auto["explicit_bytes"] / auto["factor_bytes"] if auto else None,
    }
    print(f"{example} {mode}: {wall:.2f} s, {row['mults']} multiplications"
          + (f", auto chose {row['chosen']}" if auto else ""), file=sys.stderr, flush=True)
    return row


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--out", default=os.path.join(ROOT, "bench-out", "examples"))
    p.add_argument("--examples", default=",".join(EXAMPLES))
    p.add_argument("--modes", default="implicit,explicit,auto")
    args = p.parse_args()
    modes = args.modes.split(",")
    for m in modes:
        if m not in ("implicit", "explicit", "auto"):
            p.error(f"--modes: unknown mode {m!r} (implicit, explicit, auto)")
    for e in args.examples.split(","):
        if not os.path.exists(os.path.join(ROOT, "examples", e + ".xml")):
            p.error(f"--examples: no examples/{e}.xml")
    failed = False
    print("| example | dim | unknowns | operator | wall s | set-up s (assembly) | solve s | "
          "multiplications | peak MiB, largest rank | auto: chosen (F_s / factor bytes) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for e in args.examples.split(","):
        for m in modes:
            r = run(args, e, m)
            if r is None or not r["converged"]:
                failed = True
                print(f"| {e} | | | {m} | failed | | | | | |")
                continue
            choice = f"{r['chosen']} ({r['ratio']:.2f})" if r["ratio"] is not None else ""
            dim = f"{r['dim']}D" if r["dim"] else ""
            print(f"| {e} | {dim} | {r['primal']} | {m} | {r['wall']:.2f} | "
                  f"{r['setup']:.2f} ({r['assembly']:.2f}) | {r['solve']:.2f} | {r['mults']} | "
                  f"{r['rss']:.0f} | {choice} |", flush=True)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
