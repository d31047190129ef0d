// The velocity_clamps metric (docs/METRICS.md) on both backends: particles
// moving at twice the speed limit are clamped, those at half of it are not,
// so one integration counts exactly the fast ones, on the OpenMP backend and
// on the OpenCL backend alike, and the count starts again after each read.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cpu/backend_cpu.h"
#include "host/backend_opencl.h"

namespace {

TEST(OpenClVelocityClamps, BothBackendsCountTheParticlesOverTheSpeedLimit) {
  ff::Params p;
  p.fluid.gravity[1] = 0.0f;
  const float dt = p.fluid.time_step;
  const double vmax = double(p.fluid.max_step_fraction) * p.fluid.smoothing_radius / dt;
  ff::ContainerDesc box;
  box.min = ff::Vec3(0.0f, 0.0f, 0.0f), box.max = ff::Vec3(1.0f, 1.0f, 1.0f);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> pos(0.3f, 0.7f);
  std::normal_distribution<float> dir(0.0f, 1.0f);
  ff::FluidState s;
  const int n = 1000;
  long fast = 0;
  for (int i = 0; i < n; ++i) {
    float d[3] = {dir(rng), dir(rng), dir(rng)};
    const float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const bool over = i % 3 == 0;  // 2 vmax, or 0.5 vmax: far from the limit either way
    fast += over;
    const float speed = float((over ? 2.0 : 0.5) * vmax) / len;
    s.push(pos(rng), pos(rng), pos(rng), d[0] * speed, d[1] * speed, d[2] * speed);
  }
  ff::CpuBackend cpu(2);
  ff::OpenClBackend ocl;
  cpu.init(p, box, s);
  ocl.init(p, box, s);
  cpu.integrate(dt), ocl.integrate(dt);
  ASSERT_EQ(ocl.firstNonFinite(), ff::Phase::Count);
  EXPECT_EQ(cpu.computeMetrics().velocity_clamps, fast);
  EXPECT_EQ(ocl.computeMetrics().velocity_clamps, fast);
  // Read: the next metrics count from 0; no acceleration, so the slow ones stay under the limit.
  EXPECT_EQ(cpu.computeMetrics().velocity_clamps, 0);
  EXPECT_EQ(ocl.computeMetrics().velocity_clamps, 0);
}

}  // namespace
