// The non-pressure force plug-ins of the OpenCL backend (host/forces/)
// against the OpenMP backend's (src/cpu/forces/): the same list in the same
// order, a force that only a test registers (its own kernel, built here)
// moving particles as the analytic solution says and as on the OpenMP
// backend, and a whole run with the plug-ins bit for bit as on the OpenMP
// backend where the device rounds as it does (PoCL).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "cpu/backend_cpu.h"
#include "force_plugin_case.h"
#include "host/backend_opencl.h"
#include "host/cl_program.h"
#include "host/forces/cl_force.h"
#include "opencl_backend.h"
#include "scene/scene.h"
#include "sim/simulation.h"

namespace {

// The twin of test_force_plugins.cpp's fftest::CpuSpring: the same arithmetic, not contracted.
const char* kSpringSource = R"(
#pragma OPENCL FP_CONTRACT OFF
__kernel void test_spring(__global const float* y, __global float* ay, uint n, float w2, float c) {
  const uint i = get_global_id(0);
  if (i < n) ay[i] = ay[i] - w2 * (y[i] - c);
}
)";

class ClSpring : public ff::ClForce {
 public:
  explicit ClSpring(const ff::ClContext& ctx) {
    cl::Program program(ctx.context(), kSpringSource);
    program.build({ctx.device()});
    k_ = ff::makeKernel(program, "test_spring", ctx);
  }
  const char* name() const override { return fftest::kSpringName; }
  void apply(ff::ClForceContext& c, float) override {
    const ff::ClFluidRefs& f = c.fluid;
    ff::launch(*f.queue, k_, f.n, *f.y, *f.ay, cl_uint(f.n), fftest::kSpringW2, fftest::kSpringCentre);
  }

 private:
  ff::ClKernel k_;
};

// The fluid by particle id.
ff::FluidState byId(ff::Simulation& sim) {
  ff::FluidState f, out;
  sim.backend().readFluid(f);
  out = f;
  for (size_t i = 0; i < f.size(); ++i) {
    const uint32_t k = f.id[i];
    out.x[k] = f.x[i], out.y[k] = f.y[i], out.z[k] = f.z[i];
    out.vx[k] = f.vx[i], out.vy[k] = f.vy[i], out.vz[k] = f.vz[i], out.id[k] = k;
  }
  return out;
}

// Every coordinate and velocity equal (bit for bit where the device rounds as
// the OpenMP backend, else within `tol`).
void expectSameFluid(const ff::FluidState& a, const ff::FluidState& b, bool exact, double tol) {
  ASSERT_EQ(a.size(), b.size());
  size_t differ = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const float pa[6] = {a.x[i], a.y[i], a.z[i], a.vx[i], a.vy[i], a.vz[i]};
    const float pb[6] = {b.x[i], b.y[i], b.z[i], b.vx[i], b.vy[i], b.vz[i]};
    for (int d = 0; d < 6; ++d) differ += exact ? pa[d] != pb[d] : !(std::fabs(pa[d] - pb[d]) <= tol);
  }
  EXPECT_EQ(differ, 0u) << (exact ? "bit for bit" : "within tolerance");
}

TEST(OpenClForcePlugins, RegistryListsTheCpuBackendsForcesInOrder) {
  auto ocl = fftest::openClBackend();
  ASSERT_TRUE(ocl);
  EXPECT_EQ(ocl->forceNames(), (std::vector<std::string>{"gravity", "viscosity", "control"}));
  EXPECT_EQ(ocl->forceNames(), ff::CpuBackend(2).forceNames());
}

TEST(OpenClForcePlugins, ATestsSpringForceSwingsAsTheAnalyticOscillatorAndAsOnTheCpu) {
  auto ocl = fftest::openClBackend();
  ASSERT_TRUE(ocl);
  const bool exact = ff::roundsAsTheCpuBackend(ocl->deviceInfo());
  ocl->addForce(std::make_unique<ClSpring>(ocl->context()));
  EXPECT_EQ(ocl->forceNames().back(), fftest::kSpringName);
  ff::Simulation sim(fftest::springScene(), std::move(ocl));
  fftest::expectOscillation(sim);
  auto cpu = std::make_unique<ff::CpuBackend>(2);
  cpu->addForce(std::make_unique<fftest::CpuSpring>());
  ff::Simulation ref(fftest::springScene(), std::move(cpu));
  while (ref.stepCount() < sim.stepCount()) ref.step();
  expectSameFluid(byId(sim), byId(ref), exact, 1e-5);
}

// The tiny controlled scene of the Oclgrind run (paper preset: gravity,
// viscosity, control and WCSPH) with the test's spring added on both
// backends: the same fluid after 10 steps.
TEST(OpenClForcePlugins, RunWithTheSpringAddedMatchesTheCpuBackend) {
  auto ocl = fftest::openClBackend();
  ASSERT_TRUE(ocl);
  const bool exact = ff::roundsAsTheCpuBackend(ocl->deviceInfo());
  ocl->addForce(std::make_unique<ClSpring>(ocl->context()));
  auto cpu = std::make_unique<ff::CpuBackend>(2);
  cpu->addForce(std::make_unique<fftest::CpuSpring>());
  const ff::SceneDesc scene = ff::loadScene(std::string(FF_SOURCE_DIR) + "/tests/scenes/oclgrind_tiny.json");
  ff::Simulation a(scene, std::move(ocl)), b(scene, std::move(cpu));
  for (int k = 0; k < 10; ++k) a.step(), b.step();
  ASSERT_GT(a.metrics().control_count, 0) << "the scene's control is active";
  expectSameFluid(byId(a), byId(b), exact, 1e-3);
}

TEST(OpenClForcePlugins, RunProfileNamesEachPluginAndSolverStage) {
  fftest::expectProfileNames("opencl");
}

}  // namespace
