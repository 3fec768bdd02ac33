#!/usr/bin/env python3
"""Every code block of docs/cpp_guide.md is copied from the guide's programs (examples/cpp):
each ```cpp block's lines must appear, in order and contiguous, in one of the .cpp files, and
each ```cmake block's in examples/cpp/CMakeLists.txt. A snippet edited in the guide but not in
the tested program (or the reverse) fails this check.

usage: check_guide_snippets.py SOURCE_DIR
"""
import pathlib
import re
import sys


def blocks(text, lang):
    return re.findall(r"```" + lang + r"\n(.*?)```", text, flags=re.S)


def contains(source, snippet):
    lines = [l.rstrip() for l in snippet.strip("\n").split("\n")]
    src = [l.rstrip() for l in source.split("\n")]
    n = len(lines)
    return any(src[i:i + n] == lines for i in range(len(src) - n + 1))


def main():
    root = pathlib.Path(sys.argv[1])
    guide = (root / "docs" / "cpp_guide.md").read_text()
    programs = [p.read_text() for p in sorted((root / "examples" / "cpp").glob("*.cpp"))]
    cmake = (root / "examples" / "cpp" / "CMakeLists.txt").read_text()
    failures = 0
    checked = 0
    for lang, sources in (("cpp", programs), ("cmake", [cmake])):
        for b in blocks(guide, lang):
            checked += 1
            if not any(contains(s, b) for s in sources):
                failures += 1
                print(f"docs/cpp_guide.md: this {lang} block is not in examples/cpp:\n{b}")
    print(f"{checked} code blocks checked, {failures} not found in the programs")
    return 1 if failures or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
