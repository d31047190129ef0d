// The metrics `tilt` and `base_height` (src/metrics/pose.h, docs/METRICS.md):
// how a formed shape stands, from its best rigid frame. Against the geometry
// of a box target placed by known frames: tilted by a known angle about a
// horizontal axis (the tilt is that angle, whatever the rotation about the
// vertical), and standing with its lowest voxels a known height above the
// floor (at rest, and tipped by 90 degrees, where its side becomes its base).
#include <gtest/gtest.h>

#include <cmath>

#include "metrics/pose.h"
#include "target/target_shape.h"
#include "test_scenes.h"

namespace {

ff_quat axisAngle(float ax, float ay, float az, double degrees) {
  const double h = 0.5 * degrees * M_PI / 180.0;
  const float s = float(std::sin(h));
  return FF_Q(ax * s, ay * s, az * s, float(std::cos(h)));
}

TEST(ShapePose, TiltAndBaseHeightOfAPlacedBox) {
  ff::TargetSpec spec = fftest::target(ff::TargetKind::Box, 1000);
  spec.box_size = ff::Vec3(0.5f, 1.0f, 0.25f);
  const ff::TargetShape t = ff::buildTarget(spec, 1e-3, 0.01f);
  const ff::Vec3 lo = t.boundsMin();  // voxel extents included
  const float gravity[3] = {0.0f, -9.81f, 0.0f};
  const ff::Vec3 box_lo(-1.0f, -0.2f, -1.0f), box_hi(1.0f, 2.0f, 1.0f);
  ff::RigidFrame f;
  f.c[0] = 0.1f, f.c[1] = 0.5f, f.c[2] = -0.1f;  // rest_c = 0: the shape frame's origin goes to c

  const ff::ShapePose upright = ff::shapePose(t, f, gravity, box_lo, box_hi);
  EXPECT_NEAR(upright.tilt, 0.0, 1e-3);
  EXPECT_NEAR(upright.base_height, 0.5 + lo.y() - (-0.2), 1e-5);

  // Turning about the vertical does not tilt it, nor move its base.
  f.q = axisAngle(0, 1, 0, 35.0);
  const ff::ShapePose turned = ff::shapePose(t, f, gravity, box_lo, box_hi);
  EXPECT_NEAR(turned.tilt, 0.0, 1e-2);
  EXPECT_NEAR(turned.base_height, upright.base_height, 1e-5);

  for (double deg : {6.0, 15.0, 40.0}) {
    f.q = ff_quat_mul(axisAngle(1, 0, 0, deg), axisAngle(0, 1, 0, 20.0));
    EXPECT_NEAR(ff::shapePose(t, f, gravity, box_lo, box_hi).tilt, deg, 0.02) << deg;
  }

  // Tipped onto its side by 90 degrees about z: y_world = x_rest (+ c), so
  // its base is the rest shape's lowest x, half as far from the middle as
  // its lowest y.
  f.q = axisAngle(0, 0, 1, 90.0);
  const ff::ShapePose tipped = ff::shapePose(t, f, gravity, box_lo, box_hi);
  EXPECT_NEAR(tipped.tilt, 90.0, 0.02);
  const float v = t.grid.voxel;
  EXPECT_NEAR(tipped.base_height, 0.5 + (lo.x() + 0.5 * v) - 0.5 * v + 0.2, 1e-4);
  EXPECT_GT(tipped.base_height, upright.base_height + 0.05);
}

}  // namespace
