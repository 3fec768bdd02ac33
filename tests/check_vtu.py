#!/usr/bin/env python3
"""Checks the VTU output of a structured run (tests/CMakeLists.txt):

  check_vtu.py DIR --points N --cells C --cell-type T --field NAME:COMPONENTS [--field ...]

DIR/solution.pvtu is a PUnstructuredGrid naming one readable piece per rank; the pieces
together have N points and C cells, every cell of VTK type T (9 quadrilateral, 12 hexahedron)
with its corners in VTK's order (positive area or volume), offsets and connectivity
consistent; each named point-data field has COMPONENTS values per point, "subdomain" one value
per cell, all finite; summary.json's "vtu" names the .pvtu.
"""
import argparse
import json
import math
import os
import sys
import xml.etree.ElementTree as ET

SIZES = {5: 3, 9: 4, 10: 4, 12: 8}


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def values(piece, path, name):
    for a in piece.iter("DataArray"):
        if a.get("Name") == name:
            return a, (a.text or "").split()
    fail(f"{path}: no DataArray {name}")


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def positive(cell_type, p):
    """The cell's orientation at its first corner: area (quadrilateral) or volume (hexahedron)."""
    if cell_type == 9:
        u, v = sub(p[1], p[0]), sub(p[3], p[0])
        return u[0] * v[1] - u[1] * v[0] > 0
    if cell_type == 12:
        u, v, w = sub(p[1], p[0]), sub(p[3], p[0]), sub(p[4], p[0])
        return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                u[2] * (v[0] * w[1] - v[1] * w[0])) > 0
    return True


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--points", type=int, required=True)
    ap.add_argument("--cells", type=int, required=True)
    ap.add_argument("--cell-type", type=int, required=True)
    ap.add_argument("--field", action="append", default=[])
    a = ap.parse_args()
    index = os.path.join(a.dir, "solution.pvtu")
    try:
        root = ET.parse(index).getroot()
    except (OSError, ET.ParseError) as e:
        fail(f"{index}: {e}")
    grid = root.find("PUnstructuredGrid")
    if root.get("type") != "PUnstructuredGrid" or grid is None:
        fail(f"{index}: not a PUnstructuredGrid")
    declared = {p.get("Name"): int(p.get("NumberOfComponents"))
                for p in grid.find("PPointData").iter("PDataArray")}
    fields = {}
    for f in a.field:
        name, comps = f.split(":")
        fields[name] = int(comps)
        if declared.get(name) != int(comps):
            fail(f"{index}: point data {name} declared with {declared.get(name)} components, "
                 f"expected {comps}")
    sources = [p.get("Source") for p in grid.findall("Piece")]
    if not sources:
        fail(f"{index}: names no piece")
    with open(os.path.join(a.dir, "summary.json")) as f:
        if os.path.basename(json.load(f).get("vtu", "")) != "solution.pvtu":
            fail(f"{a.dir}/summary.json: \"vtu\" does not name solution.pvtu")
    points = cells = 0
    for s in sources:
        path = os.path.join(a.dir, s)
        try:
            piece = ET.parse(path).getroot().find("UnstructuredGrid").find("Piece")
        except (OSError, ET.ParseError, AttributeError) as e:
            fail(f"{path}: not a readable VTU piece ({e})")
        np_, nc = int(piece.get("NumberOfPoints")), int(piece.get("NumberOfCells"))
        points, cells = points + np_, cells + nc
        xyz = [float(v) for v in values(piece, path, "Points")[1]]
        conn = [int(v) for v in values(piece, path, "connectivity")[1]]
        offsets = [int(v) for v in values(piece, path, "offsets")[1]]
        types = [int(v) for v in values(piece, path, "types")[1]]
        if len(xyz) != 3 * np_ or len(offsets) != nc or len(types) != nc:
            fail(f"{path}: {len(xyz)} coordinates, {len(offsets)} offsets and {len(types)} types "
                 f"for {np_} points and {nc} cells")
        if any(t != a.cell_type for t in types):
            fail(f"{path}: cell types {sorted(set(types))}, expected only {a.cell_type}")
        size = SIZES[a.cell_type]
        if offsets != [size * (c + 1) for c in range(nc)] or len(conn) != size * nc:
            fail(f"{path}: offsets or connectivity do not give {size} points per cell")
        if any(k < 0 or k >= np_ for k in conn):
            fail(f"{path}: a cell names a point outside 0 .. {np_ - 1}")
        for c in range(nc):
            corners = [xyz[3 * k:3 * k + 3] for k in conn[size * c:size * (c + 1)]]
            if not positive(a.cell_type, corners):
                fail(f"{path}: cell {c} is inverted or degenerate (not in VTK's corner order)")
        for name, comps in fields.items():
            arr, v = values(piece, path, name)
            if int(arr.get("NumberOfComponents")) != comps or len(v) != comps * np_:
                fail(f"{path}: {name} has {len(v)} values, expected {comps} per point")
            if not all(math.isfinite(float(x)) for x in v):
                fail(f"{path}: {name} has a value that is not finite")
        _, sd = values(piece, path, "subdomain")
        if len(sd) != nc:
            fail(f"{path}: subdomain has {len(sd)} values for {nc} cells")
    if points != a.points or cells != a.cells:
        fail(f"{index}: {points} points and {cells} cells, expected {a.points} and {a.cells}")
    print(f"{index}: {len(sources)} pieces, {points} points, {cells} cells of type "
          f"{a.cell_type}, fields {', '.join(fields)}: OK")


if __name__ == "__main__":
    main()
