# The verdict of one compute-sanitizer run, for run_check.sh (sourced; test_sanitize.sh checks
# it against a stand-in sanitizer). Needs $sanitizer (the program) and the array failed, to which
# a failing run adds its line. Usage: sanitize TOOL PROGRAM ARGS...
# Each tool is judged by its own summary line: memcheck's "ERROR SUMMARY: N errors", racecheck's
# "RACECHECK SUMMARY: N hazards displayed (E errors, W warnings)" (it prints no ERROR SUMMARY).
# Errors fail the check, and so does the program failing under a sanitizer that ran (the small
# shapes run nowhere else); a sanitizer that cannot attach to the device or refuses it (seen on
# gVisor) only says so.
sanitize() {
  local tool="$1" log rc=0 summary errors
  shift
  local what="compute-sanitizer $tool $(basename "$1") ${*:2}"
  log="$(timeout 120 "$sanitizer" --tool "$tool" "$@" --require-device 2>&1)" || rc=$?
  if [[ $tool == racecheck ]]; then
    summary="$(grep -Eo 'RACECHECK SUMMARY: [0-9]+ hazards? displayed \([0-9]+ errors?, [0-9]+ warnings?\)' <<< "$log" | tail -1 || true)"
    errors="$(sed -E 's/.*\(([0-9]+) error.*/\1/' <<< "$summary")"
  else
    summary="$(grep -Eo 'ERROR SUMMARY: [0-9]+ errors?' <<< "$log" | tail -1 || true)"
    errors="$(sed -E 's/ERROR SUMMARY: ([0-9]+) error.*/\1/' <<< "$summary")"
  fi
  # A sanitizer that refuses the device (seen on gVisor: "Device not supported", then the
  # program's first allocation fails) ran nothing of ours, whatever its summary says.
  if grep -q "Device not supported" <<< "$log"; then
    summary=""
  fi
  if [[ -z "$summary" ]]; then
    echo "$log" | tail -5
    echo "$what: could not run here, exit $rc (not a failure of the check)"
  elif ((errors != 0)); then
    echo "$log" | tail -40
    echo "$what: FAILED ($summary)"
    failed+=("$what ($summary)")
  elif ((rc != 0)); then
    echo "$log" | tail -20
    echo "$what: the program failed under the sanitizer, exit $rc ($summary)"
    failed+=("$what (exit $rc)")
  else
    echo "$what: $summary"
  fi
}
