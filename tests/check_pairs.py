#!/usr/bin/env python3
"""Checks a run with several contact pairs ("Contact problem/Contact pairs").

  check_pairs.py DIR [DIR2 ...] --names A,B[,...] --load F|support [--tol T]
                 [--magnitude-tol M] [--friction-pair K]

For every DIR: the run converged; summary.json's contact.pairs lists the pairs A, B, ... in
input order, each with force = |force_vector|; each pair's force component along z carries the
load F (support: the fixed boundaries' reaction contact.support_force of a nonlinear run driven
by a motion) to T (relative, default 1e-6) and its magnitude equals F to M (default T: the pair's
force is along z; a deformed master may tilt it); with elastic_contact also the contact
conditions of the solution (no penetration, lambda >= 0, complementarity, gluing; tied and
bonded pairs: no penetration and gluing) to 1e-6 of the solution's scale. contact_pressure.csv has a pair column holding every pair's index and
nothing else; solution_*.vtu hold the point field contact_pair with the same indices (and -1).
With several DIRs (rank counts) the pair forces, p_max and the contact extent agree to 1e-6 and
the contact CSV has the same rows per pair with the same multipliers (to 1e-5 of the largest).
With --friction-pair K only pair K has friction: summary.json has the friction keys, every CSV
row of pair K a friction state (open, stick, slip) and at least one closed, every other row the
state none.
"""
import csv
import glob
import json
import re
import sys

KKT_TOL = 1e-6


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def summary(d):
    with open(d + "/summary.json") as f:
        return json.load(f)


def csv_rows(d):
    with open(d + "/contact_pressure.csv") as f:
        rows = list(csv.DictReader(f))
    if not rows or "pair" not in rows[0]:
        fail(f"{d}/contact_pressure.csv has no pair column")
    return rows


def vtu_pairs(d):
    values = set()
    pieces = glob.glob(d + "/solution_*.vtu")
    if not pieces:
        fail(f"{d}: no solution_*.vtu")
    for path in pieces:
        with open(path) as f:
            xml = f.read()
        m = re.search(r'<DataArray[^>]*Name="contact_pair"[^>]*>(.*?)</DataArray>', xml, re.S)
        if not m:
            fail(f"{path}: no point field contact_pair")
        values |= {int(float(v)) for v in m.group(1).split()}
    return values


def check_friction_pair(d, s, rows, k):
    if "friction_law" not in s["contact"]:
        fail(f"{d}: no friction keys in summary.json contact")
    states = {}
    for r in rows:
        states.setdefault(int(r["pair"]), set()).add(r.get("state", "none"))
    for pair, found in states.items():
        if pair == k and ("none" in found or not found & {"stick", "slip"}):
            fail(f"{d}: friction pair {k}: states {sorted(found)}")
        if pair != k and found != {"none"}:
            fail(f"{d}: pair {pair} without friction has the states {sorted(found)}")


def check_one(d, names, load, tol, magnitude_tol, friction_pair):
    s = summary(d)
    if not s["converged"]:
        fail(f"{d}: did not converge")
    c = s["contact"]
    if load == "support":  # driven by a motion: the fixed boundaries' reaction is the load
        load = c["support_force"]
        if not load > 0.0:
            fail(f"{d}: support_force {load}: nothing is loaded")
    pairs = c.get("pairs")
    if not pairs or [p["name"] for p in pairs] != names:
        fail(f"{d}: contact.pairs {pairs}, expected the pairs {names}")
    for p in pairs:
        v = p["force_vector"]
        magnitude = sum(x * x for x in v) ** 0.5
        if abs(magnitude - p["force"]) > 1e-9 * max(magnitude, 1.0):
            fail(f"{d}: pair {p['name']}: force {p['force']} is not |force_vector| {magnitude}")
        if abs(abs(v[-1]) - load) > tol * load:
            fail(f"{d}: pair {p['name']}: force along z {v[-1]:.10g}, the load is {load}")
        if abs(p["force"] - load) > magnitude_tol * load:
            fail(f"{d}: pair {p['name']}: force {p['force']:.10g}, the load is {load}")
    if s["problem"] == "elastic_contact":
        scale_u, force = s["max_abs_u"], load
        checks = [("penetration", c["max_penetration"], KKT_TOL * scale_u),
                  ("gluing/Dirichlet residual", c["equality_residual"], KKT_TOL * scale_u)]
        # Tied and bonded rows are equalities: their multipliers take either sign.
        if s.get("contact_type", "frictionless") == "frictionless":
            checks += [("negative multiplier", -c["min_multiplier"], KKT_TOL * force),
                       ("complementarity", c["max_complementarity"], KKT_TOL * scale_u * force)]
        for name, value, limit in checks:
            if value > limit:
                fail(f"{d}: {name} {value:.3e} > {limit:.3e}")
    rows = csv_rows(d)
    if friction_pair is not None:
        check_friction_pair(d, s, rows, friction_pair)
    indices = {int(r["pair"]) for r in rows}
    if indices != set(range(len(names))):
        fail(f"{d}: contact_pressure.csv pair indices {sorted(indices)}, expected "
             f"{list(range(len(names)))}")
    if "VTU" not in s.get("parameters", {}).get("Output", {}) or \
            s["parameters"]["Output"]["VTU"]:
        found = vtu_pairs(d)
        if not set(range(len(names))) <= found or not found <= set(range(-1, len(names))):
            fail(f"{d}: contact_pair values {sorted(found)}")
    print(f"OK: {d}: " + ", ".join(f"{p['name']} {p['force']:.10g}" for p in pairs) +
          f" (load {load:.10g}); {len(rows)} contact rows")
    return s, rows


