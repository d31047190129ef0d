// The anchor (kernels/common/ff_anchor.h, params.shape_matching.anchor):
// cluster shape matching has no restoring force for the whole control set's
// rigid motion, so the fluid feedback lifts a shape with the fluid rising
// through it and a tipped shape stays tipped. Checked through the
// controller's public phases against closed forms worked out here: the
// feedback's relaxation of the set's mean velocity (c = params.control.feedback
// per step) and the anchor's decay of a tilt (the fraction alpha of its sine
// per step).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "control/controller.h"
#include "core/params.h"
#include "test_scenes.h"

namespace {

constexpr float kSpacing = 0.01f;

// A column of 3 x 9 x 3 control particles, 1 cm apart, as one cluster, its
// rest shape upright around (0.1, 0.1, 0.1), placed turned by `tilt` radians
// about the x axis through its centre.
ff::ControlSet column(double tilt) {
  ff::ControlSet s;
  const double c[3] = {0.1, 0.1, 0.1};
  for (int i = -1; i <= 1; ++i)
    for (int j = -4; j <= 4; ++j)
      for (int k = -1; k <= 1; ++k) {
        const double r[3] = {i * kSpacing, j * kSpacing, k * kSpacing};
        s.x0.push_back(float(c[0] + r[0])), s.y0.push_back(float(c[1] + r[1])),
            s.z0.push_back(float(c[2] + r[2]));
        s.x.push_back(float(c[0] + r[0]));
        s.y.push_back(float(c[1] + r[1] * std::cos(tilt) - r[2] * std::sin(tilt)));
        s.z.push_back(float(c[2] + r[1] * std::sin(tilt) + r[2] * std::cos(tilt)));
      }
  const size_t n = s.x0.size();
  s.vx.assign(n, 0.0f), s.vy.assign(n, 0.0f), s.vz.assign(n, 0.0f);
  s.rest_cx = float(c[0]), s.rest_cy = float(c[1]), s.rest_cz = float(c[2]);
  s.particle_volume = kSpacing * kSpacing * kSpacing;
  fftest::setOneCluster(s);
  return s;
}

double meanY(const ff::ControlSet& s) {
  double m = 0;
  for (float y : s.y) m += y;
  return m / double(s.size());
}

// The tilt of the column: the angle (degrees) between its long axis (the
// mean of the top layer less the mean of the bottom layer) and +y.
double tiltDegrees(const ff::ControlSet& s) {
  double top[3] = {0, 0, 0}, bottom[3] = {0, 0, 0};
  for (size_t p = 0; p < s.size(); ++p) {
    double* acc = s.y0[p] > 0.1f + 3.5f * kSpacing   ? top
                  : s.y0[p] < 0.1f - 3.5f * kSpacing ? bottom
                                                     : nullptr;
    if (acc) acc[0] += s.x[p], acc[1] += s.y[p], acc[2] += s.z[p];
  }
  const double d[3] = {top[0] - bottom[0], top[1] - bottom[1], top[2] - bottom[2]};
  return std::acos(d[1] / std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])) * 180.0 / M_PI;
}

// Fluid 1 cm apart filling the column's neighbourhood, rising at `speed`.
struct RisingFluid {
  std::vector<float> x, y, z, vx, vy, vz;
  explicit RisingFluid(float speed) {
    for (int i = -5; i <= 5; ++i)
      for (int j = -8; j <= 8; ++j)
        for (int k = -5; k <= 5; ++k) {
          x.push_back(0.1f + i * kSpacing), y.push_back(0.1f + j * kSpacing),
              z.push_back(0.1f + k * kSpacing);
          vx.push_back(0.0f), vy.push_back(speed), vz.push_back(0.0f);
        }
  }
  ff::FluidView view() const {
    ff::FluidView f;
    f.n = x.size();
    f.x = x.data(), f.y = y.data(), f.z = z.data(), f.vx = vx.data(), f.vy = vy.data(), f.vz = vz.data();
    f.volume = kSpacing * kSpacing * kSpacing;
    return f;
  }
};

// The mean fluid velocity u_bar that `c`'s control particles read from fluid
// rising through them at 0.5 m/s (RisingFluid), their fields computed.
double risingFluidSpeed(ff::Controller& c) {
  const RisingFluid fluid(0.5f);
  if (!c.computeScale(fluid.view())) return 0.0;
  double ubar = 0;
  for (float u : c.fields().uy) ubar += u;
  return ubar / double(c.fields().uy.size());
}

