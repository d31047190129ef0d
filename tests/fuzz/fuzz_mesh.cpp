// fuzz_mesh.cpp - libFuzzer target: the mesh loader (the structure checks of
// mesh_file_checks.cpp, then assimp) for one file format, FF_FUZZ_EXT
// (".obj", ".ply", ".stl" or ".off": one executable per format). The input
// is written to a file of that extension, as a user's mesh would be, and
// loaded; it must give a mesh or an ff::Error. A mesh that loads is also
// measured (volume, open edges, bounds).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.h"
#include "target/mesh_io.h"

#ifndef FF_FUZZ_EXT
#error "FF_FUZZ_EXT must name the mesh format, e.g. \".obj\""
#endif

namespace {

// One file per process, in the temp folder, removed at exit.
struct InputFile {
  std::string path;
  InputFile() {
    const char* tmp = std::getenv("TMPDIR");
    path = std::string(tmp && *tmp ? tmp : "/tmp") + "/flowform_fuzz_" + std::to_string(::getpid()) +
           FF_FUZZ_EXT;
  }
  ~InputFile() { std::remove(path.c_str()); }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static InputFile file;
  std::FILE* f = std::fopen(file.path.c_str(), "wb");
  if (!f) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  try {
    const ff::TriangleMesh mesh = ff::loadMesh(file.path);
    ff::Vec3 lo, hi;
    ff::meshBounds(mesh, lo, hi);
    (void)ff::meshVolume(mesh);
    (void)ff::openEdgeCount(mesh);
  } catch (const ff::Error&) {
  }
  return 0;
}
