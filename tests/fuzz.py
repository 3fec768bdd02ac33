#!/usr/bin/env python3
"""Fuzz harness of tfeti_contact's input (issue 16): mutants of every example input and of a mesh.

Every parameter of every examples/*.xml is mutated in turn (non-numbers, trailing garbage, nan,
+-inf, negative, zero, huge, empty, missing, wrong array length, wrong type, misspelt name), and
a small two-body .msh file is mutated (truncated at several offsets, random bytes, an unknown
node, duplicate nodes, degenerate and reversed elements, no 2D cells). Each mutant is run with
--check (the dry run: validation, mesh, partition, contact search, no solve) and passes only if
  - it ends with exit code 1 and an error that names the mutated parameter (or, for a mesh
    mutant, the mesh file), or
  - it ends with exit code 0 and the echoed validated parameters (--echo-parameters) hold what
    was written (a missing parameter: its default).
Anything else is a failure: a crash (signal, sanitizer report, exit code other than 0/1), an
error that names neither, or a silent substitution (accepted, but the value used differs from
the text). Counts are printed; the exit code is 1 if any mutant failed.

By default a deterministic sample (seed 16) of at most FUZZ_BUDGET (default 120) parameter
mutants plus every mesh mutant runs on 2 workers (about 2 minutes); FUZZ_FULL=1 runs all.

usage: fuzz.py TFETI_CONTACT EXAMPLES_DIR WORK_DIR
"""
import concurrent.futures
import copy
import json
import math
import os
import random
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

NUMERIC = {"double", "int", "float"}
# Per mutant; FUZZ_TIMEOUT raises it for slower builds (scripts/check-sanitizers.sh).
TIMEOUT = int(os.environ.get("FUZZ_TIMEOUT", "120"))


def parameters(root, path=()):
    """(path of sublists, element) of every Parameter, in document order."""
    for child in root:
        if child.tag == "Parameter":
            yield path, child
        elif child.tag == "ParameterList":
            yield from parameters(child, path + (child.get("name"),))


def scalar_type(t):
    return t[6:-1] if t.startswith("Array(") else t


def value_mutations(ptype, value):
    """(label, new type, new value) for a parameter of type ptype written as value."""
    st = scalar_type(ptype)
    array = ptype.startswith("Array(")
    out = []
    if st in NUMERIC:
        if array:
            items = [v.strip() for v in value.strip()[1:-1].split(",") if v.strip()]
            first = items[0] if items else "1"
            wrap = lambda x: "{" + ", ".join([x] + items[1:]) + "}"
            out += [("non-number", ptype, wrap("abc")), ("trailing garbage", ptype, wrap(first + "x")),
                    ("nan", ptype, wrap("nan")), ("+inf", ptype, wrap("inf")),
                    ("-inf", ptype, wrap("-inf")), ("negative", ptype, wrap("-" + first.lstrip("-"))),
                    ("zero", ptype, wrap("0")), ("huge", ptype, wrap("2147483647" if st == "int" else "1e300")),
                    ("empty", ptype, ""), ("no comma", ptype, "{" + " ".join(items or ["1", "2"]) + "}"),
                    ("longer", ptype, "{" + ", ".join(items + [first]) + "}"),
                    ("shorter", ptype, "{" + ", ".join(items[:-1]) + "}"),
                    ("wrong type", "string", value)]
        else:
            out += [("non-number", ptype, "abc"), ("trailing garbage", ptype, value + "x"),
                    ("nan", ptype, "nan"), ("+inf", ptype, "inf"), ("-inf", ptype, "-inf"),
                    ("negative", ptype, "-" + value.lstrip("-")), ("zero", ptype, "0"),
                    ("huge", ptype, "2147483647" if st == "int" else "1e300"), ("empty", ptype, ""),
                    ("two dots", ptype, value + ".1" if "." in value else value + ".5.1"),
                    ("wrong type", "string", value),
                    ("array instead", "Array(" + st + ")", "{" + value + "}")]
    elif st == "bool":
        out += [("not a bool", ptype, "maybe"), ("empty", ptype, ""), ("wrong type", "int", "1")]
    else:  # strings
        out += [("garbage", ptype, value + "zz"), ("empty", ptype, ""),
                ("wrong type", "double", "1.5")]
    return out


def parse_written(ptype, value):
    """The value Python reads from the XML text, or None if it is not a valid value."""
    st = scalar_type(ptype)

    def one(text):
        text = text.strip()
        if st == "int":
            return int(text) if re.fullmatch(r"[+-]?\d+", text) else None
        if st in ("double", "float"):
            try:
                v = float(text)
            except ValueError:
                return None
            return v if math.isfinite(v) else None
        if st == "bool":
            return {"true": True, "false": False}.get(text.lower())
        return text

    if ptype.startswith("Array("):
        text = value.strip()
        if not (text.startswith("{") and text.endswith("}")):
            return None
        inner = text[1:-1].strip()
        return [one(v) for v in inner.split(",")] if inner else []
    return one(value)


