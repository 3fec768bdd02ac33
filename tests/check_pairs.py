#!/usr/bin/env python3
"""Checks a run with several contact pairs ("Contact problem/Contact pairs").

  check_pairs.py DIR [DIR2 ...] --names A,B[,...] --load F|support [--tol T]
                 [--magnitude-tol M] [--friction-pair K[,K2...]]
                 [--pair-reference NAME=REFDIR ...] [--reference-tol R]

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
With --friction-pair K only pair K has friction (K2, ...: those pairs): summary.json has the
friction keys (friction_law "mixed" where the pairs' laws differ), each friction pair's entry of
contact.pairs its own friction record and every other entry none, every CSV row of a friction
pair a friction state (open, stick, slip) and at least one closed, every other row the state
none. With --pair-reference NAME=REFDIR the friction record of pair NAME equals the friction
keys of the single-pair run REFDIR (the same contact problem alone): the resultant contact force
(to R of its magnitude), the normal and tangential sums, stick and slip node counts, the stick
and contact extents and the largest slip, to R (relative, default 1e-6).
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


def check_friction_pairs(d, s, rows, ks):
    c = s["contact"]
    if "friction_law" not in c:
        fail(f"{d}: no friction keys in summary.json contact")
    laws = set()
    for k, p in enumerate(c["pairs"]):
        if (k in ks) != ("friction" in p):
            fail(f"{d}: pair {p['name']}: friction record {p.get('friction')}, expected "
                 f"{'one' if k in ks else 'none'}")
        if k in ks:
            laws.add(p["friction"]["friction_law"])
    expected = laws.pop() if len(laws) == 1 else "mixed"
    if c["friction_law"] != expected:
        fail(f"{d}: friction_law {c['friction_law']}, expected {expected}")
    states = {}
    for r in rows:
        states.setdefault(int(r["pair"]), set()).add(r.get("state", "none"))
    for pair, found in states.items():
        if pair in ks and ("none" in found or not found & {"stick", "slip"}):
            fail(f"{d}: friction pair {pair}: states {sorted(found)}")
        if pair not in ks and found != {"none"}:
            fail(f"{d}: pair {pair} without friction has the states {sorted(found)}")


REFERENCE_KEYS = ("normal_force", "tangential_force", "slip_nodes", "stick_nodes",
                  "stick_half_width", "contact_half_width", "stick_radius", "contact_radius",
                  "max_accumulated_slip")


def check_pair_reference(d, s, name, ref, tol):
    entry = next((p for p in s["contact"]["pairs"] if p["name"] == name), None)
    if entry is None or "friction" not in entry:
        fail(f"{d}: no friction record for pair {name}")
    r = summary(ref)
    if not r["converged"]:
        fail(f"{ref}: did not converge")
    mine, theirs = entry["friction"], r["contact"]
    # The resultant contact force: unlike the normal and tangential sums it does not depend on
    # the frame a node at a master kink takes (docs/friction.md).
    fa, fb = mine.get("contact_force", []), theirs["contact_force"]
    size = sum(v * v for v in fb) ** 0.5
    if len(fa) != len(fb) or any(abs(x - y) > tol * size for x, y in zip(fa, fb)):
        fail(f"{d}: pair {name}: contact_force {fa}, {fb} alone ({ref})")
    for key in REFERENCE_KEYS:
        if key not in theirs:
            continue
        a, b = mine.get(key), theirs[key]
        if a is None or abs(a - b) > tol * max(abs(b), 1e-300):
            fail(f"{d}: pair {name}: {key} {a}, {b} alone ({ref})")
    print(f"OK: {d}: pair {name} is its single-pair run {ref} (tangential force "
          f"{mine['tangential_force']:.10g}, {mine['stick_nodes']} stick, "
          f"{mine['slip_nodes']} slip nodes)")


def check_one(d, names, load, tol, magnitude_tol, friction_pairs):
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
    if friction_pairs is not None:
        check_friction_pairs(d, s, rows, friction_pairs)
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
    flags = {"--names", "--load", "--tol", "--magnitude-tol", "--friction-pair",
             "--pair-reference", "--reference-tol"}
    dirs = [a for i, a in enumerate(args) if a not in flags and (i == 0 or args[i - 1] not in flags)]
    names = option(args, "--names", "").split(",")
    load = option(args, "--load", "nan")
    load = load if load == "support" else float(load)
    tol = float(option(args, "--tol", 1e-6))
    magnitude_tol = float(option(args, "--magnitude-tol", tol))
    friction_pairs = option(args, "--friction-pair", None)
    friction_pairs = None if friction_pairs is None else \
        {int(k) for k in friction_pairs.split(",")}
    references = [args[i + 1].split("=", 1) for i, a in enumerate(args)
                  if a == "--pair-reference"]
    reference_tol = float(option(args, "--reference-tol", 1e-6))
    if not dirs or not names[0] or load != load:  # nan: no --load
        fail("usage: check_pairs.py DIR [DIR2 ...] --names A,B --load F [--tol T]")
    results = [(d, *check_one(d, names, load, tol, magnitude_tol, friction_pairs))
               for d in dirs]
    for d, s, _ in results:
        for name, ref in references:
            check_pair_reference(d, s, name, ref, reference_tol)
    if len(results) > 1:
        same_across(results)
