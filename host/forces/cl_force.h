// cl_force.h - a non-pressure force of the OpenCL backend, as a plug-in: the
// counterpart of src/cpu/forces/cpu_force.h, which says how the backend runs
// them. OpenClBackend owns an ordered list of them (made by makeClForces in
// host/forces/cl_forces.cpp, the one place that registers them). A force owns
// its kernels, enqueues them on the backend's queue, and its kernels call the
// per-particle bodies of kernels/common/ that its CpuForce calls, so both
// backends give the same numbers bit for bit.
#pragma once
#include "core/params.h"
#include "host/backend_opencl.h"
#include "host/dfsph_cl.h"
#include "scene/scene.h"
#include "sim/backend.h"

namespace ff {

// What a force reads and writes in a substep.
struct ClForceContext {
  const ClFluidRefs& fluid;     // sorted by the grid phase; rho from the density phase; a to add to
  OpenClBackend::Impl& device;  // the backend's buffers (the control particles' among them)
  const Params& params;
  const ContainerDesc& box;
  const ControlSet& control;  // rest shape and clusters (positions live in device)
  size_t control_count;       // control particles (0: control is off)
  bool masked;                // device.controlled flags the controlled fluid by id
  int tag;                    // the phase's non-finite tag (ff_check.h)
};

class ClForce {
 public:
  virtual ~ClForce() = default;
  // Its name in the timings ("gravity", "viscosity", "control").
  virtual const char* name() const = 0;
  // As CpuForce::phase.
  virtual Phase phase() const { return Phase::Forces; }
  // As CpuForce::prepare: enqueues what phase control_scale computes for it.
  virtual void prepare(ClForceContext& c) { (void)c; }
  // Enqueues the kernels that add the force's acceleration over a substep of
  // dt to c.fluid.ax/ay/az; they report a NaN or Inf with c.tag.
  virtual void apply(ClForceContext& c, float dt) = 0;
};

}  // namespace ff