def same(written, echoed):
    if isinstance(written, list):
        return isinstance(echoed, list) and len(written) == len(echoed) and all(
            same(a, b) for a, b in zip(written, echoed))
    if isinstance(written, bool) or isinstance(written, str):
        return written == echoed
    if written is None or echoed is None:
        return False
    return abs(written - echoed) <= 1e-9 * max(1.0, abs(written))


def echoed_at(echo, path, name):
    node = echo
    for p in path:
        node = node.get(p, {})
    return node.get(name, KeyError)


class Mutant:
    def __init__(self, label, xml_path, names, path=(), name=None, ptype=None, value=None,
                 mesh=None, expect=None):
        self.label, self.xml_path, self.names = label, xml_path, names
        self.expect = expect
        self.path, self.name, self.ptype, self.value, self.mesh = path, name, ptype, value, mesh


def xml_mutants(example, work):
    tree = ET.parse(example)
    stem = os.path.splitext(os.path.basename(example))[0]
    base_dir = os.path.dirname(os.path.abspath(example))
    entries = list(parameters(tree.getroot()))
    mutants = []

    def write(tag, mutate):
        t = copy.deepcopy(tree)
        elems = list(parameters(t.getroot()))
        for _, e in elems:  # mesh files stay next to the example
            if e.get("name") == "Mesh file" and not os.path.isabs(e.get("value")):
                e.set("value", os.path.join(base_dir, e.get("value")))
        mutate(t, elems)
        path = os.path.join(work, "%s-%03d.xml" % (stem, len(mutants)))
        t.write(path)
        return path

    for k, (path, elem) in enumerate(entries):
        name, ptype, value = elem.get("name"), elem.get("type"), elem.get("value")
        where = "/".join(path + (name,))

        def set_value(t, elems, k=k, nt=None, nv=None):
            elems[k][1].set("type", nt)
            elems[k][1].set("value", nv)

        for label, nt, nv in value_mutations(ptype, value):
            f = write(label, lambda t, e, nt=nt, nv=nv: set_value(t, e, nt=nt, nv=nv))
            mutants.append(Mutant("%s: %s: %s = %r (%s)" % (stem, where, label, nv, nt), f, [name],
                                  path, name, nt, nv))

        def remove(t, elems, k=k):
            parent = {c: p for p in t.iter() for c in p}[elems[k][1]]
            parent.remove(elems[k][1])

        f = write("missing", remove)
        mutants.append(Mutant("%s: %s: missing" % (stem, where), f, [name], path, name))
        misspelt = name[:-1] + name[-1] * 2 if len(name) > 1 else name + "x"

        def rename(t, elems, k=k, misspelt=misspelt):
            elems[k][1].set("name", misspelt)

        f = write("misspelt", rename)
        mutants.append(Mutant("%s: %s: misspelt %r" % (stem, where, misspelt), f, [misspelt]))
    return mutants


def two_body_msh():
    """Two unit squares, one above the other, 2x2 quads split into triangles each; physical
    groups: bodies lower/upper, lines fixed (lower bottom), lower_top, upper_bottom, upper_left,
    load (upper top). Returns MSH 2.2 text."""
    nodes, elems = [], []
    tag = 0
    grid = {}
    for body, y0 in ((0, 0.0), (1, 1.0)):
        for j in range(3):
            for i in range(3):
                tag += 1
                grid[body, i, j] = tag
                nodes.append("%d %g %g 0" % (tag, 0.5 * i, y0 + 0.5 * j))
    etag = 0
    lines = {"fixed": (0, 0), "lower_top": (0, 2), "upper_bottom": (1, 0), "load": (1, 2)}
    phys = {"fixed": 1, "lower_top": 2, "upper_bottom": 3, "load": 4, "upper_left": 5}
    for name, (body, j) in lines.items():
        for i in range(2):
            etag += 1
            elems.append("%d 1 2 %d %d %d %d" % (etag, phys[name], phys[name], grid[body, i, j],
                                                 grid[body, i + 1, j]))
    for j in range(2):
        etag += 1
        elems.append("%d 1 2 5 5 %d %d" % (etag, grid[1, 0, j], grid[1, 0, j + 1]))
    for body in (0, 1):
        for j in range(2):
            for i in range(2):
                a, b = grid[body, i, j], grid[body, i + 1, j]
                c, d = grid[body, i + 1, j + 1], grid[body, i, j + 1]
                for tri in ((a, b, c), (a, c, d)):
                    etag += 1
                    elems.append("%d 2 2 %d %d %d %d %d" % ((etag, 10 + body, 10 + body) + tri))
    names = ["1 %d \"%s\"" % (v, k) for k, v in phys.items()] + ["2 10 \"lower\"", "2 11 \"upper\""]
    return ("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n%d\n%s\n$EndPhysicalNames\n"
            "$Nodes\n%d\n%s\n$EndNodes\n$Elements\n%d\n%s\n$EndElements\n"
            % (len(names), "\n".join(names), len(nodes), "\n".join(nodes), len(elems),
               "\n".join(elems)))


