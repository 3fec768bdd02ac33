#!/usr/bin/env python3
"""tfeti_contact's help (tests/CMakeLists.txt):

  check_help.py EXE

`EXE --help` (and -h) exits with 0 and its output opens with tfeti_contact's own usage line,
lists --input and --output and names --kokkos-help, without Kokkos' own option list;
`EXE --kokkos-help` prints Kokkos' options and exits with 0.
"""
import subprocess
import sys


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def run(exe, *args):
    p = subprocess.run([exe, *args], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, timeout=120)
    return p.returncode, p.stdout


def main():
    exe = sys.argv[1]
    for flag in ("--help", "-h"):
        code, out = run(exe, flag)
        print(f"--- {flag} (exit code {code}), first lines:")
        print("\n".join(out.splitlines()[:3]))
        if code != 0:
            fail(f"{flag}: exit code {code}")
        lines = [l for l in out.splitlines() if l.strip()]
        if not lines or not lines[0].startswith("Usage: tfeti_contact"):
            fail(f"{flag}: the first line is {lines[0]!r} if any, not tfeti_contact's usage")
        for option in ("--input", "--output", "--kokkos-help"):
            if option not in out:
                fail(f"{flag}: the help does not mention {option}")
        if "--kokkos-num-threads" in out or "--kokkos-threads" in out:
            fail(f"{flag}: Kokkos' option list is printed too (it belongs to --kokkos-help)")
    code, out = run(exe, "--kokkos-help")
    if code != 0 or "--kokkos-num-threads" not in out and "--kokkos-threads" not in out:
        fail(f"--kokkos-help: exit code {code}, output:\n{out}")
    print("--kokkos-help: Kokkos' options, exit code 0")
    print("help: OK")


if __name__ == "__main__":
    main()
