// sph_args.h - the FfSphArgs (kernels/common/ff_sph.h) that the SPH kernels
// other than DFSPH's take: density.cl, pressure_wcsph.cl, forces.cl.
#pragma once
#include "core/params.h"
#include "ff_sph.h"
#include "scene/scene.h"

namespace ff {

// 16 floats with no padding: the kernels read the same bytes.
static_assert(sizeof(FfSphArgs) == 16 * sizeof(float), "FfSphArgs must hold 4-byte fields only");

// The run's fluid parameters and container, and the fluid grid's cell size.
inline FfSphArgs sphArgs(const FluidParams& f, const ContainerDesc& box, float cell) {
  FfSphArgs a{};
  for (int d = 0; d < 3; ++d) a.lo[d] = box.min[d], a.hi[d] = box.max[d];
  a.h = f.smoothing_radius, a.mass = f.particle_mass, a.rho0 = f.rest_density, a.gas_k = f.gas_constant;
  a.mu = f.viscosity, a.cell = cell;
  return a;
}

}  // namespace ff
