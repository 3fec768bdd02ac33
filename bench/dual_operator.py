#!/usr/bin/env python3
"""FETI "Dual operator" = implicit against explicit on the CPU (issue 29, docs/dual_operator.md):
structured elasticity in 2D ((0,2)x(0,1), plane strain) and 3D (unit cube, Hex8), clamped, the
Dirichlet preconditioner, PCPG to 1e-6, on 2 MPI ranks (run_benchmarks.py's inputs); each case solved with both operators
(and, with --storage, the explicit one in both storages; with --solves, the explicit one assembled
by solves as well as from the Schur complement, FETI "Explicit assembly").

  python3 bench/dual_operator.py [--build build] [--ranks 2] [--out bench-out/dual_operator]
                                 [--sets 2d,3d] [--max-dofs 1.1e6] [--min-dofs 0] [--storage]
                                 [--solves]

2d:  H/h = 8, 16, 32, 64 at about 0.1M unknowns, H/h = 16 at about 0.4M and 1M, and H/h = 16
     and 32 at about 4.2M
3d:  H/h = 4, 6, 8 at about 0.1M unknowns, and H/h = 8 at about 0.35M, 0.8M and 1.6M (the 3D
     pairs from 0.8M take minutes each; the 1.6M explicit run needs about 13 GiB, and 3D
     explicit at 4M does not fit this machine's 24 GiB)
Sizes here are the mesh's unknowns, which --max-dofs and --min-dofs bound; the tables print the
torn ones (primal_dim: every subdomain's dofs, 8³-element subdomains 2187 each).

Per run: iterations, the set-up time and within it the assembly of the F_s, the time of one F
apply (Output/Time dual operator: the mean of 10, slowest rank) and of the rest of an
iteration (projector P, Dirichlet preconditioner M, vector updates), the solve time, the bytes of
the subdomain factors and of the F_s, the peak memory of all ranks; then, per case, the apply
speed-up and the number of applies after which the explicit operator has paid its assembly.
Prints a markdown table (for docs/benchmarks.md) and writes every summary.json under --out; a
line per run goes to stderr.
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_benchmarks as rb  # noqa: E402

# run_benchmarks' inputs (2D: (0,2)x(0,1); 3D: the unit cube, body force (0, -1, 0)) with the
# dual operator's parameters added to the FETI list.
DUAL = """<ParameterList name="FETI">
    <Parameter name="Dual operator" type="string" value="{kind}"/>
    <Parameter name="Explicit storage" type="string" value="{storage}"/>
    <Parameter name="Explicit assembly" type="string" value="{assembly}"/>"""


# (dim, subdomains per side (x, y[, z]), elements per subdomain side)
CASES = {
    "2d": [(2, (40, 20), 8), (2, (20, 10), 16), (2, (10, 5), 32), (2, (6, 3), 64),
           (2, (40, 20), 16), (2, (64, 32), 16), (2, (128, 64), 16), (2, (64, 32), 32)],
    "3d": [(3, (8, 8, 8), 4), (3, (5, 5, 5), 6), (3, (4, 4, 4), 8), (3, (6, 6, 6), 8),
           (3, (8, 8, 8), 8), (3, (10, 10, 10), 8)],
}


def unknowns(dim, s, e):
    n = 1
    for k in s:
        n *= k * e + 1
    return dim * n


def run(o, dim, s, e, kind, storage, assembly="schur"):
    name = f"{dim}d_{'x'.join(map(str, s))}_{e}_{kind}" + (
        f"_{storage}" + ("" if assembly == "schur" else f"_{assembly}") if kind == "explicit"
        else "")
    d = os.path.join(o.out, name)
    os.makedirs(d, exist_ok=True)
    xml = os.path.join(d, "input.xml")
    text = (rb.TEMPLATE.format(problem="elasticity", sx=s[0], sy=s[1], ex=e, ey=e,
                               prec="dirichlet", solver="cholmod") if dim == 2 else
            rb.TEMPLATE3D.format(problem="elasticity", s=s[0], e=e, prec="dirichlet"))
    with open(xml, "w") as f:
        f.write(text.replace('<ParameterList name="FETI">',
                             DUAL.format(kind=kind, storage=storage, assembly=assembly)))
    res = rb.mpirun([o.build + "/bin/tfeti_contact", "--input=" + xml, "--output=" + d], o.ranks)
    if res.returncode != 0:
        return None
    with open(d + "/summary.json") as f:
        return json.load(f)


def mib(b):
    return b / 2**20


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--build", default="build")
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--out", default="bench-out/dual_operator")
    p.add_argument("--sets", default="2d,3d")
    p.add_argument("--max-dofs", type=float, default=1.1e6)
    p.add_argument("--min-dofs", type=float, default=0)
    p.add_argument("--storage", action="store_true",
                   help="also the explicit operator with the full storage")
    p.add_argument("--solves", action="store_true",
                   help="also the explicit operator assembled by solves (Explicit assembly = "
                   "solves; the default is schur)")
    o = p.parse_args()
    print("| dim | subdomains | H/h | unknowns | dual | operator | iterations | set-up s "
          "(F_s assembly s) | F apply ms | P, M, vectors ms | solve s | factors MiB | F_s MiB | "
          "peak MiB (all ranks) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    summary = []
    for key in o.sets.split(","):
        for dim, s, e in CASES[key]:
            n = unknowns(dim, s, e)
            if n > o.max_dofs or n < o.min_dofs:
                continue
            kinds = [("implicit", "packed", "schur"), ("explicit", "packed", "schur")]
            if o.storage:
                kinds.append(("explicit", "full", "schur"))
            if o.solves:
                kinds.append(("explicit", "packed", "solves"))
            rows = {}
            for kind, storage, assembly in kinds:
                r = run(o, dim, s, e, kind, storage, assembly)
                if r is None:
                    continue
                t = r["timings"]
                label = kind + (f" ({storage}{'' if assembly == 'schur' else ', solves'})"
                                if kind == "explicit" else "")
                rows[label] = r
                nsub = 1
                for k in s:
                    nsub *= k
                print(f"| {dim}D | {nsub} | {e} | {r['primal_dim']} | {r['dual_dim']} | {label} | "
                      f"{r['iterations']} | {t['setup_s']:.2f} ({t.get('dual_operator_s', 0):.2f}) "
                      f"| {1e3 * t['dual_apply_s']:.2f} | {1e3 * t.get('projector_apply_s', 0):.2f}, "
                      f"{1e3 * t.get('preconditioner_apply_s', 0):.2f}, "
                      f"{1e3 * t.get('vector_updates_s', 0):.2f} | {t['solve_s']:.2f} | "
                      f"{mib(r['factor_bytes']):.0f} | {mib(r.get('explicit_dual_bytes', 0)):.0f} | "
                      f"{r['memory']['peak_mib_all_ranks']:.0f} |", flush=True)
            im = rows.get("implicit")
            for label in ("explicit (packed)", "explicit (packed, solves)"):
                ex = rows.get(label)
                if im and ex:
                    ti, te = im["timings"], ex["timings"]
                    gain = ti["dual_apply_s"] - te["dual_apply_s"]
                    summary.append((dim, e, im["primal_dim"], label,
                                    ti["dual_apply_s"] / te["dual_apply_s"],
                                    te["dual_operator_s"] / gain if gain > 0 else float("inf"),
                                    (ti["setup_s"] + ti["solve_s"]) /
                                    (te["setup_s"] + te["solve_s"])))
    print("\n| dim | H/h | unknowns | explicit | apply speed-up | applies to pay the assembly | "
          "whole-solve speed-up (set-up + solve) |")
    print("|---|---|---|---|---|---|---|")
    for dim, e, n, label, speed, pay, whole in summary:
        print(f"| {dim}D | {e} | {n} | {label} | {speed:.2f} | {pay:.0f} | {whole:.2f} |")


if __name__ == "__main__":
    main()
