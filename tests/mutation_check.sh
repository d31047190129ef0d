#!/bin/sh
# mutation_check.sh - do the tests catch real bugs? Applies each one-line change
# of issue 14's list to a scratch copy of the committed source tree (HEAD), one at a time, builds
# the test program there and runs it; prints, for each change, the tests that
# failed and how long each took. Every change must make at least one unit test
# that runs in under a second fail (docs/TESTING.md lists which).
#
#   sh tests/mutation_check.sh [--all] [--only NAME] [--filter GTEST_FILTER] [SCRATCH_DIR]
#
# Not part of ctest: it builds the program once per change. The scratch copy
# lives in build/mutation (or the folder given) and is left there for the next
# run (ccache makes the rebuilds quick). By default the tests that take over
# a few seconds (whole runs, the viewer under xvfb) are left out; --all runs
# every test of flowform_tests.
set -eu

src=$(cd "$(dirname "$0")/.." && pwd)
scratch="$src/build/mutation"
all=0
only=
filter_arg=
while [ $# -gt 0 ]; do
  case "$1" in
    --all) all=1 ;;
    --only) only=$2; shift ;;
    --filter) filter_arg=$2; shift ;;
    *) scratch=$1 ;;
  esac
  shift
done
slow='Table1.*:OpenClRun.DefaultScene*:OpenClRun.TargetChanges*:ViewerXvfb.*:BenchCli.ControlSweep*:SeparableController.MovesAPlainParticleSystemIntoASphere:Checkpoint.*'
filter='*'
[ "$all" = 1 ] || filter="*-$slow"
[ -z "$filter_arg" ] || filter=$filter_arg

# name | file | sed expression (one line changed)
mutations='stiffness_halved|kernels/common/ff_control.h|s|return (goal - x) \* (alpha / dt);|return (goal - x) * (0.5f * alpha / dt);|
stiffness_halved_cpu|src/control/controller.cpp|s|alpha = sm_.stiffness,|alpha = 0.5f * sm_.stiffness,|
attraction_zero|kernels/common/ff_control.h|s|return r > 1e-12f ? s \* w / r : FF_ZERO_OF(T);|return r > 1e-12f ? 0.0f * s * w / r : FF_ZERO_OF(T);|
velocity_force_sign|kernels/common/ff_control.h|s|return (vsum - k \* v) / (1.0f + dt \* k);|return -(vsum - k * v) / (1.0f + dt * k);|
feedback_off_cpu|src/control/controller.cpp|s|^\( *\)v = ff_feedback_velocity(v, FF_F3(fields_.ux\[i\], fields_.uy\[i\], fields_.uz\[i\]), fb);|\1(void)fb;|
feedback_off_opencl|kernels/shape_matching.cl|s|^\( *\)v = ff_feedback_velocity(v, FF_F3(ux\[i\], uy\[i\], uz\[i\]), feedback);|\1(void)feedback;|'

mkdir -p "$scratch/src" "$scratch/build"
status=0
summary=
while IFS='|' read -r name file expr; do
  [ -n "$name" ] || continue
  [ -z "$only" ] || [ "$only" = "$name" ] || continue
  # A fresh copy of the committed tree (HEAD), every file newer than the last
  # build's objects (tar -m), so the previous change is undone in the build.
  (cd "$src" && git archive HEAD) | (cd "$scratch/src" && tar -xmf -)
  before=$(md5sum "$scratch/src/$file")
  sed -i "$expr" "$scratch/src/$file"
  if [ "$(md5sum "$scratch/src/$file")" = "$before" ]; then
    echo "== $name: the line to change was not found in $file (update this script)"
    exit 2
  fi
  echo "== $name: $file now has: $(diff "$src/$file" "$scratch/src/$file" | grep '^>' | sed 's/^> *//')"
  cmake -S "$scratch/src" -B "$scratch/build" -DCMAKE_BUILD_TYPE=Release -DFLOWFORM_PYTHON=OFF \
    -DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache >/dev/null
  cmake --build "$scratch/build" -j2 --target flowform_tests >"$scratch/build.log" 2>&1 || {
    echo "   build failed: see $scratch/build.log"
    exit 2
  }
  log="$scratch/$name.log"
  (cd "$scratch/build" && OMP_NUM_THREADS=2 POCL_MAX_PTHREAD_COUNT=2 POCL_CACHE_DIR="$scratch/build/pocl-cache" \
    FLOWFORM_MESH_PATH="$src/../shared/meshes" ./flowform_tests --gtest_filter="$filter" >"$log" 2>&1) || true
  failed=$(grep -E '^\[  FAILED  \] [A-Za-z0-9_./]+ \([0-9]+ ms\)' "$log" || true)
  if [ -z "$failed" ]; then
    echo "   NOT CAUGHT: no test failed"
    summary="$summary
$name: NOT CAUGHT"
    status=1
  else
    echo "$failed" | sed 's/^\[  FAILED  \]/   failed:/'
    fast=$(echo "$failed" | sed -E 's/.*\(([0-9]+) ms\)/\1/' | awk '$1 < 1000' | wc -l)
    echo "   $fast of them in under 1 s"
    # The fast ones, "Suite.Test (N ms)", for the summary.
    fast_names=$(echo "$failed" | sed -E 's/^\[  FAILED  \] //' |
      awk '{ms = $2; gsub(/\(/, "", ms); if (ms + 0 < 1000) printf "%s%s %s ms)", (n++ ? ", " : ""), $1, $2}')
    summary="$summary
$name: caught by ${fast_names:-no test under 1 s}"
    [ "$fast" -gt 0 ] || status=1
  fi
done <<EOF
$mutations
EOF
echo "== summary (the tests under 1 s that each change makes fail):$summary"
exit $status