MESH_XML = """<ParameterList name="tfeti_contact">
  <Parameter name="Problem" type="string" value="elastic_contact"/>
  <ParameterList name="Material">
    <Parameter name="Young's modulus" type="double" value="1.0e9"/>
    <Parameter name="Poisson's ratio" type="double" value="0.3"/>
  </ParameterList>
  <ParameterList name="Contact problem">
    <Parameter name="Mesh file" type="string" value="%s"/>
    <Parameter name="Bodies" type="Array(string)" value="{lower, upper}"/>
    <Parameter name="Subdomains per body" type="Array(int)" value="{1, 1}"/>
    <Parameter name="Fixed boundaries" type="Array(string)" value="{fixed}"/>
    <Parameter name="Symmetry boundaries" type="Array(string)" value="{upper_left}"/>
    <Parameter name="Symmetry components" type="Array(int)" value="{0}"/>
    <Parameter name="Traction boundaries" type="Array(string)" value="{load}"/>
    <Parameter name="Tractions" type="Array(double)" value="{0, -1.0e6}"/>
    <Parameter name="Slave" type="string" value="upper_bottom"/>
    <Parameter name="Master" type="string" value="lower_top"/>
  </ParameterList>
</ParameterList>
"""


def mesh_mutants(work, rng):
    text = two_body_msh()
    lines = text.split("\n")
    n0 = lines.index("$Nodes") + 2
    e0 = lines.index("$Elements") + 2
    e1 = lines.index("$EndElements")
    # Each variant with what it must give: "error" (a clear error naming the file), "accept",
    # "reoriented" (accepted, and the log says elements were reoriented) or "either" (a damaged
    # file may still be a valid mesh, e.g. a changed digit in a coordinate).
    variants = [("unchanged", text, "accept")]
    for frac in (0.1, 0.3, 0.5, 0.7, 0.9, 0.99):
        variants.append(("truncated at %d%%" % (100 * frac), text[: int(frac * len(text))],
                         "either"))
    data = bytearray(text.encode())
    for k in range(3):
        noisy = bytearray(data)
        for _ in range(12):
            noisy[rng.randrange(len(noisy))] = rng.randrange(256)
        variants.append(("random bytes %d" % k, bytes(noisy), "either"))
    variants.append(("random file", bytes(rng.randrange(256) for _ in range(2000)), "error"))
    tri = [k for k in range(e0, e1) if lines[k].split()[1] == "2"]
    bad = list(lines)
    f = bad[tri[0]].split()
    f[-1] = "999"
    bad[tri[0]] = " ".join(f)
    variants.append(("unknown node", "\n".join(bad), "error"))
    bad = list(lines)
    bad[n0] = bad[n0 + 1].split()[0] + " " + " ".join(bad[n0].split()[1:])
    variants.append(("node tag replaced by another's", "\n".join(bad), "error"))
    bad = list(lines)
    bad[n0 - 1] = str(int(bad[n0 - 1]) + 1)
    bad.insert(n0 + 1, bad[n0].split()[0] + " 0.25 0.1 0")
    variants.append(("node tag defined twice", "\n".join(bad), "error"))
    bad = list(lines)
    bad[e0 - 1] = str(int(bad[e0 - 1]) + 1)
    bad.insert(e0 + 1, bad[tri[1]])
    variants.append(("element tag defined twice", "\n".join(bad), "error"))
    bad = list(lines)
    f = bad[tri[0]].split()
    copy = 1000
    bad[n0 - 1] = str(int(bad[n0 - 1]) + 1)
    node_line = next(l for l in lines[n0:] if l.split()[0] == f[-1])
    bad.insert(n0, "%d %s" % (copy, " ".join(node_line.split()[1:])))
    k = bad.index(lines[tri[0]])
    f[-1] = str(copy)
    bad[k] = " ".join(f)
    variants.append(("coincident nodes (a crack)", "\n".join(bad), "error"))
    bad = list(lines)
    f = bad[tri[0]].split()
    f[-1] = f[-2]
    bad[tri[0]] = " ".join(f)
    variants.append(("degenerate element (repeated node)", "\n".join(bad), "error"))
    bad = list(lines)
    f = bad[tri[0]].split()
    f[-1], f[-2] = f[-2], f[-1]
    bad[tri[0]] = " ".join(f)
    variants.append(("reversed element", "\n".join(bad), "reoriented"))
    bad = [l for k, l in enumerate(lines) if k not in tri]
    bad[bad.index("$Elements") + 1] = str(e1 - e0 - len(tri))
    variants.append(("no 2D cells", "\n".join(bad), "error"))
    mutants = []
    for k, (label, content, expect) in enumerate(variants):
        msh = os.path.join(work, "mesh-%02d.msh" % k)
        with open(msh, "wb") as f:
            f.write(content if isinstance(content, bytes) else content.encode())
        xml = os.path.join(work, "mesh-%02d.xml" % k)
        with open(xml, "w") as f:
            f.write(MESH_XML % msh)
        mutants.append(Mutant("mesh: " + label, xml, [os.path.basename(msh)], mesh=msh,
                              expect=expect))
    return mutants


