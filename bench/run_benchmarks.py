#!/usr/bin/env python3
"""TFETI benchmarks on (0,2)x(0,1), 2 MPI ranks, side by side with the assembled primal problem
solved by Belos CG + MueLu and by Amesos2 KLU2 (tfeti_baseline) in the same run.

  python3 bench/run_benchmarks.py [--build build] [--ranks 2]
                                  [--sets sweep,reference,solvers,membranes,cylinders_convergence,cylinders]
                                  [--max-dofs 4.3e6] [--out bench-out] [--reserve-gib 3]

sweep:      2D elasticity, 64k, 256k, 1M and 4M unknowns, subdomains of 16x16 and 32x32 elements
reference:  Poisson 1000x500 cells and elasticity 600x300 cells, with 2 subdomains (one per
            rank) and with the fastest subdomain count found
solvers:    the local solver choice (cholmod, klu2, tacho) on the Poisson reference case
membranes:  the two-membrane contact benchmark, H/h = 8, 16, 32 up to about 4M unknowns,
            SMALBE versus the penalty method
cylinders_convergence: the two-cylinder problem against Hertz on 4 refinements, linear and
            quadratic elements
cylinders:  the two-cylinder problem refined to about 100k, 1M and 4M unknowns
cylinders_tied: the two-cylinder problem at about 100k, 500k, 1M and 4M unknowns (between
            --contact-min-dofs and --contact-max-dofs) solved with the frictionless pair (SMALBE) and with the same
            pair tied (Contact type = tied, PCPG): Hessian multiplications, solve times, ratios
hertz_sphere: the elastic Hertz sphere (examples/hertz_sphere_elastic.xml, Hex8) refined to about
            0.1M and 1M unknowns (up to --max-dofs): Hessian multiplications, setup and solve
            times, memory, errors against Hertz
hertz_sphere_parts: the elastic Hertz sphere at about 0.1M and 1M unknowns (up to --max-dofs) cut
            into 2 .. 128 METIS subdomains per body: Hessian multiplications, setup and solve
            times, memory against the subdomain count
hertz_sphere_plastic: the elasto-plastic Hertz sphere (examples/hertz_sphere_plastic_hex.xml:
            Hex8, J2, small strain, one load step) at about 0.1M, 0.5M and 1M unknowns (up to
            --max-dofs): Newton iterations, Hessian multiplications, times, memory, p_max and
            contact radius against elastic Hertz, plastic strain
cattaneo:   the Cattaneo-Mindlin problem (examples/cattaneo_cylinders.xml: Coulomb mu = 0.3,
            normal then tangential loading) at about 0.1M and 1M unknowns (up to
            --contact-max-dofs), and the same mesh and loads frictionless: Hessian
            multiplications and Newton iterations per step, Coulomb fixed-point iterations,
            times, memory, c/a against Cattaneo-Mindlin
cattaneo_sphere: the 3D Cattaneo-Mindlin sphere (examples/cattaneo_sphere.xml: Coulomb mu =
            0.3, dual mortar rows, normal then tangential loading) at about 28k, 0.1M and
            1M unknowns (between --contact-min-dofs and --contact-max-dofs; --contact-max-dofs
            2e5 leaves out the 1M size, whose Coulomb run had not finished its normal step after
            68 minutes on 2026-11-29), and the same mesh and loads frictionless
size2d:     the largest 2D linear solves: plane-strain elasticity, H/h = 16, from 1.2M to about
            23M unknowns (up to --max-dofs): times, iterations, peak memory per rank, bytes per
            unknown and the memory after every phase; a run whose estimated memory (the bytes
            per unknown of the run before it) would leave less than --reserve-gib of the
            machine's available memory is not started
sweep3d:    3D elasticity on the unit cube (clamped on x = 0, trilinear hexahedra), about 0.1M,
            0.5M, 1M and 2M unknowns, subdomains of 4^3, 6^3 and 8^3 elements, against Belos
            CG + MueLu (six rigid modes as nullspace) and, up to --direct3d-max-dofs, KLU2

Prints markdown tables (for docs/benchmarks.md) and writes every summary.json under --out; a
line per run (its case and the time so far) goes to stderr, so a long set shows its progress.
"""
import argparse
import json
import os
import subprocess
import sys
import time

TEMPLATE = """<ParameterList name="tfeti_contact">
  <Parameter name="Problem" type="string" value="{problem}"/>
  <ParameterList name="Mesh">
    <Parameter name="Domain" type="Array(double)" value="{{0, 2, 0, 1}}"/>
    <Parameter name="Subdomains" type="Array(int)" value="{{{sx}, {sy}}}"/>
    <Parameter name="Elements per subdomain" type="Array(int)" value="{{{ex}, {ey}}}"/>
  </ParameterList>
  <ParameterList name="FETI">
    <Parameter name="Preconditioner" type="string" value="{prec}"/>
    <Parameter name="Local solver" type="string" value="{solver}"/>
    <ParameterList name="PCPG">
      <Parameter name="Relative tolerance" type="double" value="1e-6"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Output">
    <Parameter name="VTU" type="bool" value="false"/>
    <Parameter name="Time dual operator" type="bool" value="true"/>
    <Parameter name="Verbosity" type="int" value="0"/>
  </ParameterList>
</ParameterList>
"""


START = time.monotonic()


def progress(msg):
    """A line per run on stderr (the tables go to stdout): what runs and the time so far."""
    print(f"[{time.monotonic() - START:8.1f} s] {msg}", file=sys.stderr, flush=True)


