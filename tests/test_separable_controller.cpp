// The controller on its own: it drives a plain particle system (no SPH, no
// pressure) into a target, reading only spans of positions and velocities.
// Each of its two forces is also run alone (the other's weight 0) against an
// analytic solution of the motion it must produce, to a tight tolerance: the
// whole-system test below still passes when either force is missing.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "control/controller.h"
#include "control/placement.h"
#include "control/shape_matching.h"
#include "target/target_shape.h"

namespace {

// The paper's poly6 kernel, written out: 315 / (64 pi r^9) (r^2 - d^2)^3.
double poly6(double d, double r) {
  const double q = r * r - d * d;
  return d < r ? 315.0 / (64.0 * M_PI * std::pow(r, 9)) * q * q * q : 0.0;
}

// One control particle at rest at the origin's side of the box, one fluid
// particle released from rest at distance d0 (its volume is tiny, so s = 1).
// Attraction alone (eq. 4) is a central force of size w_a W(d): the work it
// does up to the control particle, w_a int_0^d0 W(x) dx, must all be kinetic
// energy there: v_max = sqrt(2 w_a int_0^d0 W).
TEST(SeparableController, AttractionAloneAcceleratesAsItsPotentialSays) {
  ff::ControlParams cp;  // the paper's constants
  cp.velocity = 0.0f;
  cp.gravity_compensation = 0.0f;
  cp.recapture = 0.0f;
  ff::ShapeMatchParams sm;
  ff::Controller c;
  c.setParams(cp, sm);
  ff::ControlSet set;
  const float p[3] = {0.1f, 0.1f, 0.1f};
  set.x = {p[0]}, set.y = {p[1]}, set.z = {p[2]}, set.x0 = set.x, set.y0 = set.y, set.z0 = set.z;
  set.vx = {0.0f}, set.vy = {0.0f}, set.vz = {0.0f};
  set.particle_volume = 1e-6f;
  c.reset(set);
  const double r = cp.radius, d0 = 0.02, wa = cp.attraction;
  const double dir[3] = {0.6, 0.0, 0.8};
  std::vector<float> x = {float(p[0] - d0 * dir[0])}, y = {p[1]}, z = {float(p[2] - d0 * dir[2])};
  std::vector<float> vx = {0.0f}, vy = {0.0f}, vz = {0.0f};
  ff::FluidView f;
  f.n = 1;
  f.x = x.data(), f.y = y.data(), f.z = z.data(), f.vx = vx.data(), f.vy = vy.data(), f.vz = vz.data();
  f.volume = 1e-12f;
  const float dt = 2e-5f;
  double vmax = 0.0, closest = d0;
  for (int step = 0; step < 10000; ++step) {  // 0.2 s: past the control particle once
    float ax = 0, ay = 0, az = 0;
    ASSERT_TRUE(c.computeScale(f));
    ASSERT_TRUE(c.addForces(f, dt, &ax, &ay, &az));
    vx[0] += dt * ax, vy[0] += dt * ay, vz[0] += dt * az;
    x[0] += dt * vx[0], y[0] += dt * vy[0], z[0] += dt * vz[0];
    vmax = std::max(vmax, std::sqrt(double(vx[0]) * vx[0] + double(vy[0]) * vy[0] + double(vz[0]) * vz[0]));
    const double dx = x[0] - p[0], dy = y[0] - p[1], dz = z[0] - p[2];
    closest = std::min(closest, std::sqrt(dx * dx + dy * dy + dz * dz));
  }
  // int_0^d (r^2 - x^2)^3 dx = r^6 d - r^4 d^3 + 3/5 r^2 d^5 - d^7 / 7
  const double coef = 315.0 / (64.0 * M_PI * std::pow(r, 9));
  const double work = wa * coef *
                      (std::pow(r, 6) * d0 - std::pow(r, 4) * std::pow(d0, 3) +
                       0.6 * r * r * std::pow(d0, 5) - std::pow(d0, 7) / 7.0);
  const double expect = std::sqrt(2.0 * work);
  ASSERT_GT(expect, 0.2);  // ~0.3 m/s
  EXPECT_NEAR(vmax, expect, 2e-3 * expect);
  EXPECT_LT(closest, 1e-4);  // it passes through the control particle: a central force
  EXPECT_EQ(vy[0], 0.0f);    // and stays on the line through it
}

// Control particles moving at one velocity V; fluid particles held in place.
// The velocity force alone (eq. 6, implicit over dt) is then
// a = K (V - v) / (1 + dt K), K = w_v sum_i W_i, so each step divides v - V
// by (1 + dt K): after n steps v = V + (v0 - V) (1 + dt K)^-n, exactly.
TEST(SeparableController, VelocityAloneRelaxesTowardsTheControlVelocity) {
  ff::ControlParams cp;
  cp.attraction = 0.0f;
  cp.gravity_compensation = 0.0f;
  cp.recapture = 0.0f;
  ff::ShapeMatchParams sm;
  ff::Controller c;
  c.setParams(cp, sm);
  const double V[3] = {0.5, -0.25, 0.125};
  ff::ControlSet set;
  const double cps[3][3] = {{0.10, 0.10, 0.10}, {0.11, 0.10, 0.10}, {0.10, 0.115, 0.105}};
  for (const auto& q : cps) {
    set.x.push_back(float(q[0])), set.y.push_back(float(q[1])), set.z.push_back(float(q[2]));
    set.vx.push_back(float(V[0])), set.vy.push_back(float(V[1])), set.vz.push_back(float(V[2]));
  }
  set.x0 = set.x, set.y0 = set.y, set.z0 = set.z;
  set.particle_volume = 1e-6f;
  c.reset(set);
  const double fluid[4][3] = {
      {0.105, 0.10, 0.10}, {0.10, 0.12, 0.11}, {0.09, 0.09, 0.095}, {0.12, 0.11, 0.10}};
  std::vector<float> x, y, z, vx(4, -0.3f), vy(4, 0.2f), vz(4, 0.4f);
  for (const auto& q : fluid) x.push_back(float(q[0])), y.push_back(float(q[1])), z.push_back(float(q[2]));
  ff::FluidView f;
  f.n = 4;
  f.x = x.data(), f.y = y.data(), f.z = z.data(), f.vx = vx.data(), f.vy = vy.data(), f.vz = vz.data();
  f.volume = 1e-6f;
  const float dt = 0.004f;
  const int steps = 100;
  for (int step = 0; step < steps; ++step) {
    std::vector<float> ax(4, 0.0f), ay(4, 0.0f), az(4, 0.0f);
    ASSERT_TRUE(c.computeScale(f));
    ASSERT_TRUE(c.addForces(f, dt, ax.data(), ay.data(), az.data()));
    for (size_t e = 0; e < 4; ++e) vx[e] += dt * ax[e], vy[e] += dt * ay[e], vz[e] += dt * az[e];
  }
  const double v0[3] = {-0.3, 0.2, 0.4};
  for (size_t e = 0; e < 4; ++e) {
    double k = 0;
    for (const auto& q : cps) {
      const double dx = q[0] - x[e], dy = q[1] - y[e], dz = q[2] - z[e];
      k += cp.velocity * poly6(std::sqrt(dx * dx + dy * dy + dz * dz), cp.radius);
    }
    const double left = std::pow(1.0 + dt * k, -steps);
    ASSERT_LT(left, 0.6) << "fluid particle " << e << ": too little relaxation to test";
    const float got[3] = {vx[e], vy[e], vz[e]};
    for (int d = 0; d < 3; ++d)
      EXPECT_NEAR(got[d], V[d] + (v0[d] - V[d]) * left, 1e-5) << "fluid particle " << e << ", axis " << d;
  }
}

TEST(SeparableController, MovesAPlainParticleSystemIntoASphere) {
  // 3000 particles scattered in a flat ellipsoid (0.16 m wide, 0.08 m
  // thick), at rest. With no pressure nothing stops particles that converge
  // from far apart from passing through each other, so the start is kept
  // moderately flat. The sphere's reference particles map onto its bounding
  // box, so the disc is exactly what the squashed sphere covers.
  const size_t n = 3000;
  const float volume_each = 2.5e-7f;  // as the paper's particles: 0.0002 kg / 800 kg/m^3
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> x(n), y(n), z(n), vx(n, 0.0f), vy(n, 0.0f), vz(n, 0.0f), ax(n), ay(n), az(n);
  for (size_t i = 0; i < n;) {
    const float a = u(rng), b = u(rng), c = u(rng);
    if (a * a + b * b + c * c > 1.0f) continue;
    x[i] = 0.15f + 0.08f * a, y[i] = 0.065f + 0.04f * b, z[i] = 0.15f + 0.08f * c;
    ++i;
  }

  ff::TargetSpec spec;
  spec.kind = ff::TargetKind::Sphere;
  spec.control_count = 800;
  const double fluid_volume = double(n) * volume_each;
  ff::TargetShape sphere = ff::buildTarget(spec, fluid_volume, 0.01f);
  const float radius = float(std::cbrt(3.0 * sphere.shape_volume / (4.0 * M_PI)));

  ff::Controller c;
  ff::ControlParams cp;  // the paper's constants
  ff::ShapeMatchParams sm;
  c.setParams(cp, sm);
  ff::Vec3 lo(1e9f, 1e9f, 1e9f), hi(-1e9f, -1e9f, -1e9f);
  for (size_t i = 0; i < n; ++i)
    lo = lo.cwiseMin(ff::Vec3(x[i], y[i], z[i])), hi = hi.cwiseMax(ff::Vec3(x[i], y[i], z[i]));
  c.reset(ff::placeControlParticles(sphere, lo, hi, sm, ff::Vec3(-1, -1, -1), ff::Vec3(1, 1, 1)));

  ff::FluidView f;
  f.n = n;
  f.x = x.data(), f.y = y.data(), f.z = z.data(), f.vx = vx.data(), f.vy = vy.data(), f.vz = vz.data();
  f.volume = volume_each;
  const float dt = 0.004f;
  for (int step = 0; step < 750; ++step) {  // 3 s
    std::fill(ax.begin(), ax.end(), 0.0f), std::fill(ay.begin(), ay.end(), 0.0f),
        std::fill(az.begin(), az.end(), 0.0f);
    c.step(f, dt, ax.data(), ay.data(), az.data());
    for (size_t i = 0; i < n; ++i) {
      vx[i] += dt * ax[i], vy[i] += dt * ay[i], vz[i] += dt * az[i];
      x[i] += dt * vx[i], y[i] += dt * vy[i], z[i] += dt * vz[i];
    }
  }
  // Where is the sphere now? The control particles' best rigid fit says.
  ff_quat q = FF_Q(0, 0, 0, 1);
  float centre[3];
  ff::bestFitFrame(c.set(), q, centre, 100);
  size_t inside = 0;
  double spread = 0;
  for (size_t i = 0; i < n; ++i) {
    const float dx = x[i] - centre[0], dy = y[i] - centre[1], dz = z[i] - centre[2];
    const float r = std::sqrt(dx * dx + dy * dy + dz * dz);
    inside += r < 1.15f * radius ? 1 : 0;
    spread += r;
  }
  // A sphere of the same volume (radius ~0.056 m) holds 90% of the
  // particles afterwards.
  EXPECT_GT(double(inside) / n, 0.9) << "radius " << radius;
  // ... and the cloud is round: its mean distance from the centre is what a
  // uniformly filled ball gives (3/4 R), not a disc's.
  EXPECT_NEAR(spread / n, 0.75 * radius, 0.2 * radius);
  // The initial disc did not satisfy this.
  ASSERT_GT(hi.x() - lo.x(), 2.5f * radius);
}

}  // namespace
