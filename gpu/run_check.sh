#!/usr/bin/env bash
# Configures, builds and runs the standalone checks of the batched explicit dual operator and of
# its blocks' assembly (gpu/README.md) in a few minutes. Exit status 0 with "skipped: ..." where
# there is no CUDA compiler or no GPU (the host checks still run); non-zero when a check fails.
#   gpu/run_check.sh [BUILD_DIR]      (default: gpu/build next to this script)
# Environment: BLOCKS (512), ROWS (1158), REPEATS (20), EXPORT_FILES (exported blocks, space-
# separated, instead of synthetic ones), CUDA_ARCH ("80;90"), ASSEMBLY (1: also the F_s assembly
# check; 0: the apply only), SANITIZE (1: compute-sanitizer memcheck and racecheck on small
# shapes where it can run; 0: not).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/build}"
blocks="${BLOCKS:-512}" rows="${ROWS:-1158}" repeats="${REPEATS:-20}"
args=("--blocks=$blocks" "--rows=$rows" "--repeats=$repeats")
for f in ${EXPORT_FILES:-}; do args+=("--file=$f"); done

nvcc_path="$(command -v nvcc || true)"
for c in /usr/local/cuda/bin/nvcc /usr/local/cuda-*/bin/nvcc; do
  [[ -z "$nvcc_path" && -x "$c" ]] && nvcc_path="$c"
done
cmake_args=(-S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release)
[[ -n "$nvcc_path" ]] && cmake_args+=("-DCMAKE_CUDA_COMPILER=$nvcc_path" "-DCMAKE_CUDA_ARCHITECTURES=${CUDA_ARCH:-80;90}")
cmake "${cmake_args[@]}" > "$build.configure.log" 2>&1 || { cat "$build.configure.log"; exit 1; }
cmake --build "$build" -j "$(nproc)" > "$build.build.log" 2>&1 || { cat "$build.build.log"; exit 1; }

has_gpu=0
# nvidia-smi's list is read whole first: under pipefail, grep -q closing the pipe early could
# fail the listing and turn a machine with a GPU into a skip.
gpu_list="$(command -v nvidia-smi > /dev/null && nvidia-smi -L 2> /dev/null || true)"
if [[ -x "$build/dual_apply_check_cuda" ]] && grep -q GPU <<< "$gpu_list"; then
  has_gpu=1
fi
# With a device every step runs even when an earlier one fails (a session with a GPU is short:
# one failure must not hide the other figures); the exit status says whether any failed.
failed=()
step() {
  local limit="$1"
  shift
  echo "== $*"
  local rc=0
  timeout "$limit" "$@" --require-device || rc=$?
  if ((rc != 0)); then failed+=("$(basename "$1") ${*:2} (exit $rc)"); fi
}
# compute-sanitizer (memcheck, racecheck) on small shapes, where it can run; sanitize.sh judges
# each run by its tool's summary.
sanitizer="$(command -v compute-sanitizer || true)"
if [[ -z "$sanitizer" && -n "$nvcc_path" && -x "$(dirname "$nvcc_path")/compute-sanitizer" ]]; then
  sanitizer="$(dirname "$nvcc_path")/compute-sanitizer"
fi
source "$here/sanitize.sh"
if [[ $has_gpu == 1 ]]; then
  nvidia-smi --query-gpu=name,memory.total,clocks.max.memory --format=csv,noheader || true
  step 240 "$build/dual_apply_check_cuda" "${args[@]}"
  # fp64 and fp32 at other block sizes (2D-like, larger 3D subdomains, and blocks beyond the
  # full kernel's shared x_s), synthetic only.
  if [[ -z "${EXPORT_FILES:-}" ]]; then
    step 60 "$build/dual_apply_check_cuda" --blocks=4096 --rows=256 --repeats="$repeats"
    step 180 "$build/dual_apply_check_cuda" --blocks=128 --rows=2400 --repeats="$repeats"
    step 60 "$build/dual_apply_check_cuda" --blocks=4 --rows=7000 --repeats=3
    # Blocks of different sizes in one batch, as a tearing gives them (1 row, 1157 rows, the
    # rest in 579..1158): the offsets and the per-block bounds of every kernel.
    step 60 "$build/dual_apply_check_cuda" --blocks=300 --rows=1158 --sizes=varying --repeats="$repeats"
  fi
  # The assembly of the F_s on the device (cuSOLVER potrf, cuBLAS trsm and syrk), both orderings:
  # the prototype's 512 subdomains of 8³ Hex8, then smaller and larger subdomains.
  if [[ "${ASSEMBLY:-1}" == 1 && ! -x "$build/dual_assembly_check_cuda" ]]; then
    echo "no assembly check: built without cuBLAS or cuSOLVER (see $build.configure.log)"
    failed+=("assembly check not built")
  elif [[ "${ASSEMBLY:-1}" == 1 ]]; then
    step 120 "$build/dual_assembly_check_cuda" --elements=8 --count=512
    step 60 "$build/dual_assembly_check_cuda" --elements=6 --count=512
    step 60 "$build/dual_assembly_check_cuda" --elements=10 --count=128
  fi
  if [[ "${SANITIZE:-1}" == 1 && -z "$sanitizer" ]]; then
    echo "no compute-sanitizer on PATH or beside $nvcc_path: memcheck and racecheck not run"
  elif [[ "${SANITIZE:-1}" == 1 ]]; then
    # racecheck on the apply only: in the assembly, shared memory is cuBLAS's and cuSOLVER's
    # (not ours to check) and the tiled mirror's.
    sanitize memcheck "$build/dual_apply_check_cuda" --blocks=3 --rows=300 --repeats=1 --host-threads=4
    sanitize racecheck "$build/dual_apply_check_cuda" --blocks=3 --rows=300 --repeats=1 --host-threads=4
    sanitize memcheck "$build/dual_apply_check_cuda" --blocks=5 --rows=300 --sizes=varying --repeats=1 --host-threads=4
    if [[ "${ASSEMBLY:-1}" == 1 && -x "$build/dual_assembly_check_cuda" ]]; then
      sanitize memcheck "$build/dual_assembly_check_cuda" --elements=3 --count=4 --streams=2 --phases=1
    fi
  fi
  if (( ${#failed[@]} )); then
    printf 'FAILED: %s\n' "${failed[@]}"
    exit 1
  fi
  echo "all device checks passed"
  exit 0
fi
# No device: the host check on a smaller batch (the same code path and reference), then skip.
small=("--blocks=$(( blocks < 32 ? blocks : 32 ))" "--rows=$rows" "--repeats=3")
[[ -n "${EXPORT_FILES:-}" ]] && small=("${args[@]}")
timeout 300 "$build/dual_apply_check_cpu" "${small[@]}"
[[ "${ASSEMBLY:-1}" == 1 ]] && timeout 120 "$build/dual_assembly_check_cpu"
if [[ -z "$nvcc_path" ]]; then
  echo "skipped: no CUDA compiler (host check only; the device figures need a machine with CUDA and a GPU)"
else
  echo "skipped: no GPU (dual_apply_check_cuda built with $nvcc_path; run this script on a machine with a GPU for the device figures)"
fi
exit 0