# Open MPI's own failure to start a singleton (its daemon could not be launched, seen once in
# 2026-12-07's full ctest under load): the program never ran, so the input is not judged by it.
MPI_START_FAILED = re.compile(r"ompi_rte_init failed|Unable to start a daemon on the local node")


def run(exe, m):
    echo = m.xml_path + ".echo.json"
    for attempt in range(3):
        if os.path.exists(echo):
            os.remove(echo)
        try:
            p = subprocess.run([exe, "--input=" + m.xml_path, "--check",
                                "--echo-parameters=" + echo],
                               capture_output=True, text=True, errors="replace", timeout=TIMEOUT)
        except subprocess.TimeoutExpired:
            return "crash", "timeout after %d s" % TIMEOUT
        err = p.stdout + p.stderr
        if p.returncode == 0 or not MPI_START_FAILED.search(err):
            break
        print("fuzz: %s: Open MPI did not start (attempt %d), run again" % (m.label, attempt + 1))
    if re.search(r"ERROR: (Address|Leak)Sanitizer|runtime error:", err):
        return "crash", "sanitizer report: " + err[-2000:]
    if p.returncode not in (0, 1):
        return "crash", "exit code %d: %s" % (p.returncode, err[-2000:])
    if p.returncode == 1:
        if m.mesh is not None and m.expect in ("accept", "reoriented"):
            return "unclear", "a valid mesh was rejected: " + err[-600:]
        if any(n in err for n in m.names) and "error" in err:
            return "clear", ""
        return "unclear", err[-600:]
    if m.mesh is not None:
        if m.expect == "error":
            return "substituted", "a broken mesh was accepted: " + err[-300:]
        if m.expect == "reoriented" and "reoriented" not in err:
            return "substituted", "reversed elements were not reported as reoriented"
        return "accepted", ""
    if m.name is None:  # misspelt names must never pass
        return "substituted", "a misspelt parameter was accepted"
    with open(echo) as f:
        echoed = echoed_at(json.load(f), m.path, m.name)
    if m.value is None:  # missing: the default is used
        return ("accepted", "") if echoed is not KeyError else ("substituted", "not echoed")
    written = parse_written(m.ptype, m.value)
    if m.name == "Mesh file" and isinstance(echoed, str) and echoed.endswith(m.value):
        return "accepted", ""
    if written is None or (isinstance(written, list) and None in written) or not same(written, echoed):
        return "substituted", "wrote %r (%s), echoed %r" % (m.value, m.ptype, echoed)
    return "accepted", ""


def main():
    exe, examples, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    rng = random.Random(16)
    mutants = []
    for name in sorted(os.listdir(examples)):
        if name.endswith(".xml"):
            mutants += xml_mutants(os.path.join(examples, name), work)
    total = len(mutants)
    budget = int(os.environ.get("FUZZ_BUDGET", "120"))
    if not os.environ.get("FUZZ_FULL") and total > budget:
        mutants = sorted(rng.sample(mutants, budget), key=lambda m: m.xml_path)
    mutants += mesh_mutants(work, rng)
    counts = {"clear": 0, "accepted": 0, "crash": 0, "substituted": 0, "unclear": 0}
    failures = []
    with concurrent.futures.ThreadPoolExecutor(int(os.environ.get("FUZZ_JOBS", "2"))) as pool:
        for m, (kind, detail) in zip(mutants, pool.map(lambda m: run(exe, m), mutants)):
            counts[kind] += 1
            if kind not in ("clear", "accepted"):
                failures.append("%s [%s] %s" % (m.label, kind, detail))
    for f in failures:
        print("FAIL:", f)
    meshes = sum(1 for m in mutants if m.mesh)
    print("fuzz: %d parameter mutants (of %d over the examples), %d mesh mutants"
          % (len(mutants) - meshes, total, meshes))
    print("fuzz: tried %d, clear errors %d, accepted %d, crashes %d, silent substitutions %d, "
          "unclear errors %d" % (len(mutants), counts["clear"], counts["accepted"],
                                 counts["crash"], counts["substituted"], counts["unclear"]))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
