#!/usr/bin/env python3
"""Plots of a nonlinear (elasto-plastic) contact run of tfeti_contact (Problem = nonlinear_contact):

  python3 examples/plot_nonlinear.py OUTPUT_DIR [--elastic ELASTIC_DIR] [--zoom Z]

writes into OUTPUT_DIR
  contact_pressure.png  2D: the final contact pressure against x [mm] (extent_measure
                        "half_width", two cylinders) or against the angle from the bottom [deg]
                        ("angle", pin in a hole); with Hertz's p(x) = p_max sqrt(1 - x^2/a^2) if
                        the summary has it, and ELASTIC_DIR's contact_pressure.csv as "elastic"
                        if given. 3D (a point contact: the Hertz sphere, a rigid indenter): the
                        nodal pressure of every slave node against its radius from the contact
                        axis [mm], one colour per load step (contact_pressure_step_NNNN.csv),
                        with Hertz's p(r) at the full load if the summary has it and ELASTIC_DIR's
                        final pressures if given;
  von_mises.png         (2D) the von Mises stress in a window of half-size Z around the point of
                        maximum pressure (default 0.1 m for half_width, 0.5 m for angle), with the
                        yield stress as a contour line;
  plastic_strain.png    (2D) the equivalent plastic strain in the same window, if any is positive
                        (a 3D run's stresses and plastic strain are in its VTU files);
  convergence.png       the relative residual (and increment) of every accepted nonlinear
                        iteration against the cumulative iteration number, steps marked;
  solution_norm.png     the solution norm against the cumulative iteration number.
Reads summary.json, iterations.csv, contact_pressure.csv (and, in 3D, the per-step
contact_pressure_step_NNNN.csv) and, in 2D, solution_*.vtu (ASCII).
"""
import argparse
import csv
import glob
import json
import math
import os
import statistics

from plot_python import ensure_matplotlib

ensure_matplotlib()
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from vtu_reading import read_vtu  # noqa: E402


def read_csv(path):
    with open(path) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def save(fig, d, name):
    out = os.path.join(d, name)
    fig.tight_layout()
    fig.savefig(out, dpi=150)
    plt.close(fig)
    return out


def pressure_profile(d, angle_mode):
    """(abscissa, pressure [MPa]) sorted: x [mm], or the angle [deg] from the downward direction
    (computed about the origin, the hole centre, if the file has no angle column)."""
    rows = read_csv(os.path.join(d, "contact_pressure.csv"))
    if angle_mode:
        s = [r["angle"] if "angle" in r else math.degrees(math.atan2(r["x"], -r["y"]))
             for r in rows]
    else:
        s = [r["x"] * 1e3 for r in rows]
    return zip(*sorted(zip(s, [r["pressure"] / 1e6 for r in rows]))), rows


def pressure_plot(d, summary, elastic):
    c = summary["contact"]
    angle_mode = c.get("extent_measure", "half_width") == "angle"
    (s, p), rows = pressure_profile(d, angle_mode)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(s, p, "o-", ms=3, label="final step (nodal)")
    extents = [c.get("contact_extent", 0.0) * (1 if angle_mode else 1e3)]
    if elastic:
        (se, pe), _ = pressure_profile(elastic, angle_mode)
        ax.plot(se, pe, "s-", ms=3, label="elastic")
    if "hertz" in c:
        a, p0 = c["hertz"]["half_width"], c["hertz"]["p_max"]
        xs = [a * i / 200 for i in range(201)]
        ph = [p0 * math.sqrt(max(0.0, 1 - (v / a) ** 2)) / 1e6 for v in xs]
        if angle_mode:
            # x = r sin(angle) on the contact circle (symmetry axis x = 0), r from the data.
            r = statistics.median([q["x"] / math.sin(math.radians(q["angle"])) for q in rows
                                   if "angle" in q and abs(q["angle"]) > 1.0] or [1.0])
            xs = [math.degrees(math.asin(min(1.0, v / r))) for v in xs]
        else:
            xs = [v * 1e3 for v in xs]
        ax.plot(xs, ph, "k--", label="Hertz")
        extents.append(max(xs))
    if max(extents) > 0:
        ax.set_xlim(0, min(max(s), 2 * max(extents)))
    ax.set_xlabel("angle from the bottom [deg]" if angle_mode else "x [mm]")
    ax.set_ylabel("contact pressure [MPa]")
    extent = (f"contact angle {c.get('contact_extent', 0):.1f} deg" if angle_mode
              else f"half-width {c.get('contact_extent', 0) * 1e3:.2f} mm")
    ax.set_title(f"p_max {c['p_max'] / 1e6:.0f} MPa, {extent}")
    ax.legend()
    return save(fig, d, "contact_pressure.png")


