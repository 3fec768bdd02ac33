#!/usr/bin/env bash
# Fresh machine to a tested build: dependencies, build, then every test (labels unit,
# integration, scaling) through ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
cd build
ctest --output-on-failure -j"$(nproc)" "$@"