TEMPLATE3D = """<ParameterList name="tfeti_contact">
  <Parameter name="Problem" type="string" value="{problem}"/>
  <ParameterList name="Mesh">
    <Parameter name="Domain" type="Array(double)" value="{{0, 1, 0, 1, 0, 1}}"/>
    <Parameter name="Subdomains" type="Array(int)" value="{{{s}, {s}, {s}}}"/>
    <Parameter name="Elements per subdomain" type="Array(int)" value="{{{e}, {e}, {e}}}"/>
  </ParameterList>
  <ParameterList name="Load">
    <Parameter name="Body force" type="Array(double)" value="{{0, -1, 0}}"/>
  </ParameterList>
  <ParameterList name="FETI">
    <Parameter name="Preconditioner" type="string" value="{prec}"/>
    <ParameterList name="PCPG">
      <Parameter name="Relative tolerance" type="double" value="1e-6"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Output">
    <Parameter name="VTU" type="bool" value="false"/>
    <Parameter name="Time dual operator" type="bool" value="true"/>
    <Parameter name="Verbosity" type="int" value="0"/>
  </ParameterList>
</ParameterList>
"""


def mpirun(args, ranks):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = ["mpirun", "--oversubscribe", "--bind-to", "core", "-np", str(ranks)] + args
    # The case: the output directory's name (it names the size), or the baseline's options.
    what = " ".join(os.path.basename(a) if a.startswith("--output=") else a for a in args[1:]
                    if not a.startswith("--input="))
    progress(f"{os.path.basename(args[0])} {what} on {ranks} ranks")
    t = time.monotonic()
    res = subprocess.run(cmd, env=env, capture_output=True, text=True)
    if res.returncode != 0:
        print("FAILED:", " ".join(cmd), res.stdout, res.stderr, file=sys.stderr)
    progress(f"  {'done' if res.returncode == 0 else 'FAILED'} in {time.monotonic() - t:.1f} s")
    return res


def feti(o, problem, nx, ny, sx, sy, prec="dirichlet", solver="cholmod"):
    name = f"{problem}_{nx}x{ny}_{sx}x{sy}_{prec}_{solver}"
    d = os.path.join(o.out, name)
    os.makedirs(d, exist_ok=True)
    xml = os.path.join(d, "input.xml")
    with open(xml, "w") as f:
        f.write(TEMPLATE.format(problem=problem, sx=sx, sy=sy, ex=nx // sx, ey=ny // sy,
                                prec=prec, solver=solver))
    res = mpirun([o.build + "/bin/tfeti_contact", "--input=" + xml, "--output=" + d], o.ranks)
    if res.returncode != 0:
        return None
    with open(d + "/summary.json") as f:
        return json.load(f)


def baseline(o, problem, nx, ny, solver):
    res = mpirun([o.build + "/bin/tfeti_baseline", "--problem=" + problem, f"--nx={nx}",
                  f"--ny={ny}", "--solver=" + solver], o.ranks)
    for line in res.stdout.splitlines():
        if line.startswith("{"):
            return json.loads(line)
    return None


def row(label, s):
    t = s["timings"]
    return (f"| {label} | {s['primal_dim']:,} | {s['subdomains']} | {t['setup_s']:.2f} | "
            f"{t['solve_s']:.2f} | {s['iterations']} | {1e3 * t['per_iteration_s']:.1f} | "
            f"{1e3 * t['dual_apply_s']:.1f} | {s['factor_bytes'] / 2**20:.0f} | "
            f"{s['dual_apply_bandwidth_gb_s']:.1f} | {s['peak_rss_mb']:.0f} |")


HEADER = ("| case | unknowns | subdomains | setup s | solve s | iterations | ms/iteration | "
          "ms/F-apply | factors MiB | F-apply GB/s | peak MiB/rank |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|")


def base_row(label, b):
    if b is None:
        return f"| {label} | failed | | | | | |"
    return (f"| {label} | {b['solver']} | {b['setup_s']:.2f} | {b['solve_s']:.2f} | "
            f"{b.get('iterations', '')} | {b['relative_residual']:.1e} | {b['peak_rss_mb']:.0f} |")


BASE_HEADER = ("| case | baseline | setup s | solve s | iterations | rel. residual | peak MiB/rank |\n"
               "|---|---|---|---|---|---|---|")


