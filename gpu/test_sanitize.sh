#!/usr/bin/env bash
# Checks sanitize.sh's verdicts with a stand-in compute-sanitizer that prints what the real one
# prints in each case (clean, warnings only, errors, the program failing, no attach, the device
# refused as on gVisor), so that a device session's memcheck and racecheck cannot pass unjudged.
# Exit status 0 when every verdict is the expected one.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cat > "$work/stand-in" << 'STANDIN'
#!/usr/bin/env bash
case "$SANITIZER_CASE" in
  race-clean) echo "========= RACECHECK SUMMARY: 0 hazards displayed (0 errors, 0 warnings)" ;;
  race-warnings) echo "========= RACECHECK SUMMARY: 2 hazards displayed (0 errors, 2 warnings)" ;;
  race-error) echo "========= RACECHECK SUMMARY: 1 hazard displayed (1 error, 0 warnings)" ;;
  race-program-fails)
    echo "error 3.1e-02 (limit 1e-12)  FAILED"
    echo "========= RACECHECK SUMMARY: 0 hazards displayed (0 errors, 0 warnings)"
    exit 1 ;;
  mem-clean) echo "========= ERROR SUMMARY: 0 errors" ;;
  mem-errors) echo "========= Invalid __global__ read of size 8 bytes"
    echo "========= ERROR SUMMARY: 3 errors"; exit 1 ;;
  mem-program-fails) echo "========= ERROR SUMMARY: 0 errors"; exit 2 ;;
  no-attach) echo "========= Error: Target application terminated before first instrumented API call"
    exit 255 ;;
  device-refused) echo "========= Error: Device not supported. Please refer to the Supported Devices section"
    echo "error: CUDA error 999 (unknown error) at the first allocation"
    echo "========= ERROR SUMMARY: 1 error"
    exit 1 ;;
esac
STANDIN
chmod +x "$work/stand-in"
sanitizer="$work/stand-in"
source "$here/sanitize.sh"
wrong=0
expect() {
  local case="$1" tool="$2" verdict="$3" out
  failed=()
  out="$(SANITIZER_CASE="$case" sanitize "$tool" /bin/program --x=1 && echo "failed=${#failed[@]}")"
  local got=pass
  grep -q "failed=1" <<< "$out" && got=fail
  grep -q "could not run here" <<< "$out" && got=skip
  printf '%-20s %-10s %-5s (expected %s)\n' "$case" "$tool" "$got" "$verdict"
  [[ $got == "$verdict" ]] || wrong=1
}
expect race-clean racecheck pass
expect race-warnings racecheck pass
expect race-error racecheck fail
expect race-program-fails racecheck fail
expect mem-clean memcheck pass
expect mem-errors memcheck fail
expect mem-program-fails memcheck fail
expect no-attach memcheck skip
expect no-attach racecheck skip
expect device-refused memcheck skip
expect device-refused racecheck skip
# A memcheck summary does not stand for racecheck's, nor the reverse.
expect race-clean memcheck skip
expect mem-clean racecheck skip
((wrong == 0)) && echo "sanitizer verdicts as expected"
