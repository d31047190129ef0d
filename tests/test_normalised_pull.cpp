// test_normalised_pull.cpp - the normalised pull (params.control.normalise,
// docs/CONTROL_UNITS.md "Normalised pull"): the control's pull does not
// depend on the control particles' density, nor the result on the fluid's
// resolution.
//
// The resolution test's scene: a cube of fluid on the floor and a tall box
// target (1 x 2 x 1) of the fluid's volume over it, which the fluid must
// climb into.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>
#include <vector>

#include "control/controller.h"
#include "cpu/backend_cpu.h"
#include "sim/simulation.h"

namespace {

// side^3 fluid particles filling the same 0.063 m cube whatever `side` is
// (the particle mass and smoothing radius scaled with the spacing); `size`
// scales the whole scene (container, cube, spacing) as a user would.
ff::SceneDesc tallBoxScene(int normalise, int control_count, int side, const char* preset = "paper",
                           double size = 1.0) {
  ff::SceneDesc s;
  s.source = "test";
  s.params = ff::presetParams(preset);
  s.params.control.normalise = normalise;
  const double ref = 10.0, scale = size * ref / double(side);  // spacing relative to the 10^3 block's
  s.params.fluid.particle_mass *= float(scale * scale * scale);
  s.params.fluid.smoothing_radius *= float(scale);
  s.container.min = ff::Vec3(0, 0, 0);
  s.container.max = ff::Vec3(float(0.2 * size), float(0.25 * size), float(0.2 * size));
  ff::FluidBlockDesc block;
  const float extent = float(side) * s.params.fluid.restSpacing(), mid = float(0.1 * size);
  block.origin = ff::Vec3(mid - 0.5f * extent, 0.0f, mid - 0.5f * extent);
  block.dims[0] = block.dims[1] = block.dims[2] = side;
  s.fluid = {block};
  ff::TargetSpec box;
  box.kind = ff::TargetKind::Box;
  box.box_size = ff::Vec3(1.0f, 2.0f, 1.0f);
  box.control_count = control_count;
  s.schedule.push_back({0.0, box});
  return s;
}

struct End {
  double iou = 0.0, filled = 0.0;
  long control = 0;
};

End run(const ff::SceneDesc& scene, double seconds) {
  ff::Simulation sim(scene, std::make_unique<ff::CpuBackend>(2));
  const int steps = int(seconds / double(sim.scene().params.fluid.time_step) + 0.5);
  for (int i = 0; i < steps; ++i) sim.step();
  return {sim.metrics().iou, sim.metrics().filled, sim.metrics().control_count};
}

// Müller et al. 2003's poly6, written out again (not taken from kernels/common).
double poly6(double d, double r) {
  if (d >= r) return 0.0;
  const double q = r * r - d * d;
  return 315.0 / (64.0 * M_PI * std::pow(r, 9)) * q * q * q;
}

// Control particles filling the cube [0, L]^3 on a lattice of spacing d,
// empty (no fluid around them: s = 1), at rest, in one cluster.
ff::ControlSet cubeLattice(double L, double d) {
  ff::ControlSet s;
  const int n = int(std::lround(L / d));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        s.x.push_back(float((i + 0.5) * d)), s.y.push_back(float((j + 0.5) * d)),
            s.z.push_back(float((k + 0.5) * d));
        s.vx.push_back(0.0f), s.vy.push_back(0.0f), s.vz.push_back(0.0f);
      }
  s.x0 = s.x, s.y0 = s.y, s.z0 = s.z;
  const size_t m = s.x.size();
  ff::Clusters& c = s.clusters;
  c.start = {0, uint32_t(m)};
  for (size_t i = 0; i < m; ++i) c.members.push_back(uint32_t(i)), c.of.push_back(0);
  for (size_t i = 0; i <= m; ++i) c.of_start.push_back(uint32_t(i));
  s.rest_cx = s.rest_cy = s.rest_cz = float(0.5 * L);
  c.rest_cx = {s.rest_cx}, c.rest_cy = {s.rest_cy}, c.rest_cz = {s.rest_cz};
  s.particle_volume = float(d * d * d);
  return s;
}

