// pose.h - how the formed shape stands: its tilt and the height of its base
// above the container's floor, at the control particles' best rigid fit (the
// metrics `tilt` and `base_height`, docs/METRICS.md).
#pragma once
#include "core/vec3.h"
#include "metrics/iou.h"
#include "target/target_shape.h"

namespace ff {

struct ShapePose {
  double tilt = 0.0;         // degrees between the shape's rest "up" and the world's
  double base_height = 0.0;  // m: the shape's lowest point above the floor
};

// "Up" is against `gravity` (+y without gravity). tilt: the angle between
// R up and up, R the frame's rotation (the rest shape stands upright: R = 1
// is 0 degrees). base_height: the lowest inside voxel of the target placed by
// `frame` (its centre along up, less half a voxel) above the container's
// lowest point along up (the floor, for gravity along an axis).
ShapePose shapePose(const TargetShape& target, const RigidFrame& frame, const float gravity[3],
                    const Vec3& box_lo, const Vec3& box_hi);

}  // namespace ff
