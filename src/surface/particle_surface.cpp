// particle_surface.cpp - the surface's options checked, then made by the
// surface module (surface/surface_module.h: OpenVDB, loaded on first use).
#include "surface/particle_surface.h"

#include <cmath>
#include <string>

#include "core/error.h"
#include "surface/surface_module.h"

namespace ff {

void validateSurfaceOptions(const SurfaceOptions& o, const std::string& what) {
  if (!(std::isfinite(o.radius) && o.radius >= 0.75f && o.radius <= 4.0f))
    throw Error(what + "radius must be in [0.75, 4] rest spacings, got " + std::to_string(o.radius));
  if (!(std::isfinite(o.voxel) && o.voxel >= 0.1f && o.voxel <= 1.0f))
    throw Error(what + "voxel must be in [0.1, 1] rest spacings, got " + std::to_string(o.voxel));
  if (o.smoothing < 0 || o.smoothing > 20)
    throw Error(what + "smoothing must be in [0, 20] iterations, got " + std::to_string(o.smoothing));
  if (o.radius / o.voxel < 1.5f)
    throw Error(what + "radius must be at least 1.5 voxels (radius " + std::to_string(o.radius) + ", voxel " +
                std::to_string(o.voxel) + " rest spacings)");
}

SurfaceMesh particleSurface(size_t n, const float* x, const float* y, const float* z, float spacing,
                            const SurfaceOptions& o, const std::string& vdb_path, double time) {
  validateSurfaceOptions(o, "surface: ");
  if (!(std::isfinite(spacing) && spacing > 0.0f)) throw Error("surface: the rest spacing must be positive");
  const FfSurfaceCall call{n, x, y, z, spacing, &o, vdb_path.c_str(), time};
  return callSurfaceModule(call);
}

}  // namespace ff