// The x accelerations the controller gives fluid particles at (x, L/2, L/2)
// for each x in xs, the control particles on a lattice of spacing d.
std::vector<double> pullAlongX(const ff::Params& p, double L, double d, const std::vector<double>& xs) {
  ff::Controller c;
  c.setParams(p.control, p.shape);
  c.reset(cubeLattice(L, d));
  std::vector<float> x, y, z, v(xs.size(), 0.0f);
  for (double xi : xs) x.push_back(float(xi)), y.push_back(float(0.5 * L)), z.push_back(float(0.5 * L));
  ff::FluidView f;
  f.n = xs.size();
  f.x = x.data(), f.y = y.data(), f.z = z.data(), f.vx = v.data(), f.vy = v.data(), f.vz = v.data();
  f.volume = 1e-12f;  // no fluid to speak of: every control particle is empty (s = 1)
  std::vector<float> ax(xs.size(), 0.0f), ay = ax, az = ax;
  EXPECT_TRUE(c.computeScale(f));
  EXPECT_TRUE(c.addForces(f, 0.004f, ax.data(), ay.data(), az.data()));
  return std::vector<double>(ax.begin(), ax.end());
}

// The continuum limit of the normalised attraction on x, independently: with
// s = 1, g attraction_g (int (p - x)/|p - x| W dV) / max(int W dV, 1/2) over
// the cube, by the midpoint rule on a grid of r/40.
double continuumPull(const ff::Params& p, double L, double xe) {
  const double r = p.control.radius, h = r / 40.0, g = 9.81;
  const double ye = 0.5 * L, ze = 0.5 * L;
  double wsum = 0.0, fx = 0.0;
  for (double px = std::max(0.0, xe - r) + 0.5 * h; px < std::min(L, xe + r); px += h)
    for (double py = ye - r + 0.5 * h; py < ye + r; py += h)
      for (double pz = ze - r + 0.5 * h; pz < ze + r; pz += h) {
        const double dx = px - xe, dy = py - ye, dz = pz - ze, dd = std::sqrt(dx * dx + dy * dy + dz * dz);
        const double w = poly6(dd, r) * h * h * h;
        wsum += w;
        if (dd > 0.0) fx += dx / dd * w;
      }
  return double(p.control.attraction_g) * g * fx / std::max(wsum, 0.5);
}

// A control set of 1/8 the density pulls the same fluid into the same shape:
// the normalised attraction on fluid around a cube of empty control
// particles, from a lattice of spacing r/4 and one of r/2 (1/8 the
// particles), both match the continuum value within 0.1 of the most
// attraction (g attraction_g). That bound is the midpoint rule's: the coarse
// lattice samples the kernel's support (radius r) with about 33 points, and
// the lattice sum of the kernel alone misses its integral by a few percent
// there (checked below), which the ratio in the normalisation can double.
// The paper's formulation, the same sums unnormalised, pulls 8 times more
// weakly from the sparse set.
TEST(NormalisedPull, OneEighthTheControlDensityPullsAlike) {
  ff::Params p = ff::presetParams("paper");
  p.control.normalise = 1;
  p.control.gravity_compensation = 0.0f, p.control.recapture = 0.0f;
  const double r = p.control.radius, L = 0.09, dense = r / 4.0, sparse = r / 2.0;
  // Outside the face x = L, on it, and inside (the attraction points into the cube: -x).
  const std::vector<double> xs = {L + 0.02, L + 0.01, L, L - 0.01, L - 0.02};
  const std::vector<double> a_dense = pullAlongX(p, L, dense, xs), a_sparse = pullAlongX(p, L, sparse, xs);
  const double most = double(p.control.attraction_g) * 9.81;
  for (size_t k = 0; k < xs.size(); ++k) {
    const double want = continuumPull(p, L, xs[k]);
    std::printf("x - L = %+.3f: dense %.3f sparse %.3f continuum %.3f m/s^2\n", xs[k] - L, a_dense[k],
                a_sparse[k], want);
    EXPECT_NEAR(a_dense[k], want, 0.1 * most) << "x - L = " << xs[k] - L;
    EXPECT_NEAR(a_sparse[k], want, 0.1 * most) << "x - L = " << xs[k] - L;
  }
  EXPECT_LT(a_dense[2], -0.2 * most);  // at the surface the pull is strong: the comparison means something
  // The bound's premise: the coarse lattice's kernel sum at the surface is within a few percent of 1/2.
  double wsum = 0.0;
  const ff::ControlSet cs = cubeLattice(L, sparse);
  for (size_t i = 0; i < cs.size(); ++i)
    wsum += cs.particle_volume * poly6(std::sqrt(std::pow(cs.x[i] - L, 2) + std::pow(cs.y[i] - 0.5 * L, 2) +
                                                 std::pow(cs.z[i] - 0.5 * L, 2)),
                                       r);
  EXPECT_NEAR(wsum, 0.5, 0.05);
  // The paper's formulation: w_a sum_i s_i dir W, about 8 times weaker from the sparse set.
  p.control.normalise = 0;
  const std::vector<double> raw_dense = pullAlongX(p, L, dense, xs),
                            raw_sparse = pullAlongX(p, L, sparse, xs);
  std::printf("paper's: at the surface dense %.3f sparse %.3f m/s^2\n", raw_dense[2], raw_sparse[2]);
  EXPECT_GT(raw_dense[2] / raw_sparse[2], 4.0);
}