def sweep(o):
    print("\n## Elasticity size sweep (H/h = 16 and 32, Dirichlet preconditioner, CHOLMOD)\n")
    print(HEADER)
    base = []
    for nx, ny in [(256, 128), (512, 256), (1024, 512), (2048, 1024)]:
        if 2 * (nx + 1) * (ny + 1) > o.max_dofs:
            continue
        runs = []
        for ratio in (16, 32):
            s = feti(o, "elasticity", nx, ny, nx // ratio, ny // ratio)
            if s:
                runs.append(s)
                print(row(f"elasticity {nx}x{ny}, H/h={ratio}", s), flush=True)
        best = min(runs, key=lambda s: s["timings"]["setup_s"] + s["timings"]["solve_s"],
                   default=None)
        for solver in ["muelu"] + (["klu2"] if nx <= 1024 else []):
            base.append((f"elasticity {nx}x{ny}", baseline(o, "elasticity", nx, ny, solver), best))
    print("\n" + BASE_HEADER)
    for label, b, s in base:
        ratio = ""
        if b and s:
            tf = s["timings"]["setup_s"] + s["timings"]["solve_s"]
            ratio = (f" TFETI ({s['subdomains']} subdomains) {tf:.2f} s / baseline "
                     f"{b['setup_s'] + b['solve_s']:.2f} s = {tf / (b['setup_s'] + b['solve_s']):.2f}x")
        print(base_row(label, b) + ratio)


# (cells x, cells y): H/h = 16, the subdomains 16x16 elements; the last has 20.08M unknowns
# untorn (22.66M with the subdomains' copies of the interface nodes).
SIZE2D = [(1024, 512), (2048, 1024), (2816, 1408), (3456, 1728), (4480, 2240)]


def available_gib():
    with open("/proc/meminfo") as f:
        for line in f:
            if line.startswith("MemAvailable:"):
                return int(line.split()[1]) / 2**20
    return 0.0


def size2d(o):
    print("\n## Size: the largest 2D linear solves (elasticity, H/h = 16, Dirichlet, CHOLMOD, "
          f"{o.ranks} ranks)\n")
    print("| cells | unknowns | untorn unknowns | subdomains | setup s | solve s | iterations | "
          "peak MiB/rank | bytes/unknown | K+ factors MiB | preconditioner factors MiB |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|", flush=True)
    per_unknown = 1000.0  # bytes per unknown over all ranks before the first measurement
    phases = []
    for nx, ny in SIZE2D:
        sx, sy = nx // 16, ny // 16
        unknowns = sx * sy * 2 * 17 * 17
        if unknowns > o.max_dofs:
            continue
        need = per_unknown * unknowns * 1.1 / 2**30
        free = available_gib()
        if need + o.reserve_gib > free:
            progress(f"size2d {nx}x{ny}: not started, it needs about {need:.1f} GiB and "
                     f"{free:.1f} GiB are available ({o.reserve_gib} GiB kept for the system)")
            print(f"| {nx}x{ny} | {unknowns:,} | not started: needs ~{need:.1f} GiB, "
                  f"{free:.1f} GiB available | | | | | | | | |", flush=True)
            break
        progress(f"size2d {nx}x{ny}: {unknowns:,} unknowns, about {need:.1f} GiB "
                 f"({free:.1f} GiB available)")
        s = feti(o, "elasticity", nx, ny, sx, sy)
        if not s:
            break
        m = s["memory"]
        per_unknown = m["bytes_per_unknown"]
        t = s["timings"]
        print(f"| {nx}x{ny} | {s['primal_dim']:,} | {2 * (nx + 1) * (ny + 1):,} | "
              f"{s['subdomains']} | {t['setup_s']:.1f} | {t['solve_s']:.1f} | "
              f"{s['iterations']} | {m['peak_mib_per_rank']:.0f} | {per_unknown:.0f} | "
              f"{s['factor_bytes'] / 2**20:.0f} | "
              f"{s['preconditioner_factor_bytes'] / 2**20:.0f} |", flush=True)
        phases.append((f"{nx}x{ny}", m))
    for label, m in phases:
        print(f"\nMemory after each phase, {label} (MiB per rank, the larger rank; "
              "peak: the high-water mark so far)\n")
        print("| phase | resident | peak | peak, all ranks |\n|---|---|---|---|")
        for p in m["phases"]:
            print(f"| {p['phase']} | {p['rss_mib_max']:.0f} | {p['peak_mib_max']:.0f} | "
                  f"{p['peak_mib_sum']:.0f} |")


def reference(o):
    print("\n## Reference cases (2 ranks)\n")
    print(HEADER)
    for problem, nx, ny in [("poisson", 1000, 500), ("elasticity", 600, 300)]:
        runs = []
        for sx, sy in [(2, 1), (10, 5), (20, 10), (40, 20), (50, 25)]:
            s = feti(o, problem, nx, ny, sx, sy)
            if s:
                runs.append(s)
                print(row(f"{problem} {nx}x{ny}, {sx}x{sy} subdomains", s), flush=True)
        if runs:
            best = min(runs, key=lambda s: s["timings"]["setup_s"] + s["timings"]["solve_s"])
            print(f"| fastest: {best['subdomains']} subdomains | | | | | | | | | | |")
        print("\n" + BASE_HEADER)
        for solver in ("muelu", "klu2"):
            b = baseline(o, problem, nx, ny, solver)
            line = base_row(f"{problem} {nx}x{ny}", b)
            if b and runs:
                tb = b["setup_s"] + b["solve_s"]
                for s in (runs[0], best):
                    tf = s["timings"]["setup_s"] + s["timings"]["solve_s"]
                    line += f" TFETI {s['subdomains']} subdomains / {b['solver']}: {tf / tb:.2f}x;"
            print(line, flush=True)
        print("\n" + HEADER)


MEMBRANES = """<ParameterList name="tfeti_contact">
  <Parameter name="Problem" type="string" value="two_membranes"/>
  <ParameterList name="Mesh">
    <Parameter name="Subdomains" type="Array(int)" value="{{{n}, {n}}}"/>
    <Parameter name="Elements per subdomain" type="Array(int)" value="{{{m}, {m}}}"/>
  </ParameterList>
  <ParameterList name="FETI">
    <Parameter name="Dual solver" type="string" value="{method}"/>
  </ParameterList>
  <ParameterList name="Output">
    <Parameter name="VTU" type="bool" value="false"/>
    <Parameter name="Verbosity" type="int" value="0"/>
  </ParameterList>
</ParameterList>
"""


def membranes(o):
    print("\n## Two membranes (SMALBE-M and the penalty method, MPRGP, Dirichlet preconditioner "
          "in face, CHOLMOD)\n")
    print("| H/h | 1/H | unknowns | subdomains | solver | outer | Hessian mults | setup s | "
          "solve s | ms/mult | peak MiB/rank | force error |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|")
    # H/h = 8 stops near 1M unknowns: beyond, tens of thousands of 8x8 subdomains make every
    # multiplication overhead-bound (docs/benchmarks.md).
    cases = [(8, n) for n in (4, 8, 16, 32, 64)] + \
            [(16, n) for n in (4, 8, 16, 32, 64, 88)] + \
            [(32, n) for n in (2, 4, 8, 16, 32, 44)]
    for m, n in cases:
        if 2 * (n * m + 1) ** 2 > o.max_dofs:
            continue
        for method in ("SMALBE", "penalty"):
            d = os.path.join(o.out, f"membranes_{n}x{n}_{m}_{method}")
            os.makedirs(d, exist_ok=True)
            xml = os.path.join(d, "input.xml")
            with open(xml, "w") as f:
                f.write(MEMBRANES.format(n=n, m=m, method=method))
            res = mpirun([o.build + "/bin/tfeti_contact", "--input=" + xml, "--output=" + d],
                         o.ranks)
            try:
                with open(d + "/summary.json") as f:
                    s = json.load(f)
            except OSError:
                print(f"| {m} | {n} | | | {method} | failed |")
                continue
            q, t, c = s["qp"], s["timings"], s["contact"]
            conv = "" if s["converged"] else " (not converged)"
            print(f"| {m} | {n} | {s['primal_dim']:,} | {s['subdomains']} | {method}{conv} | "
                  f"{q['outer_iterations']} | {q['hessian_multiplications']} | "
                  f"{t['setup_s']:.2f} | {t['solve_s']:.2f} | "
                  f"{1e3 * t['per_multiplication_s']:.2f} | {s['peak_rss_mb']:.0f} | "
                  f"{abs(c['force'] - c['expected_force']) / c['expected_force']:.1e} |",
                  flush=True)


def cylinders_run(o, name, sf, order, subdomains, tied=False):
    root = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(root, "..", "examples", "two_cylinders_elastic.xml")) as f:
        xml = f.read()
    xml = xml.replace('value="two_cylinders.geo"',
                      'value="%s"' % os.path.join(root, "..", "examples", "two_cylinders.geo"))
    xml = xml.replace('<Parameter name="Mesh size factor" type="double" value="0.5"/>',
                      f'<Parameter name="Mesh size factor" type="double" value="{sf}"/>')
    xml = xml.replace('<Parameter name="Element order" type="int" value="1"/>',
                      f'<Parameter name="Element order" type="int" value="{order}"/>')
    xml = xml.replace('value="{8, 8}"', f'value="{{{subdomains}, {subdomains}}}"')
    xml = xml.replace('<ParameterList name="FETI">', '<ParameterList name="Output">\n'
                      '    <Parameter name="VTU" type="bool" value="false"/>\n'
                      '  </ParameterList>\n  <ParameterList name="FETI">')
    if tied:
        # The same rows held with equality (B_I u = gap) and solved by PCPG to the relative
        # tolerance of the contact solve (SMALBE's 1e-7 of the projected right-hand side).
        xml = xml.replace('<Parameter name="Search radius"',
                          '<Parameter name="Contact type" type="string" value="tied"/>\n'
                          '    <Parameter name="Search radius"')
        xml = xml.replace('<Parameter name="Dual solver" type="string" value="SMALBE"/>',
                          '<Parameter name="Dual solver" type="string" value="PCPG"/>\n'
                          '    <ParameterList name="PCPG">\n'
                          '      <Parameter name="Relative tolerance" type="double" value="1e-7"/>\n'
                          '    </ParameterList>')
        xml = xml.replace('<Parameter name="Compare" type="bool" value="true"/>',
                          '<Parameter name="Compare" type="bool" value="false"/>')
    for key, value in o.feti_set:
        xml = set_parameter(xml, key, value)
    d = os.path.join(o.out, name)
    os.makedirs(d, exist_ok=True)
    return run_input(o, xml, d)


