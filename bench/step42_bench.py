#!/usr/bin/env python3
"""deal.II's tutorial step-42 (3D elasto-plastic indentation by a rigid sphere) and tfeti_contact
on the same meshes, in the same run, 2 MPI ranks each.

  python3 bench/step42_bench.py [SIZES ...] [--variants plastic,elastic,elastic_linear]
                                [--ranks 2]
                                [--build build] [--out bench-out/step42]

SIZES: elements per side, powers of two (default 32 64); step-42 refines its unit cube globally
log2(N) times, tfeti_contact meshes examples/indentation_step42.geo with the same N (Gmsh
transfinite, the same nodes) into (N/8)^3 subdomains of 8^3 elements.

step-42 is the tutorial's step-42.cc from Debian's libdeal.ii-doc, built against libdeal.ii-dev
(apt-get install libdeal.ii-dev libdeal.ii-doc; neither is needed by the project itself). The
plastic variant is the file unchanged; the elastic one substitutes sigma_0(1e10) for
sigma_0(400.0) (the tutorial's own way of switching plasticity off in its first Newton
iteration). It runs one refinement cycle ("number of cycles" = 1, global refinement, the sphere
obstacle) and prints its contact force, its Newton iterations, its timer table and its memory.

tfeti_contact runs examples/indentation_step42.xml (Newton, inexact QPs, line search) with the
mesh's N and subdomain count substituted, the yield stress 1e10 for the elastic variant. The
elastic_linear variant is the same elastic problem with the settings an elastic-only run would
take (exact QPs: `Inexact QP factor` 1; `Preconditioner` lumped), against step-42's elastic
variant run again in its row.

Prints a markdown table (docs/benchmarks.md, "deal.II step-42 against tfeti_contact") and writes
both codes' logs and tfeti_contact's summary.json under --out.
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STEP42_SRC = "/usr/share/doc/libdeal.ii-doc/examples/step-42"
MPI_ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMP_NUM_THREADS="1")


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def build_step42(out, variant):
    """step-42 built into out/step42-<variant> (once); returns the executable."""
    variant = "elastic" if variant == "elastic_linear" else variant
    src = os.path.join(STEP42_SRC, "step-42.cc")
    if not os.path.exists(src) or not os.path.exists("/usr/share/cmake/deal.II"):
        sys.exit("step-42 needs deal.II: apt-get install libdeal.ii-dev libdeal.ii-doc")
    d = os.path.join(out, "step42-" + variant)
    exe = os.path.join(d, "step-42")
    if os.path.exists(exe):
        return exe
    os.makedirs(d, exist_ok=True)
    text = open(src).read()
    if variant == "elastic":
        if text.count("sigma_0(400.0)") != 1:
            sys.exit(f"{src}: expected one 'sigma_0(400.0)' to substitute")
        text = text.replace("sigma_0(400.0)", "sigma_0(1e10)")
    open(os.path.join(d, "step-42.cc"), "w").write(text)
    shutil.copy(os.path.join(STEP42_SRC, "CMakeLists.txt"), d)
    log(f"building step-42 ({variant}) in {d}")
    subprocess.run(["cmake", "-DCMAKE_BUILD_TYPE=Release", "."], cwd=d, check=True,
                   stdout=subprocess.DEVNULL)
    subprocess.run(["make"], cwd=d, check=True, stdout=subprocess.DEVNULL)
    return exe


def run_step42(exe, n, ranks, out, variant):
    refinements = int(round(math.log2(n)))
    if 2 ** refinements != n:
        sys.exit(f"step-42 refines globally: N = {n} is not a power of two")
    d = os.path.join(out, f"step42_{variant}_{n}")
    os.makedirs(d, exist_ok=True)
    prm = os.path.join(d, "run.prm")
    with open(prm, "w") as f:
        f.write(f"set polynomial degree             = 1\n"
                f"set number of initial refinements = {refinements}\n"
                f"set number of cycles              = 1\n"
                f"set refinement strategy           = global\n"
                f"set obstacle                      = sphere\n"
                f"set output directory              = {d}/\n")
    t0 = time.time()
    p = subprocess.run(["mpiexec", "-n", str(ranks), "--oversubscribe", exe, prm], env=MPI_ENV,
                       capture_output=True, text=True)
    wall = time.time() - t0
    open(os.path.join(d, "step42.log"), "w").write(p.stdout + p.stderr)
    if p.returncode != 0:
        sys.exit(f"step-42 failed (N = {n}), see {d}/step42.log")
    text = p.stdout
    force = float(re.search(r"Contact force = (\S+)", text).group(1))
    newton = len(re.findall(r"Newton iteration \d+", text))
    rss = re.search(r"Peak virtual memory used, resident in kB: \d+ (\d+)", text)
    sections = {m.group(1).strip(): float(m.group(2)) for m in
                re.finditer(r"^\| ([A-Za-z][^|]*?)\s*\|\s*\d+ \|\s*([\d.]+)s", text, re.M)}
    krylov = sum(int(k) for k in re.findall(r"in (\d+) Bicgstab iterations", text))
    return {"code": "step-42", "force": force, "newton": newton, "wall": wall,
            "rss_mb": int(rss.group(1)) / 1024 if rss else float("nan"),
            "solve": sections.get("Solve", float("nan")),
            "assembly": sections.get("Assembling", float("nan")) +
            sections.get("Residual and lambda", 0.0),
            "inner": krylov, "sections": sections}


def run_tfeti(exe, n, ranks, variant, out):
    d = os.path.join(out, f"tfeti_{variant}_{n}")
    os.makedirs(d, exist_ok=True)
    geo = open(os.path.join(ROOT, "examples/indentation_step42.geo")).read()
    geo = re.sub(r"^N = \d+;", f"N = {n};", geo, flags=re.M)
    open(os.path.join(d, "mesh.geo"), "w").write(geo)
    xml = open(os.path.join(ROOT, "examples/indentation_step42.xml")).read()
    xml = xml.replace('value="indentation_step42.geo"', 'value="mesh.geo"')
    subdomains = max(1, (n // 8) ** 3)
    xml = re.sub(r'(name="Subdomains per body" type="Array\(int\)" value=)"\{\d+\}"',
                 rf'\1"{{{subdomains}}}"', xml)
    if variant in ("elastic", "elastic_linear"):
        xml = xml.replace('name="Yield stress" type="double" value="489.898"',
                          'name="Yield stress" type="double" value="1e10"')
    if variant == "elastic_linear":
        # What an elastic-only run would set: exact QPs (no loose first QP to tighten in a
        # second Newton iteration) and the lumped preconditioner (no interior factorizations).
        for old, new in (('name="Inexact QP factor" type="double" value="1e6"',
                          'name="Inexact QP factor" type="double" value="1"'),
                         ('<Parameter name="Dual solver" type="string" value="SMALBE"/>',
                          '<Parameter name="Dual solver" type="string" value="SMALBE"/>\n'
                          '    <Parameter name="Preconditioner" type="string" value="lumped"/>')):
            if xml.count(old) != 1:
                sys.exit(f"examples/indentation_step42.xml: expected one '{old}' to substitute")
            xml = xml.replace(old, new)
    open(os.path.join(d, "input.xml"), "w").write(xml)
    t0 = time.time()
    p = subprocess.run(["mpiexec", "-n", str(ranks), "--oversubscribe", exe, "--input=input.xml",
                        "--output=" + os.path.join(d, "out")], cwd=d, env=MPI_ENV,
                       capture_output=True, text=True)
    wall = time.time() - t0
    open(os.path.join(d, "tfeti.log"), "w").write(p.stdout + p.stderr)
    if p.returncode != 0:
        sys.exit(f"tfeti_contact failed (N = {n}, {variant}), see {d}/tfeti.log")
    s = json.load(open(os.path.join(d, "out", "summary.json")))
    nl = s["nonlinear"]
    t = s.get("timings", {})
    return {"code": "tfeti_contact", "force": s["contact"]["force"],
            "newton": nl["total_iterations"], "wall": wall, "rss_mb": s.get("peak_rss_mb"),
            "multiplications": nl["total_hessian_multiplications"], "timings": t,
            "unknowns": s["primal_dim"], "subdomains": s["subdomains"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("sizes", nargs="*", type=int, default=[32, 64])
    ap.add_argument("--variants", default="plastic,elastic,elastic_linear")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "bench-out", "step42"))
    a = ap.parse_args()
    out = os.path.abspath(a.out)
    os.makedirs(out, exist_ok=True)
    exe = os.path.join(os.path.abspath(a.build), "bin", "tfeti_contact")
    if not os.path.exists(exe):
        sys.exit(f"{exe}: build the project first")
    rows, results = [], []
    for variant in a.variants.split(","):
        step42 = build_step42(out, variant)
        for n in a.sizes:
            log(f"N = {n}, {variant}: step-42")
            r42 = run_step42(step42, n, a.ranks, out, variant)
            log(f"  step-42: {r42['wall']:.1f} s, {r42['newton']} Newton iterations, force "
                f"{r42['force']}")
            log(f"N = {n}, {variant}: tfeti_contact")
            rt = run_tfeti(exe, n, a.ranks, variant, out)
            log(f"  tfeti_contact: {rt['wall']:.1f} s, {rt['newton']} iterations, "
                f"{rt['multiplications']} multiplications, force {rt['force']}")
            results.append({"n": n, "variant": variant, "step42": r42, "tfeti": rt})
            rel = abs(rt["force"] - r42["force"]) / abs(r42["force"])
            t = rt["timings"]
            rows.append(
                f"| {n}^3 | {rt['unknowns']:,} | {variant} | {r42['wall']:.1f} "
                f"({r42['newton']} Newton, assembly {r42['assembly']:.1f}, solve "
                f"{r42['solve']:.1f}) | {rt['wall']:.1f} ({rt['newton']} Newton, "
                f"{rt['multiplications']} mult., factorization "
                f"{t.get('factorization_s', float('nan')):.1f}, solve "
                f"{t.get('solve_s', float('nan')):.1f}) | {r42['wall'] / rt['wall']:.2f} | "
                f"{r42['rss_mb']:.0f} / {rt['rss_mb']:.0f} | {r42['force']:.6g} / "
                f"{rt['force']:.6g} ({rel:.1e}) |")
    json.dump(results, open(os.path.join(out, "results.json"), "w"), indent=1)
    print(f"| mesh | unknowns | variant | step-42 wall s | tfeti_contact wall s | speed-up | "
          f"peak RSS MB rank 0 (step-42 / tfeti) | contact force (step-42 / tfeti, rel. diff.) |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(r)


if __name__ == "__main__":
    main()