// The paper's parameters with the anchor on or off.
ff::Params anchored(int anchor) {
  ff::Params p = ff::presetParams("paper");
  p.shape.anchor = anchor;
  return p;
}

// `c` with params p, gravity -9.81 m/s^2 along y, and the control set s.
void start(ff::Controller& c, const ff::Params& p, ff::ControlSet s) {
  const float g[3] = {0.0f, -9.81f, 0.0f};
  c.setParams(p.control, p.shape);
  c.setGravity(g);
  c.reset(std::move(s));
}

}  // namespace

// A control set standing in fluid that rises through it at 0.5 m/s. Without
// the anchor the feedback relaxes the set's mean velocity towards the mean
// fluid velocity ubar read around its particles, V_k = ubar (1 - (1 - c)^k)
// after k steps (the damping and one cluster's goals leave the mean
// unchanged), and the set climbs h sum_k V_k. With it the set stays at the
// height it was placed at.
TEST(Anchor, RisingFluidDoesNotLiftTheSetAsAWhole) {
  const int steps = 100;  // 0.5 s
  for (int anchor : {0, 1}) {
    const ff::Params p = anchored(anchor);
    ff::Controller c;
    start(c, p, column(0.0));
    const RisingFluid fluid(0.5f);
    ASSERT_TRUE(c.computeScale(fluid.view()));
    double ubar = 0;
    for (float u : c.fields().uy) ubar += u;
    ubar /= double(c.fields().uy.size());
    ASSERT_GT(ubar, 0.25);  // the kernel is mostly filled: most of 0.5 m/s
    const double y0 = meanY(c.set());
    for (int k = 0; k < steps; ++k) ASSERT_TRUE(c.shapeMatchStep());
    const double climb = meanY(c.set()) - y0;
    if (anchor) {
      EXPECT_NEAR(climb, 0.0, 1e-5) << "anchored: the set stays at its height";
    } else {
      const double cf = p.control.feedback, h = p.shape.time_step;
      double want = 0, v = 0;
      for (int k = 0; k < steps; ++k) v += cf * (ubar - v), want += h * v;
      ASSERT_GT(want, 0.05);  // the closed form climbs more than 5 cm
      EXPECT_NEAR(climb, want, 1e-3 * want) << "the feedback carries the whole set up";
    }
  }
}

// A column tipped by 20 degrees, with no fluid around it. Cluster shape
// matching keeps any rigid rotation: without the anchor it stays tipped. With
// it the tilt's sine falls by the fraction alpha per step, sin t_(k+1) =
// (1 - alpha) sin t_k while small: below 0.5 degrees after 30 steps.
TEST(Anchor, ATippedSetStandsBackUp) {
  const double tilt = 20.0 * M_PI / 180.0;
  for (int anchor : {0, 1}) {
    const ff::Params p = anchored(anchor);
    ff::Controller c;
    start(c, p, column(tilt));
    ASSERT_NEAR(tiltDegrees(c.set()), 20.0, 1e-3);
    const double y0 = meanY(c.set());
    const int steps = 30;
    for (int k = 0; k < steps; ++k) ASSERT_TRUE(c.shapeMatchStep());
    if (anchor) {
      double s = std::sin(tilt);
      for (int k = 0; k < steps; ++k) s *= 1.0 - p.shape.stiffness;
      ASSERT_LT(std::asin(s) * 180.0 / M_PI, 0.01);  // the closed form's bound
      EXPECT_LT(tiltDegrees(c.set()), 0.5) << "anchored: it stands back up";
      EXPECT_NEAR(meanY(c.set()), y0, 1e-5) << "turning about its centre keeps its height";
    } else {
      EXPECT_NEAR(tiltDegrees(c.set()), 20.0, 0.1) << "shape matching keeps a rigid rotation";
    }
  }
}

