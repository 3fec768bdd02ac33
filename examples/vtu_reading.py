"""Reading the ASCII VTU pieces that tfeti_contact writes (solution_<rank>.vtu): data arrays
and a matplotlib triangulation of all pieces. Shared by the plot scripts of this directory."""
import glob
import os
import re

import matplotlib.tri as mtri

# Triangles of the VTK cells: corners of linear/quadratic triangles and quadrilaterals.
TRIANGLES = {5: [(0, 1, 2)], 22: [(0, 1, 2)], 9: [(0, 1, 2), (0, 2, 3)],
             28: [(0, 1, 2), (0, 2, 3)]}


def data_array(xml, name, required=True):
    m = re.search(r'<DataArray[^>]*Name="%s"[^>]*>(.*?)</DataArray>' % re.escape(name), xml, re.S)
    if not m:
        if not required:
            return None
        raise SystemExit(f"no DataArray {name} in the VTU piece")
    return [float(v) for v in m.group(1).split()]


def read_vtu(d, names):
    """Triangulation of all pieces (undeformed) and the nodal fields `names` (None: missing)."""
    xs, ys, tris, fields = [], [], [], {n: [] for n in names}
    for path in sorted(glob.glob(os.path.join(d, "solution_*.vtu"))):
        with open(path) as f:
            xml = f.read()
        base = len(xs)
        pts = data_array(xml, "Points")
        xs += pts[0::3]
        ys += pts[1::3]
        for n in names:
            values = data_array(xml, n, required=False)
            fields[n] = None if values is None or fields[n] is None else fields[n] + values
        conn = [int(v) for v in data_array(xml, "connectivity")]
        ends = [int(v) for v in data_array(xml, "offsets")]
        for t, start, end in zip(data_array(xml, "types"), [0] + ends, ends):
            cell = conn[start:end]
            tris += [[base + cell[i] for i in tri] for tri in TRIANGLES.get(int(t), [])]
    if not xs:
        raise SystemExit(f"no solution_*.vtu in {d}")
    return mtri.Triangulation(xs, ys, tris), fields
