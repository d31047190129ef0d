// particle_surface.h - a closed triangle mesh of the liquid from its
// particles, through OpenVDB: ParticlesToLevelSet (a sphere per particle),
// an erosion back to the fluid's extent, mean-curvature smoothing, then
// VolumeToMesh (quads split into triangles), wound outwards.
// OpenVDB's threads follow OpenMP's thread count (omp_get_max_threads).
#pragma once
#include <cstddef>
#include <string>

#include "surface/surface_mesh.h"
#include "surface/surface_options.h"

namespace ff {

// `spacing` is the fluid's rest spacing (metres). If `vdb_path` is not empty
// the smoothed level set (a FloatGrid named "surface", y-up metres) is also
// written there, with `time` as the grid's metadata "time". Throws ff::Error for bad options or an unwritable
// vdb_path. No particles: an empty mesh.
SurfaceMesh particleSurface(size_t n, const float* x, const float* y, const float* z, float spacing,
                            const SurfaceOptions& options, const std::string& vdb_path = "",
                            double time = 0.0);

// Throws ff::Error naming the bad field, prefixed by `what`.
void validateSurfaceOptions(const SurfaceOptions& options, const std::string& what);

}  // namespace ff
