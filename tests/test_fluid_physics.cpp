// Whole-fluid checks on the OpenMP backend: the wall boundary has no density
// deficiency, a resting column is hydrostatic, and nothing leaves the box.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cpu/backend_cpu.h"
#include "ff_sph.h"
#include "sim/simulation.h"
#include "test_scenes.h"

namespace {

TEST(FluidPhysics, NoDensityDeficiencyAtTheWalls) {
  // A lattice at rest spacing filling the box exactly: with the analytic wall
  // term, particles touching a wall (and a corner) see the interior density.
  ff::Params p;
  const float sp = p.fluid.restSpacing();
  const int n = 12;
  ff::SceneDesc s = fftest::blockScene(ff::Vec3(n * sp, n * sp, n * sp), ff::Vec3(0, 0, 0), n, n, n);
  auto backend = std::make_unique<ff::CpuBackend>();
  ff::CpuBackend* cpu = backend.get();
  ff::Simulation sim(s, std::move(backend));
  cpu->buildGrid();
  cpu->computeDensity();
  const auto& f = cpu->fluid();
  double interior = 0, wall = 0, corner = 0;
  int ni = 0, nw = 0, nc = 0;
  for (size_t i = 0; i < f.size(); ++i) {
    int ix = int(f.s.x[i] / sp), iy = int(f.s.y[i] / sp), iz = int(f.s.z[i] / sp);
    auto inner = [&](int a) { return a >= 3 && a < n - 3; };
    if (inner(ix) && inner(iy) && inner(iz)) interior += f.rho[i], ++ni;
    if (ix == 0 && inner(iy) && inner(iz)) wall += f.rho[i], ++nw;
    if (ix == 0 && iy == 0 && iz == 0) corner += f.rho[i], ++nc;
  }
  interior /= ni, wall /= nw, corner /= nc;
  // The same particles without any wall term: the deficiency we remove.
  double bare = 0;
  {
    const float h = p.fluid.smoothing_radius, c = ff_poly6_coef(h);
    int nb = 0;
    for (size_t i = 0; i < f.size(); ++i) {
      int ix = int(f.s.x[i] / sp), iy = int(f.s.y[i] / sp), iz = int(f.s.z[i] / sp);
      if (!(ix == 0 && iy >= 3 && iy < n - 3 && iz >= 3 && iz < n - 3)) continue;
      double sum = 0;
      for (size_t j = 0; j < f.size(); ++j) {
        const float dx = f.s.x[i] - f.s.x[j], dy = f.s.y[i] - f.s.y[j], dz = f.s.z[i] - f.s.z[j];
        sum += p.fluid.particle_mass * ff_poly6(dx * dx + dy * dy + dz * dz, h * h, c);
      }
      bare += sum, ++nb;
    }
    bare /= nb;
  }
  // Without it the wall layer misses the kernel share beyond the wall at
  // d = spacing / 2, about 17%.
  EXPECT_LT(bare / interior, 0.88) << "bare wall layer " << bare;
  // The analytic wall integrates the kernel over a continuous half-space; the
  // lattice beyond a real wall would be discrete, which differs by a few
  // percent (0.0032 m from the wall the first mirror layer sits at 0.0095 m,
  // where poly6 is steep); 5% is well below the 17% it removes.
  EXPECT_NEAR(wall / interior, 1.0, 0.05) << "interior " << interior << " wall " << wall;
  EXPECT_NEAR(corner / interior, 1.0, 0.08) << "corner " << corner;
}

TEST(FluidPhysics, RestingColumnIsHydrostatic) {
  // In equilibrium the pressure at height y carries the weight of the fluid
  // above it: rho g (H - y) = g M(>y) / A.
  //
  // Discretisation: Mueller et al.'s symmetric force -sum_j m_j (p_i + p_j) /
  // (2 rho_j) grad W equals -(1/2) grad p in the continuum (the p_i half sums
  // to ~0), and on a neighbourhood of h = 1.9 spacings the gradient is further
  // scaled by the kernel-gradient moment M_yy = sum_j V_j (y_j - y_i) dW_ij/dy_i
  // (1 in the continuum). So the solver's equilibrium is
  // p(y) = 2 g M(>y) / (A M_yy): we measure M_yy on the settled particles,
  // independently of the pressure values, and check that.
  //
  // Stiffness: the paper's k = 0.5 gives a sound speed of sqrt(k) = 0.7 m/s,
  // and under g = 9.81 a column compresses by rho0 g H / k: 300% for 0.15 m,
  // far outside the regime where SPH discretises a liquid (we measured a
  // 0.19 m column crushed to 0.05 m). The law holds for any g, so the test
  // keeps the paper's k, h and mass and uses g = 0.3 m/s^2, where the
  // 0.126 m column compresses by rho0 g H / k = 7.6% at the bottom.
  // Tolerance: 10% of the bottom pressure. The pressure is read as a slab
  // average of SPH values that are smoothed over h = 0.012 m, about a tenth
  // of the column, and the fluid density varies by 7.6% over the height.
  // Statics do not depend on viscosity, so the test settles with a larger one.
  ff::Params p;
  p.fluid.viscosity = 2.0f;
  p.fluid.gravity[1] = -0.3f;
  const float sp = p.fluid.restSpacing();
  const int nx = 8, ny = 20, nz = 8;
  ff::SceneDesc s = fftest::blockScene(ff::Vec3(nx * sp, 0.3f, nz * sp), ff::Vec3(0, 0, 0), nx, ny, nz);
  s.params = p;
  auto backend = std::make_unique<ff::CpuBackend>();
  ff::CpuBackend* cpu = backend.get();
  ff::Simulation sim(s, std::move(backend));
  // Settle: step with extra velocity damping (statics only, not dynamics).
  for (int i = 0; i < 600; ++i) {
    sim.step();
    auto& st = cpu->fluid().s;
    for (size_t k = 0; k < st.size(); ++k) st.vx[k] *= 0.97f, st.vy[k] *= 0.97f, st.vz[k] *= 0.97f;
  }
  cpu->buildGrid();
  cpu->computeDensity();
  const auto& f = cpu->fluid();
  ASSERT_LT(sim.metrics().max_speed, 0.02);
  const double g = -p.fluid.gravity[1], area = double(nx * sp) * double(nz * sp), m = p.fluid.particle_mass;
  float top = 0;
  for (float y : f.s.y) top = std::max(top, y);
  const float h = p.fluid.smoothing_radius;
  // Kernel-gradient moment over the bulk of the settled column.
  const float coef = ff_spiky_grad_coef(h);
  double myy = 0;
  int nm = 0;
  for (size_t i = 0; i < f.size(); ++i) {
    if (f.s.y[i] < 1.5f * h || f.s.y[i] > top - 1.5f * h) continue;
    if (f.s.x[i] < h || f.s.x[i] > nx * sp - h || f.s.z[i] < h || f.s.z[i] > nz * sp - h) continue;
    double sum = 0;
    for (size_t j = 0; j < f.size(); ++j) {
      const float dx = f.s.x[i] - f.s.x[j], dy = f.s.y[i] - f.s.y[j], dz = f.s.z[i] - f.s.z[j];
      const float r = std::sqrt(dx * dx + dy * dy + dz * dz);
      const float gfac = ff_spiky_grad_factor(r, h, coef);  // grad W = -gfac (x_i - x_j)
      sum += double(m / f.rho[j]) * double(-dy) * double(-gfac * dy);
    }
    myy += sum, ++nm;
  }
  ASSERT_GT(nm, 0);
  myy /= nm;
  ASSERT_GT(myy, 0.5);
  ASSERT_LT(myy, 1.5);
  const double scale = 2.0 / myy;
  const double p_bottom = scale * g * m * double(f.size()) / area;
  int checked = 0;
  // Slabs away from the free surface (kernel deficiency there) and the floor layer.
  for (float y0 = h; y0 + 0.5f * h < top - 1.5f * h; y0 += 0.5f * h) {
    double psum = 0;
    int np = 0;
    long above = 0;
    for (size_t i = 0; i < f.size(); ++i) {
      if (f.s.y[i] >= y0 && f.s.y[i] < y0 + 0.5f * h) psum += f.p[i], ++np;
      if (f.s.y[i] >= y0 + 0.25f * h) ++above;
    }
    if (np < 10) continue;
    const double expect = scale * g * m * double(above) / area;
    EXPECT_NEAR(psum / np, expect, 0.10 * p_bottom) << "slab at y=" << y0;
    ++checked;
  }
  EXPECT_GE(checked, 8);
}

TEST(FluidPhysics, NoParticleLeavesTheBoxInAViolentScene) {
  ff::Params p;
  ff::SceneDesc s =
      fftest::blockScene(ff::Vec3(0.12f, 0.12f, 0.12f), ff::Vec3(0.02f, 0.02f, 0.02f), 12, 12, 12);
  s.fluid[0].velocity = ff::Vec3(6.0f, 9.0f, -4.0f);  // thrown into a corner at speed
  s.params.fluid.gravity[1] = -30.0f;
  auto backend = std::make_unique<ff::CpuBackend>();
  ff::CpuBackend* cpu = backend.get();
  ff::Simulation sim(s, std::move(backend));
  for (int i = 0; i < 400; ++i) {
    sim.step();
    const auto& st = cpu->fluid().s;
    for (size_t k = 0; k < st.size(); ++k) {
      ASSERT_TRUE(st.x[k] >= 0.0f && st.x[k] <= 0.12f) << "step " << i;
      ASSERT_TRUE(st.y[k] >= 0.0f && st.y[k] <= 0.12f) << "step " << i;
      ASSERT_TRUE(st.z[k] >= 0.0f && st.z[k] <= 0.12f) << "step " << i;
    }
  }
}

}  // namespace
