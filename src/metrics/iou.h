// iou.h - voxel intersection over union between the target and the fluid
// (the voxels of the target's padded grid; fluid beyond it: fluid_shares.h).
#pragma once
#include <cstdint>

#include "ff_rotation.h"
#include "grid/uniform_grid.h"
#include "target/target_shape.h"

namespace ff {

struct RigidFrame {
  ff_quat q = FF_Q(0.0f, 0.0f, 0.0f, 1.0f);  // rotation from the target frame to the world
  float c[3] = {0, 0, 0};                    // world position of the target's rest centre `rest_c`
  float rest_c[3] = {0, 0, 0};
};

// The target's voxel grid, padded by `pad` voxels on every side, is placed in
// the world by `frame` (x_world = R (x_rest - rest_c) + c). A voxel is a target
// voxel if it is inside the shape, a fluid voxel if the SPH density of the
// fluid particles at its centre is at least `fraction` * rho0. Returns
// |target & fluid| and |target | fluid| over the padded grid, and, where
// `thin` (per voxel of the unpadded grid, grid index order; nonzero: a thin
// voxel, see thinVoxels) is given, |thin & fluid|. `grid` indexes the
// particles (any order) with cell size >= h.
struct IouCounts {
  long inter = 0, uni = 0, inter_thin = 0;
};
IouCounts voxelIou(const TargetShape& target, const RigidFrame& frame, int pad, const float* x,
                   const float* y, const float* z, const UniformGrid& grid, float mass, float h, float rho0,
                   float fraction, const uint8_t* thin = nullptr);

}  // namespace ff
