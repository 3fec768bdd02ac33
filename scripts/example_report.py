#!/usr/bin/env python3
"""What a run of tfeti_contact produced, for a person: draws the pictures of a contact run (with
examples/plot_*.py) and prints where the results and pictures are and what they show.

  python3 scripts/example_report.py OUTPUT_DIR [--seconds S] [--ranks N] [--no-plots]

Needs only the standard library (the plot scripts find a Python with matplotlib themselves).
Exit code 1 when OUTPUT_DIR has no summary.json or a plot script fails.
"""
import argparse
import glob
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

FILES = [
    ("summary.json", "every figure of the run (README.md, \"summary.json\")"),
    ("steps.pvd", "ParaView time series of the load steps (time = load factor): open it and "
                  "press play"),
    ("solution.pvtu", "final state for ParaView (u or the displacement, stresses where computed, "
                      "subdomain ids)"),
    ("contact_pressure.csv", "contact pressure per slave node (x, y, multiplier, pressure)"),
    ("steps.csv", "per load step: iterations, p_max, contact extent, von Mises"),
    ("iterations.csv", "every nonlinear iteration: residual, increment, MPRGP iterations"),
    ("contact.csv", "the contact line: multiplier and both membranes' displacement"),
]
PICTURES = {
    "contact_pressure.png": "contact pressure along the contact surface, against Hertz",
    "von_mises.png": "von Mises stress near the contact",
    "plastic_strain.png": "equivalent plastic strain near the contact",
    "convergence.png": "relative residual and increment of every nonlinear iteration",
    "solution_norm.png": "||u|| over the nonlinear iterations",
}
PLOTS = {"nonlinear_contact": "plot_nonlinear.py", "elastic_contact": "plot_two_cylinders.py"}


def plot(d, problem):
    script = PLOTS.get(problem)
    if not script:
        return True
    r = subprocess.run([sys.executable, os.path.join(ROOT, "examples", script), d],
                       stdout=subprocess.DEVNULL)
    return r.returncode == 0


def contact_lines(s):
    c = s.get("contact")
    if not c or "p_max" not in c:
        return []
    lines = []
    h, err = c.get("hertz"), c.get("relative_error", {})
    # A line contact (2D) has a half-width and a force per unit length, a point contact (3D) a
    # contact radius and a force.
    key, label, unit = ("contact_radius", "contact radius", "N") if "contact_radius" in c else \
        ("half_width", "half-width", "N/m")
    width = c.get(key)
    if h:
        lines.append(f"  p_max       {c['p_max'] / 1e6:8.1f} MPa   Hertz {h['p_max'] / 1e6:8.1f} MPa"
                     f"   error {100 * err['p_max']:.2f} %")
        lines.append(f"  {label:11s} {width * 1e3:8.3f} mm    Hertz {h[key] * 1e3:8.3f} mm"
                     f"    error {100 * err[key]:.2f} %")
    else:
        lines.append(f"  p_max {c['p_max']:.4g}, contact extent {c.get('contact_extent', width)}")
    if "force_relative_error" in c:
        lines.append(f"  contact force {c['force']:.6g} {unit} against the applied "
                     f"{c['applied_force']:.6g} {unit} (relative error "
                     f"{c['force_relative_error']:.1e})")
    return lines


def what_it_shows(s):
    problem = s.get("problem", "?")
    lines = []
    if problem == "nonlinear_contact":
        nl = s["nonlinear"]
        lines.append(f"{problem}: {nl['converged_steps']} load steps to load factor "
                     f"{nl['load_factor']:g}, {nl['total_iterations']} nonlinear iterations, "
                     f"{nl['total_hessian_multiplications']} Hessian multiplications; "
                     f"{s['subdomains']} subdomains, {s['primal_dim']} unknowns")
        if s.get("max_plastic_strain", 0) > 0:
            lines.append(f"  max von Mises {s['max_von_mises'] / 1e6:.0f} MPa, max plastic strain "
                         f"{s['max_plastic_strain']:.2e}")
    elif problem in ("elastic_contact", "two_membranes"):
        lines.append(f"{problem}: {s['subdomains']} subdomains, {s['primal_dim']} unknowns, "
                     f"{s['contact_rows']} contact rows, {s['dual_solver']} "
                     f"({s['qp']['hessian_multiplications']} Hessian multiplications)")
    elif s.get("study") == "scalability":
        lines.append(f"scalability table: {len(s['table'])} rows "
                     f"({'all converged' if s['all_converged'] else 'NOT all converged'})")
    else:
        lines.append(f"{problem}: {s.get('subdomains')} subdomains, {s.get('primal_dim')} unknowns,"
                     f" {s.get('iterations')} iterations, relative residual "
                     f"{s.get('relative_residual', 0):.1e}")
        if "error_vs_direct" in s:
            lines.append(f"  max relative error against a direct solve {s['error_vs_direct']:.1e}")
    if "converged" in s and not s["converged"]:
        lines.append("  NOT CONVERGED: see the messages above and summary.json")
    return lines + contact_lines(s)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--seconds", type=float, help="wall time of the run")
    ap.add_argument("--ranks", type=int)
    ap.add_argument("--no-plots", action="store_true")
    o = ap.parse_args()
    path = os.path.join(o.dir, "summary.json")
    if not os.path.exists(path):
        raise SystemExit(f"{path}: no such file (the run wrote no summary)")
    with open(path) as f:
        s = json.load(f)
    ok = o.no_plots or plot(o.dir, s.get("problem"))
    took = f" in {o.seconds:.0f} s" if o.seconds is not None else ""
    on = f" on {o.ranks} MPI ranks" if o.ranks else ""
    print(f"\n== Solved{took}{on}. Results in {o.dir}/:")
    for name, what in FILES:
        if os.path.exists(os.path.join(o.dir, name)):
            print(f"  {name:22s} {what}")
    steps = sorted(glob.glob(os.path.join(o.dir, "step_*.pvtu")))
    if steps:
        print(f"  {'step_NNNN.pvtu':22s} {len(steps)} load steps "
              "(and contact_pressure_step_NNNN.csv)")
    pictures = [p for p in PICTURES if os.path.exists(os.path.join(o.dir, p))]
    if pictures:
        print("Pictures:")
        for p in pictures:
            print(f"  {os.path.join(o.dir, p):40s} {PICTURES[p]}")
    print("What they show:")
    for line in what_it_shows(s):
        print(line)
    if not ok:
        print("a plot script failed (see its message above)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
