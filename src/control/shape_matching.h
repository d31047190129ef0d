// shape_matching.h - cluster-based shape matching (Mueller et al. 2005,
// paper eq. 7-9) on the CPU. The per-cluster math is in ff_rotation.h and
// ff_control.h, shared with the OpenCL kernels.
#pragma once
#include <vector>

#include "control/control_set.h"
#include "ff_rotation.h"

namespace ff {

// Centre of mass and rotation of every cluster. `q` holds one warm-start
// quaternion per cluster and receives the new rotations.
void clusterFrames(const ControlSet& set, std::vector<ff_quat>& q, std::vector<float>& cx,
                   std::vector<float>& cy, std::vector<float>& cz, int iterations);

// Mean velocity of every cluster's members.
void clusterVelocities(const ControlSet& set, std::vector<float>& vx, std::vector<float>& vy,
                       std::vector<float>& vz);

// Goal of every control particle: the mean over its clusters of R_c (x0 - c0_c) + c_c (eq. 8).
void clusterGoals(const ControlSet& set, const std::vector<ff_quat>& q, const std::vector<float>& cx,
                  const std::vector<float>& cy, const std::vector<float>& cz, std::vector<float>& gx,
                  std::vector<float>& gy, std::vector<float>& gz);

// Best-fit rigid frame of all control particles against their rest shape:
// x ~ R (x0 - rest_c) + c. `q` is the warm start and receives R.
void bestFitFrame(const ControlSet& set, ff_quat& q, float c[3], int iterations);

}  // namespace ff
