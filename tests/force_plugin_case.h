// force_plugin_case.h - the case of the force plug-in tests
// (test_force_plugins.cpp, test_opencl_force_plugins.cpp): a spring force
// that only the tests register, the scene it swings in, the analytic check of
// its motion, and the stages `run --profile` lists.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.h"
#include "core/params.h"
#include "cpu/forces/cpu_force.h"
#include "scene/scene.h"
#include "sim/simulation.h"

namespace fftest {

// a_y += -w^2 (y - c): a period of 1 s about y = c.
constexpr const char* kSpringName = "test spring";
constexpr float kSpringW2 = float(4.0 * M_PI * M_PI);
constexpr float kSpringCentre = 0.5f;
constexpr float kSpringAmplitude = 0.05f;  // peak speed 0.31 m/s, under the limit max_step_fraction h / dt

// The spring as a force of the OpenMP backend (test_opencl_force_plugins.cpp
// has its OpenCL twin, the same arithmetic in a kernel).
class CpuSpring : public ff::CpuForce {
 public:
  const char* name() const override { return kSpringName; }
  bool apply(ff::CpuForceContext& c, float) override {
    ff::CpuFluid& f = c.fluid;
    for (size_t i = 0; i < f.size(); ++i) f.ay[i] = f.ay[i] - kSpringW2 * (f.s.y[i] - kSpringCentre);
    return true;
  }
};

// Two particles 0.4 m apart in a 1 m box (the paper's h is 0.012 m): out of
// each other's and the walls' reach, no gravity, starting at c + A.
inline ff::SceneDesc springScene() {
  ff::SceneDesc s;
  s.source = "force plug-in test";
  s.params = ff::presetParams("paper");
  for (float& g : s.params.fluid.gravity) g = 0.0f;
  s.container.min = ff::Vec3(0.0f, 0.0f, 0.0f);
  s.container.max = ff::Vec3(1.0f, 1.0f, 1.0f);
  const float sp = 0.02f;
  for (float x : {0.3f, 0.7f}) {
    ff::FluidBlockDesc b;
    b.dims[0] = b.dims[1] = b.dims[2] = 1;
    b.spacing = sp;
    b.origin = ff::Vec3(x - 0.5f * sp, kSpringCentre + kSpringAmplitude - 0.5f * sp, 0.5f - 0.5f * sp);
    s.fluid.push_back(b);
  }
  return s;
}

// Runs 1 s (a period) and checks y against c + A cos(w t) after every step:
// symplectic Euler keeps the amplitude within w dt / 2 (1.3% at dt = 4 ms),
// so 3% of A; x and z stay where they were.
inline void expectOscillation(ff::Simulation& sim) {
  const double w = std::sqrt(double(kSpringW2));
  ff::FluidState start;
  sim.backend().readFluid(start);
  ASSERT_EQ(start.size(), 2u);
  double worst = 0.0;
  ff::FluidState f;
  while (sim.time() < 1.0 - 1e-9) {
    sim.step();
    sim.backend().readFluid(f);
    const double y = kSpringCentre + kSpringAmplitude * std::cos(w * sim.time());
    for (size_t i = 0; i < f.size(); ++i) {
      worst = std::max(worst, std::fabs(f.y[i] - y));
      const size_t k = start.id[0] == f.id[i] ? 0 : 1;
      ASSERT_EQ(start.id[k], f.id[i]);
      EXPECT_EQ(f.x[i], start.x[k]);
      EXPECT_EQ(f.z[i], start.z[k]);
    }
  }
  EXPECT_LT(worst, 0.03 * kSpringAmplitude) << "worst distance from the analytic path (m)";
  // A period later: back at the top.
  for (size_t i = 0; i < f.size(); ++i)
    EXPECT_NEAR(f.y[i], kSpringCentre + kSpringAmplitude, 0.03 * kSpringAmplitude);
}

// The (phase, stage) lines of `flowform run`'s profile: a phase line is
// "  NAME  ms", its stages follow as "    NAME  ms".
inline std::vector<std::pair<std::string, std::string>> profileStages(const std::string& out) {
  std::vector<std::pair<std::string, std::string>> stages;
  const size_t from = out.find("ms per step by phase");
  if (from == std::string::npos) return stages;
  std::istringstream in(out.substr(from));
  std::string line, phase;
  auto name = [](const std::string& l, size_t at) {
    const size_t end = l.find("  ", at);  // names have single spaces; columns are padded
    return l.substr(at, end == std::string::npos ? std::string::npos : end - at);
  };
  while (std::getline(in, line)) {
    if (line.rfind("    ", 0) == 0 && !phase.empty())
      stages.emplace_back(phase, name(line, 4));
    else if (line.rfind("  ", 0) == 0)
      phase = name(line, 2);
  }
  return stages;
}

// `flowform run --profile` on a tiny water scene with control lists each
// plug-in under its phase and the DFSPH solver's stages.
inline void expectProfileNames(const std::string& backend) {
  const std::string scene = std::string(FF_SOURCE_DIR) + "/tests/scenes/oclgrind_tiny_water.json";
  const CliResult r = runFlowform("run '" + scene + "' --steps 2 --profile --threads 2 --backend " + backend);
  ASSERT_EQ(r.code, 0) << r.out;
  const std::vector<std::pair<std::string, std::string>> listed = profileStages(r.out);
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"forces", "gravity"},         {"forces", "viscosity"},          {"control_scale", "control"},
      {"control_forces", "control"}, {"pressure", "divergence solve"}, {"pressure", "density solve"}};
  for (const auto& stage : expected)
    EXPECT_NE(std::find(listed.begin(), listed.end(), stage), listed.end())
        << backend << ": no stage '" << stage.second << "' under " << stage.first << "\n"
        << r.out;
}

}  // namespace fftest
