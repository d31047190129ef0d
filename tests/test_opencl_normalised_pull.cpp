// The normalised pull (params.control.normalise = 1) on the OpenCL backend:
// the same shared formula (ff_pull_scale, kernels/common/ff_control.h) on
// both backends, so where the device rounds as the OpenMP backend (PoCL) a
// run gives the same particles bit for bit.
#include <gtest/gtest.h>

#include <memory>

#include "cpu/backend_cpu.h"
#include "host/backend_opencl.h"
#include "host/cl_program.h"
#include "sim/simulation.h"
#include "test_scenes.h"

namespace {

TEST(OpenClNormalisedPull, RunMatchesTheCpuBackend) {
  ff::SceneDesc s = fftest::blockScene(ff::Vec3(0.2f, 0.2f, 0.2f), ff::Vec3(0.06f, 0.0f, 0.06f), 12, 12, 12);
  s.schedule.push_back({0.0, fftest::target(ff::TargetKind::Torus, 500)});
  s.params.control.normalise = 1;
  auto ocl_backend = std::make_unique<ff::OpenClBackend>();
  const bool exact = ff::roundsAsTheCpuBackend(ocl_backend->deviceInfo());
  ff::Simulation cpu(s, std::make_unique<ff::CpuBackend>(2)), ocl(s, std::move(ocl_backend));
  for (int i = 0; i < 40; ++i) cpu.step(), ocl.step();
  ff::FluidState a, b;
  cpu.backend().readFluid(a), ocl.backend().readFluid(b);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_GT(cpu.metrics().max_speed, 0.05);  // the fluid moves: the comparison means something
  if (!exact) GTEST_SKIP() << "the device rounds differently: whole runs are compared in test_opencl_run.cpp";
  EXPECT_TRUE(a.id == b.id);
  EXPECT_TRUE(a.x == b.x && a.y == b.y && a.z == b.z) << "positions differ";
  EXPECT_TRUE(a.vx == b.vx && a.vy == b.vy && a.vz == b.vz) << "velocities differ";
}

}  // namespace
