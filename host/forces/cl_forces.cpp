// cl_forces.cpp - the one place that registers the OpenCL backend's
// non-pressure forces: a new force is its file in host/forces/ (a ClForce
// and its make function) and one line in each list below, in the order of
// src/cpu/forces/cpu_forces.cpp.
#include "host/forces/cl_forces.h"

namespace ff {

std::unique_ptr<ClForce> makeClGravity(const cl::Program& program, const ClContext& ctx);    // gravity.cpp
std::unique_ptr<ClForce> makeClViscosity(const cl::Program& program, const ClContext& ctx);  // viscosity.cpp
std::unique_ptr<ClForce> makeClControl(const cl::Program& program, const ClContext& ctx);    // control.cpp

std::vector<std::unique_ptr<ClForce>> makeClForces(const cl::Program& program, const ClContext& ctx) {
  std::vector<std::unique_ptr<ClForce>> forces;
  forces.push_back(makeClGravity(program, ctx));
  forces.push_back(makeClViscosity(program, ctx));
  forces.push_back(makeClControl(program, ctx));
  return forces;
}

}  // namespace ff
