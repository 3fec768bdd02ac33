#!/usr/bin/env python3
"""Plots of an elastic contact run of tfeti_contact (Problem = elastic_contact):

  python3 examples/plot_two_cylinders.py OUTPUT_DIR [--zoom 0.08]

writes OUTPUT_DIR/contact_pressure.png, the computed nodal contact pressure against Hertz's
p(r) = p_max sqrt(1 - r^2/a^2) when the run compared with Hertz: in 2D along the contact surface
(r = x, the two cylinders), in 3D against the radius from the contact axis (the Hertz sphere,
docs/hertz_sphere.md: every slave node, so the scatter around a ring shows, and the recovered
pressure); and in 2D OUTPUT_DIR/von_mises.png (the von Mises stress near the contact, from the
VTU pieces). Reads
summary.json, contact_pressure.csv and, in 2D, solution_*.vtu (ASCII) in OUTPUT_DIR.
"""
import argparse
import csv
import json
import math
import os

from plot_python import ensure_matplotlib

ensure_matplotlib()
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from vtu_reading import read_vtu  # noqa: E402


def pressure_plot(d, summary):
    with open(os.path.join(d, "contact_pressure.csv")) as f:
        rows = [r for r in csv.DictReader(f)]
    c = summary["contact"]
    # A line contact is plotted along x, a point contact (3D) against the radius.
    extent, coordinate = ("contact_radius", "radius") if "contact_radius" in c else \
        ("half_width", "x")
    x = [float(r[coordinate]) for r in rows]
    p = [float(r["pressure"]) for r in rows]
    fig, ax = plt.subplots(figsize=(6, 4))
    if extent == "half_width":
        ax.plot([v * 1e3 for v in x], [v / 1e6 for v in p], "o-", ms=3, label="TFETI (nodal)")
    else:
        ax.plot([v * 1e3 for v in x], [v / 1e6 for v in p], "o", ms=3,
                label="TFETI (every slave node)")
        # The recovered pressure (a least-squares fit over each node's facet neighbours).
        if rows and "pressure_recovered" in rows[0]:
            ax.plot([v * 1e3 for v in x], [float(r["pressure_recovered"]) / 1e6 for r in rows],
                    "x", ms=3, label="TFETI (recovered)")
    if "hertz" in c:
        a, p0 = c["hertz"][extent], c["hertz"]["p_max"]
        xs = [a * i / 200 for i in range(201)]
        ax.plot([v * 1e3 for v in xs], [p0 * math.sqrt(max(0.0, 1 - (v / a) ** 2)) / 1e6
                                       for v in xs], "k--", label="Hertz")
    ax.set_xlim(0, 2e3 * c.get("hertz", {}).get(extent, max(x)))
    ax.set_xlabel(f"{'radius r' if extent == 'contact_radius' else 'x'} [mm]")
    ax.set_ylabel("contact pressure [MPa]")
    label = "contact radius" if extent == "contact_radius" else "half-width"
    recovered = (f" (recovered {c['p_max_recovered'] / 1e6:.0f})" if "p_max_recovered" in c
                 else "")
    ax.set_title(f"p_max {c['p_max'] / 1e6:.0f} MPa{recovered}, {label} {c[extent] * 1e3:.2f} mm")
    ax.legend()
    fig.tight_layout()
    out = os.path.join(d, "contact_pressure.png")
    fig.savefig(out, dpi=150)
    return out


def von_mises_plot(d, zoom):
    tri, fields = read_vtu(d, ["von_mises"])
    vm = fields["von_mises"]
    if vm is None:
        raise SystemExit(f"no von_mises field in the VTU pieces of {d}")
    fig, ax = plt.subplots(figsize=(6, 5))
    tpc = ax.tripcolor(tri, [v / 1e6 for v in vm], shading="gouraud", cmap="viridis")
    fig.colorbar(tpc, ax=ax, label="von Mises [MPa]")
    ax.set_xlim(0, zoom)
    ax.set_ylim(-zoom, zoom)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    fig.tight_layout()
    out = os.path.join(d, "von_mises.png")
    fig.savefig(out, dpi=150)
    return out


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--zoom", type=float, default=0.08, help="half-size of the stress window [m]")
    o = ap.parse_args()
    with open(os.path.join(o.dir, "summary.json")) as f:
        summary = json.load(f)
    print("wrote", pressure_plot(o.dir, summary))
    # The stress picture is a 2D section; a 3D run's stresses are in solution.pvtu.
    if summary.get("dimension", 2) == 2:
        print("wrote", von_mises_plot(o.dir, o.zoom))
