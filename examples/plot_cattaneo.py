#!/usr/bin/env python3
"""Cattaneo-Mindlin partial slip of a frictional run of tfeti_contact (Problem =
nonlinear_contact, Friction law = Coulomb; 2D examples/cattaneo_cylinders.xml, 3D
examples/cattaneo_sphere.xml):

  python3 examples/plot_cattaneo.py OUTPUT_DIR

writes OUTPUT_DIR/cattaneo_traction.png: the nodal contact pressure p and the magnitude of the
tangential traction |q| of the final state against the closed forms, Hertz's
p(x) = p0 sqrt(1 - x^2/a^2) (p0 = 2P/(pi a)) and Cattaneo-Mindlin's
|q(x)| = mu p(x) - mu p0 (c/a) sqrt(1 - x^2/c^2) for |x| < c (the stick zone), mu p(x) outside
(the slip zones), c = a sqrt(1 - Q/(mu P)); x from the middle of the closed nodes, a their half
extent. 3D (a sphere): against the distance r from the contact axis (the CSV's radius),
p(r) = p0 sqrt(1 - r^2/a^2) with p0 = 3P/(2 pi a^2) and Mindlin's |q(r)| of the same form with
c = a (1 - Q/(mu P))^(1/3); a half or quarter model (every closed node at y >= 0, or at x, y >=
0) carries half or a quarter of the sphere's P, which p0 takes into account. Reads summary.json
(contact: normal_force P, tangential_force Q, friction_coefficient, cattaneo_mindlin) and
contact_pressure.csv (x, [y, radius,] pressure, tangential_traction, state).
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


def closed_forms(a, p0, mu, c):
    """x, p(x) and |q(x)| on [-a, a]."""
    xs = [a * (-1 + 2 * i / 400) for i in range(401)]
    p = [p0 * math.sqrt(max(0.0, 1 - (x / a) ** 2)) for x in xs]
    q = [mu * pi - (mu * p0 * (c / a) * math.sqrt(max(0.0, 1 - (x / c) ** 2)) if c > 0 and
                    abs(x) < c else 0.0) for x, pi in zip(xs, p)]
    return xs, p, q


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("output_dir")
    d = parser.parse_args().output_dir
    with open(os.path.join(d, "summary.json")) as f:
        c = json.load(f)["contact"]
    if "cattaneo_mindlin" not in c:
        raise SystemExit(f"{d}/summary.json: no contact.cattaneo_mindlin (a Coulomb run)")
    cm = c["cattaneo_mindlin"]
    mu, P, Q = c["friction_coefficient"], cm["normal_force"], cm["tangential_force"]
    with open(os.path.join(d, "contact_pressure.csv")) as f:
        rows = list(csv.DictReader(f))
    closed = [r for r in rows if r["state"] != "open"]
    three_d = "contact_radius" in cm
    if three_d:
        # Distances from the contact axis; the share of the sphere the model holds.
        eps = 1e-9 * max(abs(float(r["radius"])) for r in closed)
        half = all(float(r["y"]) >= -eps for r in closed)
        quarter = half and all(float(r["x"]) >= -eps for r in closed)
        share = 0.25 if quarter else 0.5 if half else 1.0
        a = cm["contact_radius"]
        p0 = 3 * (P / share) / (2 * math.pi * a * a)
        c_cm = a * (max(0.0, 1 - Q / (mu * P))) ** (1.0 / 3.0)
        x = [float(r["radius"]) * 1e3 for r in rows]
        xs, p, q = closed_forms(a, p0, mu, c_cm)
        xs, p, q = zip(*[(v, pv, qv) for v, pv, qv in zip(xs, p, q) if v >= 0])
    else:
        xc = [float(r["x"]) for r in closed]
        centre = 0.5 * (min(xc) + max(xc))
        a = cm["contact_half_width"]
        p0 = 2 * P / (math.pi * a)
        c_cm = a * math.sqrt(max(0.0, 1 - Q / (mu * P)))
        x = [(float(r["x"]) - centre) * 1e3 for r in rows]
        xs, p, q = closed_forms(a, p0, mu, c_cm)

    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(x, [float(r["pressure"]) / 1e6 for r in rows], "o", ms=3, color="C0",
            label="pressure p (TFETI, nodal)")
    ax.plot(x, [abs(float(r["tangential_traction"])) / 1e6 for r in rows], "s", ms=3,
            color="C1", label="|tangential traction| (TFETI)")
    var = "r" if three_d else "x"
    ax.plot([v * 1e3 for v in xs], [v / 1e6 for v in p], "k--", lw=1,
            label=f"Hertz p({var}), p0 = " + ("3P/(2 pi a^2)" if three_d else "2P/(pi a)"))
    ax.plot([v * 1e3 for v in xs], [mu * v / 1e6 for v in p], "k:", lw=1, label=f"mu p({var})")
    ax.plot([v * 1e3 for v in xs], [v / 1e6 for v in q], "r-", lw=1,
            label=f"{'Mindlin' if three_d else 'Cattaneo-Mindlin'} |q({var})|")
    stick = cm["stick_radius" if three_d else "stick_half_width"]
    for s in ((1,) if three_d else (-1, 1)):
        ax.axvline(s * stick * 1e3, color="C1", lw=0.8, alpha=0.6)
    ax.set_xlim(0 if three_d else -1.4e3 * a, 1.4e3 * a)
    ax.set_xlabel("distance r from the contact axis [mm]" if three_d
                  else "x from the contact's middle [mm]")
    ax.set_ylabel("traction [MPa]")
    law = "(1 - Q/(mu P))^(1/3)" if three_d else "sqrt(1 - Q/(mu P))"
    ax.set_title(f"Q/(mu P) = {cm['q_over_mu_p']:.3f}: c/a = {cm['stick_ratio']:.3f}, "
                 f"{law} = {cm.get('stick_ratio_closed_form', float('nan')):.3f}",
                 fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    out = os.path.join(d, "cattaneo_traction.png")
    fig.savefig(out, dpi=150)
    print(out)


if __name__ == "__main__":
    main()
