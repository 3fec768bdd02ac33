#!/usr/bin/env python3
"""Dual mortar against node-to-segment (node-to-face) contact on the same meshes, same run:
Hertz's sphere on unstructured Tet4/Tet10 meshes (examples/hertz_sphere_tet4.geo), the 2D
cylinders on Quad9 (examples/two_cylinders.geo) and the contact patch tests
(tests/inputs/patch_mortar_*.xml). Prints a Markdown table: unknowns, p_max, contact radius
(half-width) and max von Mises errors against Hertz (p_max raw and recovered, von Mises at the
Gauss points and of the nodal averages), the RMS and largest deviation of the nodal
pressures from Hertz's profile inside 0.8 a (3D), the patch tests' pressure spread, Hessian
multiplications and wall time.

  python3 bench/mortar_accuracy.py BUILD_DIR [--ranks 2] [--quick]
"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(exe, ranks, xml_text, out):
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, "input.xml")
    with open(path, "w") as f:
        f.write(xml_text)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    t = time.time()
    subprocess.run(["mpiexec", "-n", str(ranks), "--oversubscribe", exe, "--input=" + path,
                    "--output=" + out], check=True, env=env, stdout=subprocess.DEVNULL)
    wall = time.time() - t
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    with open(os.path.join(out, "contact_pressure.csv")) as f:
        rows = list(csv.DictReader(f))
    return s, rows, wall


def with_params(text, **kv):
    for name, value in kv.items():
        name = name.replace("_", " ")
        new, n = re.subn(r'(name="%s" type="[^"]*" value=")[^"]*"' % re.escape(name),
                         lambda m: m.group(1) + str(value) + '"', text)
        if n == 0:  # add it before the search radius
            new = text.replace('<Parameter name="Search radius"',
                               '<Parameter name="%s" type="string" value="%s"/>\n'
                               '    <Parameter name="Search radius"' % (name, value), 1)
        text = new
    return text


def profile_deviation(rows, a, p0):
    dev = []
    for r in rows:
        rad = float(r["radius"])
        if rad < 0.8 * a:
            ph = p0 * math.sqrt(1.0 - (rad / a) ** 2)
            dev.append((float(r["pressure"]) - ph) / p0)
    if not dev:
        return float("nan"), float("nan")
    return math.sqrt(sum(d * d for d in dev) / len(dev)), max(abs(d) for d in dev)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--quick", action="store_true", help="the coarsest meshes only")
    args = ap.parse_args()
    exe = os.path.join(os.path.abspath(args.build), "bin", "tfeti_contact")
    work = tempfile.mkdtemp(prefix="mortar_bench_")
    with open(os.path.join(ROOT, "tests/inputs/hertz_sphere_tet4_coarse.xml")) as f:
        sphere = f.read().replace("../../examples/", ROOT + "/examples/")
    with open(os.path.join(ROOT, "examples/two_cylinders_elastic.xml")) as f:
        cyl = f.read().replace('value="two_cylinders.geo"',
                               'value="%s/examples/two_cylinders.geo"' % ROOT)
    cyl = cyl.replace('<Parameter name="Element order"',
                      '<Parameter name="Quadrilaterals" type="bool" value="true"/>\n'
                      '    <Parameter name="Element order"', 1)
    cases = []
    for order, factors in ((1, (2.0, 1.0, 0.625, 0.5)), (2, (2.0, 1.25, 1.0))):
        for fac in factors[:2] if args.quick else factors:
            cases.append(("sphere", "Tet4" if order == 1 else "Tet10", fac,
                          with_params(sphere, Element_order=order, Mesh_size_factor=fac)))
    for fac in (1.0,) if args.quick else (1.0, 0.5):
        cases.append(("cylinders", "Quad9", fac,
                      with_params(cyl, Element_order=2, Mesh_size_factor=fac)))
    print("| problem | elements | size factor | unknowns | discretization | p_max | "
          "p_max recovered | extent | max von Mises | nodal von Mises | profile RMS / max | "
          "rows | Hessian mults | wall s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for kind, elements, fac, text in cases:
        for disc in ("node_to_segment", "mortar"):
            out = os.path.join(work, "%s_%s_%g_%s" % (kind, elements, fac, disc))
            s, rows, wall = run(exe, args.ranks, with_params(text, Contact_discretization=disc),
                                out)
            c = s["contact"]
            extent = "contact_radius" if "contact_radius" in c else "half_width"
            prof = "—"
            if kind == "sphere":
                rms, worst = profile_deviation(rows, c["hertz"]["contact_radius"],
                                               c["hertz"]["p_max"])
                prof = "%.1f %% / %.1f %%" % (100 * rms, 100 * worst)
            vm = s["max_von_mises"] / c["hertz"]["max_von_mises"] - 1.0
            vmn = s["max_von_mises_nodal"] / c["hertz"]["max_von_mises"] - 1.0
            epr = c["p_max_recovered"] / c["hertz"]["p_max"] - 1.0
            # Signed errors (summary.json's relative_error holds magnitudes).
            ep = c["p_max"] / c["hertz"]["p_max"] - 1.0
            ee = c[extent] / c["hertz"][extent] - 1.0
            print("| %s | %s | %g | %d | %s | %+.2f %% | %+.2f %% | %+.2f %% | %+.2f %% | %+.2f %% "
                  "| %s | %d | %d | %.1f |"
                  % (kind, elements, fac, s["primal_dim"], disc, 100 * ep, 100 * epr,
                     100 * ee, 100 * vm, 100 * vmn, prof, c["rows"],
                     s["qp"]["hessian_multiplications"], wall), flush=True)
    for case in ("patch_mortar_2d", "patch_mortar_2d_quadratic", "patch_mortar_3d",
                 "patch_mortar_3d_quadratic"):
        with open(os.path.join(ROOT, "tests/inputs", case + ".xml")) as f:
            text = f.read().replace("../meshes/", ROOT + "/tests/meshes/")
        for disc in ("node_to_segment", "mortar"):
            out = os.path.join(work, case + "_" + disc)
            s, rows, wall = run(exe, args.ranks, with_params(text, Contact_discretization=disc),
                                out)
            p = [float(r["pressure"]) / 1e7 - 1.0 for r in rows]
            print("| %s | patch | — | %d | %s | pressure %+.1e .. %+.1e | | | | | | %d | %d | %.1f |"
                  % (case, s["primal_dim"], disc, min(p), max(p), len(rows),
                     s["qp"]["hessian_multiplications"], wall), flush=True)
    print("\noutputs in " + work, file=sys.stderr)


if __name__ == "__main__":
    main()
