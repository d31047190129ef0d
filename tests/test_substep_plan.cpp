// test_substep_plan.cpp - a frame step's substeps (FluidParams::substepPlan):
// equal ones that end on the frame, or ones as long as the CFL conditions
// allow that carry over it (fluid.substep_carry), against counts and clocks
// worked out here by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/params.h"
#include "cpu/backend_cpu.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"

namespace {

// Water at a 4 ms frame step whose CFL substep is `frame / ratio`: the speed
// that makes cfl h / v_max that long, no pressure condition, no cap below it.
ff::FluidParams waterAtRatio(double ratio, double& speed) {
  ff::FluidParams f = ff::presetParams("water").fluid;
  f.setTimeStep(0.004f);
  f.max_substep_fall = 0.0f, f.max_substep = 1.0f;
  speed = ratio * double(f.cfl) * double(f.smoothing_radius) / double(f.time_step);
  return f;
}

// Substeps 3.2 to a frame: equal substeps that end on the frame take 4 each
// (ceil 3.2); substeps that carry over take 16 per 5 frame steps, as many as
// the 5 x 3.2 = 16 the fluid's clock needs, each no longer than the CFL
// condition allows, and the fluid's clock leads the frames by less than one.
TEST(SubstepPlan, CarriedSubstepsAreAsFewAsTheFluidsClockNeeds) {
  double v = 0.0;
  ff::FluidParams f = waterAtRatio(3.2, v);
  ASSERT_EQ(f.substep_carry, 1) << "the water preset carries its substeps";
  const double frame = double(f.time_step), limit = frame / 3.2;
  ASSERT_NEAR(f.substepLimit(0.0, v), limit, 1e-9 * limit);

  ff::FluidParams equal = f;
  equal.substep_carry = 0;
  const ff::SubstepPlan e = equal.substepPlan(0.0, 0.0, v);
  EXPECT_EQ(e.count, 4);
  EXPECT_EQ(e.dt, f.time_step / 4.0f);
  EXPECT_EQ(e.advance, double(f.time_step));
  EXPECT_EQ(e.lead, 0.0);

  double lead = 0.0, fluid_clock = 0.0;
  int substeps = 0;
  const int frames = 500;
  for (int k = 0; k < frames; ++k) {
    const ff::SubstepPlan p = f.substepPlan(lead, 0.0, v);
    ASSERT_GE(p.count, 1);
    EXPECT_LE(double(p.dt), limit * (1.0 + 1e-6)) << "frame " << k;
    EXPECT_EQ(p.advance, double(p.count) * double(p.dt)) << "frame " << k;
    fluid_clock += p.advance;
    substeps += p.count;
    lead = p.lead;
    EXPECT_GE(lead, 0.0) << "frame " << k;
    EXPECT_LT(lead, double(p.dt)) << "frame " << k;
    // The lead is the fluid's clock less the frame clock.
    EXPECT_NEAR(lead, fluid_clock - double(k + 1) * frame, 1e-9) << "frame " << k;
  }
  // 500 frames of 3.2 substeps: 1600, against 2000 equal ones.
  EXPECT_NEAR(substeps, frames * 3.2, 1.0);
}

// Where the cap allows more than the frame step (the water preset's 4.01 ms
// at 4 ms frames, no CFL binding), each frame step is one substep of exactly
// the frame step, as equal substeps give, and the clocks stay together.
TEST(SubstepPlan, ACapLongerThanTheFrameGivesOneWholeSubstep) {
  ff::FluidParams f = ff::presetParams("water").fluid;
  f.setTimeStep(0.004f);
  f.max_substep_fall = 0.0f, f.max_substep = 0.00401f;
  ff::FluidParams equal = f;
  equal.substep_carry = 0;
  for (const ff::FluidParams& p : {f, equal}) {
    const ff::SubstepPlan s = p.substepPlan(0.0, 0.0, 0.0);
    EXPECT_EQ(s.count, 1);
    EXPECT_EQ(s.dt, 0.004f);
    EXPECT_EQ(s.lead, 0.0);
  }
}

// max_substeps bounds the count: the substeps are then longer than the CFL
// condition asks, and end on the frame (no lead), as equal substeps do. A
// frame step made shorter than the lead (the viewer's slider) starts the
// frame clock afresh instead of taking no substep.
TEST(SubstepPlan, BoundedCountAndAShortenedFrameStillStep) {
  double v = 0.0;
  ff::FluidParams f = waterAtRatio(40.0, v);
  f.max_substeps = 16;
  ff::SubstepPlan p = f.substepPlan(0.0, 0.0, v);
  EXPECT_EQ(p.count, 16);
  EXPECT_NEAR(double(p.dt), double(f.time_step) / 16.0, 1e-12);
  EXPECT_NEAR(p.lead, 0.0, 1e-12);

  ff::FluidParams one = waterAtRatio(0.5, v);
  p = one.substepPlan(double(one.time_step) * 1.5, 0.0, v);
  EXPECT_EQ(p.count, 1);
  EXPECT_EQ(p.dt, one.time_step);
}

// A small water dam break: the metrics' time is the fluid's clock, ahead of
// the frame steps by less than a frame step, and over the run the fluid
// takes fewer substeps than equal ones would (which land on every frame).
TEST(SubstepPlan, DamBreakRunsOnTheFluidsClock) {
  const char* text = R"({
    "name": "carry", "preset": "water",
    "container": {"min": [0, 0, 0], "max": [0.25, 0.15, 0.06]},
    "fluid": [{"origin": [0, 0, 0], "dims": [10, 16, 8]}]
  })";
  int counts[2] = {0, 0};
  double most_lead = 0.0;
  for (int carry = 0; carry < 2; ++carry) {
    ff::SceneDesc scene = ff::parseScene(text, "carry.json", "");
    scene.params.fluid.substep_carry = carry;
    ff::Simulation sim(scene, std::make_unique<ff::CpuBackend>(2));
    const double frame = double(sim.scene().params.fluid.time_step);
    while (sim.stepCount() < 60) {
      ASSERT_NO_THROW(sim.step());
      const ff::StepMetrics& m = sim.metrics();
      const double frames = double(m.step) * frame, lead = sim.time() - frames;
      EXPECT_EQ(m.time, sim.time());
      if (carry) {
        EXPECT_GE(lead, -1e-12) << "step " << m.step;
        EXPECT_LT(lead, frame) << "step " << m.step;
        most_lead = std::max(most_lead, lead);
      } else {
        EXPECT_NEAR(lead, 0.0, 1e-9) << "step " << m.step;
      }
      counts[carry] += m.substeps;
    }
    EXPECT_EQ(sim.metrics().solver_capped, 0);
  }
  std::printf("substeps over 60 frame steps: %d equal, %d carried\n", counts[0], counts[1]);
  EXPECT_LT(counts[1], counts[0]);
  EXPECT_GT(most_lead, 0.0) << "no frame step carried a substep over";
}

}  // namespace
