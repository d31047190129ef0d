// The non-pressure forces as plug-ins (src/cpu/forces/): the registered list
// and its order, a force that only a test registers moving particles as the
// analytic solution says, and the plug-ins and solver stages named in the
// timings of `flowform run --profile`. The OpenCL counterparts are in
// test_opencl_force_plugins.cpp.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "cpu/backend_cpu.h"
#include "force_plugin_case.h"
#include "sim/simulation.h"

namespace {

TEST(ForcePlugins, RegistryListsGravityViscosityControlInOrder) {
  const ff::CpuBackend cpu(2);
  EXPECT_EQ(cpu.forceNames(), (std::vector<std::string>{"gravity", "viscosity", "control"}));
}

// Two lone particles (out of each other's and the walls' reach, no gravity):
// only the spring acts, so y follows the oscillator c + A cos(w t) up to the
// error of symplectic Euler (amplitude within w dt / 2 = 1.3% of A at the
// paper's dt). Without the plug-in running they would stay put; run twice,
// they would swing at sqrt(2) w.
TEST(ForcePlugins, ATestsSpringForceSwingsAsTheAnalyticOscillator) {
  auto backend = std::make_unique<ff::CpuBackend>(2);
  backend->addForce(std::make_unique<fftest::CpuSpring>());
  EXPECT_EQ(backend->forceNames().back(), fftest::kSpringName);
  ff::Simulation sim(fftest::springScene(), std::move(backend));
  fftest::expectOscillation(sim);
  bool timed = false;
  for (const ff::StageTime& s : sim.stageMs())
    timed = timed || (s.phase == "forces" && s.name == fftest::kSpringName);
  EXPECT_TRUE(timed) << "the test's force is not among the timed stages";
}

// `run --profile` names each plug-in under its phase and the DFSPH solver's
// stages (the water preset); test_opencl_force_plugins.cpp does so on OpenCL.
TEST(ForcePlugins, RunProfileNamesEachPluginAndSolverStage) {
  fftest::expectProfileNames("cpu");
}

}  // namespace
