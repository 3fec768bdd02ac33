#!/usr/bin/env bash
# Fresh machine to a solved example: dependencies, build, then the main example, the reference
# paper's two cylinders in contact (elastic, 4 load steps, against Hertz) on 2 MPI ranks into
# out/two_cylinders; then its pictures and a report of where everything is and what it shows.
#   RANKS=N      MPI ranks (default 2)
#   INPUT=FILE   another input, e.g. examples/poisson.xml (default examples/two_cylinders.xml)
#   OUTPUT=DIR   output directory (default out/<input name>)
#   SKIP_BUILD=1 use the existing build (TFETI_CONTACT=PATH: that executable)
set -euo pipefail
cd "$(dirname "$0")/.."
input="${INPUT:-examples/two_cylinders.xml}"
output="${OUTPUT:-out/$(basename "$input" .xml)}"
ranks="${RANKS:-2}"
exe="${TFETI_CONTACT:-build/bin/tfeti_contact}"
if [ "${SKIP_BUILD:-0}" != 1 ]; then bash scripts/build.sh; fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
echo "== Solving $input on $ranks MPI ranks into $output"
start=$(date +%s.%N)
code=0
mpirun --oversubscribe -np "$ranks" "$exe" --input="$input" --output="$output" || code=$?
seconds=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
# Exit codes 2 and 3 (not converged) still leave a summary worth reporting.
if [ "$code" -eq 0 ] || [ "$code" -eq 2 ] || [ "$code" -eq 3 ]; then
  python3 scripts/example_report.py "$output" --seconds "$seconds" --ranks "$ranks" || code=$((code == 0 ? 1 : code))
fi
exit "$code"
