#!/usr/bin/env python3
"""Checks what scripts/run-example.sh produced (tests/CMakeLists.txt):

  check_example.py OUTPUT_DIR REPORT_FILE
  check_example.py --pngs OUTPUT_DIR NAME [NAME ...]   (each OUTPUT_DIR/NAME a readable PNG)

- REPORT_FILE (the script's standard output) names the output directory and the pictures, and
  gives p_max and the half-width (the contact radius of a 3D run) against Hertz with the values
  of summary.json;
- every picture it names is a readable PNG (signature, IHDR of a non-empty image, every chunk's
  CRC, and IDAT data that zlib inflates to the size the header implies);
- a nonlinear run (the main example): the report names contact_pressure.png, von_mises.png,
  convergence.png and steps.pvd, a VTK collection listing every step_NNNN.pvtu of the directory
  in step order, with the load factors of summary.json's steps as (increasing) times, each file
  present; an elastic 3D run (the Hertz sphere): contact_pressure.png.
"""
import glob
import json
import os
import re
import struct
import sys
import xml.etree.ElementTree as ET
import zlib


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def check_png(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail(f"{path}: not a PNG")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        (crc,) = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])
        if zlib.crc32(kind + body) & 0xFFFFFFFF != crc:
            fail(f"{path}: bad CRC in chunk {kind}")
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
        if kind == b"IEND":
            break
    if header is None or header[0] == 0 or header[1] == 0 or kind != b"IEND":
        fail(f"{path}: no image header or no end")
    width, height, depth, colour = header[:4]
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[colour]
    expected = height * (1 + (width * channels * depth + 7) // 8)  # a filter byte per row
    if len(zlib.decompress(idat)) != expected:
        fail(f"{path}: image data of the wrong size")
    return width, height


def main(d, report_path):
    with open(os.path.join(d, "summary.json")) as f:
        s = json.load(f)
    with open(report_path) as f:
        report = f.read()
    if not s.get("converged"):
        fail("the example did not converge")
    if d not in report:
        fail("the report does not say where the results are")
    # p_max and the half-width (contact radius) as printed, against summary.json.
    c = s["contact"]
    extent = ("contact radius", "contact_radius") if "contact_radius" in c else \
        ("half-width", "half_width")
    for label, key, scale in [("p_max", "p_max", 1e6), extent + (1e-3,)]:
        m = re.search(label + r"\s+([\d.]+) \S+\s+Hertz\s+([\d.]+) \S+\s+error ([\d.]+) %", report)
        if not m:
            fail(f"the report gives no {label} against Hertz")
        value, hertz, err = (float(v) for v in m.groups())
        if abs(value * scale - c[key]) > 1e-3 * c[key] or \
                abs(hertz * scale - c["hertz"][key]) > 1e-3 * c["hertz"][key] or \
                abs(err - 100 * c["relative_error"][key]) > 0.006:
            fail(f"the report's {label} line disagrees with summary.json: {m.group(0)}")
    pictures = re.findall(r"(\S+\.png)", report)
    nonlinear = s.get("problem") == "nonlinear_contact"
    expected = ["contact_pressure.png", "von_mises.png", "convergence.png"] if nonlinear else \
        ["contact_pressure.png"]
    for name in expected:
        if os.path.join(d, name) not in pictures:
            fail(f"the report names no {name}")
    for p in pictures:
        w, h = check_png(p)
        print(f"{p}: PNG {w} x {h}")
    if not nonlinear:
        print(f"OK: {len(pictures)} pictures, report consistent")
        return
    if "steps.pvd" not in report:
        fail("the report does not name steps.pvd")
    root = ET.parse(os.path.join(d, "steps.pvd")).getroot()
    if root.get("type") != "Collection":
        fail("steps.pvd is not a VTK collection")
    sets = root.findall("./Collection/DataSet")
    files = [e.get("file") for e in sets]
    times = [float(e.get("timestep")) for e in sets]
    on_disk = sorted(os.path.basename(p) for p in glob.glob(os.path.join(d, "step_*.pvtu")))
    if files != on_disk:
        fail(f"steps.pvd lists {files}, the directory has {on_disk}")
    steps = s["steps"]
    if [f"step_{st['step']:04d}.pvtu" for st in steps] != files:
        fail("steps.pvd does not list the converged steps in order")
    if any(abs(t - st["load_factor"]) > 1e-12 for t, st in zip(times, steps)) or \
            any(b <= a for a, b in zip(times, times[1:])) or abs(times[-1] - 1.0) > 1e-12:
        fail(f"the collection's times {times} are not the steps' load factors")
    for name in files:
        if not os.path.exists(os.path.join(d, name)):
            fail(f"{name} is missing")
    print(f"OK: {len(files)} steps in steps.pvd, {len(pictures)} pictures, report consistent")


if __name__ == "__main__":
    if sys.argv[1] == "--pngs":
        for name in sys.argv[3:]:
            w, h = check_png(os.path.join(sys.argv[2], name))
            print(f"{name}: PNG {w} x {h}")
    else:
        main(*sys.argv[1:3])
