"""The plot scripts need matplotlib, which scripts/install-deps.sh installs for the system
Python (Debian's python3-matplotlib). The first python3 on PATH may be another one (pyenv, a
virtual environment, /usr/local) without it: then the script runs itself again with the first
Python that has matplotlib, so that `python3 examples/plot_*.py` works whichever python3 that is.
"""
import os
import shutil
import subprocess
import sys

_GUARD = "TFETI_PLOT_PYTHON_SWITCHED"


def candidates():
    """Every python3 on PATH, then the system ones, each once, this interpreter excluded."""
    seen = {os.path.realpath(sys.executable)}
    names = []
    for d in os.environ.get("PATH", "").split(os.pathsep):
        p = shutil.which("python3", path=d) if d else None
        if p:
            names.append(p)
    names += ["/usr/bin/python3", "/usr/local/bin/python3"]
    for p in names:
        real = os.path.realpath(p)
        if os.path.exists(p) and real not in seen:
            seen.add(real)
            yield p


def has_matplotlib(python):
    try:
        return subprocess.run([python, "-c", "import matplotlib"], stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, timeout=60).returncode == 0
    except (OSError, subprocess.TimeoutExpired):
        return False


def ensure_matplotlib():
    """Returns if this interpreter has matplotlib; else re-executes the running script with one
    that has it, or exits naming the install script."""
    try:
        import matplotlib  # noqa: F401
        return
    except ImportError:
        pass
    if not os.environ.get(_GUARD):
        for python in candidates():
            if has_matplotlib(python):
                os.environ[_GUARD] = python
                os.execv(python, [python] + sys.argv)
    raise SystemExit(f"{sys.argv[0]}: no Python with matplotlib found ({sys.executable} and every "
                     "python3 on PATH lack it); run scripts/install-deps.sh, which installs "
                     "python3-matplotlib")