// At twice the fluid particles (in the same volume), the iou at 2 s is within 0.05.
TEST(NormalisedPull, TwiceTheParticlesGiveTheSameIou) {
  const double t = 2.0;
  const End coarse = run(tallBoxScene(1, 1024, 8), t), fine = run(tallBoxScene(1, 1024, 10), t);
  std::printf("8^3: iou %.3f filled %.3f; 10^3: iou %.3f filled %.3f\n", coarse.iou, coarse.filled, fine.iou,
              fine.filled);
  EXPECT_GT(fine.iou, 0.6);
  EXPECT_NEAR(fine.iou, coarse.iou, 0.05);
}

// The same on the default (water) preset as it comes, normalised pull
// included: 512 and 1000 fluid particles (1.95 times as many) in the same
// volume give the same iou at 2 s within 0.05 (issue 10's resolution test).
TEST(NormalisedPull, TwiceTheParticlesGiveTheSameIouOnTheDefaultPreset) {
  const double t = 2.0;
  const int normalise = ff::presetParams("default").control.normalise;
  EXPECT_EQ(normalise, 1);  // the default preset's pull is the normalised one
  const End coarse = run(tallBoxScene(normalise, 1024, 8, "default"), t),
            fine = run(tallBoxScene(normalise, 1024, 10, "default"), t);
  std::printf("default preset, 8^3: iou %.3f filled %.3f; 10^3: iou %.3f filled %.3f\n", coarse.iou,
              coarse.filled, fine.iou, fine.filled);
  EXPECT_GT(fine.iou, 0.6);
  EXPECT_NEAR(fine.iou, coarse.iou, 0.05);
}

// iou after every step of a run: (time, iou).
std::vector<std::pair<double, double>> iouCurve(const ff::SceneDesc& scene, double seconds,
                                                long* controls = nullptr) {
  ff::Simulation sim(scene, std::make_unique<ff::CpuBackend>(2));
  if (controls) *controls = long(sim.target()->reference.size());
  const double dt = double(sim.scene().params.fluid.time_step);
  std::vector<std::pair<double, double>> out;
  for (int i = 0, steps = int(seconds / dt + 0.5); i < steps; ++i) {
    sim.step();
    out.push_back({(i + 1) * dt, sim.metrics().iou});
  }
  return out;
}

// The curve's iou at time t, linear between steps.
double iouAt(const std::vector<std::pair<double, double>>& curve, double t) {
  for (size_t k = 1; k < curve.size(); ++k)
    if (curve[k].first >= t) {
      const auto &a = curve[k - 1], &b = curve[k];
      return a.second + (b.second - a.second) * (t - a.first) / (b.first - a.first);
    }
  return curve.back().second;
}

// The same scene twice as large (container, cube and particle spacing; the
// same particle and control counts) on the default preset gives the same iou
// curve within 0.05 (issue 10's scale goal), over every step of 1.5 s. Under
// the same gravity a scene c times as large falls on a clock sqrt(c) times
// slower (its time scale is sqrt(L / g)), so the large scene's curve is read
// at t sqrt(2). This holds only if every control constant is relative to
// the scene: the reach to the control spacing (with the radius in metres the
// large scene's 128 control particles reach half as far relative to the
// shape), the pull to g and not to the control particles' density, and the
// shape-matching clock to the fall time sqrt(r / g) (in seconds, the control
// set of the large scene moves as far in the same time, twice as fast, and
// its fluid overshoots while the small one's does not).
TEST(NormalisedPull, TwiceTheSizeGivesTheSameIouCurveOnTheDefaultPreset) {
  const double t = 1.5, c = 2.0, clock = std::sqrt(c);
  const auto small = iouCurve(tallBoxScene(1, 128, 8, "default"), t),
             large = iouCurve(tallBoxScene(1, 128, 8, "default", c), t * clock);
  double worst = 0.0, when = 0.0;
  for (const auto& [ts, iou] : small) {
    const double d = std::fabs(iouAt(large, ts * clock) - iou);
    if (d > worst) worst = d, when = ts;
  }
  std::printf(
      "default preset, size 1 / size 2 at %.1f s: iou %.3f / %.3f; largest difference %.3f at %.3f s\n", t,
      small.back().second, large.back().second, worst, when);
  EXPECT_GT(small.back().second, 0.6);
  EXPECT_LT(worst, 0.05);
}

