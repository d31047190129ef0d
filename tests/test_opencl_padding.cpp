// The fluid buffers are padded to a multiple of 8 for the 8-wide loads. PoCL
// zeroes new memory, a GPU does not: with FLOWFORM_CL_POISON=1 every new
// device buffer starts as NaN, so a kernel that reads padding it never wrote
// (0 x NaN = NaN) fails here. 343 particles (7^3, not a multiple of 8 or of
// any work-group size) with a target, on both kernel variants, against the
// OpenMP backend.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "cpu/backend_cpu.h"
#include "host/backend_opencl.h"
#include "sim/simulation.h"

namespace {

// Sets FLOWFORM_CL_POISON=1 for its lifetime.
struct Poison {
  Poison() { setenv("FLOWFORM_CL_POISON", "1", 1); }
  ~Poison() { unsetenv("FLOWFORM_CL_POISON"); }
};

// The default scene (container, parameters, sphere target) with one block of 7^3 particles.
ff::SceneDesc scene343() {
  ff::SceneDesc s = ff::defaultScene();
  s.fluid.resize(1);
  ff::FluidBlockDesc& b = s.fluid.at(0);
  const float sp = s.params.fluid.restSpacing();
  for (int d = 0; d < 3; ++d) {
    if (d != 1) b.origin[d] += 0.5f * float(b.dims[d] - 7) * sp;
    b.dims[d] = 7;
  }
  s.schedule.resize(1);
  return s;
}

void runPoisoned(ff::OpenClBackend::KernelVariant variant) {
  const Poison poison;
  ASSERT_TRUE(ff::clPoisonEnabled());
  const ff::SceneDesc scene = scene343();
  auto backend = std::make_unique<ff::OpenClBackend>();
  backend->setKernelVariant(variant);
  ff::Simulation ocl(scene, std::move(backend));
  ff::Simulation cpu(scene, std::make_unique<ff::CpuBackend>(2));
  ASSERT_TRUE(ocl.target());
  for (long s = 1; s <= 200; ++s) {
    ASSERT_NO_THROW(ocl.step()) << "opencl, step " << s;
    ASSERT_NO_THROW(cpu.step()) << "cpu, step " << s;
    const ff::StepMetrics& m = ocl.metrics();
    ASSERT_TRUE(std::isfinite(m.iou) && std::isfinite(m.max_speed) && std::isfinite(m.kinetic_energy))
        << "step " << s;
  }
  ff::FluidState f;
  ocl.backend().readFluid(f);
  ASSERT_EQ(f.size(), 343u);
  for (size_t i = 0; i < f.size(); ++i)
    ASSERT_TRUE(std::isfinite(f.x[i]) && std::isfinite(f.vy[i])) << "particle " << i;
  std::printf("%s kernels: iou opencl %.4f cpu %.4f\n",
              variant == ff::OpenClBackend::KernelVariant::Lanes ? "lanes" : "scalar", ocl.metrics().iou,
              cpu.metrics().iou);
  EXPECT_GT(ocl.metrics().control_count, 0);
  EXPECT_GT(cpu.metrics().iou, 0.2);  // a shape is forming: the comparison means something
  EXPECT_NEAR(ocl.metrics().iou, cpu.metrics().iou, 0.02);
}

TEST(OpenClPadding, PoisonedBuffersScalarKernels343Particles) {
  runPoisoned(ff::OpenClBackend::KernelVariant::Scalar);
}

TEST(OpenClPadding, PoisonedBuffersLanesKernels343Particles) {
  runPoisoned(ff::OpenClBackend::KernelVariant::Lanes);
}

}  // namespace
