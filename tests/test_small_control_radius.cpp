// A control radius of about one control spacing or less (issue 10, item 7:
// `control.radius_spacings` x0.25 = 0.765 spacings on the water bunny): the
// coverage one spacing outside the shape, which scales the gravity the
// control carries and the recapture's strength (ff_control_held), is 0 there
// (the kernel does not reach that far) and must not come out as rounding
// noise of either sign (docs/CONTROL_UNITS.md, "Radius in control spacings").
// The expected coverage is integrated here in double precision over the
// half-space from the poly6 kernel written out again, not from kernels/common.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "cpu/backend_cpu.h"
#include "ff_control.h"
#include "ff_sph.h"
#include "sim/simulation.h"
#include "test_meshes.h"

namespace {

// The share of the poly6 kernel of radius h (315 / (64 pi h^9) (h^2 - r^2)^3)
// beyond a plane at distance d from its centre: the midpoint rule over slices
// z in [d, h] and rings rho in [0, sqrt(h^2 - z^2)], n points each.
double poly6ShareBeyond(double d, double h, int n = 400) {
  if (d >= h) return 0.0;
  const double coef = 315.0 / (64.0 * M_PI * std::pow(h, 9));
  double sum = 0.0;
  const double dz = (h - d) / n;
  for (int i = 0; i < n; ++i) {
    const double z = d + (i + 0.5) * dz, rmax = std::sqrt(h * h - z * z), dr = rmax / n;
    for (int j = 0; j < n; ++j) {
      const double rho = (j + 0.5) * dr, q = h * h - z * z - rho * rho;
      sum += 2.0 * M_PI * rho * dr * dz * coef * q * q * q;
    }
  }
  return sum;
}

TEST(SmallControlRadius, FullCoverageIsExactAndNeverNegativeNearOneSpacing) {
  // The water bunny's control particle volume (3228 derived control
  // particles, spacing 9.764 mm) and two others; radii from half a spacing to
  // the water preset's 3.06 spacings.
  for (const float v_c : {9.30968e-07f, 9.3838e-07f, 1.0e-06f}) {
    const double s = std::cbrt(double(v_c));
    for (const double k :
         {0.5, 0.765, 0.9, 1.0, 1.005, 1.01, 1.02, 1.03, 1.05, 1.1, 1.2, 1.3, 1.53, 2.0, 3.06}) {
      const float r = float(k * s);
      const float got = ff_control_full_coverage(v_c, r, ff_poly6_coef(r));
      const double want = poly6ShareBeyond(double(std::cbrt(v_c)), double(r));
      SCOPED_TRACE(testing::Message() << "v_c " << v_c << ", radius " << k << " spacings");
      EXPECT_GE(got, 0.0f);
      if (want == 0.0)
        EXPECT_EQ(got, 0.0f);  // the kernel does not reach one spacing out
      else
        EXPECT_NEAR(double(got), want, 2e-5 * want + 1e-12);
    }
  }
}

TEST(SmallControlRadius, HeldShareStaysInZeroToOne) {
  // With no coverage one spacing out, fluid in reach is carried whole (the
  // limit of wsum v_c / full_at as full_at -> 0+), fluid out of reach not at all.
  EXPECT_EQ(ff_control_held(1e-3f, 1e-6f, 0.0f), 1.0f);
  EXPECT_EQ(ff_control_held(0.0f, 1e-6f, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(ff_control_held(1e5f, 1e-6f, 0.15f), 0.1f / 0.15f);
  EXPECT_EQ(ff_control_held(1e6f, 1e-6f, 0.15f), 1.0f);
}

// The stability sweep's run that exploded: the water bunny at 0.765 control
// spacings clamped all 23,991 particle substeps and reached 25 m/s in its
// first 2 steps. Now no particle needs the velocity limit and none moves
// faster than the sweep's explosion speed (2 sqrt(2 g L), 5.60 m/s).
TEST(SmallControlRadius, WaterBunnyAtQuarterRadiusNeedsNoClamp) {
  FF_SCENE_MESHES_OR_SKIP();
  ff::SceneDesc scene = ff::loadScene(FF_SOURCE_DIR "/scenes/water/bunny.json");
  ASSERT_EQ(scene.preset, "water");
  scene.params.control.radius_spacings *= 0.25f;
  ff::Simulation sim(scene, std::make_unique<ff::CpuBackend>(2));
  for (int i = 0; i < 3; ++i) {
    sim.step();  // throws on a NaN
    EXPECT_EQ(sim.metrics().velocity_clamps, 0) << "step " << i + 1;
    EXPECT_LT(sim.metrics().max_speed, 2.0 * std::sqrt(2.0 * 9.81 * 0.4)) << "step " << i + 1;
  }
}

}  // namespace
