// test_fluid_shares.cpp - the metrics iou (over all the fluid), filled,
// captured and stray (docs/METRICS.md) on hand-built cases whose answers are
// known exactly, and the controller's reach flags against a brute-force
// distance test.
//
// The cases pick the smoothing radius h = 0.9 voxel and rho0 = m / voxel^3:
// every fluid particle sits at a voxel centre, so a voxel centre holds density
// m W(0) = 2.15 rho0 when a particle sits on it and 0 otherwise (the next
// particle is a voxel away, beyond h). A voxel is then a fluid voxel exactly
// when a particle sits on it, and one particle's rest volume is one voxel.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "control/controller.h"
#include "cpu/backend_cpu.h"
#include "ff_rotation.h"
#include "grid/uniform_grid.h"
#include "metrics/fluid_shares.h"
#include "metrics/iou.h"
#include "target/target_shape.h"
#include "thin_target.h"

namespace {

constexpr float kVoxel = 0.01f, kMass = 0.0002f, kH = 0.9f * kVoxel;
constexpr float kRho0 = kMass / (kVoxel * kVoxel * kVoxel);
constexpr int kPad = 2;

// A box target of nx x ny x nz voxels, every voxel inside, origin at 0.
ff::TargetShape boxTarget(int nx, int ny, int nz) {
  ff::TargetShape t;
  ff::VoxelGrid& g = t.grid;
  g.voxel = kVoxel, g.nx = nx, g.ny = ny, g.nz = nz;
  g.origin = ff::Vec3(0.0f, 0.0f, 0.0f);
  g.inside.assign(size_t(nx) * ny * nz, 1);
  return t;
}

struct Fluid {
  std::vector<float> x, y, z;
  std::vector<uint32_t> id;
  void add(const ff_float3& p) {
    id.push_back(uint32_t(x.size()));
    x.push_back(p.x), y.push_back(p.y), z.push_back(p.z);
  }
  size_t size() const { return x.size(); }
};

// World position of the centre of target voxel (i, j, k) at the frame.
ff_float3 world(const ff::TargetShape& t, const ff::RigidFrame& f, int i, int j, int k) {
  const ff::Vec3 c = t.grid.center(i, j, k);
  return ff_mat3_mul_vec(ff_quat_to_mat3(f.q),
                         FF_F3(c.x() - f.rest_c[0], c.y() - f.rest_c[1], c.z() - f.rest_c[2])) +
         FF_F3(f.c[0], f.c[1], f.c[2]);
}

ff::StepMetrics measure(const ff::TargetShape& t, const ff::RigidFrame& f, const Fluid& fl,
                        const uint8_t* controlled, const uint8_t* reached,
                        const ff::ThinVoxels* thin = nullptr) {
  ff::UniformGrid grid;
  const float lo[3] = {-1.0f, -1.0f, -1.0f}, hi[3] = {1.0f, 1.0f, 1.0f};
  grid.build(fl.size(), fl.x.data(), fl.y.data(), fl.z.data(), kH, lo, hi);
  const ff::IouCounts c = ff::voxelIou(t, f, kPad, fl.x.data(), fl.y.data(), fl.z.data(), grid, kMass, kH,
                                       kRho0, 0.5f, thin ? thin->thin.data() : nullptr);
  const ff::FluidShares s = ff::fluidShares(t, f, kPad, fl.x.data(), fl.y.data(), fl.z.data(), fl.id.data(),
                                            fl.size(), controlled, reached);
  ff::StepMetrics m;
  ff::setShapeMetrics(m, c, s, ff::targetVoxelCount(t), ff::particleVoxels(kMass / kRho0, t),
                      thin ? thin->count : 0);
  return m;
}

// A frame turned 90 degrees about y and moved: the voxel lattice stays a lattice.
ff::RigidFrame turnedFrame(const ff::TargetShape& t) {
  ff::RigidFrame f;
  f.q = FF_Q(0.0f, std::sin(0.25f * FF_PI), 0.0f, std::cos(0.25f * FF_PI));
  const ff::Vec3 mid = t.grid.center(t.grid.nx / 2, t.grid.ny / 2, t.grid.nz / 2);
  f.rest_c[0] = mid.x(), f.rest_c[1] = mid.y(), f.rest_c[2] = mid.z();
  f.c[0] = 0.3f, f.c[1] = 0.1f, f.c[2] = 0.2f;
  return f;
}

// One particle at the centre of every voxel of the whole target grid.
Fluid filling(const ff::TargetShape& t, const ff::RigidFrame& f) {
  Fluid fl;
  for (int k = 0; k < t.grid.nz; ++k)
    for (int j = 0; j < t.grid.ny; ++j)
      for (int i = 0; i < t.grid.nx; ++i) fl.add(world(t, f, i, j, k));
  return fl;
}

TEST(FluidShares, FluidExactlyFillingTheTargetScoresOne) {
  const ff::TargetShape t = boxTarget(10, 8, 6);
  const ff::RigidFrame f = turnedFrame(t);
  Fluid fl = filling(t, f);
  const std::vector<uint8_t> reached(fl.size(), 1);
  const ff::StepMetrics m = measure(t, f, fl, nullptr, reached.data());
  EXPECT_DOUBLE_EQ(m.iou, 1.0);
  EXPECT_DOUBLE_EQ(m.filled, 1.0);
  EXPECT_DOUBLE_EQ(m.captured, 1.0);
  EXPECT_DOUBLE_EQ(m.stray, 0.0);
}

TEST(FluidShares, FluidFarFromTheTargetCountsAgainstTheIou) {
  // The target filled, plus a pool of 240 particles far beyond the padded
  // grid: 480 target voxels against 480 + 240 in the union.
  const ff::TargetShape t = boxTarget(10, 8, 6);
  const ff::RigidFrame f = turnedFrame(t);
  Fluid fl = filling(t, f);
  const size_t in_shape = fl.size();
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 10; ++i)
        fl.add(FF_F3(0.6f + kVoxel * float(i), 0.005f + kVoxel * float(j), 0.6f + kVoxel * float(k)));
  const size_t pool = fl.size() - in_shape;
  ASSERT_EQ(pool, 240u);
  // The pool is out of every control particle's reach.
  std::vector<uint8_t> reached(fl.size(), 1);
  for (size_t i = in_shape; i < fl.size(); ++i) reached[i] = 0;
  const ff::StepMetrics m = measure(t, f, fl, nullptr, reached.data());
  EXPECT_NEAR(m.iou, 480.0 / 720.0, 1e-6);  // the pool's volume: 240 voxels up to float rounding
  EXPECT_DOUBLE_EQ(m.filled, 1.0);
  EXPECT_NEAR(m.captured, 480.0 / 720.0, 1e-12);
  EXPECT_NEAR(m.stray, 240.0 / 720.0, 1e-12);
  // Only the controlled fluid counts for captured and stray; all of it for the iou.
  std::vector<uint8_t> controlled(fl.size(), 1);
  for (size_t i = in_shape; i < fl.size(); ++i) controlled[i] = 0;
  const ff::StepMetrics mc = measure(t, f, fl, controlled.data(), reached.data());
  EXPECT_DOUBLE_EQ(mc.captured, 1.0);
  EXPECT_DOUBLE_EQ(mc.stray, 0.0);
  EXPECT_NEAR(mc.iou, 480.0 / 720.0, 1e-6);
}

