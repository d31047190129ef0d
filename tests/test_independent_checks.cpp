// The metrics and the integrator of the OpenMP backend against values worked
// out independently here: closed forms (kinetic energy, free fall, the speed
// limit), brute-force sums written out again in double precision (the density
// at rest), and exact voxel counts (iou of fluid that covers everything, and
// of fluid far away). None of the expected numbers comes from the code.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "cpu/backend_cpu.h"
#include "grid/uniform_grid.h"
#include "metrics/iou.h"
#include "target/target_shape.h"

namespace {

// A container [0, 1]^3: every test's particles stay far from its walls, so
// no wall term acts.
ff::ContainerDesc bigBox() {
  ff::ContainerDesc c;
  c.min = ff::Vec3(0.0f, 0.0f, 0.0f);
  c.max = ff::Vec3(1.0f, 1.0f, 1.0f);
  return c;
}

// An n^3 lattice at spacing sp with its corner at (0.4, 0.4, 0.4), all with velocity v.
ff::FluidState lattice(int n, float sp, const float v[3]) {
  ff::FluidState s;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) s.push(0.4f + sp * i, 0.4f + sp * j, 0.4f + sp * k, v[0], v[1], v[2]);
  return s;
}

// Kinetic energy of a block moving as one: 1/2 N m |v|^2, and max speed |v|.
TEST(IndependentChecks, KineticEnergyOfAMovingBlock) {
  const ff::Params p;
  const float v[3] = {0.3f, -0.4f, 1.2f};  // |v| = 1.3 m/s
  const ff::FluidState s = lattice(6, p.fluid.restSpacing(), v);
  ff::CpuBackend cpu(2);
  cpu.init(p, bigBox(), s);
  cpu.buildGrid(), cpu.computeDensity();
  const ff::StepMetrics m = cpu.computeMetrics();
  const double want = 0.5 * 216 * double(p.fluid.particle_mass) * (0.09 + 0.16 + 1.44);
  EXPECT_NEAR(m.kinetic_energy, want, 1e-6 * want);
  EXPECT_NEAR(m.max_speed, 1.3, 1e-6);
}

// A block at rest: the density error is the mean of |rho_i - rho0| / rho0
// with rho_i = sum_j m W_poly6(|x_i - x_j|, h), summed here by brute force,
// and the compression the mean of max(rho_i - rho0, 0) / rho0. At the rest
// spacing nothing is compressed; at 0.8 of it the inside is.
TEST(IndependentChecks, DensityErrorOfABlockAtRest) {
  const ff::Params p;
  const float zero[3] = {0, 0, 0};
  for (const float squeeze : {1.0f, 0.8f}) {
    SCOPED_TRACE(squeeze);
    const ff::FluidState s = lattice(8, squeeze * p.fluid.restSpacing(), zero);
    ff::CpuBackend cpu(2);
    cpu.init(p, bigBox(), s);
    cpu.buildGrid(), cpu.computeDensity();
    const ff::StepMetrics m = cpu.computeMetrics();
    const double h = p.fluid.smoothing_radius, m0 = p.fluid.particle_mass, rho0 = p.fluid.rest_density;
    const double coef = 315.0 / (64.0 * M_PI * std::pow(h, 9));
    double err = 0.0, comp = 0.0, rho_max = 0.0;
    for (size_t i = 0; i < s.size(); ++i) {
      double rho = 0.0;
      for (size_t j = 0; j < s.size(); ++j) {
        const double dx = double(s.x[i]) - s.x[j], dy = double(s.y[i]) - s.y[j], dz = double(s.z[i]) - s.z[j];
        const double q = h * h - (dx * dx + dy * dy + dz * dz);
        if (q > 0) rho += m0 * coef * q * q * q;
      }
      err += std::fabs(rho - rho0) / rho0;
      comp += std::max(rho - rho0, 0.0) / rho0;
      rho_max = std::max(rho_max, rho);
    }
    err /= double(s.size()), comp /= double(s.size());
    ASSERT_GT(err, 0.05);  // the block's surface is half empty: a clear, non-zero error
    EXPECT_NEAR(m.density_error, err, 1e-5 * err);
    if (squeeze == 1.0f) {
      EXPECT_EQ(comp, 0.0);
      EXPECT_EQ(m.compression, 0.0);
    } else {
      ASSERT_GT(comp, 1e-3);  // the squeezed block's inside is compressed
      EXPECT_LT(comp, err);   // and the surface's deficit is not compression
      EXPECT_NEAR(m.compression, comp, 1e-5 * comp);
    }
    EXPECT_NEAR(m.max_density, rho_max, 1e-5 * rho_max);
  }
}