def step_pressures(d):
    """[(step, rows)] of the per-step contact_pressure_step_NNNN.csv files, in step order."""
    out = []
    for path in sorted(glob.glob(os.path.join(d, "contact_pressure_step_*.csv"))):
        step = int(os.path.basename(path)[len("contact_pressure_step_"):-len(".csv")])
        out.append((step, read_csv(path)))
    return out


def pressure_plot_3d(d, summary, elastic):
    """A point contact in 3D: pressure against the radius from the contact axis, per step."""
    c = summary["contact"]
    factors = {st["step"]: st["load_factor"] for st in summary.get("steps", [])}
    steps = step_pressures(d) or [(max(factors, default=0), read_csv(
        os.path.join(d, "contact_pressure.csv")))]
    fig, ax = plt.subplots(figsize=(6, 4))
    colours = plt.cm.viridis([i / max(1, len(steps) - 1) for i in range(len(steps))])
    radius_max = 0.0
    for (step, rows), colour in zip(steps, colours):
        r = [q["radius"] * 1e3 for q in rows]
        label = f"step {step}" + (f" (load factor {factors[step]:.3g})" if step in factors else "")
        ax.plot(r, [q["pressure"] / 1e6 for q in rows], "o", ms=2.5, color=colour, label=label)
        radius_max = max([radius_max] + [v for v, q in zip(r, rows) if q["pressure"] > 0])
    if elastic:
        rows = read_csv(os.path.join(elastic, "contact_pressure.csv"))
        ax.plot([q["radius"] * 1e3 for q in rows], [q["pressure"] / 1e6 for q in rows], "s",
                ms=2.5, mfc="none", color="gray", label="elastic")
    if "hertz" in c:
        a, p0 = c["hertz"]["contact_radius"], c["hertz"]["p_max"]
        xs = [a * i / 200 for i in range(201)]
        ax.plot([v * 1e3 for v in xs], [p0 * math.sqrt(max(0.0, 1 - (v / a) ** 2)) / 1e6
                                       for v in xs], "k--", label="Hertz (elastic, full load)")
        radius_max = max(radius_max, a * 1e3)
    if radius_max > 0:
        ax.set_xlim(0, 1.6 * radius_max)
    ax.set_xlabel("radius r from the contact axis [mm]")
    ax.set_ylabel("contact pressure [MPa]")
    ax.set_title(f"p_max {c['p_max'] / 1e6:.0f} MPa, contact radius "
                 f"{c.get('contact_extent', 0) * 1e3:.2f} mm", fontsize=10)
    ax.legend(fontsize=8)
    return save(fig, d, "contact_pressure.png")


def field_plot(d, tri, values, centre, zoom, label, name, cmap, level=None):
    fig, ax = plt.subplots(figsize=(6, 5))
    tpc = ax.tripcolor(tri, values, shading="gouraud", cmap=cmap)
    fig.colorbar(tpc, ax=ax, label=label)
    if level is not None and min(values) < level < max(values):
        ax.tricontour(tri, values, levels=[level], colors="w", linewidths=1)
        ax.set_title(f"white: yield stress {level:.0f} MPa")
    ax.set_xlim(max(min(tri.x), centre[0] - zoom), centre[0] + zoom)
    ax.set_ylim(centre[1] - zoom, centre[1] + zoom)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    return save(fig, d, name)


