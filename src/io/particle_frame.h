// particle_frame.h - one snapshot of a run for export: the fluid with its
// density and pressure, the control particles with their rest positions and
// density scale s, and the simulated time and step. Plain data: it is filled
// from a Simulation by src/sim/export_frame.h (or by any other producer).
#pragma once
#include <cstdint>
#include <vector>

#include "core/fluid_state.h"

namespace ff {

struct ParticleFrame {
  double time = 0.0;
  long step = 0;
  float spacing = 0.0f;                          // the fluid's rest spacing (for surface meshes)
  FluidState fluid;                              // fluid.id is each particle's stable identity
  std::vector<float> density, pressure;          // per fluid particle, same order
  FluidState control;                            // control particles: position, velocity, id = index
  std::vector<float> rest_x, rest_y, rest_z, s;  // per control particle: rest position, eq. 5 scale
};

}  // namespace ff
