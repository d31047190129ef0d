// cpu_force.h - a non-pressure force of the OpenMP backend, as a plug-in
// (after SPlisHSPlasH's non-pressure forces, without their singletons).
// CpuBackend owns an ordered list of them (made by makeCpuForces in
// src/cpu/forces/cpu_forces.cpp, the one place that registers them) and runs
// them in every substep after the density phase and before the pressure solve:
// the forces phase clears a, then each force of phase Forces adds its
// acceleration in the list's order; phase control_scale runs the prepare()
// and phase control_forces the apply() of the forces of phase ControlForces.
// The OpenCL backend has the same list (host/forces/).
#pragma once
#include "control/controller.h"
#include "cpu/fluid_cpu.h"
#include "cpu/neighbour_cache.h"
#include "sim/backend.h"

namespace ff {

// What a force reads and writes in a substep.
struct CpuForceContext {
  CpuFluid& fluid;  // sorted by the grid phase; rho from the density phase; a to add to
  const Params& params;
  const ContainerDesc& box;
  Controller& controller;  // the control particles (the control force)
  const FluidView& view;   // the fluid as the Controller reads it
  // The density phase's neighbour lists of this substep (the pressure
  // solver's; null where it keeps none): a force that walks the neighbours
  // within H may walk these instead of the grid.
  const NeighbourCache* neighbours;
};

class CpuForce {
 public:
  virtual ~CpuForce() = default;
  // Its name in the timings ("gravity", "viscosity", "control").
  virtual const char* name() const = 0;
  // The phase its apply() runs and is timed in: Forces, or ControlForces for
  // a force that needs prepare()'s results of the same substep.
  virtual Phase phase() const { return Phase::Forces; }
  // Phase control_scale, for a force of phase ControlForces: what it reads
  // from this substep's fluid before any force of that phase adds to a (the
  // control's density scale). False if a value is not finite.
  virtual bool prepare(CpuForceContext& c) {
    (void)c;
    return true;
  }
  // Adds the force's acceleration over a substep of dt to c.fluid.ax/ay/az.
  // False if a value is not finite.
  virtual bool apply(CpuForceContext& c, float dt) = 0;
};

}  // namespace ff
