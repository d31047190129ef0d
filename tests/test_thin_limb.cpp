// test_thin_limb.cpp - adaptive control (docs/CONTROL_UNITS.md, "Thin
// features") on one shape with a thick body and thin limbs, through
// placement as a run uses it: each control particle's radius is the local
// thickness of the voxelised shape around it, known here in closed form (a
// square bar k voxels across, k odd, is k voxels thick along its length; a
// cube's core is as thick as the cube), clamped to [min_radius, radius]; and
// a limb that hangs beside the body is never matched in one cluster with it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "control/placement.h"
#include "core/params.h"
#include "target/target_shape.h"

namespace {

constexpr float kVoxel = 0.005f;  // 5 mm: the default control radius 0.03 m is 6 voxels

// A target whose inside voxels are those `inside(i, j, k)` says, on an n^3
// grid with a border of outside voxels, with the reference particles at the
// inside voxels' centres in grid index order (as buildTarget makes them).
ff::TargetShape voxelTarget(int n, const std::function<bool(int, int, int)>& inside) {
  ff::TargetShape t;
  t.label = "voxel test shape";
  ff::VoxelGrid& g = t.grid;
  g.voxel = kVoxel, g.nx = g.ny = g.nz = n;
  g.origin = ff::Vec3(-0.5f * n * kVoxel, -0.5f * n * kVoxel, -0.5f * n * kVoxel);
  g.inside.assign(size_t(n) * n * n, 0);
  for (int k = 1; k < n - 1; ++k)
    for (int j = 1; j < n - 1; ++j)
      for (int i = 1; i < n - 1; ++i)
        if (inside(i, j, k)) g.inside[g.index(i, j, k)] = 1;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (g.inside[g.index(i, j, k)]) t.reference.push_back(g.center(i, j, k));
  t.shape_volume = t.voxel_volume();
  return t;
}

struct Voxel {
  int i, j, k;
};

// The voxel of each control particle, from its rest position.
std::vector<Voxel> voxelsOf(const ff::ControlSet& s, const ff::VoxelGrid& g) {
  std::vector<Voxel> v(s.size());
  for (size_t p = 0; p < s.size(); ++p)
    v[p] = {int(std::floor((s.x0[p] - g.origin.x()) / g.voxel)),
            int(std::floor((s.y0[p] - g.origin.y()) / g.voxel)),
            int(std::floor((s.z0[p] - g.origin.z()) / g.voxel))};
  return v;
}

bool in(int v, int lo, int count) {
  return v >= lo && v < lo + count;
}

ff::ControlSet place(const ff::TargetShape& t, const ff::AdaptiveControl& a) {
  ff::Vec3 lo = t.reference[0], hi = t.reference[0];
  for (const ff::Vec3& r : t.reference) lo = lo.cwiseMin(r), hi = hi.cwiseMax(r);
  return ff::placeControlParticles(t, lo, hi, ff::ShapeMatchParams(), ff::Vec3(-1, -1, -1), ff::Vec3(1, 1, 1),
                                   a);
}

// A body 16 voxels wide (8 cm) with an arm 3 x 3 voxels across (1.5 cm) and
// a finger 1 voxel across, each 22 voxels long. Along the arm, away from the
// body and the tip, the largest inside ball centred on a voxel centre has
// radius 1.5 voxels (its centre 2 voxels from the outside) and holds the
// whole 3 x 3 cross-section (the corners are sqrt(2) from the axis): 3 voxels
// thick, 1.5 cm, half the control radius. The finger is 1 voxel thick, below
// the smallest radius, so it gets that. The body's core lies in a ball of
// radius 7.5 voxels: thicker than the control radius, which it keeps.
TEST(ThinLimb, EachControlParticlesRadiusIsTheLocalThicknessOfItsPart) {
  const int body = 2, width = 16, arm_lo = 9, arm_w = 3, length = 22;
  const ff::TargetShape t = voxelTarget(44, [&](int i, int j, int k) {
    const bool in_body = in(i, body, width) && in(j, body, width) && in(k, body, width);
    const bool arm = in(i, body + width, length) && in(j, arm_lo, arm_w) && in(k, arm_lo, arm_w);
    const bool finger = in(j, body + width, length) && i == 10 && k == 10;
    return in_body || arm || finger;
  });
  ff::ControlParams cp;  // radius 0.03 m
  ASSERT_FLOAT_EQ(cp.radius, 6.0f * kVoxel);
  cp.adaptive = 1;
  const float fluid_spacing = 0.004f;
  const ff::AdaptiveControl a = ff::adaptiveControl(cp, kVoxel, fluid_spacing);
  // The smallest radius: 2 fluid spacings (8 mm), more than 1.5 voxels (7.5 mm).
  ASSERT_NEAR(a.min_radius, 2.0f * fluid_spacing, 1e-7f);
  const ff::ControlSet s = place(t, a);
  ASSERT_EQ(s.size(), t.reference.size());
  const std::vector<Voxel> v = voxelsOf(s, t.grid);

  const double arm_radius = std::clamp(3.0 * kVoxel, double(a.min_radius), double(cp.radius));  // 1.5 cm
  const double finger_radius = std::clamp(1.0 * kVoxel, double(a.min_radius), double(cp.radius));
  ASSERT_LT(arm_radius, 0.6 * cp.radius);
  ASSERT_EQ(finger_radius, double(a.min_radius));
  int n_arm = 0, n_finger = 0, n_core = 0;
  double arm_sum = 0.0, core_sum = 0.0;
  // Away from the body (its balls reach 7.5 voxels out of it) and 2 voxels
  // short of the tips (whose corners no ball of 1.5 voxels holds).
  const int from = body + width + 8, to = body + width + length - 2;
  for (size_t p = 0; p < s.size(); ++p) {
    const double r = double(s.radius_scale[p]) * cp.radius;
    if (in(v[p].i, from, to - from) && in(v[p].j, arm_lo, arm_w) && in(v[p].k, arm_lo, arm_w)) {
      EXPECT_NEAR(r, arm_radius, 1e-6) << "arm voxel " << v[p].i << " " << v[p].j << " " << v[p].k;
      ++n_arm, arm_sum += r;
    } else if (in(v[p].j, from, to - from) && v[p].i == 10 && v[p].k == 10) {
      EXPECT_NEAR(r, finger_radius, 1e-6) << "finger voxel " << v[p].j;
      ++n_finger;
    } else if (in(v[p].i, body + 4, width - 8) && in(v[p].j, body + 4, width - 8) &&
               in(v[p].k, body + 4, width - 8)) {
      EXPECT_EQ(s.radius_scale[p], 1.0f) << "core voxel " << v[p].i << " " << v[p].j << " " << v[p].k;
      ++n_core, core_sum += r;
    }
    EXPECT_GE(r, a.min_radius * (1.0 - 1e-6));
    EXPECT_LE(s.radius_scale[p], 1.0f);
  }
  EXPECT_EQ(n_arm, (to - from) * arm_w * arm_w);
  EXPECT_EQ(n_finger, to - from);
  EXPECT_EQ(n_core, 8 * 8 * 8);
  std::printf(
      "  arm: %d control particles of mean radius %.2f mm (local thickness 15 mm); body core: %d of %.2f "
      "mm\n",
      n_arm, 1e3 * arm_sum / n_arm, n_core, 1e3 * core_sum / n_core);

  // Off: one radius everywhere, the arm's as the body's.
  cp.adaptive = 0;
  const ff::ControlSet off = place(t, ff::adaptiveControl(cp, kVoxel, fluid_spacing));
  for (float r : off.radius_scale) ASSERT_EQ(r, 1.0f);
}

// An arm 3 voxels across hangs down beside the body, one voxel of air
// between them, joined to it only at the shoulder (its top 3 voxels). The
// paper's cube clusters (5 voxels wide) around the gap hold the arm and the
// body's side as one rigid piece; with adaptive control every cluster that
// holds a particle of the arm below the shoulder holds no particle of the
// body (inside such a cube the two are not connected), so the arm's
// clusters follow the arm.
TEST(ThinLimb, AnArmBesideTheBodyIsNeverInTheBodysClusters) {
  const int body = 2, width = 16, gap = 1, arm_w = 3;
  const int arm_i = body + width + gap;  // the arm's first column
  const int top = body + width;          // the body's and the arm's top (exclusive)
  const ff::TargetShape t = voxelTarget(28, [&](int i, int j, int k) {
    const bool in_body = in(i, body, width) && in(j, body, width) && in(k, body, width);
    const bool arm = in(i, arm_i, arm_w) && in(j, body, width) && in(k, 8, arm_w);
    const bool shoulder = in(i, body + width, gap) && in(j, top - 3, 3) && in(k, 8, arm_w);
    return in_body || arm || shoulder;
  });
  const std::vector<Voxel> v = [&] {
    ff::ControlParams cp;
    return voxelsOf(place(t, ff::adaptiveControl(cp, kVoxel, 0.004f)), t.grid);
  }();
  auto mixed = [&](bool adaptive) {
    ff::ControlParams cp;
    cp.adaptive = adaptive ? 1 : 0;
    const ff::ControlSet s = place(t, ff::adaptiveControl(cp, kVoxel, 0.004f));
    const ff::Clusters& cl = s.clusters;
    // Every particle is in a cluster, whichever kind.
    for (size_t p = 0; p < s.size(); ++p) EXPECT_GE(cl.of_start[p + 1] - cl.of_start[p], 1u);
    int count = 0;
    for (size_t c = 0; c < cl.count(); ++c) {
      bool lower_arm = false, body_part = false;
      for (uint32_t m = cl.start[c]; m < cl.start[c + 1]; ++m) {
        const Voxel& w = v[cl.members[m]];
        // More than a cluster's width (4 voxels) below the shoulder: a cube
        // that reaches the shoulder holds both legitimately, connected
        // through it.
        lower_arm = lower_arm || (w.i >= arm_i && w.j < top - 3 - 4);
        body_part = body_part || w.i < body + width;
      }
      count += lower_arm && body_part;
    }
    return count;
  };
  EXPECT_GT(mixed(false), 0)
      << "the cube clusters should join the arm to the body (else the test shows nothing)";
  EXPECT_EQ(mixed(true), 0) << "a cluster holds both the hanging arm and the body";
}

}  // namespace
