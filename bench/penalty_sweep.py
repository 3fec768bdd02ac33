#!/usr/bin/env python3
"""The nonlinear test inputs by the penalty method against SMALBE (docs/qp_solvers.md, "The
penalty method's equality projection" and "The penalty's warm start"): every
tests/inputs/nl_*.xml but the restart, stop, cycle and penalty variants, once as it is (SMALBE)
and once with `Dual solver` = penalty and MPRGP's `Relative tolerance` set to the input's SMALBE
one. Relative paths in the inputs are made absolute, so the copies run from OUT.

  python3 bench/penalty_sweep.py [--build build] [--ranks 1] [--out bench-out/penalty]
                                 [--only nl_a,nl_b,...] [--solvers penalty,smalbe]
                                 [--timeout 240]

Per run (one JSON line in OUT/<solver>.jsonl): exit code, wall time, converged steps, Newton
iterations, Hessian multiplications, the load factor reached and p_max. Then a table: the runs
that converged, and the multiplications summed over the inputs every solver converged on.
nl_block_tresca_beyond and nl_not_converging stop by design (exit code 3).
"""
import argparse
import glob
import json
import os
import re
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SKIP = re.compile(r"restart|stop|cycle|penalty")


def variant(src, dst, penalty):
    tree = ET.parse(src)
    root = tree.getroot()
    for e in root.iter("Parameter"):
        value = e.get("value", "")
        if value.startswith("../"):
            e.set("value", os.path.normpath(os.path.join(os.path.dirname(src), value)))
    if penalty:
        feti = root.find("ParameterList[@name='FETI']")
        solver = None if feti is None else feti.find("Parameter[@name='Dual solver']")
        if solver is None:
            sys.exit(f"penalty_sweep: {src}: no FETI/Dual solver parameter to set to penalty")
        solver.set("value", "penalty")
        smalbe = feti.find("ParameterList[@name='SMALBE']")
        if smalbe is not None:
            tol = smalbe.find("Parameter[@name='Relative tolerance']")
            feti.remove(smalbe)
            if tol is not None:
                mprgp = feti.find("ParameterList[@name='MPRGP']")
                if mprgp is None:
                    mprgp = ET.SubElement(feti, "ParameterList", {"name": "MPRGP"})
                rt = mprgp.find("Parameter[@name='Relative tolerance']")
                if rt is None:
                    rt = ET.SubElement(mprgp, "Parameter",
                                       {"name": "Relative tolerance", "type": "double"})
                rt.set("value", tol.get("value"))
    tree.write(dst)


def run(exe, ranks, xml, out, timeout):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = ["mpirun", "--oversubscribe", "-np", str(ranks), exe, "--input=" + xml,
           "--output=" + out]
    start = time.time()
    try:
        rc = subprocess.run(cmd, env=env, capture_output=True, text=True,
                            timeout=timeout).returncode
    except subprocess.TimeoutExpired:
        rc = "timeout"
    r = {"rc": rc, "wall": round(time.time() - start, 1)}
    try:
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
        nl = s.get("nonlinear", {})
        r.update(steps=nl.get("converged_steps"), iterations=nl.get("total_iterations"),
                 multiplications=nl.get("total_hessian_multiplications"),
                 load_factor=nl.get("load_factor"), p_max=s.get("contact", {}).get("p_max"))
    except (OSError, ValueError):
        pass
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--out", default=os.path.join(ROOT, "bench-out", "penalty"))
    ap.add_argument("--only", default="")
    ap.add_argument("--solvers", default="penalty,smalbe")
    ap.add_argument("--timeout", type=float, default=240)
    a = ap.parse_args()
    exe = os.path.join(a.build, "bin", "tfeti_contact")
    if not os.access(exe, os.X_OK):
        sys.exit(f"penalty_sweep: {exe}: not built (bash scripts/build.sh)")
    only = set(filter(None, a.only.split(",")))
    swept = [f for f in sorted(glob.glob(os.path.join(ROOT, "tests", "inputs", "nl_*.xml")))
             if not SKIP.search(os.path.basename(f))]
    unknown = only - {os.path.basename(f)[:-4] for f in swept}
    if unknown:
        sys.exit(f"penalty_sweep: --only: not among the swept inputs: {', '.join(sorted(unknown))}")
    inputs = [f for f in swept if not only or os.path.basename(f)[:-4] in only]
    solvers = [s for s in a.solvers.split(",") if s]
    for s in solvers:
        if s not in ("penalty", "smalbe"):
            sys.exit(f"penalty_sweep: --solvers: unknown solver {s!r} (penalty, smalbe)")
    results = {s: {} for s in solvers}
    for solver in solvers:
        folder = os.path.join(a.out, solver)
        os.makedirs(os.path.join(folder, "inputs"), exist_ok=True)
        with open(os.path.join(a.out, solver + ".jsonl"), "w") as log:
            for src in inputs:
                name = os.path.basename(src)[:-4]
                xml = os.path.join(folder, "inputs", name + ".xml")
                variant(src, xml, solver == "penalty")
                r = run(exe, a.ranks, xml, os.path.join(folder, name), a.timeout)
                r["input"] = name
                results[solver][name] = r
                log.write(json.dumps(r) + "\n")
                log.flush()
                print(f"{solver} {name}: exit {r['rc']}, {r.get('multiplications')} "
                      f"multiplications, {r['wall']} s", file=sys.stderr, flush=True)
    names = [os.path.basename(f)[:-4] for f in inputs]
    common = [n for n in names if all(results[s][n]["rc"] == 0 for s in solvers)]
    print("| solver | converged | multiplications on the " + str(len(common)) +
          " inputs all converged on | wall s, all runs |")
    print("|---|---|---|---|")
    for s in solvers:
        done = sum(1 for n in names if results[s][n]["rc"] == 0)
        mult = sum(results[s][n].get("multiplications") or 0 for n in common)
        wall = sum(results[s][n]["wall"] for n in names)
        print(f"| {s} | {done} of {len(names)} | {mult:,} | {wall:.1f} |")


if __name__ == "__main__":
    main()
