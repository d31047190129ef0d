// The controller on its own: it drives a plain particle system (no SPH, no
// pressure) into a target, reading only spans of positions and velocities.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "control/controller.h"
#include "control/placement.h"
#include "control/shape_matching.h"
#include "target/target_shape.h"

namespace {

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
