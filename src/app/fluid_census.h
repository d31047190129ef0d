// fluid_census.h - counts the fluid particles a bench run lost: those with a
// NaN or infinite position or velocity, and those outside the container.
#pragma once
#include "core/fluid_state.h"
#include "scene/scene.h"

namespace ff::app {

struct FluidCensus {
  long nonfinite = 0;  // a NaN or Inf in the position or the velocity
  long outside = 0;    // finite, but outside the container
  long lost() const { return nonfinite + outside; }
};

FluidCensus countLostFluid(const FluidState& f, const ContainerDesc& c);

}  // namespace ff::app
