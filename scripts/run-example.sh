#!/usr/bin/env bash
# Fresh machine to a solved example: dependencies, build, then the main example (Poisson,
# H = 1/4, h = 1/64, TFETI + Dirichlet preconditioner) on 2 MPI ranks into out/poisson.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpirun --oversubscribe -np "${RANKS:-2}" build/bin/tfeti_contact \
  --input="${INPUT:-examples/poisson.xml}" --output="${OUTPUT:-out/poisson}"