// A box target, the fluid's iou against it.
struct IouCase {
  ff::Params p;
  ff::TargetShape target;
  ff::RigidFrame frame;  // the target's rest centre at (0.5, 0.5, 0.5)
  IouCase() {
    ff::TargetSpec spec;
    spec.kind = ff::TargetKind::Box;
    spec.box_size = ff::Vec3(2.0f, 1.0f, 1.5f);
    target = ff::buildTarget(spec, 2e-4, p.fluid.restSpacing());
    for (int d = 0; d < 3; ++d) frame.c[d] = 0.5f;
  }
  double iou(const ff::FluidState& s) const {
    ff::UniformGrid g;
    g.build(s.size(), s.x.data(), s.y.data(), s.z.data(), p.fluid.smoothing_radius);
    // The padded grid's voxel counts (fluid beyond it: tests/test_fluid_shares.cpp).
    const ff::IouCounts k =
        ff::voxelIou(target, frame, 2, s.x.data(), s.y.data(), s.z.data(), g, p.fluid.particle_mass,
                     p.fluid.smoothing_radius, p.fluid.rest_density, 0.5f);
    return k.uni > 0 ? double(k.inter) / double(k.uni) : 0.0;
  }
};

// Fluid at the rest spacing over all of the padded grid and beyond: every
// voxel is a fluid voxel, so iou = (target voxels) / (padded grid voxels).
TEST(IndependentChecks, IouOfFluidCoveringEverythingIsTheTargetsShareOfTheGrid) {
  const IouCase c;
  const ff::VoxelGrid& g = c.target.grid;
  const float sp = c.p.fluid.restSpacing();
  ff::FluidState s;
  const float reach = 2.0f * c.p.fluid.smoothing_radius;  // beyond the padding by a kernel radius
  const float half[3] = {0.5f * g.nx * g.voxel + 2 * g.voxel + reach,
                         0.5f * g.ny * g.voxel + 2 * g.voxel + reach,
                         0.5f * g.nz * g.voxel + 2 * g.voxel + reach};
  for (float z = 0.5f - half[2]; z <= 0.5f + half[2]; z += sp)
    for (float y = 0.5f - half[1]; y <= 0.5f + half[1]; y += sp)
      for (float x = 0.5f - half[0]; x <= 0.5f + half[0]; x += sp) s.push(x, y, z, 0, 0, 0);
  const size_t inside = size_t(std::count(g.inside.begin(), g.inside.end(), uint8_t(1)));
  const double padded = double(g.nx + 4) * double(g.ny + 4) * double(g.nz + 4);
  ASSERT_GT(inside, 100u);
  EXPECT_DOUBLE_EQ(c.iou(s), double(inside) / padded);
}

// Fluid out of reach of the target's padded grid: no voxel in common, iou 0.
TEST(IndependentChecks, IouOfDisjointFluidIsZero) {
  const IouCase c;
  const float zero[3] = {0, 0, 0};
  ff::FluidState s = lattice(8, c.p.fluid.restSpacing(), zero);
  for (size_t i = 0; i < s.size(); ++i) s.x[i] -= 0.35f;  // x in [0.05, 0.1]; the target spans ~0.4 .. 0.6
  EXPECT_EQ(c.iou(s), 0.0);
  // The same fluid moved onto the target's centre does overlap it.
  for (size_t i = 0; i < s.size(); ++i)
    s.x[i] += 0.35f + 0.5f - 0.4f - 0.02f, s.y[i] += 0.08f, s.z[i] += 0.08f;
  EXPECT_GT(c.iou(s), 0.0);
}

// The OpenMP backend's steps on particles out of each other's and the walls'
// reach: gravity only.
void stepAlone(ff::CpuBackend& cpu, float dt) {
  cpu.buildGrid(), cpu.computeDensity(), cpu.computeForces(0.0f), cpu.solvePressure(dt), cpu.integrate(dt);
}

