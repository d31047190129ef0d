// Whole runs on the OpenCL backend (PoCL here) against the OpenMP backend:
// the default scene's dynamics end at the same iou, and target changes in the
// middle of a run (from the schedule, and through the API) work on both.
//
// The default scene is run as it is: 8000 particles, 500 steps (2 s, the
// sphere forming), then into the scheduled switch to the torus.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "cpu/backend_cpu.h"
#include "gpu_tolerance.h"
#include "host/backend_factory.h"
#include "host/backend_opencl.h"
#include "host/cl_program.h"
#include "sim/simulation.h"

namespace {

// The OpenCL backend through the factory, as `flowform run --backend opencl`
// makes it. No OpenCL is a failure with the reason, never a skip.
std::unique_ptr<ff::Backend> openCl() {
  try {
    std::string note;
    return ff::makeBackend("opencl", -1, 2, &note);
  } catch (const ff::Error& e) {
    ADD_FAILURE() << "the OpenCL backend did not start: " << e.what()
                  << "\n(PoCL, package pocl-opencl-icd, is a declared dependency; .ci/setup installs it)";
    return nullptr;
  }
}

// The default scene on the `paper` preset (WCSPH): these whole runs and
// their bounds (gpu_tolerance.h) were set on it, and they run again under
// the scalar, poisoned and GPU-rounding variants, where the default `water`
// preset's DFSPH costs minutes on PoCL. DFSPH on OpenCL has its own runs in
// test_opencl_dfsph.cpp and the default scene's host syncs.
ff::SceneDesc defaultSceneOnPaper() {
  ff::SceneDesc s = ff::defaultScene();
  s.preset = "paper";
  s.params = ff::presetParams("paper");
  return s;
}

// The default scene's container, parameters and schedule with 14^3 particles,
// for the API test below, which needs a scene, not the default one.
ff::SceneDesc shortDefaultScene() {
  ff::SceneDesc s = defaultSceneOnPaper();
  ff::FluidBlockDesc& b = s.fluid.at(0);
  const float sp = s.params.fluid.restSpacing();
  // Same centre on the floor, 14 particles per side.
  for (int d = 0; d < 3; ++d) {
    if (d != 1) b.origin[d] += 0.5f * float(b.dims[d] - 14) * sp;
    b.dims[d] = 14;
  }
  return s;
}

// Whether the backend rounds as the OpenMP backend (PoCL): then the runs
// agree exactly, elsewhere within the GPU bounds of gpu_tolerance.h.
bool exact(ff::Backend& backend) {
  const auto* cl = dynamic_cast<const ff::OpenClBackend*>(&backend);
  EXPECT_TRUE(cl);
  return cl && ff::roundsAsTheCpuBackend(cl->deviceInfo());
}
double runIouTol(ff::Backend& backend) {
  return exact(backend) ? ff::test::kExactRunIouTol : ff::test::kGpuRunIouTol;
}

bool finite(const ff::StepMetrics& m) {
  return std::isfinite(m.iou) && std::isfinite(m.coverage) && std::isfinite(m.max_speed) &&
         std::isfinite(m.density_error) && std::isfinite(m.kinetic_energy);
}

// Absolute checks of a run's state, independent of the other backend: every
// particle of the scene is still there exactly once (ids a permutation: mass
// is conserved), finite, and inside the container.
void expectPhysicalState(ff::Simulation& sim, const char* what) {
  ff::FluidState f;
  sim.backend().readFluid(f);
  const ff::SceneDesc& scene = sim.scene();
  ASSERT_EQ(f.size(), size_t(scene.fluidCount())) << what;
  std::vector<char> seen(f.size(), 0);
  size_t outside = 0, bad_ids = 0;
  const ff::Vec3 lo = scene.container.min, hi = scene.container.max;
  for (size_t i = 0; i < f.size(); ++i) {
    const float p[3] = {f.x[i], f.y[i], f.z[i]}, v[3] = {f.vx[i], f.vy[i], f.vz[i]};
    for (int d = 0; d < 3; ++d) {
      ASSERT_TRUE(std::isfinite(p[d]) && std::isfinite(v[d])) << what << ", particle " << i;
      outside += p[d] < lo[d] || p[d] > hi[d];
    }
    if (f.id[i] >= f.size() || seen[f.id[i]]++) ++bad_ids;
  }
  EXPECT_EQ(outside, 0u) << what << ": coordinates outside the container";
  EXPECT_EQ(bad_ids, 0u) << what << ": particle ids lost or repeated";
}

TEST(OpenClRun, DefaultSceneEndsAtTheCpuBackendsIou) {
  auto backend = openCl();
  ASSERT_TRUE(backend);
  const ff::SceneDesc scene = defaultSceneOnPaper();
  ff::Simulation ocl(scene, std::move(backend));
  ff::Simulation cpu(scene, std::make_unique<ff::CpuBackend>(2));
  std::printf("OpenCL device: %s\n", ocl.backend().device().c_str());
  const long steps = 500;
  long clamps_cpu = 0, clamps_ocl = 0;
  for (long s = 1; s <= steps; ++s) {
    ASSERT_NO_THROW(cpu.step()) << "cpu, step " << s;
    ASSERT_NO_THROW(ocl.step()) << "opencl, step " << s;
    ASSERT_TRUE(finite(ocl.metrics())) << "step " << s;
    clamps_cpu += cpu.metrics().velocity_clamps, clamps_ocl += ocl.metrics().velocity_clamps;
    if (s % 100 == 0)
      std::printf("  step %ld  iou cpu %.4f opencl %.4f   max_speed cpu %.4f opencl %.4f\n", s,
                  cpu.metrics().iou, ocl.metrics().iou, cpu.metrics().max_speed, ocl.metrics().max_speed);
  }
  EXPECT_EQ(ocl.target()->label, "sphere");
  EXPECT_GT(cpu.metrics().iou, 0.5);  // the sphere has formed: the comparison means something
  EXPECT_GT(ocl.metrics().iou, 0.5);  // and on OpenCL, on its own
  expectPhysicalState(ocl, "opencl, step 500");
  EXPECT_NEAR(ocl.metrics().iou, cpu.metrics().iou, runIouTol(ocl.backend()));
  EXPECT_NEAR(ocl.metrics().coverage, cpu.metrics().coverage, runIouTol(ocl.backend()));
  // The velocity clamps are counted from the same shared body (ff_integrate.h):
  // the same count where the backends round alike.
  std::printf("  velocity clamps over %ld steps: cpu %ld opencl %ld\n", steps, clamps_cpu, clamps_ocl);
  if (exact(ocl.backend())) {
    EXPECT_EQ(clamps_ocl, clamps_cpu);
  }
  // The schedule switches to the torus at 2 s, at the start of step 501.
  for (long s = 501; s <= 505; ++s) {
    ASSERT_NO_THROW(cpu.step()) << "cpu, step " << s;
    ASSERT_NO_THROW(ocl.step()) << "opencl, step " << s;
    ASSERT_TRUE(finite(ocl.metrics())) << "step " << s;
  }
  EXPECT_EQ(ocl.target()->label, "torus");
  EXPECT_EQ(ocl.metrics().control_count, long(ocl.target()->reference.size()));
  EXPECT_EQ(ocl.metrics().control_count, cpu.metrics().control_count);
}

TEST(OpenClRun, TargetChangesMidRunOnBothBackends) {
  auto backend = openCl();
  ASSERT_TRUE(backend);
  ff::SceneDesc scene = shortDefaultScene();
  scene.schedule.resize(1);  // the sphere; then the torus through the API at step 100
  ff::Simulation ocl(scene, std::move(backend));
  ff::Simulation cpu(scene, std::make_unique<ff::CpuBackend>(2));
  ff::TargetSpec torus;
  torus.kind = ff::TargetKind::Torus;
  double iou_at_change = 0.0;
  for (long s = 1; s <= 400; ++s) {
    if (s == 101) {
      cpu.setTarget(torus);
      ocl.setTarget(torus);
      ff::ControlSet cc, co;
      ff::ControlFields fc, fo;
      cpu.backend().readControl(cc, fc);
      ocl.backend().readControl(co, fo);
      ASSERT_EQ(ocl.target()->label, "torus");
      ASSERT_EQ(co.size(), ocl.target()->reference.size());
      ASSERT_EQ(co.size(), cc.size());
      double d = 0.0;  // both placed the torus on (nearly) the same fluid
      for (size_t i = 0; i < co.size(); ++i)
        d = std::max({d, double(std::fabs(co.x[i] - cc.x[i])), double(std::fabs(co.y[i] - cc.y[i])),
                      double(std::fabs(co.z[i] - cc.z[i]))});
      // Bit for bit on PoCL; the GPU bound where rounding differs (gpu_tolerance.h).
      const double tol = exact(ocl.backend()) ? ff::test::kExactPlacementTol : ff::test::kGpuPlacementTol;
      std::printf("  control particles placed %.3g m apart (tolerance %.3g m)\n", d, tol);
      EXPECT_LT(d, tol) << "control particles placed differently";
    }
    ASSERT_NO_THROW(cpu.step()) << "cpu, step " << s;
    ASSERT_NO_THROW(ocl.step()) << "opencl, step " << s;
    ASSERT_TRUE(finite(ocl.metrics())) << "step " << s;
    if (s == 101) {
      iou_at_change = ocl.metrics().iou;
      EXPECT_EQ(ocl.metrics().control_count, long(ocl.target()->reference.size()));
      EXPECT_EQ(ocl.metrics().control_count, cpu.metrics().control_count);
    }
    if (s % 50 == 0)
      std::printf("  step %ld  target %s  iou cpu %.4f opencl %.4f   kinetic energy cpu %.6g opencl %.6g\n",
                  s, ocl.target()->label.c_str(), cpu.metrics().iou, ocl.metrics().iou,
                  cpu.metrics().kinetic_energy, ocl.metrics().kinetic_energy);
  }
  EXPECT_GT(ocl.metrics().iou, iou_at_change + 0.1);  // the torus is forming out of the sphere
  expectPhysicalState(ocl, "opencl, step 400");
  EXPECT_NEAR(ocl.metrics().iou, cpu.metrics().iou, runIouTol(ocl.backend()));
  // Switching control off and on again.
  ocl.clearTarget();
  ocl.step();
  EXPECT_EQ(ocl.metrics().control_count, 0);
  ocl.setTarget(torus);
  ocl.step();
  EXPECT_TRUE(finite(ocl.metrics()));
  EXPECT_GT(ocl.metrics().control_count, 0);
}

}  // namespace
