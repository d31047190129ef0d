// The instruction-set instances of the OpenMP backend's hot loops
// (src/parallel/simd8.h) against each other: a CPU without AVX2 runs the
// portable instances, one without AVX-512 the AVX2 ones alone, so each cap
// must give the same run as the widest instance, bit for bit: the fluid (positions, velocities), the control
// particles and their fields, and the whole saved state. The oracle is the
// other instance: they are compiled separately for different instruction
// sets from one body, and a lane test, a lane mask or a sum that one of them
// got wrong moves some particle.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "cli_run.h"
#include "core/error.h"
#include "core/state_io.h"
#include "cpu/backend_cpu.h"
#include "parallel/simd8.h"
#include "scene/scene.h"
#include "sim/simulation.h"
#include "test_scenes.h"

namespace {

using ff::simd::Isa;

// Restores the process's instruction set when it goes out of scope.
struct IsaCap {
  explicit IsaCap(Isa cap) { ff::simd::capIsa(cap); }
  ~IsaCap() { ff::simd::capIsa(Isa::Avx512); }
};

struct Run {
  ff::FluidState fluid;  // by particle id
  ff::ControlSet control;
  ff::ControlFields fields;
  std::vector<char> state;  // Simulation::saveState
  long control_count = 0;
  long solver_iterations = 0;
};

Run runCapped(const ff::SceneDesc& scene, int steps, Isa cap) {
  IsaCap guard(cap);
  EXPECT_EQ(ff::simd::isa(), cap);
  ff::Simulation sim(scene, std::make_unique<ff::CpuBackend>(2));
  Run r;
  for (int k = 0; k < steps; ++k) {
    sim.step();
    r.control_count = std::max(r.control_count, sim.metrics().control_count);
    r.solver_iterations += sim.metrics().solver_iterations;
  }
  ff::FluidState f;
  sim.backend().readFluid(f);
  r.fluid = f;
  for (size_t i = 0; i < f.size(); ++i) {
    const uint32_t k = f.id[i];
    r.fluid.x[k] = f.x[i], r.fluid.y[k] = f.y[i], r.fluid.z[k] = f.z[i];
    r.fluid.vx[k] = f.vx[i], r.fluid.vy[k] = f.vy[i], r.fluid.vz[k] = f.vz[i], r.fluid.id[k] = k;
  }
  sim.backend().readControl(r.control, r.fields);
  ff::StateWriter w;
  sim.saveState(w);
  r.state = w.data();
  return r;
}

// Count of values that differ in their bits (NaN never equals: a NaN counts).
size_t differing(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size()) + 1;
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += a[i] == b[i] ? 0 : 1;
  return n;
}

void expectSameRun(const Run& a, const Run& b, const char* what) {
  SCOPED_TRACE(what);
  const std::vector<float>* fa[] = {&a.fluid.x,  &a.fluid.y,  &a.fluid.z,
                                    &a.fluid.vx, &a.fluid.vy, &a.fluid.vz};
  const std::vector<float>* fb[] = {&b.fluid.x,  &b.fluid.y,  &b.fluid.z,
                                    &b.fluid.vx, &b.fluid.vy, &b.fluid.vz};
  for (int d = 0; d < 6; ++d) EXPECT_EQ(differing(*fa[d], *fb[d]), 0u) << "fluid component " << d;
  ASSERT_GT(a.control.size(), 0u) << "the run ends with a target active";
  const std::vector<float>* ca[] = {&a.control.x,  &a.control.y, &a.control.z, &a.control.vx, &a.control.vy,
                                    &a.control.vz, &a.fields.s,  &a.fields.ux, &a.fields.uy,  &a.fields.uz};
  const std::vector<float>* cb[] = {&b.control.x,  &b.control.y, &b.control.z, &b.control.vx, &b.control.vy,
                                    &b.control.vz, &b.fields.s,  &b.fields.ux, &b.fields.uy,  &b.fields.uz};
  for (int d = 0; d < 10; ++d) EXPECT_EQ(differing(*ca[d], *cb[d]), 0u) << "control component " << d;
  EXPECT_TRUE(a.state == b.state) << "the saved states differ";
}