TEST(FluidShares, HalfFilledTargetAndFluidBesideIt) {
  // The lower half of a 10 x 8 x 6 box filled (240 of 480 voxels), and one
  // layer of 8 x 6 = 48 particles in the voxels just beside the box (inside
  // the padded grid): iou = 240 / (480 + 48).
  const ff::TargetShape t = boxTarget(10, 8, 6);
  const ff::RigidFrame f;  // identity: rest frame = world
  Fluid fl;
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 10; ++i) fl.add(world(t, f, i, j, k));
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 8; ++j) fl.add(world(t, f, -1, j, k));
  const std::vector<uint8_t> reached(fl.size(), 1);
  const ff::StepMetrics m = measure(t, f, fl, nullptr, reached.data());
  EXPECT_NEAR(m.filled, 240.0 / 480.0, 1e-12);
  EXPECT_NEAR(m.iou, 240.0 / 528.0, 1e-12);
  EXPECT_NEAR(m.captured, 240.0 / 288.0, 1e-12);
}

TEST(FluidShares, ReachFlagsMatchTheDistanceToTheNearestControlParticle) {
  // Control particles on a 6^3 lattice (spacing 0.01); fluid inside, in a
  // shell around it and in a blob 0.2 m away. reached must be exactly "some
  // control particle closer than the control radius".
  ff::ControlSet set;
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i) {
        set.x.push_back(0.1f + 0.01f * float(i)), set.y.push_back(0.1f + 0.01f * float(j));
        set.z.push_back(0.1f + 0.01f * float(k));
      }
  set.vx.assign(set.x.size(), 0.0f), set.vy = set.vx, set.vz = set.vx;
  set.x0 = set.x, set.y0 = set.y, set.z0 = set.z;
  set.particle_volume = 1e-6f;
  ff::ControlParams cp;
  cp.radius = 0.03f;
  ff::Controller ctl;
  ctl.setParams(cp, ff::ShapeMatchParams());
  ctl.reset(set);
  Fluid fl;
  for (int k = 0; k < 24; ++k)
    for (int j = 0; j < 24; ++j)
      for (int i = 0; i < 24; ++i)
        fl.add(FF_F3(0.04f + 0.0073f * float(i), 0.04f + 0.0073f * float(j), 0.04f + 0.0073f * float(k)));
  for (int i = 0; i < 50; ++i) fl.add(FF_F3(0.35f + 0.001f * float(i), 0.12f, 0.12f));
  std::vector<float> v(fl.size(), 0.0f), ax(fl.size(), 0.0f), ay = ax, az = ax;
  ff::FluidView view;
  view.n = fl.size(), view.x = fl.x.data(), view.y = fl.y.data(), view.z = fl.z.data();
  view.vx = v.data(), view.vy = v.data(), view.vz = v.data(), view.volume = 1e-7f;
  ASSERT_TRUE(ctl.computeScale(view));
  ASSERT_TRUE(ctl.addForces(view, 0.004f, ax.data(), ay.data(), az.data()));
  const std::vector<uint8_t>& reached = ctl.reached();
  ASSERT_EQ(reached.size(), fl.size());
  long in = 0, out = 0;
  for (size_t e = 0; e < fl.size(); ++e) {
    double best = 1e9;
    for (size_t c = 0; c < set.size(); ++c) {
      const double dx = double(set.x[c]) - fl.x[e], dy = double(set.y[c]) - fl.y[e],
                   dz = double(set.z[c]) - fl.z[e];
      best = std::min(best, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
    if (std::fabs(best - 0.03) < 1e-5) continue;  // on the radius itself: float rounding decides
    EXPECT_EQ(reached[e] != 0, best < 0.03) << "particle " << e << " at " << best << " m";
    (best < 0.03 ? in : out) += 1;
  }
  EXPECT_GT(in, 1000);
  EXPECT_GT(out, 1000);  // both kinds occur: the comparison means something
}

// filled_thin on a shape with a known thin part: a block 9 voxels wide with a
// rod one voxel thick and 8 long standing on it, in a grid with a border of
// outside voxels. The thin voxels (local thickness below the control radius,
// 3.06 voxels: the water preset's) are found by brute force from the
// definition (docs/METRICS.md): voxel v's thickness is the largest 2 R_c over
// the inside voxel centres c whose ball reaches v's centre, R_c = c's distance
// to the nearest outside voxel centre less half a voxel. The fluid fills the
// rod's lower half and the block's lower four layers; filled_thin must be the
// share of the brute-force thin voxels that hold a particle.
TEST(FluidShares, ThinPartsFilledCountsTheThinVoxelsThatHoldFluid) {
  const ff::TargetShape t = fftest::thinTarget(kVoxel);
  const ff::VoxelGrid& g = t.grid;
  auto block = fftest::thinTargetBlock;
  auto rod = fftest::thinTargetRod;
  const float radius = 3.06f * kVoxel;
  const std::vector<uint8_t> expect = fftest::bruteThinVoxels(g, radius);
  long thin_count = 0;
  for (uint8_t v : expect) thin_count += v;
  const ff::ThinVoxels thin = ff::metricsThinVoxels(t, radius);
  EXPECT_EQ(thin.count, thin_count);
  EXPECT_TRUE(thin.thin == expect) << "the thin voxels differ from the brute force";
  // What the brute force must find: the rod is thin, the block's middle is not.
  for (int j = 11; j <= 18; ++j) EXPECT_EQ(expect[g.index(6, j, 6)], 1) << "rod voxel y " << j;
  EXPECT_EQ(expect[g.index(6, 6, 6)], 0);
  ASSERT_GT(thin_count, 8);  // the rod and the block's edges and corners

  Fluid fl;
  long thin_filled = 0;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        if ((block(i, j, k) && j <= 5) || (rod(i, j, k) && j <= 14)) {
          fl.add(world(t, ff::RigidFrame(), i, j, k));
          thin_filled += expect[g.index(i, j, k)];
        }
  const std::vector<uint8_t> reached(fl.size(), 1);
  const ff::StepMetrics m = measure(t, ff::RigidFrame(), fl, nullptr, reached.data(), &thin);
  EXPECT_NEAR(m.filled_thin, double(thin_filled) / double(thin_count), 1e-12);
  EXPECT_GT(m.filled_thin, 0.0);
  EXPECT_LT(m.filled_thin, 1.0);
  // Without thin voxels it reads 1 (every thin voxel holds fluid).
  EXPECT_DOUBLE_EQ(measure(t, ff::RigidFrame(), fl, nullptr, reached.data()).filled_thin, 1.0);
}

// The CPU backend finds the thin voxels again when the control radius is
// edited while a target is active (the viewer's slider, a script's params
// action, the Python module); the OpenCL backend's twin is in
// test_opencl_phases.cpp.
TEST(FluidShares, FilledThinFollowsAControlRadiusEditedAfterTheTarget) {
  ff::CpuBackend cpu(2);
  fftest::expectFilledThinFollowsTheRadius(cpu);
}

}  // namespace