// FF_ANCHOR_STAND (anchor = 2), the water preset's: the set never rises above
// its anchor (where its rigid rest shape stands on the floor). Placed 1 mm
// above it, in fluid that rises through it at 0.5 m/s (which lifts the same
// set more than 5 cm without the anchor: the test above), its rigid velocity
// along up becomes -alpha / h times its height each step, whatever the
// feedback gave it: the height falls by the fraction alpha per step,
// 1 mm (1 - alpha)^k after k steps, until it is back at its anchor. And it
// stays upright: nothing turns it.
TEST(Anchor, StandingSetDoesNotClimbWithFluidRisingThroughIt) {
  const ff::Params p = anchored(2);
  ff::Controller c;
  ff::ControlSet s = column(0.0);
  const double above = 0.001;
  s.anchor_x = 0.1f, s.anchor_y = float(meanY(s) - above), s.anchor_z = 0.1f;
  start(c, p, s);
  const double ubar = risingFluidSpeed(c);
  ASSERT_GT(ubar, 0.25);
  const double anchor = s.anchor_y, a = p.shape.stiffness;
  // Once back at its anchor (to float precision), a step that finds it at or
  // below lets the feedback lift it by h c ubar, which the next steps take
  // away again: it stays within one such lift of its anchor.
  const double lift = p.shape.time_step * p.control.feedback * ubar;
  for (int k = 1; k <= 100; ++k) {
    ASSERT_TRUE(c.shapeMatchStep());
    const double height = meanY(c.set()) - anchor, want = above * std::pow(1.0 - a, k);
    SCOPED_TRACE(k);
    if (want > 0.1 * lift) {
      EXPECT_NEAR(height, want, 1e-7) << "back down to its anchor";
    } else {
      EXPECT_GT(height, -1e-7);
      EXPECT_LT(height, std::max(want, lift) + 1e-7) << "it never climbs off its anchor";
    }
  }
  ASSERT_LT(lift, 1e-4);  // 0.05 mm
  EXPECT_LT(tiltDegrees(c.set()), 0.01) << "and upright";
}

// Placed 20 cm below its anchor (a shape placed partly under the floor, which
// rises to stand on it as it forms), the standing anchor leaves it alone:
// with fluid rising through it, it climbs as without the anchor (the
// feedback's closed form, 5-20 cm in 0.5 s).
TEST(Anchor, StandingSetBelowItsAnchorRisesFreely) {
  const int steps = 100;
  const ff::Params p = anchored(2);
  ff::Controller c;
  ff::ControlSet s = column(0.0);
  s.anchor_x = 0.1f, s.anchor_y = 0.3f, s.anchor_z = 0.1f;
  start(c, p, s);
  const double ubar = risingFluidSpeed(c);
  const double y0 = meanY(c.set()), cf = p.control.feedback, h = p.shape.time_step;
  for (int k = 0; k < steps; ++k) ASSERT_TRUE(c.shapeMatchStep());
  double want = 0, v = 0;
  for (int k = 0; k < steps; ++k) v += cf * (ubar - v), want += h * v;
  ASSERT_GT(want, 0.05);
  ASSERT_LT(want, 0.2);  // stays below the anchor
  EXPECT_NEAR(meanY(c.set()) - y0, want, 1e-3 * want) << "below its anchor the set is free";
}

// A column tipped by 20 degrees: the standing anchor turns it back at the
// rate k = sqrt(g / l) at which an inverted pendulum of length l tips, l the
// column's centre's height above its lowest rest particle (4 cm): the tilt t
// follows t_(k+1) = t_k - k h sin t_k (k h sin t: the angle turned in a step
// at angular velocity k sin t), iterated here. Its height stays.
TEST(Anchor, StandingSetIsRightedAtTheRateItWouldTip) {
  const double tilt = 20.0 * M_PI / 180.0;
  const ff::Params p = anchored(2);
  ff::Controller c;
  start(c, p, column(tilt));
  const double y0 = meanY(c.set()), h = p.shape.time_step, k = std::sqrt(9.81 / (4.0 * kSpacing));
  double t = tilt;
  for (int step = 1; step <= 40; ++step) {
    ASSERT_TRUE(c.shapeMatchStep());
    t -= k * h * std::sin(t);
    if (step % 10 == 0) {
      SCOPED_TRACE(step);
      // First-order integration of the turn: within 5% of the closed form.
      EXPECT_NEAR(tiltDegrees(c.set()), t * 180.0 / M_PI, 0.05 * t * 180.0 / M_PI + 0.01);
    }
  }
  EXPECT_LT(t * 180.0 / M_PI, 5.0);  // the closed form rights most of it
  EXPECT_NEAR(meanY(c.set()), y0, 1e-5) << "turning about its centre keeps its height";
}