def stress_plots(d, summary, zoom):
    rows = read_csv(os.path.join(d, "contact_pressure.csv"))
    top = max(rows, key=lambda r: r["pressure"])
    centre = (top["x"], top["y"])
    tri, f = read_vtu(d, ["von_mises", "plastic_strain"])
    if f["von_mises"] is None:
        raise SystemExit(f"no von_mises field in {d}/solution_*.vtu")
    # One yield stress for all bodies, or the bodies' own ("materials"): the lowest as the line.
    yields = [m.get("yield_stress") for m in summary.get("materials", {}).values()] or \
        [summary.get("material", {}).get("yield_stress")]
    yields = [y for y in yields if y]
    yield_stress = min(yields) if yields else None
    out = [field_plot(d, tri, [v / 1e6 for v in f["von_mises"]], centre, zoom,
                      "von Mises [MPa]", "von_mises.png", "viridis",
                      yield_stress / 1e6 if yield_stress else None)]
    if f["plastic_strain"] and max(f["plastic_strain"]) > 0:
        out.append(field_plot(d, tri, f["plastic_strain"], centre, zoom,
                              "equivalent plastic strain", "plastic_strain.png", "magma"))
    return out


def history_plots(d):
    rows = read_csv(os.path.join(d, "iterations.csv"))
    acc = [r for r in rows if r["accepted"] == 1]
    n = list(range(1, len(acc) + 1))
    # n[i] is the first iteration of a new load step: a boundary between n[i] - 1 and n[i].
    starts = [n[i] for i in range(1, len(acc)) if acc[i]["step"] != acc[i - 1]["step"]]
    title = (f"{len({r['step'] for r in acc})} load steps, {len(acc)} iterations "
             f"({len(rows) - len(acc)} rejected), "
             f"{sum(int(r['mprgp_iterations']) for r in rows)} MPRGP iterations")

    def figure(ylabel):
        fig, ax = plt.subplots(figsize=(7, 4))
        for s in starts:
            ax.axvline(s - 0.5, color="gray", ls=":", lw=0.8)
        ax.set_xlabel("nonlinear iteration (cumulative; dotted: load step boundaries)")
        ax.set_ylabel(ylabel)
        ax.set_title(title, fontsize=9)
        return fig, ax

    fig, ax = figure("relative residual / increment")
    for key, label in [("relative_residual", "residual"), ("relative_increment", "||du|| / ||u||")]:
        # Zeros have no place on a log scale.
        ax.semilogy(n, [r[key] if r[key] > 0 else math.nan for r in acc], "o-", ms=3, label=label)
    ax.legend()
    out = [save(fig, d, "convergence.png")]
    fig, ax = figure("||u||")
    ax.plot(n, [r["solution_norm"] for r in acc], "o-", ms=3)
    return out + [save(fig, d, "solution_norm.png")]


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--elastic", help="output directory of the elastic run, to compare with")
    ap.add_argument("--zoom", type=float, help="half-size of the stress window [m]")
    o = ap.parse_args()
    with open(os.path.join(o.dir, "summary.json")) as f:
        summary = json.load(f)
    angle_mode = summary["contact"].get("extent_measure") == "angle"
    zoom = o.zoom if o.zoom else (0.5 if angle_mode else 0.1)
    if summary.get("dimension", 2) == 3:
        # A 3D run: the pressure against the radius; its stress fields are in the VTU files.
        outputs = [pressure_plot_3d(o.dir, summary, o.elastic)]
    else:
        outputs = [pressure_plot(o.dir, summary, o.elastic)] + stress_plots(o.dir, summary, zoom)
    for out in outputs + history_plots(o.dir):
        print("wrote", out)
