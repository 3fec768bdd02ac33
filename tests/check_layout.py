#!/usr/bin/env python3
"""The source tree's house rules (docs: README.md "Layout"), checked so that they stay true.

- every package's src/ is grouped in area folders, with at most a handful of files at its top;
- every area folder has a README.md naming each of its source files, and every README names
  only files that exist (so a moved or renamed file cannot leave its README stale);
- no source file is longer than 800 lines;
- every .cpp of a package is in its CMake source list, and every listed .cpp exists;
- the README's layout tree names every area folder under its package.

Usage: check_layout.py REPO_ROOT. Prints one line per violation and exits 1 if any.
"""
import os
import re
import sys

MAX_LINES = 800
MAX_TOP_FILES = 5
PACKAGES = ("tfeti", "contact", "plasticity")
SOURCE = re.compile(r"^(tfeti|contact|plasticity)_\w+\.(hpp|cpp)$")


def check_package(root, pkg, layout_text, errors):
    """layout_text: the area folders the README's layout tree names, per package."""
    src = os.path.join(root, "packages", pkg, "src")
    top = sorted(f for f in os.listdir(src) if os.path.isfile(os.path.join(src, f)))
    top_sources = [f for f in top if SOURCE.match(f)]
    if len(top_sources) > MAX_TOP_FILES:
        errors.append(f"packages/{pkg}/src: {len(top_sources)} source files at the top "
                      f"(at most {MAX_TOP_FILES}; put them in an area folder)")
    if "README.md" not in top:
        errors.append(f"packages/{pkg}/src: no README.md")
    areas = sorted(d for d in os.listdir(src) if os.path.isdir(os.path.join(src, d)))
    if not areas:
        errors.append(f"packages/{pkg}/src: no area folders")
    cmake = open(os.path.join(root, "packages", pkg, "CMakeLists.txt")).read()
    listed = set(re.findall(r"src/([\w/]+\.cpp)", cmake))
    present = set()
    for area in areas:
        folder = os.path.join(src, area)
        where = f"packages/{pkg}/src/{area}"
        if area not in layout_text.get(pkg, ()):
            errors.append(f"README.md, Layout: the folder {where}/ is not named")
        files = sorted(f for f in os.listdir(folder) if SOURCE.match(f))
        readme_path = os.path.join(folder, "README.md")
        if not os.path.isfile(readme_path):
            errors.append(f"{where}: no README.md")
            readme = ""
        else:
            readme = open(readme_path).read()
        # A README names a file or its pair by its stem (`tfeti_Tearing.*`); a template's
        # _decl/_def headers by the stem they share.
        stems = {os.path.splitext(f)[0] for f in files}
        for f in files:
            stem = re.sub(r"_(decl|def)$", "", os.path.splitext(f)[0])
            if stem not in readme:
                errors.append(f"{where}/README.md does not name {f}")
        for named in sorted(set(re.findall(r"\b((?:tfeti|contact|plasticity)_[A-Z]\w*)", readme))):
            if named not in stems and not any(s.startswith(named) for s in stems):
                errors.append(f"{where}/README.md names {named}, which is not in the folder")
        for f in files:
            path = os.path.join(folder, f)
            with open(path) as fh:
                n = sum(1 for _ in fh)
            if n > MAX_LINES:
                errors.append(f"{where}/{f}: {n} lines (at most {MAX_LINES})")
            if f.endswith(".cpp"):
                present.add(f"{area}/{f}")
    for cpp in sorted(present - listed):
        errors.append(f"packages/{pkg}/src/{cpp} is not in packages/{pkg}/CMakeLists.txt")
    for cpp in sorted(listed - present):
        errors.append(f"packages/{pkg}/CMakeLists.txt lists src/{cpp}, which does not exist")


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    root = sys.argv[1]
    readme = open(os.path.join(root, "README.md")).read()
    match = re.search(r"^## Layout\n(.*?)^## ", readme, re.S | re.M)
    # The layout's tree: "packages/<pkg>/src/" lines, each followed by its indented "<area>/" lines.
    layout, pkg = {}, None
    for line in (match.group(1) if match else "").splitlines():
        m = re.match(r"^packages/(\w+)/src/", line)
        if m:
            pkg = m.group(1)
            layout[pkg] = set()
            continue
        m = re.match(r"^\s+(\w+)/\s", line)
        if m and pkg:
            layout[pkg].add(m.group(1))
    errors = [] if match else ["README.md: no '## Layout' section"]
    for pkg in PACKAGES:
        check_package(root, pkg, layout, errors)
    for e in errors:
        print(e)
    print(f"layout: {len(errors)} violation(s)")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