def set_parameter(xml, key, value):
    """--set LIST/NAME=VALUE: a parameter of the FETI list or one of its sublists (e.g.
    SMALBE/Penalty=30), added at the list's start. The type: bool for true/false, double for a
    number, string otherwise, or given as a prefix (int:20)."""
    path, name = key.rsplit("/", 1) if "/" in key else ("", key)
    if value.split(":", 1)[0] in ("int", "double", "string", "bool") and ":" in value:
        kind, value = value.split(":", 1)
    elif value in ("true", "false"):
        kind = "bool"
    else:
        try:
            float(value)
            kind = "double"
        except ValueError:
            kind = "string"
    entry = f'<Parameter name="{name}" type="{kind}" value="{value}"/>'
    head = '<ParameterList name="FETI">'
    at = xml.index(head) + len(head)
    for sub in filter(None, path.split("/")):
        tag = f'<ParameterList name="{sub}">'
        if xml.find(tag, at) < 0:
            xml = xml[:at] + "\n" + tag + "</ParameterList>" + xml[at:]
        at = xml.index(tag, at) + len(tag)
    return xml[:at] + "\n" + entry + xml[at:]


def cylinders_tied(o):
    """The contact solve against the linear solve of the same pair tied (Contact type = tied:
    the contact rows as equality rows, B_I u = gap), same mesh, decomposition and tolerance."""
    print("\n## Two cylinders: frictionless contact (SMALBE) against the pair tied (PCPG), "
          "2 ranks\n")
    print("| size factor | unknowns | subdomains | contact mults | contact outer | contact solve s "
          "| tied mults | tied solve s | mults ratio | time ratio | p_max error |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|")
    for sf, subs in ((0.22, 16), (0.1, 80), (0.07, 160), (0.035, 650)):
        if not o.contact_min_dofs <= 78e3 * (0.25 / sf) ** 2 <= o.contact_max_dofs:
            continue
        progress(f"two cylinders, size factor {sf} (about {78e3 * (0.25 / sf) ** 2:,.0f} "
                 f"unknowns): contact, then tied")
        c = cylinders_run(o, f"cylinders_contact_sf{sf}", sf, 1, subs)
        t = cylinders_run(o, f"cylinders_tied_sf{sf}", sf, 1, subs, tied=True)
        if c is None or t is None:
            print(f"| {sf} | failed |", flush=True)
            continue
        cm, tm = c["qp"]["hessian_multiplications"], t["qp"]["hessian_multiplications"]
        cs, ts = c["timings"]["solve_s"], t["timings"]["solve_s"]
        conv = "" if c["converged"] else " (not converged)"
        print(f"| {sf} | {c['primal_dim']:,} | {c['subdomains']} | {cm}{conv} | "
              f"{c['qp']['outer_iterations']} | {cs:.2f} | {tm} | {ts:.2f} | {cm / tm:.1f} | "
              f"{cs / ts:.1f} | {100 * c['contact']['relative_error']['p_max']:.2f} % |",
              flush=True)
        progress(f"  size factor {sf}: contact {cm} multiplications ({cs:.1f} s), tied {tm} "
                 f"({ts:.1f} s), ratio {cm / tm:.1f} (time {cs / ts:.1f})")


