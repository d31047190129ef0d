// A target change places the new shape standing on the floor (issue 10,
// "Clean target changes"): a shape lower than the fluid of the current shape
// stands on that fluid's floor instead of forming around the middle of its
// height, in the air, with the fluid that falls beneath it out of the
// control's reach (Fig. 12's box on the water preset: 7% of its fluid).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <numeric>

#include "control/placement.h"
#include "test_scenes.h"

namespace {

// The lowest and highest points of the rigid goal shape the placed control
// particles form around: their centre of mass plus the rest shape's extent
// about its own centre.
struct Extent {
  double lo = 0.0, hi = 0.0;
};
Extent goalExtentY(const ff::ControlSet& s) {
  const double n = double(s.size());
  const double com = std::accumulate(s.y.begin(), s.y.end(), 0.0) / n;
  const double rest = std::accumulate(s.y0.begin(), s.y0.end(), 0.0) / n;
  const auto [mn, mx] = std::minmax_element(s.y0.begin(), s.y0.end());
  return {com + (*mn - rest), com + (*mx - rest)};
}

// A flat box over a region three times as tall: standing (gravity -y), the
// goal's bottom is the region's floor; with gravity +y its top is the
// region's ceiling; without gravity (and by default, the first target) it is
// centred on the region's height as before.
TEST(TargetChangeStanding, ALowShapeStandsOnItsRegionsFloor) {
  ff::TargetSpec flat = fftest::target(ff::TargetKind::Box, 800);
  flat.box_size = ff::Vec3(1.0f, 0.25f, 1.0f);
  const ff::TargetShape t = ff::buildTarget(flat, 8e-4, 0.01f);
  const ff::Vec3 lo(0.05f, 0.02f, 0.05f), hi(0.2f, 0.3f, 0.2f), box_lo(-1, -1, -1), box_hi(1, 1, 1);
  auto place = [&](const float g[3]) {
    return goalExtentY(ff::placeControlParticles(t, lo, hi, ff::ShapeMatchParams(), box_lo, box_hi,
                                                 ff::AdaptiveControl(), ff::standingFor(g)));
  };
  const float down[3] = {0.0f, -9.81f, 0.0f}, up[3] = {0.0f, 9.81f, 0.0f}, none[3] = {0.0f, 0.0f, 0.0f};
  const Extent d = place(down), u = place(up), z = place(none);
  const double h = d.hi - d.lo;
  std::printf(
      "  goal shape %.4g m tall in a region %.4g m tall: bottom %.4g (down), top %.4g (up), "
      "middle %.4g (none; region middle %.4g)\n",
      h, double(hi.y() - lo.y()), d.lo, u.hi, 0.5 * (z.lo + z.hi), 0.5 * double(lo.y() + hi.y()));
  ASSERT_LT(h, 0.5 * double(hi.y() - lo.y())) << "the box is not low for its region";
  EXPECT_NEAR(d.lo, lo.y(), 1e-5);
  EXPECT_NEAR(u.hi, hi.y(), 1e-5);
  EXPECT_NEAR(0.5 * (z.lo + z.hi), 0.5 * double(lo.y() + hi.y()), 1e-5);
  const ff::ControlSet first =
      ff::placeControlParticles(t, lo, hi, ff::ShapeMatchParams(), box_lo, box_hi, ff::AdaptiveControl());
  EXPECT_NEAR(goalExtentY(first).lo, z.lo, 1e-6) << "the default must place as before";
  // A shape at least as tall as its region is placed as before.
  const ff::Vec3 flat_hi(0.2f, 0.05f, 0.2f);
  const Extent tall = goalExtentY(ff::placeControlParticles(
      t, lo, flat_hi, ff::ShapeMatchParams(), box_lo, box_hi, ff::AdaptiveControl(), ff::standingFor(down)));
  const Extent tall0 = goalExtentY(ff::placeControlParticles(t, lo, flat_hi, ff::ShapeMatchParams(), box_lo,
                                                             box_hi, ff::AdaptiveControl()));
  EXPECT_EQ(tall.lo, tall0.lo);
}

// The first target is placed stretched over its fluid as before, but the
// standing anchor (ff_anchor.h) holds it where its rigid rest shape stands
// on the container's floor, not at the middle of the fluid column it was
// placed over: a box H tall standing on the floor has its centre H / 2 above
// it (H from the voxel layers: the highest and lowest voxel centres plus one
// voxel). Before, a lying letter was held 6-8 cm up with the fluid under it
// out of reach (docs/RESULTS.md, "The unseen set"). A shape that would be
// anchored within `reach` of the floor keeps its placed anchor.
TEST(TargetChangeStanding, TheFirstTargetIsAnchoredStandingOnTheFloor) {
  ff::TargetSpec flat = fftest::target(ff::TargetKind::Box, 800);
  flat.box_size = ff::Vec3(1.0f, 0.25f, 1.0f);
  const ff::TargetShape t = ff::buildTarget(flat, 8e-4, 0.01f);
  const ff::Vec3 lo(0.05f, 0.0f, 0.05f), hi(0.2f, 0.3f, 0.2f), box_lo(0, 0, 0), box_hi(0.3f, 0.5f, 0.3f);
  const float down[3] = {0.0f, -9.81f, 0.0f}, up[3] = {0.0f, 9.81f, 0.0f};
  auto place = [&](const float g[3], float reach = 0.03f) {
    ff::Standing s = ff::standingFor(g);
    s.unstretched = false;
    s.reach = reach;
    return ff::placeControlParticles(t, lo, hi, ff::ShapeMatchParams(), box_lo, box_hi, ff::AdaptiveControl(),
                                     s);
  };
  const ff::ControlSet d = place(down), u = place(up);
  const ff::ControlSet before =
      ff::placeControlParticles(t, lo, hi, ff::ShapeMatchParams(), box_lo, box_hi, ff::AdaptiveControl());
  const auto [mn, mx] =
      std::minmax_element(t.reference.begin(), t.reference.end(),
                          [](const ff::Vec3& a, const ff::Vec3& b) { return a.y() < b.y(); });
  const double height = double(mx->y()) - double(mn->y()) + double(t.grid.voxel);
  std::printf(
      "  box %.4g m tall over a region %.4g m tall: anchored at %.4g (down), %.4g (up), placed centre %.4g\n",
      height, double(hi.y() - lo.y()), double(d.anchor_y), double(u.anchor_y), double(before.anchor_y));
  ASSERT_LT(height, 0.5 * double(hi.y() - lo.y())) << "the box is not low for its region";
  EXPECT_NEAR(d.anchor_y, box_lo.y() + 0.5 * height, 1e-5);
  EXPECT_NEAR(u.anchor_y, box_hi.y() - 0.5 * height, 1e-5);
  // Placed as before (stretched, the capped shift), only the anchor moves.
  EXPECT_EQ(d.y, before.y);
  EXPECT_EQ(d.anchor_x, before.anchor_x);
  EXPECT_EQ(d.anchor_z, before.anchor_z);
  EXPECT_NEAR(before.anchor_y, 0.5 * double(lo.y() + hi.y()), 1e-5) << "without gravity: the placed centre";
  // Its placed centre is 0.15 - H / 2 = 0.128 m above where it stands: within
  // a reach of 0.13 m it keeps it, beyond a reach of 0.12 m it does not.
  EXPECT_EQ(place(down, 0.13f).anchor_y, before.anchor_y);
  EXPECT_NEAR(place(down, 0.12f).anchor_y, box_lo.y() + 0.5 * height, 1e-5);
}

}  // namespace
