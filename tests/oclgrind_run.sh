#!/bin/sh
# tests/oclgrind_run.sh OCLGRIND FLOWFORM SCENE VARIANT [STEPS]
# Runs SCENE for STEPS steps (default 4; the scene changes its target before
# the last) on Oclgrind's simulated OpenCL device with the given kernel
# variant, checking every kernel launch for out-of-bounds accesses, data races (--data-races) and API misuse
# (--check-api). Fails on any Oclgrind diagnostic or a failed run.
set -u
oclgrind=$1 flowform=$2 scene=$3 variant=$4 steps=${5:-4}
dir=$(mktemp -d) || exit 1
trap 'rm -rf "$dir"' EXIT
"$oclgrind" --data-races --check-api --num-threads 2 --log "$dir/oclgrind.log" \
  "$flowform" run "$scene" --backend opencl --kernels "$variant" --steps "$steps" > "$dir/run.log" 2>&1
rc=$?
cat "$dir/run.log"
if [ $rc -ne 0 ]; then echo "oclgrind_run: flowform failed (exit $rc)"; exit 1; fi
grep -q "Oclgrind Simulator" "$dir/run.log" || { echo "oclgrind_run: the run did not use Oclgrind's device"; exit 1; }
grep -q "$variant kernels" "$dir/run.log" || { echo "oclgrind_run: not the $variant kernels"; exit 1; }
grep -q "target=box" "$dir/run.log" || { echo "oclgrind_run: the target change did not happen"; exit 1; }
if [ -s "$dir/oclgrind.log" ]; then
  echo "oclgrind_run: Oclgrind reported:"; cat "$dir/oclgrind.log"; exit 1
fi
echo "oclgrind_run: no Oclgrind diagnostics ($variant kernels)"