def same_across(results):
    (d0, s0, rows0) = results[0]
    c0 = s0["contact"]
    extent = next(k for k in ("contact_radius", "half_width", "contact_extent", "angle") if k in c0)
    lscale = max(abs(float(r["lambda"])) for r in rows0)
    for d, s, rows in results[1:]:
        c = s["contact"]
        for p0, p in zip(c0["pairs"], c["pairs"]):
            if abs(p["force"] - p0["force"]) > 1e-6 * p0["force"]:
                fail(f"{d}: pair {p['name']} force {p['force']}, {p0['force']} in {d0}")
        for key in ("p_max", extent):
            if abs(c[key] - c0[key]) > 1e-6 * abs(c0[key]):
                fail(f"{d}: {key} {c[key]}, {c0[key]} in {d0}")
        # Rows matched by position: the nearest row of the other run, within 1e-6 of the rows'
        # extent (positions are the current ones in a nonlinear run: rounding apart).
        def points(rs, k):
            return [([float(r["x"]), float(r["y"]), float(r.get("z", 0.0))], float(r["lambda"]))
                    for r in rs if int(r["pair"]) == k]
        for k in range(len(c0["pairs"])):
            a, b = points(rows0, k), points(rows, k)
            if len(a) != len(b):
                fail(f"{d}: pair {k} has {len(b)} contact rows, {len(a)} in {d0}")
            coords = [x for p, _ in a for x in p]
            span = max(coords) - min(coords) if coords else 0.0
            for pa, la in a:
                dist, lb = min((sum((u - v) ** 2 for u, v in zip(pa, pb)) ** 0.5, l)
                               for pb, l in b)
                if dist > 1e-6 * span:
                    fail(f"{d}: pair {k}: no contact row at {pa} (nearest {dist:.3e} away)")
                if abs(la - lb) > 1e-5 * lscale:
                    fail(f"{d}: pair {k}: lambda {lb:.8e} vs {la:.8e} at {pa}")
    print("OK: the same pair forces and contact rows in", [r[0] for r in results])


def option(args, name, default):
    return args[args.index(name) + 1] if name in args else default


if __name__ == "__main__":
    args = sys.argv[1:]
    flags = {"--names", "--load", "--tol", "--magnitude-tol", "--friction-pair"}
    dirs = [a for i, a in enumerate(args) if a not in flags and (i == 0 or args[i - 1] not in flags)]
    names = option(args, "--names", "").split(",")
    load = option(args, "--load", "nan")
    load = load if load == "support" else float(load)
    tol = float(option(args, "--tol", 1e-6))
    magnitude_tol = float(option(args, "--magnitude-tol", tol))
    friction_pair = option(args, "--friction-pair", None)
    friction_pair = None if friction_pair is None else int(friction_pair)
    if not dirs or not names[0] or load != load:  # nan: no --load
        fail("usage: check_pairs.py DIR [DIR2 ...] --names A,B --load F [--tol T]")
    results = [(d, *check_one(d, names, load, tol, magnitude_tol, friction_pair))
               for d in dirs]
    if len(results) > 1:
        same_across(results)