// Issue 10's resolution test with the derived control count (no
// control_count): 1728 and 3375 fluid particles (12^3 and 15^3, 1.95 times
// as many) in the same volume give the same control set, the same iou at 2 s
// within 0.05 (the test), and the same iou curve within 0.05 over
// every step after the first climb. The count follows the scene's fluid
// volume (control.auto_count), not its particle count. The preset's 3226 is
// the count of 12,000 fluid particles at the default voxel, too many for a
// test, so it is set to the 12^3 block's, ceil(1728 / 1.55^3) = 465: 1728
// particles keep one control particle per 1.55 fluid spacings, 3375 the
// same set.
//
// Why not every step: in the first climb (to about 0.15 s; the iou rises from
// 0.55 to its first peak, about 0.88 at 0.12 s) the pull stretches the
// tension-free liquid into particle layers 1.4-2 spacings apart, and the
// iou's 0.5 rho0 voxel test flips voxels by where a voxel centre falls
// between two layers, which depends on the spacing and not on the control
// (docs/PERFORMANCE.md, "Why the first climb differs between resolutions";
// the bulk's mean height and speed agree within 0.04 mm and 0.002 m/s).
// Measured on 834d219 (2026-11-30; this test, and bench/tall_box_resolution.py's
// scenes for the other counts), the largest difference over every step is
// 0.049 at 0.08 s (12^3 / 15^3; 0.045 at 16^3, 0.085 at 24^3): the noise
// floor of this 550-voxel target, not the mechanism. From 0.15 s on it is
// 0.025 at 0.18 s (0.024 at 16^3, 0.035 at 24^3). The derivation before
// auto_count (one control particle per 1.55 fluid spacings at any count:
// 504 against 1024 control particles, a radius and a shape-matching step 0.8
// times as large) leaves the coarse curve by 0.197 at 0.15 s in this test
// (auto_count 0 here, a temporary change; 0.11 still at 0.33 s), so the
// window keeps what the test guards. At 2 s both counts have filled the box
// (iou 1.000) with either derivation: the reading at 2 s alone would
// not see the derivation.
TEST(NormalisedPull, TwiceTheParticlesGiveTheSameIouCurveWithTheDerivedCount) {
  const double t = 2.0, climb = 0.15;
  auto scene = [](int side) {
    ff::SceneDesc s = tallBoxScene(1, 0, side, "default");
    s.params.control.auto_count = int(std::ceil(1728.0 / (1.55 * 1.55 * 1.55)));
    return s;
  };
  long controls[2] = {0, 0};
  const auto coarse = iouCurve(scene(12), t, &controls[0]), fine = iouCurve(scene(15), t, &controls[1]);
  double worst = 0.0, when = 0.0, climb_worst = 0.0, climb_when = 0.0;
  for (const auto& [tc, iou] : coarse) {
    const double d = std::fabs(iouAt(fine, tc) - iou);
    if (tc < climb && d > climb_worst) climb_worst = d, climb_when = tc;
    if (tc >= climb && d > worst) worst = d, when = tc;
  }
  const double at_end = std::fabs(fine.back().second - coarse.back().second);
  std::printf(
      "default preset, derived count, 12^3 / 15^3: %ld / %ld control particles, iou at %.1f s %.3f / %.3f; "
      "largest difference from %.2f s on %.3f at %.3f s (in the first climb, not asserted: %.3f at %.3f s)\n",
      controls[0], controls[1], t, coarse.back().second, fine.back().second, climb, worst, when, climb_worst,
      climb_when);
  EXPECT_NEAR(double(controls[1]) / double(controls[0]), 1.0, 0.05);
  EXPECT_GT(coarse.back().second, 0.9);
  EXPECT_LT(at_end, 0.05);
  EXPECT_LT(worst, 0.05);
}

}  // namespace