// Free fall: the integrator is symplectic Euler (v += g dt, then x += v dt),
// so after n steps v = n g dt and y = y0 + g dt^2 n (n + 1) / 2, which is the
// analytic path y0 + g t^2 / 2 shifted by g dt t / 2.
TEST(IndependentChecks, FreeFallFollowsTheAnalyticPath) {
  const ff::Params p;
  const float dt = p.fluid.time_step, g = p.fluid.gravity[1];
  ff::FluidState s;
  s.push(0.3f, 0.8f, 0.3f, 0, 0, 0);
  s.push(0.7f, 0.8f, 0.7f, 0, 0, 0);  // far from the first: no neighbour
  ff::CpuBackend cpu(2);
  cpu.init(p, bigBox(), s);
  const int n = 20;  // 0.08 s, 0.78 m/s: under the speed limit (max_step_fraction h / dt = 1.5 m/s)
  for (int i = 0; i < n; ++i) stepAlone(cpu, dt);
  const ff::FluidState& f = cpu.fluid().s;
  const double t = n * double(dt);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(f.vy[i], g * t, 1e-5 * std::fabs(g * t));
    EXPECT_NEAR(f.y[i], 0.8 + g * dt * dt * n * (n + 1) / 2.0, 2e-6);
    EXPECT_NEAR(f.y[i] - (0.8 + 0.5 * g * t * t), 0.5 * g * dt * t, 2e-6);
    EXPECT_EQ(f.vx[i], 0.0f);
    EXPECT_EQ(f.vz[i], 0.0f);
  }
}

// The speed limit: a particle faster than max_step_fraction h / dt leaves the
// step at exactly that speed, in the same direction.
TEST(IndependentChecks, VelocityIsClampedToTheStepLimit) {
  ff::Params p;
  p.fluid.gravity[1] = 0.0f;
  const float dt = p.fluid.time_step;
  const double vmax = double(p.fluid.max_step_fraction) * p.fluid.smoothing_radius / dt;
  ff::FluidState s;
  s.push(0.5f, 0.5f, 0.5f, 6.0f, -8.0f, 0.0f);  // 10 m/s
  ff::CpuBackend cpu(2);
  cpu.init(p, bigBox(), s);
  stepAlone(cpu, dt);
  const ff::FluidState& f = cpu.fluid().s;
  EXPECT_NEAR(std::hypot(f.vx[0], f.vy[0], f.vz[0]), vmax, 1e-6 * vmax);
  EXPECT_NEAR(f.vx[0], 0.6 * vmax, 1e-6 * vmax);
  EXPECT_NEAR(f.vy[0], -0.8 * vmax, 1e-6 * vmax);
  EXPECT_NEAR(f.x[0], 0.5 + 0.6 * vmax * dt, 1e-6);
  // The metric counts that one clamp, and the next metrics start again from 0.
  EXPECT_EQ(cpu.computeMetrics().velocity_clamps, 1);
  EXPECT_EQ(cpu.computeMetrics().velocity_clamps, 0);
}

// The grid build sorts the particles by cell: `id` must still name each
// particle, so every sorted slot holds the position and velocity that the
// particle of that id had before.
TEST(IndependentChecks, IdsFollowTheirParticlesThroughTheReorder) {
  const ff::Params p;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.2f, 0.8f);
  ff::FluidState s;
  for (int i = 0; i < 1000; ++i) s.push(u(rng), u(rng), u(rng), float(i), -float(i), 0.5f * float(i));
  ff::CpuBackend cpu(2);
  cpu.init(p, bigBox(), s);
  cpu.buildGrid();
  const ff::FluidState& f = cpu.fluid().s;
  ASSERT_EQ(f.size(), s.size());
  std::vector<uint32_t> ids = f.id;
  std::sort(ids.begin(), ids.end());
  std::vector<uint32_t> all(s.size());
  std::iota(all.begin(), all.end(), 0u);
  EXPECT_EQ(ids, all) << "the ids are not a permutation of 0 .. n-1";
  size_t moved = 0, wrong = 0;
  for (size_t k = 0; k < f.size(); ++k) {
    const uint32_t i = f.id[k];
    moved += i != k;
    wrong += f.x[k] != s.x[i] || f.y[k] != s.y[i] || f.z[k] != s.z[i] || f.vx[k] != float(i) ||
             f.vy[k] != -float(i) || f.vz[k] != 0.5f * float(i);
  }
  EXPECT_GT(moved, 500u) << "the grid did not reorder: the test shows nothing";
  EXPECT_EQ(wrong, 0u);
}

}  // namespace
