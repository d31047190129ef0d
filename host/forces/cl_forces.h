// cl_forces.h - the OpenCL backend's registered non-pressure forces.
#pragma once
#include <memory>
#include <vector>

#include "host/cl_context.h"
#include "host/forces/cl_force.h"

namespace ff {

// Gravity, viscosity, control, as makeCpuForces: every force the backend
// runs, in order, with their kernels made from `program`.
std::vector<std::unique_ptr<ClForce>> makeClForces(const cl::Program& program, const ClContext& ctx);

}  // namespace ff
