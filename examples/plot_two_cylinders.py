#!/usr/bin/env python3
"""Plots of a two-cylinder run of tfeti_contact (Problem = elastic_contact):

  python3 examples/plot_two_cylinders.py OUTPUT_DIR [--zoom 0.08]

writes OUTPUT_DIR/contact_pressure.png (the computed contact pressure along the contact surface
against Hertz's p(x) = p_max sqrt(1 - x^2/a^2)) and OUTPUT_DIR/von_mises.png (the von Mises
stress near the contact, from the VTU pieces). Reads summary.json, contact_pressure.csv and
solution_*.vtu (ASCII) in OUTPUT_DIR.
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
    x = [float(r["x"]) for r in rows]
    p = [float(r["pressure"]) for r in rows]
    c = summary["contact"]
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot([v * 1e3 for v in x], [v / 1e6 for v in p], "o-", ms=3, label="TFETI (nodal)")
    if "hertz" in c:
        a, p0 = c["hertz"]["half_width"], c["hertz"]["p_max"]
        xs = [a * i / 200 for i in range(201)]
        ax.plot([v * 1e3 for v in xs], [p0 * math.sqrt(max(0.0, 1 - (v / a) ** 2)) / 1e6
                                       for v in xs], "k--", label="Hertz")
    ax.set_xlim(0, 2e3 * c.get("hertz", {}).get("half_width", max(x)))
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("contact pressure [MPa]")
    ax.set_title(f"p_max {c['p_max'] / 1e6:.0f} MPa, half-width {c['half_width'] * 1e3:.2f} mm")
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
    print("wrote", von_mises_plot(o.dir, o.zoom))
