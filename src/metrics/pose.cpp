#include "metrics/pose.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ff {

ShapePose shapePose(const TargetShape& target, const RigidFrame& frame, const float gravity[3],
                    const Vec3& box_lo, const Vec3& box_hi) {
  const double g = std::sqrt(double(gravity[0]) * gravity[0] + double(gravity[1]) * gravity[1] +
                             double(gravity[2]) * gravity[2]);
  double up[3] = {0.0, 1.0, 0.0};
  if (g > 0.0)
    for (int d = 0; d < 3; ++d) up[d] = -double(gravity[d]) / g;
  const ff_mat3 r = ff_quat_to_mat3(frame.q);
  const float upf[3] = {float(up[0]), float(up[1]), float(up[2])};
  const ff_float3 rup = ff_mat3_mul_vec(r, FF_F3(upf[0], upf[1], upf[2]));
  // The angle from the dot and cross products (acos loses it near 0).
  const double cosine = rup.x * up[0] + rup.y * up[1] + rup.z * up[2];
  const double cx = rup.y * up[2] - rup.z * up[1], cy = rup.z * up[0] - rup.x * up[2],
               cz = rup.x * up[1] - rup.y * up[0];
  ShapePose pose;
  pose.tilt = std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), cosine) * (180.0 / M_PI);

  double floor = std::numeric_limits<double>::max();  // the box's lowest corner along up
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner((k & 1) ? box_hi.x() : box_lo.x(), (k & 2) ? box_hi.y() : box_lo.y(),
                      (k & 4) ? box_hi.z() : box_lo.z());
    floor = std::min(floor, corner.x() * up[0] + corner.y() * up[1] + corner.z() * up[2]);
  }
  double lowest = std::numeric_limits<double>::max();
  for (const Vec3& x0 : target.reference) {
    const ff_float3 w = ff_mat3_mul_vec(
        r, FF_F3(x0.x() - frame.rest_c[0], x0.y() - frame.rest_c[1], x0.z() - frame.rest_c[2]));
    const double h = (double(w.x) + frame.c[0]) * up[0] + (double(w.y) + frame.c[1]) * up[1] +
                     (double(w.z) + frame.c[2]) * up[2];
    lowest = std::min(lowest, h);
  }
  pose.base_height = target.reference.empty() ? 0.0 : lowest - 0.5 * double(target.grid.voxel) - floor;
  return pose;
}

}  // namespace ff
