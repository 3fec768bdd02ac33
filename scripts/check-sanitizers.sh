#!/usr/bin/env bash
# Builds the tree with AddressSanitizer + UndefinedBehaviorSanitizer + _GLIBCXX_ASSERTIONS
# (-DTFETI_SANITIZE=ON) in its own build directory and runs the unit, integration and fuzz tests
# under it, leak checking on. Suppressed: only the MPI, Gmsh and hwloc libraries' own allocations
# (scripts/sanitizer-suppressions.txt). Usage: bash scripts/check-sanitizers.sh [BUILD_DIR]
# (default build-sanitize; JOBS=2). Prints the counts and the run time at the end.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=${1:-build-sanitize}
jobs=${JOBS:-2}
start=$(date +%s)
launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTFETI_SANITIZE=ON "${launcher[@]}"
cmake --build "$build" -j"$jobs"
built=$(date +%s)

# fast_unwind_on_malloc=0: Open MPI, PMIx and their plugins are built without frame pointers, so the
# fast unwinder stops one frame above malloc and the suppressions below cannot match their leaks.
# The plugins stay loaded (no dlclose) so that their frames keep a module name.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:halt_on_error=1:detect_odr_violation=0:fast_unwind_on_malloc=0
export OMPI_MCA_mca_base_component_disable_dlclose=1 PMIX_MCA_mca_base_component_disable_dlclose=1
export LSAN_OPTIONS=suppressions=$root/scripts/sanitizer-suppressions.txt:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Each fuzz mutant gets the same 5x time limit as the tests (TFETI_TEST_TIMEOUT_SCALE).
export FUZZ_TIMEOUT=${FUZZ_TIMEOUT:-600}
cd "$build"
status=0
# Sanitized runs are 2-5x slower: the build multiplies every test's TIMEOUT by 5.
ctest -L 'unit|integration|fuzz' -j"$jobs" --timeout 1800 --output-on-failure \
  | tee sanitizer-ctest.log || status=$?
end=$(date +%s)
echo "check-sanitizers: $(grep -E 'tests passed' sanitizer-ctest.log)"
echo "check-sanitizers: build $((built - start)) s, tests $((end - built)) s, $(date -u +%FT%TZ)"
# Any sanitizer report in a test's output is a failure even if the test passed otherwise.
if grep -qE 'ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:' Testing/Temporary/LastTest.log; then
  echo "check-sanitizers: sanitizer reports in Testing/Temporary/LastTest.log"
  grep -nE 'ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:' Testing/Temporary/LastTest.log | head -20
  status=1
fi
exit $status
