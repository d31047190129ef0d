#!/bin/sh
# bench/pack_gpu_bundle.sh [BUILD_DIR] [OUT.tar.gz]
# Packs what bench/gpu_check.sh needs on a bare machine with an OpenCL GPU
# driver (e.g. NVIDIA's, which installs /etc/OpenCL/vendors/nvidia.icd) into
# one tarball of at most 64 MiB:
#   bin/      flowform and flowform_tests (stripped)
#   lib/      the shared libraries they need (ldd), without glibc itself,
#             including Debian's OpenCL ICD loader libOpenCL.so.1 (ocl-icd)
#   meshes/   the Table 1 meshes, from $FLOWFORM_MESH_PATH or ../shared/meshes
#   scenes/, tests/scenes/, bench/gpu_check.sh
# On the GPU machine: tar xzf flowform-gpu.tar.gz && cd flowform-gpu && sh bench/gpu_check.sh
set -eu
cd "$(dirname "$0")/.."
build=${1:-build}
out=${2:-$build/flowform-gpu.tar.gz}
limit=$((64 * 1024 * 1024))
for b in flowform flowform_tests; do
  [ -x "$build/$b" ] || { echo "pack_gpu_bundle: $build/$b not built (cmake --build $build)"; exit 1; }
done
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
root=$stage/flowform-gpu
mkdir -p "$root/bin" "$root/lib" "$root/meshes" "$root/bench" "$root/tests"
for b in flowform flowform_tests; do
  cp "$build/$b" "$root/bin/$b"
  strip "$root/bin/$b"
done
# Every library the binaries load, except glibc's own (the target's glibc must
# be at least Debian 12's 2.36) and the dynamic loader.
ldd "$build/flowform" "$build/flowform_tests" | awk '/=> \//{print $3}' | sort -u | while read -r lib; do
  case $(basename "$lib") in
    libc.so.*|libm.so.*|libpthread.so.*|libdl.so.*|librt.so.*|ld-linux*) ;;
    *) cp -L "$lib" "$root/lib/" ;;
  esac
done
[ -f "$root/lib/libOpenCL.so.1" ] || { echo "pack_gpu_bundle: libOpenCL.so.1 (ocl-icd-libopencl1) not found"; exit 1; }
meshes=""
for d in $(echo "${FLOWFORM_MESH_PATH:-}" | tr ':' ' ') ../shared/meshes; do
  [ -f "$d/bunny.obj" ] && { meshes=$d; break; }
done
if [ -n "$meshes" ]; then
  for m in bunny teapot runner dragon; do cp "$meshes/$m.obj" "$root/meshes/"; done
else
  echo "pack_gpu_bundle: no Table 1 meshes (set FLOWFORM_MESH_PATH); the bundle skips Table 1"
fi
cp -r scenes "$root/scenes"
cp -r tests/scenes "$root/tests/scenes"
cp bench/gpu_check.sh "$root/bench/"
mkdir -p "$(dirname "$out")"
tar -C "$stage" -czf "$out" flowform-gpu
size=$(stat -c %s "$out")
echo "pack_gpu_bundle: $out: $size bytes ($(du -sh "$root" | cut -f1) unpacked; $(ls "$root/lib" | wc -l) libraries)"
if [ "$size" -gt "$limit" ]; then echo "pack_gpu_bundle: over 64 MiB"; exit 1; fi