def cylinders_convergence(o):
    print("\n## Two cylinders against Hertz: mesh convergence (2 ranks, 8 + 8 subdomains)\n")
    print("| elements | size factor | unknowns | p_max MPa | error | half-width mm | error | "
          "max von Mises MPa | outer | Hessian mults | setup s | solve s |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|")
    for order in (1, 2):
        for sf in (4, 2, 1, 0.5, 0.25):
            s = cylinders_run(o, f"cylinders_p{order}_sf{sf}", sf, order, 8)
            if s is None:
                print(f"| P{order} | {sf} | failed |")
                continue
            c, q, t = s["contact"], s["qp"], s["timings"]
            print(f"| {'linear' if order == 1 else 'quadratic'} | {sf} | {s['primal_dim']:,} | "
                  f"{c['p_max'] / 1e6:.1f} | {100 * c['relative_error']['p_max']:.2f} % | "
                  f"{1e3 * c['half_width']:.3f} | {100 * c['relative_error']['half_width']:.2f} % | "
                  f"{s['max_von_mises'] / 1e6:.1f} | {q['outer_iterations']} | "
                  f"{q['hessian_multiplications']} | {t['setup_s']:.2f} | {t['solve_s']:.2f} |",
                  flush=True)
    print("\nHertz: p_max 1182.9 MPa, half-width 21.528 mm, max von Mises about 0.557 p_max = "
          "658.9 MPa")


def cylinders(o):
    print("\n## Two cylinders, refined (2 ranks, linear elements, SMALBE)\n")
    print("| size factor | unknowns | subdomains | setup s | solve s | outer | Hessian mults | "
          "ms/mult | peak MiB/rank | p_max error | half-width error |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|")
    # Unknowns ~ 78k (0.25 / sf)^2 on this graded mesh; about 3000 unknowns per subdomain.
    for sf, subs in ((0.22, 16), (0.07, 160), (0.035, 650)):
        if 78e3 * (0.25 / sf) ** 2 > o.contact_max_dofs:
            print(f"| {sf} | about {78e3 * (0.25 / sf) ** 2:,.0f}: skipped, above "
                  f"--contact-max-dofs |")
            continue
        s = cylinders_run(o, f"cylinders_sf{sf}", sf, 1, subs)
        if s is None:
            print(f"| {sf} | failed |")
            continue
        c, q, t = s["contact"], s["qp"], s["timings"]
        m = q["hessian_multiplications"]
        print(f"| {sf} | {s['primal_dim']:,} | {s['subdomains']} | {t['setup_s']:.2f} | "
              f"{t['solve_s']:.2f} | {q['outer_iterations']} | {m} | "
              f"{1e3 * t['solve_s'] / max(m, 1):.1f} | "
              f"{s['peak_rss_mb']:.0f} | {100 * c['relative_error']['p_max']:.2f} % | "
              f"{100 * c['relative_error']['half_width']:.2f} % |", flush=True)


