// surface_module.h - the surface module, libflowform_surface.so: OpenVDB's
// level-set surface (surface/vdb/level_set_surface.cpp) in a library of its
// own, loaded the first time a surface is made. OpenVDB's shared library
// binds some 57,000 symbols when it loads, most of a command's start-up
// (docs/PERFORMANCE.md), and only --surface and the Python exporter's
// surfaces need it.
#pragma once
#include <cstddef>

#include "surface/surface_mesh.h"
#include "surface/surface_options.h"

// One surface to make (particleSurface's arguments). vdb_path: "" for none.
struct FfSurfaceCall {
  size_t n;
  const float *x, *y, *z;
  float spacing;
  const ff::SurfaceOptions* options;
  const char* vdb_path;
  double time;
};
// The module's entry: 0 and the mesh in *out, or 1 and the message in error.
using FfSurfaceModuleFn = int (*)(const FfSurfaceCall* call, ff::SurfaceMesh* out, char* error,
                                  size_t error_size);

namespace ff {

// The module's file name; it is looked for next to the running program, next
// to the library or module that holds this code (the Python module), then in
// the build folder.
constexpr const char* kSurfaceModuleName = "libflowform_surface.so";

// Makes the surface through the module, loading it on the first call.
// Throws ff::Error with the module's message, or naming the places it looked
// in if it cannot be loaded.
SurfaceMesh callSurfaceModule(const FfSurfaceCall& call);

}  // namespace ff
