#!/usr/bin/env python3
"""Hessian-multiplication counts of the two-cylinder contact solve (issue 11), without timing.

Solves examples/two_cylinders_elastic.xml at the given size factors (SIZE:SUBDOMAINS_PER_BODY)
with the FETI parameters of --set, and prints one line per size: F applications, outer
iterations, the step kinds, and the solution's quality (p_max and half-width against Hertz, the
contact force against the load, the equality residual). Counts do not depend on machine load.

    python3 bench/cylinder_counts.py --sizes 0.5:8,0.22:16 --set SMALBE/Penalty=30
"""
import argparse
import hashlib
import json
import re
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_benchmarks as rb  # noqa: E402


def face_counts(message):
    """SMALBE's face phase (FETI/SMALBE/Face solve = pcpg) as its message reports it."""
    m = re.search(r"face solve: (\d+) face solves, (\d+) face CG steps, (\d+) active-set", message)
    if not m:
        return {}
    return {"face_solves": int(m.group(1)), "face_cg": int(m.group(2)),
            "active_set_changes": int(m.group(3)),
            "face_accepted": "(the last a face solve)" in message}


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--build", default="build")
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--out", default="bench-out/counts")
    p.add_argument("--sizes", default="0.5:8,0.22:16")
    p.add_argument("--tied", action="store_true", help="the pair tied (PCPG) instead")
    p.add_argument("--set", action="append", default=[], metavar="LIST/NAME=VALUE")
    o = p.parse_args()
    o.feti_set = [tuple(a.split("=", 1)) for a in o.set]
    # A --set of a parameter the example already gives (SMALBE's tolerances) replaces it.
    given = [k.rsplit("/", 1)[-1] for k, _ in o.feti_set]
    run = rb.cylinders_run

    def cylinders_run(o, name, sf, order, subs, tied=False):
        orig = rb.set_parameter

        def set_parameter(xml, key, value):
            # Only within the list the key names (its last sublist, or FETI), nested lists
            # skipped over to the list's own closing tag.
            path, name = key.rsplit("/", 1) if "/" in key else ("FETI", key)
            tag = '<ParameterList name="%s">' % path.rsplit("/", 1)[-1]
            if name in given and tag in xml:
                at = xml.index(tag)
                depth, end = 0, at
                for m in re.finditer(r"<ParameterList[^>]*[^/]>|</ParameterList>", xml[at:]):
                    depth += -1 if m.group(0).startswith("</") else 1
                    if depth == 0:
                        end = at + m.start()
                        break
                body = re.sub(r'\s*<Parameter name="%s" type="[a-z]+" value="[^"]*"/>' %
                              re.escape(name), "", xml[at:end], count=1)
                xml = xml[:at] + body + xml[end:]
            return orig(xml, key, value)
        rb.set_parameter = set_parameter
        try:
            return run(o, name, sf, order, subs, tied)
        finally:
            rb.set_parameter = orig
    label = ",".join(o.set) or "defaults"
    for size in o.sizes.split(","):
        sf, subs = size.split(":")
        name = f"{'tied' if o.tied else 'contact'}_sf{sf}_{hashlib.md5(label.encode()).hexdigest()[:8]}"
        s = cylinders_run(o, name, float(sf), 1, int(subs), tied=o.tied)
        if s is None:
            print(f"{sf} {label}: failed", flush=True)
            continue
        q, c = s["qp"], s.get("contact", {})
        err = c.get("relative_error", {})
        print(json.dumps({"size_factor": float(sf), "unknowns": s["primal_dim"],
                          "subdomains": s["subdomains"], "set": label,
                          "mults": q["hessian_multiplications"],
                          "outer": q.get("outer_iterations"),
                          "cg": q.get("cg_steps"), "expansion": q.get("expansion_steps"),
                          "proportioning": q.get("proportioning_steps"),
                          **face_counts(q.get("message", "")),
                          "converged": s["converged"],
                          "p_max_err": err.get("p_max"), "half_width_err": err.get("half_width"),
                          "force": c.get("force"),
                          "force_error": c.get("force_relative_error"),
                          "equality_residual": c.get("equality_residual")}), flush=True)


if __name__ == "__main__":
    main()