def feti3d(o, n, e, prec):
    name = f"elasticity3d_{n}_{e}_{prec}"
    d = os.path.join(o.out, name)
    os.makedirs(d, exist_ok=True)
    xml = os.path.join(d, "input.xml")
    with open(xml, "w") as f:
        f.write(TEMPLATE3D.format(problem="elasticity", s=n // e, e=e, prec=prec))
    res = mpirun([o.build + "/bin/tfeti_contact", "--input=" + xml, "--output=" + d], o.ranks)
    if res.returncode != 0:
        return None
    with open(d + "/summary.json") as f:
        return json.load(f)


def sweep3d(o):
    print("\n## 3D elasticity on the unit cube (TFETI, CHOLMOD)\n")
    print(HEADER)
    base = []
    # n elements per side; n is a multiple of each subdomain size tried.
    for n, sizes in [(32, (4, 8)), (56, (4, 7, 8)), (72, (4, 6, 8)), (88, (4, 8))]:
        if 3 * (n + 1) ** 3 > o.max_dofs:
            continue
        runs = []
        for e in sizes:
            for prec in o.preconditioners3d.split(","):
                s = feti3d(o, n, e, prec)
                if s:
                    runs.append(s)
                    print(row(f"elasticity {n}^3, H/h={e}, {prec}", s), flush=True)
        best = min(runs, key=lambda s: s["timings"]["setup_s"] + s["timings"]["solve_s"],
                   default=None)
        solvers = ["muelu"] + (["klu2"] if 3 * (n + 1) ** 3 <= o.direct3d_max_dofs else [])
        for solver in solvers:
            b = baseline3d(o, n, solver)
            base.append((f"elasticity {n}^3", b, best))
            print(base_row(f"elasticity {n}^3", b), flush=True)
    print("\n" + BASE_HEADER)
    for label, b, s in base:
        ratio = ""
        if b and s:
            tf = s["timings"]["setup_s"] + s["timings"]["solve_s"]
            tb = b["setup_s"] + b["solve_s"]
            ratio = (f" TFETI ({s['subdomains']} subdomains, {s['preconditioner']}) {tf:.2f} s / "
                     f"baseline {tb:.2f} s = {tf / tb:.2f}x")
        print(base_row(label, b) + ratio)


def baseline3d(o, n, solver):
    res = mpirun([o.build + "/bin/tfeti_baseline", "--problem=elasticity", f"--nx={n}",
                  f"--ny={n}", f"--nz={n}", "--lx=1", "--ly=1", "--lz=1", "--bx=0", "--by=-1",
                  "--bz=0", "--solver=" + solver], o.ranks)
    for line in res.stdout.splitlines():
        if line.startswith("{"):
            return json.loads(line)
    return None


# The Hertz sphere's refinements: the .geo's zone divisions n (across) and m (deep), the k layers
# around it, and subdomains per body. Zone elements stay cubes (t = m s / n) over the same zone
# s = 1.5 a; the torn unknowns are about 4.2 per unit of n^2 (m + k) + 2 k n m per body (measured:
# 101,046 at 18, 8, 15; 544,806 at 32, 14, 27; 1,040,184 at 40, 17, 33).
HERTZ_SIZES = [(18, 8, 15, 16), (40, 17, 33, 128)]
# The subdomain-count sweep: the 0.1M and 1M meshes of HERTZ_SIZES, each at several subdomain
# counts per body.
HERTZ_PARTS = ([(18, 8, 15, p) for p in (2, 4, 8, 16)] +
               [(40, 17, 33, p) for p in (8, 16, 32, 128)])
HERTZ_PLASTIC_SIZES = [(18, 8, 15, 16), (32, 14, 27, 64), (40, 17, 33, 128)]


def run_input(o, xml, d):
    """tfeti_contact on the input text xml, written to D/input.xml, with its output in D; the
    summary, or None if the run wrote none."""
    path = os.path.join(d, "input.xml")
    with open(path, "w") as f:
        f.write(xml)
    mpirun([o.build + "/bin/tfeti_contact", "--input=" + path, "--output=" + d], o.ranks)
    try:
        with open(d + "/summary.json") as f:
            return json.load(f)
    except OSError:
        return None


def hertz_unknowns(n, m, k):
    return 4.2 * 2 * (n * n * (m + k) + 2 * k * n * m)


def hertz_run(o, example, n, m, k, parts):
    """examples/EXAMPLE.xml on the Hertz sphere's mesh refined to n, m, k with parts subdomains
    per body, without VTU output; the summary, or None if the run failed."""
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples")
    name = f"{example}_{n}_{m}_{k}_{parts}"
    d = os.path.join(o.out, name)
    os.makedirs(d, exist_ok=True)
    s_zone = 0.0225
    with open(os.path.join(d, "mesh.geo"), "w") as f:
        f.write(f"n = {n};\nm = {m};\nk = {k};\ns = {s_zone};\nt = {m * s_zone / n};\n"
                f'Include "{os.path.join(root, "hertz_sphere_elastic.geo")}";\n')
    with open(os.path.join(root, example + ".xml")) as f:
        xml = f.read()
    xml = xml.replace('value="hertz_sphere_elastic.geo"',
                      'value="%s"' % os.path.join(d, "mesh.geo"))
    xml = xml.replace('value="{4, 4}"', f'value="{{{parts}, {parts}}}"')
    xml = xml.replace('<ParameterList name="FETI">', '<ParameterList name="Output">\n'
                      '    <Parameter name="VTU" type="bool" value="false"/>\n'
                      '  </ParameterList>\n  <ParameterList name="FETI">')
    return run_input(o, xml, d)


def hertz_cases(o, sizes, example):
    """(n, m, k, summary or None) for each size up to --max-dofs."""
    for n, m, k, parts in sizes:
        if hertz_unknowns(n, m, k) <= o.max_dofs:
            yield n, m, k, hertz_run(o, example, n, m, k, parts)


def hertz_sphere(o):
    print("\n## Hertz sphere (Hex8, SMALBE, relative tolerance 1e-7)\n")
    print("| mesh n, m, k | unknowns | subdomains | contact rows | outer it. / Hessian mult. | "
          "setup s | solve s | ms/Hessian mult. | peak MiB/rank | p_max error | radius error | "
          "max von Mises error |\n|---|---|---|---|---|---|---|---|---|---|---|---|")
    for n, m, k, r in hertz_cases(o, HERTZ_SIZES, "hertz_sphere_elastic"):
        if r is None:
            print(f"| {n}, {m}, {k} | failed | | | | | | | | | | |", flush=True)
            continue
        t, q, c = r["timings"], r["qp"], r["contact"]
        vm = r["max_von_mises"] / c["hertz"]["max_von_mises"] - 1
        print(f"| {n}, {m}, {k} | {r['primal_dim']:,} | {r['subdomains']} | {c['rows']} | "
              f"{q['outer_iterations']} / {q['hessian_multiplications']} | {t['setup_s']:.1f} | "
              f"{t['solve_s']:.1f} | {1e3 * t['solve_s'] / max(q['hessian_multiplications'], 1):.0f} | "
              f"{r['peak_rss_mb']:.0f} | {100 * c['relative_error']['p_max']:.2f} % | "
              f"{100 * c['relative_error']['contact_radius']:.2f} % | {100 * vm:.1f} % |",
              flush=True)


def hertz_sphere_parts(o):
    print("\n## Hertz sphere against the subdomain count (Hex8, SMALBE, relative tolerance 1e-7)\n")
    print("| mesh n, m, k | subdomains (both bodies) | torn unknowns | dual | Hessian mult. | "
          "setup s | solve s | ms/Hessian mult. | peak MiB/rank | factor GB | p_max error |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|")
    for n, m, k, r in hertz_cases(o, HERTZ_PARTS, "hertz_sphere_elastic"):
        if r is None:
            print(f"| {n}, {m}, {k} | | failed | | | | | | | | |", flush=True)
            continue
        t, q, c = r["timings"], r["qp"], r["contact"]
        mult = q["hessian_multiplications"]
        print(f"| {n}, {m}, {k} | {r['subdomains']} | {r['primal_dim']:,} | {r['dual_dim']:,} | "
              f"{mult} | {t['setup_s']:.1f} | {t['solve_s']:.1f} | "
              f"{1e3 * t['solve_s'] / max(mult, 1):.0f} | {r['peak_rss_mb']:.0f} | "
              f"{r['factor_bytes'] / 1e9:.2f} | {100 * c['relative_error']['p_max']:.2f} % |",
              flush=True)


def hertz_sphere_plastic(o):
    print("\n## Elasto-plastic Hertz sphere (examples/hertz_sphere_plastic_hex.xml: Hex8, J2, small "
          "strain, one load step, SMALBE)\n")
    print("| mesh n, m, k | unknowns | subdomains | Newton it. | Hessian mult. | mult. per Newton it. "
          "| setup s | solve s | wall s | peak MiB/rank | p_max / Hertz | radius / Hertz | max von "
          "Mises MPa | max plastic strain | force / applied |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for n, m, k, r in hertz_cases(o, HERTZ_PLASTIC_SIZES, "hertz_sphere_plastic_hex"):
        if r is None or not r.get("converged"):
            print(f"| {n}, {m}, {k} | {'not converged' if r else 'failed'} | | | | | | | | | | | "
                  "| | |", flush=True)
            continue
        t, nl, c = r["timings"], r["nonlinear"], r["contact"]
        it, mult = nl["total_iterations"], nl["total_hessian_multiplications"]
        print(f"| {n}, {m}, {k} | {r['primal_dim']:,} | {r['subdomains']} | {it} | {mult} | "
              f"{mult / max(it, 1):.0f} | {t['setup_s']:.1f} | {t['solve_s']:.1f} | "
              f"{r['wall_time']:.1f} | {r['peak_rss_mb']:.0f} | "
              f"{c['p_max'] / c['hertz']['p_max']:.3f} | "
              f"{c['contact_radius'] / c['hertz']['contact_radius']:.3f} | "
              f"{r['max_von_mises'] / 1e6:.1f} | {r['max_plastic_strain']:.2e} | "
              f"{c['force'] / c['applied_force']:.6f} |", flush=True)


# Unknowns of examples/cattaneo_cylinders.geo against its mesh size factor (19,161 nodes at 0.5,
# 116,943 at 0.2: ~ 2 x 4.8e3 / sf^2), and subdomains per body for about 3000 unknowns each.
CATTANEO_SIZES = ((0.31, 16), (0.1, 160))


# examples/cattaneo_sphere.xml (3D, Tet4, a size field at the contact): 28,488 unknowns at size
# factor 1 with 4 + 4 subdomains; about 0.1M at 0.6 (unknowns ~ sf^-2.85), about 1M at 0.28
# (944,547) on 8 + 8 subdomains: the frictionless run takes 16 minutes and 6.7 GB a rank there
# (2026-11-29; fewer subdomains cut the multiplications, docs/benchmarks.md).
CATTANEO_SPHERE_SIZES = ((1.0, 4, 2.85e4), (0.6, 14, 1.0e5), (0.28, 8, 1.0e6))


def cattaneo_run(o, name, sf, subdomains, friction=True, example="cattaneo_cylinders",
                 defaults=("0.5", "{8, 8}")):
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples")
    with open(os.path.join(root, example + ".xml")) as f:
        xml = f.read()
    xml = xml.replace(f'value="{example}.geo"',
                      'value="%s"' % os.path.join(root, example + ".geo"))
    xml = xml.replace(f'<Parameter name="Mesh size factor" type="double" value="{defaults[0]}"/>',
                      f'<Parameter name="Mesh size factor" type="double" value="{sf}"/>')
    xml = xml.replace(f'value="{defaults[1]}"', f'value="{{{subdomains}, {subdomains}}}"')
    xml = xml.replace('<ParameterList name="FETI">', '<ParameterList name="Output">\n'
                      '    <Parameter name="VTU" type="bool" value="false"/>\n'
                      '  </ParameterList>\n  <ParameterList name="FETI">')
    if not friction:
        # The same mesh, steps and loads without the Friction list: the top edge's prescribed
        # u_x then slides the cylinder on the block with no tangential force.
        a = xml.index('<ParameterList name="Friction">')
        b = xml.index("</ParameterList>", a) + len("</ParameterList>")
        xml = xml[:a] + xml[b:]
    for key, value in o.feti_set:
        xml = set_parameter(xml, key, value)
    d = os.path.join(o.out, name)
    os.makedirs(d, exist_ok=True)
    return run_input(o, xml, d)


def cattaneo_table(o, title, cases, example, defaults):
    """Coulomb friction against the frictionless problem on the same mesh and load steps: one
    table row per case (size factor, subdomains per body, estimated unknowns) and friction."""
    print(f"\n## {title} (Coulomb mu = 0.3) against frictionless, same mesh and steps, SMALBE, "
          f"{o.ranks} ranks\n")
    print("| size factor | unknowns | subdomains | friction | Hessian mults step 1 / 2 | Newton "
          "it. step 1 / 2 | fixed-point it. step 1 / 2 | setup s | solve s | peak MiB/rank | "
          "Q/(mu P) | c/a | c/a closed form |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for sf, subs, dofs in cases:
        if dofs > o.contact_max_dofs or dofs < o.contact_min_dofs:
            continue
        for friction in (True, False):
            label = "Coulomb" if friction else "none"
            progress(f"{title}, size factor {sf} (about {dofs:,.0f} unknowns), friction {label}")
            s = cattaneo_run(o, f"{example}_sf{sf}_{label}", sf, subs, friction, example, defaults)
            if s is None:
                print(f"| {sf} | failed | | {label} |", flush=True)
                continue
            steps, t, c = s["steps"], s["timings"], s["contact"]
            mults = " / ".join(str(x["hessian_multiplications"]) for x in steps)
            newton = " / ".join(str(x["outer_iterations"]) for x in steps)
            fp = " / ".join(str(x["iterations"]) for x in s["nonlinear"].get("fixed_point", []))
            cm = c.get("cattaneo_mindlin", {})
            conv = "" if s["converged"] else " (not converged)"
            print(f"| {sf} | {s['primal_dim']:,} | {s['subdomains']} | {label}{conv} | {mults} | "
                  f"{newton} | {fp or '-'} | {t['setup_s']:.1f} | {t['solve_s']:.1f} | "
                  f"{s['peak_rss_mb']:.0f} | {cm.get('q_over_mu_p', float('nan')):.4f} | "
                  f"{cm.get('stick_ratio', float('nan')):.4f} | "
                  f"{cm.get('stick_ratio_closed_form', float('nan')):.4f} |", flush=True)
            progress(f"  {s['nonlinear']['total_hessian_multiplications']} Hessian "
                     f"multiplications, solve {t['solve_s']:.1f} s")


def cattaneo(o):
    cattaneo_table(o, "Cattaneo-Mindlin cylinders",
                   [(sf, subs, 2 * 4.8e3 / sf ** 2) for sf, subs in CATTANEO_SIZES],
                   "cattaneo_cylinders", ("0.5", "{8, 8}"))


def cattaneo_sphere(o):
    cattaneo_table(o, "Cattaneo-Mindlin sphere", CATTANEO_SPHERE_SIZES, "cattaneo_sphere",
                   ("1.0", "{4, 4}"))


def solvers(o):
    print("\n## Local solver choice (Poisson 1000x500, 20x10 subdomains of 50x50 elements)\n")
    print(HEADER)
    for solver in ("cholmod", "klu2", "tacho"):
        s = feti(o, "poisson", 1000, 500, 20, 10, solver=solver)
        if s:
            print(row(f"local solver {solver}", s), flush=True)


if __name__ == "__main__":
    p = argparse.ArgumentParser()
    p.add_argument("--build", default="build")
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--sets",
                   default="solvers,reference,sweep,membranes,cylinders_convergence,cylinders")
    p.add_argument("--max-dofs", type=float, default=4.3e6)
    p.add_argument("--out", default="bench-out")
    p.add_argument("--reserve-gib", type=float, default=3.0,
                   help="size2d: memory left to the system; a run that would leave less is "
                   "not started")
    p.add_argument("--preconditioners3d", default="lumped,dirichlet")
    p.add_argument("--direct3d-max-dofs", type=float, default=5e4,
                   help="largest 3D case solved by KLU2 (its fill grows fast in 3D: at 32^3 "
                   "cells, 107,811 unknowns, it did not finish in 9 minutes on a quiet machine)")
    p.add_argument("--contact-min-dofs", type=float, default=0,
                   help="smallest case of the cattaneo, cattaneo_sphere and cylinders_tied "
                   "sets (with --contact-max-dofs: one size)")
    p.add_argument("--contact-max-dofs", type=float, default=1.5e6,
                   help="largest two-cylinder case; the 4M one takes over an hour (docs)")
    p.add_argument("--set", action="append", default=[], metavar="LIST/NAME=VALUE",
                   help="two-cylinder sets: a FETI parameter for every run, e.g. "
                   "SMALBE/Penalty=30 (repeatable)")
    o = p.parse_args()
    o.feti_set = [tuple(a.split("=", 1)) for a in o.set]
    for name in o.sets.split(","):
        {"sweep": sweep, "reference": reference, "solvers": solvers, "membranes": membranes,
         "cylinders_convergence": cylinders_convergence, "cylinders": cylinders,
         "sweep3d": sweep3d, "cylinders_tied": cylinders_tied, "size2d": size2d,
         "hertz_sphere": hertz_sphere, "hertz_sphere_parts": hertz_sphere_parts,
         "hertz_sphere_plastic": hertz_sphere_plastic,
         "cattaneo": cattaneo,
         "cattaneo_sphere": cattaneo_sphere}[name](o)
