// force_pressure.h - the pressure that DFSPH's pressure force reads along a
// direction, per particle: the pairs' mean pressures weighted as the force
// along n weighs them (ff_dfsph_force_pressure in kernels/common/ff_dfsph.h;
// docs/PRESETS.md). A readout of any backend's particles and pressures.
#pragma once
#include <vector>

#include "core/fluid_state.h"

namespace ff {

struct ForcePressure {
  std::vector<float> p;   // p_n,i, the pressure the force along n reads at particle i
  std::vector<float> at;  // x_n,i, where along n it reads it
};

// Over the particles of `s` with pressures p[0 .. s.size()), pairs within
// `support` (the DFSPH kernel's H) and the unit direction n.
ForcePressure forcePressure(const FluidState& s, const float* p, float support, const float n[3]);

}  // namespace ff