// Each cap the CPU allows against the widest instance, on `scene`.
void expectEveryCapAlike(const ff::SceneDesc& scene, int steps, bool dfsph) {
  const Isa widest = ff::simd::isa();
  if (widest == Isa::Portable)
    GTEST_SKIP() << "this CPU has no AVX2 (or FLOWFORM_SIMD=portable): one instance only";
  const Run ref = runCapped(scene, steps, widest);
  ASSERT_GT(ref.control_count, 0) << "the control acts";
  if (dfsph) {
    EXPECT_GT(ref.solver_iterations, 0) << "DFSPH iterates";
  }
  // The fluid moved: a run that did nothing would match trivially.
  ff::FluidState start = ff::Simulation::makeFluid(scene);
  EXPECT_GT(differing(start.y, ref.fluid.y), start.size() / 2);
  if (widest == Isa::Avx512) expectSameRun(ref, runCapped(scene, steps, Isa::Avx2), "avx2 against avx512");
  expectSameRun(ref, runCapped(scene, steps, Isa::Portable), "portable against the widest");
}

// The paper preset (WCSPH) with the control: a sphere, then a box.
TEST(SimdPaths, PaperPresetRunIsBitIdenticalInEveryInstance) {
  const ff::SceneDesc scene = ff::loadScene(std::string(FF_SOURCE_DIR) + "/tests/scenes/oclgrind_tiny.json");
  expectEveryCapAlike(scene, 12, false);
}

// The water preset (DFSPH: factor, divergence and density solves, the
// neighbour cache) with the control, 8 x 8 x 8 particles.
TEST(SimdPaths, WaterPresetRunIsBitIdenticalInEveryInstance) {
  ff::SceneDesc scene = ff::loadScene(std::string(FF_SOURCE_DIR) + "/tests/scenes/oclgrind_tiny_water.json");
  scene.fluid[0].dims[0] = scene.fluid[0].dims[1] = scene.fluid[0].dims[2] = 8;
  expectEveryCapAlike(scene, 12, true);
}

TEST(SimdPaths, CapIsaLowersTheInstanceAndRestores) {
  const Isa widest = ff::simd::isa();
  {
    IsaCap guard(Isa::Portable);
    EXPECT_EQ(ff::simd::isa(), Isa::Portable);
    EXPECT_FALSE(ff::simd::hasAvx2());
    EXPECT_FALSE(ff::simd::hasAvx512());
    EXPECT_NE(ff::CpuBackend(1).device().find("portable"), std::string::npos);
  }
  EXPECT_EQ(ff::simd::isa(), widest);
}

// $FLOWFORM_SIMD as a user sets it: the run names the instance it took and
// computes the same metrics; a name it does not know is refused in one line.
TEST(SimdPaths, FlowformSimdPicksTheInstanceOrIsRefused) {
  const std::string args = "run '" + std::string(FF_SOURCE_DIR) +
                           "/tests/scenes/oclgrind_tiny.json' --backend cpu --threads 2 --steps 4 --metrics ";
  fftest::TempDir dir("simd_paths");
  const std::string a = (dir.path() / "native.csv").string(), b = (dir.path() / "portable.csv").string();
  const fftest::CliResult native = fftest::runFlowform(args + "'" + a + "'");
  ASSERT_EQ(native.code, 0) << native.out;
  const fftest::CliResult portable = fftest::runFlowform(args + "'" + b + "'", "FLOWFORM_SIMD=portable");
  ASSERT_EQ(portable.code, 0) << portable.out;
  EXPECT_NE(portable.out.find("2 threads, portable)"), std::string::npos) << portable.out;
  EXPECT_NE(native.out.find(std::string("2 threads, ") + ff::simd::isaName(ff::simd::isa()) + ")"),
            std::string::npos)
      << native.out;
  auto read = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_FALSE(read(a).empty());
  EXPECT_EQ(read(a), read(b));
  const fftest::CliResult bad = fftest::runFlowform(args + "'" + a + "'", "FLOWFORM_SIMD=sse9");
  EXPECT_EQ(bad.code, 1) << bad.out;
  EXPECT_NE(bad.out.find("FLOWFORM_SIMD: unknown instruction set 'sse9' (known: native, avx2, portable)"),
            std::string::npos)
      << bad.out;
}

}  // namespace
