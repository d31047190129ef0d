// A target change keeps the controlled volume (issue 10): with the recapture
// on, each new target is made for all the controlled fluid, n m / rho0, not
// only for the fluid still inside the current shape, so the control set does
// not shrink from one change to the next while fluid lies outside the shape.
// The control set's volume is measured independently of the volume the code
// scales the shape to: the count of inside voxels times the voxel's volume.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

#include "control/control_set.h"
#include "cpu/backend_cpu.h"
#include "sim/simulation.h"
#include "test_scenes.h"

namespace {

// The rest volume of the control set the backend runs: control particles
// times their rest volume (a voxel each).
double controlVolume(ff::Simulation& sim) {
  ff::ControlSet set;
  ff::ControlFields fields;
  sim.backend().readControl(set, fields);
  return double(set.size()) * double(set.particle_volume);
}

// A cube of fluid; a torus is set at the start, and the target changes every
// 5 steps (0.02 s), while the fluid is still about the cube: its middle lies
// in the torus's hole and its corners outside the ring, so well over a tenth
// of the fluid is outside the torus at the first change.
ff::SceneDesc cubeScene(const char* preset) {
  ff::SceneDesc s = fftest::blockScene(ff::Vec3(0.3f, 0.3f, 0.3f), ff::Vec3(0.1f, 0.0f, 0.1f), 13, 13, 13);
  s.params = ff::presetParams(preset);
  s.schedule.push_back({0.0, fftest::target(ff::TargetKind::Torus)});
  return s;
}

const ff::TargetKind kChanges[] = {ff::TargetKind::Sphere, ff::TargetKind::Capsule, ff::TargetKind::Box,
                                   ff::TargetKind::Torus};

TEST(TargetChangeVolume, EachChangeKeepsTheControlledVolume) {
  for (const char* preset : {"water", "paper"}) {
    SCOPED_TRACE(preset);
    ff::SceneDesc s = cubeScene(preset);
    ff::Simulation sim(s, std::make_unique<ff::CpuBackend>(2));
    const long n = long(s.fluidCount());
    const double volume = double(n) * double(s.params.fluid.restVolume());
    ASSERT_EQ(sim.controlledCount(), n);
    // The voxel size is searched near the default (1.55 fluid spacings) so
    // that the inside voxels hold the volume within 1% (kVolumeTolerance in
    // src/target/target_shape.cpp); 3% leaves room for a shape whose count
    // jumps across that band at every size tried. At the default voxel
    // itself the box (a cube 8.4 voxels wide) took 9^3 voxels, 24% too many.
    const double tol = 0.03 * volume;
    EXPECT_NEAR(controlVolume(sim), volume, tol) << "the first target";
    for (ff::TargetKind k : kChanges) {
      for (int i = 0; i < 5; ++i) sim.step();
      sim.setTarget(fftest::target(k));
      EXPECT_EQ(sim.controlledCount(), n) << sim.target()->label << ": all the fluid stays controlled";
      const double v = controlVolume(sim);
      std::printf("%s: %s: control set %.4g m^3 for %.4g m^3 of fluid (%zu control particles)\n", preset,
                  sim.target()->label.c_str(), v, volume, sim.target()->reference.size());
      EXPECT_NEAR(v, volume, tol) << sim.target()->label;
    }
  }
}

// The same changes without the recapture make each new shape only from the
// fluid inside the current one, which here is well short of all of it: the
// case above is one where a shrinking control set would show.
TEST(TargetChangeVolume, WithoutTheRecaptureTheShapeHoldsOnlyTheFluidInside) {
  ff::SceneDesc s = cubeScene("water");
  s.params.control.recapture = 0.0f;
  ff::Simulation sim(s, std::make_unique<ff::CpuBackend>(2));
  const long n = long(s.fluidCount());
  for (int i = 0; i < 5; ++i) sim.step();
  sim.setTarget(fftest::target(kChanges[0]));
  std::printf("without the recapture: %ld of %ld fluid particles in the new shape\n", sim.controlledCount(),
              n);
  EXPECT_LT(double(sim.controlledCount()), 0.9 * double(n));
  EXPECT_LT(controlVolume(sim), 0.9 * double(n) * double(s.params.fluid.restVolume()));
}

}  // namespace
