#!/bin/sh
# bench/gpu_check.sh - everything worth knowing from one session on a GPU
# machine, in at most --budget seconds (default 480), all into one folder.
# Run from the repo root (uses ./build) or from an unpacked
# bench/pack_gpu_bundle.sh bundle (uses ./bin and ./lib).
#
#   sh bench/gpu_check.sh [--out DIR] [--budget S] [--seconds S] [--max-fluid N]
#                         [--steps N] [--device N]
#
# Stages (each logged to DIR/NN_name.log, exit codes and times in DIR/summary.txt):
#   devices      flowform devices (both kernel variants' choice)
#   build_log    the kernel compiler's log for the device (FLOWFORM_CL_BUILD_LOG)
#   phases       the per-phase equivalence tests and the whole runs against
#                the OpenMP backend (flowform_tests OpenClPhases.*, OpenClRun.*,
#                OpenClPadding.*, the DFSPH solver's stages OpenClDfsph.*)
#                with poisoned buffers; off PoCL they hold the GPU tolerances
#                of tests/gpu_tolerance.h (docs/GPU.md, "Rounding"): 1e-5 of
#                each quantity's error scale per phase, 2e-3 m placement and
#                0.04 iou for whole runs
#   run_*        the Table 1 bunny and the default scene for --seconds
#                (default 4) on the scalar and the lanes kernels, metrics CSV
#   bench_*      flowform bench --dambreak --solver dfsph (12k and 100k dam
#                breaks over 0.5 s; --quick on a CPU device), --table1, and
#                --fluid-sweep up to --max-fluid (default 1000000), OpenCL
#                only, CSV
# A stage that would pass the budget is cut by `timeout` (exit 124).
# On a CPU OpenCL device (PoCL: a test of the script, not of a GPU) the
# defaults shrink so that the whole script fits the budget there too: runs of
# 1 s (--seconds) and a Table 1 bench of 50 steps (--steps); options given
# explicitly win. summary.txt says which were used.
set -u
out="gpu_check_$(date -u +%Y%m%dT%H%M%SZ)" budget=480 seconds="" max_fluid=1000000 steps="" device="" dev_index=""
while [ $# -gt 0 ]; do
  case $1 in
    --out) out=$2; shift 2 ;;
    --budget) budget=$2; shift 2 ;;
    --seconds) seconds=$2; shift 2 ;;
    --max-fluid) max_fluid=$2; shift 2 ;;
    --steps) steps=$2; shift 2 ;;
    --device) device="--device $2" dev_index=$2; shift 2 ;;
    *) echo "gpu_check: unknown option $1 (see the header of bench/gpu_check.sh)"; exit 2 ;;
  esac
done
if [ -x bin/flowform ]; then
  bin=$PWD/bin
  export LD_LIBRARY_PATH="$PWD/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  meshes=$PWD/meshes
elif [ -x build/flowform ]; then
  bin=$PWD/build
  meshes=$PWD/../shared/meshes
else
  echo "gpu_check: no bin/flowform (bundle) or build/flowform (repo root) here"; exit 2
fi
export FLOWFORM_MESH_PATH="${FLOWFORM_MESH_PATH:-$meshes}"
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/$out/pocl-cache}"
mkdir -p "$out" || exit 2
start=$(date +%s)
n=0 failed=0
echo "gpu_check: $(date -u) on $(hostname), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)" > "$out/summary.txt"
# stage NAME CAP_SECONDS COMMAND...: runs COMMAND with at most CAP seconds
# (and never past the budget), output into DIR/NN_NAME.log.
stage() {
  name=$1 cap=$2; shift 2
  n=$((n + 1))
  log=$(printf '%s/%02d_%s.log' "$out" "$n" "$name")
  left=$((budget - ($(date +%s) - start)))
  [ "$cap" -gt "$left" ] && cap=$left
  if [ "$cap" -le 0 ]; then echo "$name: skipped (budget spent)" | tee -a "$out/summary.txt"; return; fi
  t0=$(date +%s)
  echo "\$ $*" > "$log"
  timeout "$cap" "$@" >> "$log" 2>&1
  rc=$?
  [ $rc -ne 0 ] && failed=$((failed + 1))
  echo "$name: exit $rc, $(($(date +%s) - t0)) s (cap $cap s)" | tee -a "$out/summary.txt"
}
fl=$bin/flowform
# The device the OpenCL stages use: --device N, else the first GPU, else
# device 0 (as flowform picks it); its type from `flowform devices`.
dev_types=$("$fl" devices 2>/dev/null | sed -n 's/^  device \([0-9]*\): .*\[\([A-Z]*\)\].*/\1 \2/p')
if [ -n "$dev_index" ]; then
  dev_type=$(echo "$dev_types" | awk -v d="$dev_index" '$1 == d {print $2}')
elif echo "$dev_types" | grep -q ' GPU$'; then
  dev_type=GPU
else
  dev_type=$(echo "$dev_types" | awk 'NR == 1 {print $2}')
fi
if [ "$dev_type" = CPU ]; then
  seconds=${seconds:-1} steps=${steps:-50} dambreak="--quick"
else
  seconds=${seconds:-4} steps=${steps:-200} dambreak="--seconds 0.5 --max-fluid $max_fluid"
fi
echo "device type ${dev_type:-unknown}: runs of $seconds s, Table 1 bench of $steps steps, budget $budget s" | tee -a "$out/summary.txt"
has_bunny() {
  for d in $(echo "$FLOWFORM_MESH_PATH" | tr ':' ' '); do [ -f "$d/bunny.obj" ] && return 0; done
  return 1
}
# shellcheck disable=SC2086
{
  stage devices 30 "$fl" devices
  stage build_log 60 env FLOWFORM_CL_BUILD_LOG="$out/kernel_build_log.txt" "$fl" run --backend opencl $device --steps 1
  stage phases 180 env FLOWFORM_CL_POISON=1 "$bin/flowform_tests" --gtest_filter='OpenClPhases.*:OpenClPadding.*:OpenClRun.*:OpenClDfsph.*'
  for k in scalar lanes; do
    if has_bunny; then
      stage "run_bunny_$k" 90 "$fl" run scenes/bunny.json --backend opencl $device --kernels $k --seconds "$seconds" --metrics "$out/bunny_$k.csv"
    else
      echo "run_bunny_$k: skipped (no bunny.obj on FLOWFORM_MESH_PATH)" | tee -a "$out/summary.txt"
    fi
    stage "run_default_$k" 90 "$fl" run --backend opencl $device --kernels $k --seconds "$seconds" --metrics "$out/default_$k.csv"
  done
  stage bench_dambreak_dfsph 150 "$fl" bench --dambreak --solver dfsph --backend opencl $device $dambreak
  stage bench_table1 120 "$fl" bench --table1 --backend opencl $device --steps "$steps" --warmup 20 --csv "$out/bench_table1.csv"
  left=$((budget - ($(date +%s) - start) - 10))
  stage bench_fluid_sweep 600 "$fl" bench --fluid-sweep --backend opencl $device --max-fluid "$max_fluid" --budget "$left" --csv "$out/bench_fluid_sweep.csv"
}
total=$(($(date +%s) - start))
echo "gpu_check: $n stages, $failed failed, $total s in all; results in $out" | tee -a "$out/summary.txt"
[ "$failed" -eq 0 ]
