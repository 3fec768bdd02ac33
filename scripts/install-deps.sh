#!/usr/bin/env bash
# Installs every system dependency of the project from Debian packages. Idempotent:
# packages already present are skipped by apt-get, and the apt lists are refreshed only
# when something is missing.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  # Debian's Trilinos CMake configs reference every package, so the whole set is needed
  trilinos-all-dev
  # TPL libraries the Trilinos configs link but trilinos-all-dev does not pull in
  libptscotch-dev libscotch-dev
  libmetis-dev libopenmpi-dev openmpi-bin
  # local subdomain factorization (CHOLMOD) and its siblings
  libsuitesparse-dev
  # an optimized BLAS/LAPACK: installing it switches Debian's alternatives libblas.so.3 and
  # liblapack.so.3 (netlib's reference code otherwise) to OpenBLAS for CHOLMOD, Trilinos and
  # MueLu alike; the serial variant starts no threads (every MPI rank is one core). It cut the
  # 3D setup's CPU time by 40 % (docs/benchmarks.md, "OpenBLAS and CHOLMOD's threads").
  libopenblas0-serial
  # unstructured meshes: the Gmsh C++ API (gmsh.h) meshes .geo files and reads .msh files
  libgmsh-dev
  # output checks and plot scripts
  python3 python3-matplotlib clang-format
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; fi
export DEBIAN_FRONTEND=noninteractive
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
