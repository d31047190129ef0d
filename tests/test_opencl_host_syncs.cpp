// Host synchronisations of the OpenCL step loop: with profiling off (the
// default) a step whose metrics are not requested waits for nothing, and it
// reads nothing back but what its pressure solver must: nothing for WCSPH
// (the `paper` preset), the stopping test of each DFSPH solve for `water`
// (the default), one small read per batch of iterations (host/dfsph_cl.h);
// a step with metrics reads its sums and the NaN record.
#include <gtest/gtest.h>

#include <memory>

#include "core/params.h"
#include "host/backend_opencl.h"
#include "host/dfsph_cl.h"
#include "sim/simulation.h"

namespace {

// The default scene on `preset`: 20 steps with metrics every 5th; checks the
// host syncs of each step against what it may do.
void checkSyncs(const std::string& preset) {
  ff::SceneDesc scene = ff::defaultScene();
  scene.preset = preset;
  scene.params = ff::presetParams(preset);
  const bool dfsph = scene.params.fluid.solver == ff::PressureSolverKind::Dfsph;
  const int max_it = scene.params.fluid.max_iterations, batch = ff::ClDfsphSolver::kIterationBatch;
  ff::Simulation sim(scene, std::make_unique<ff::OpenClBackend>());
  sim.setMetricsEvery(5);
  int with = 0, without = 0;
  for (int s = 1; s <= 20; ++s) {
    const ff::Backend::HostSyncs before = sim.backend().hostSyncs();
    sim.step();
    const ff::Backend::HostSyncs after = sim.backend().hostSyncs();
    EXPECT_EQ(sim.metricsFresh(), s % 5 == 0) << "step " << s;
    EXPECT_EQ(after.waits, before.waits) << "step " << s << ": profiling is off, no phase may wait";
    if (sim.metricsFresh()) {
      ++with;
      EXPECT_GT(after.reads, before.reads) << "step " << s << ": the metrics are read back";
      continue;
    }
    ++without;
    const long reads = after.reads - before.reads, solves = 2L * sim.metrics().substeps;
    if (!dfsph) {
      EXPECT_EQ(reads, 0) << "step " << s << ": no metrics asked, nothing to read";
    } else {  // each of the two solves per substep: its first test, then one per batch
      EXPECT_GE(reads, solves) << "step " << s;
      EXPECT_LE(reads, solves * (1 + (max_it + batch - 1) / batch)) << "step " << s;
    }
  }
  EXPECT_EQ(with, 4);
  EXPECT_EQ(without, 16);
  EXPECT_GT(sim.metrics().iou, 0.0);  // the metrics steps measured the sphere forming
  // requestMetrics() asks for the next step's.
  sim.requestMetrics();
  sim.step();
  EXPECT_TRUE(sim.metricsFresh());
  // Profiling on: every phase waits once.
  sim.setProfiling(true);
  const ff::Backend::HostSyncs before = sim.backend().hostSyncs();
  sim.step();
  EXPECT_GE(sim.backend().hostSyncs().waits - before.waits, long(ff::Phase::Metrics));
}

TEST(OpenClHostSyncs, NoBlockingReadInStepsWithoutMetrics) {
  checkSyncs("paper");
}

TEST(OpenClHostSyncs, DfsphReadsOnlyItsStoppingTests) {
  checkSyncs("water");
}

// Simulation::setShapeMetricsOnRequest on OpenCL: the steps without the
// target's metrics launch neither the iou nor the shares kernel, and the
// requested step reads the same values as a run that computes them every step.
TEST(OpenClHostSyncs, ShapeMetricsOnRequestAreTheEveryStepValues) {
  ff::SceneDesc scene = ff::defaultScene();
  ff::Simulation every(scene, std::make_unique<ff::OpenClBackend>()),
      asked(scene, std::make_unique<ff::OpenClBackend>());
  asked.setShapeMetricsOnRequest(true);
  for (int k = 1; k <= 8; ++k) {
    const bool request = k == 8;
    if (request) asked.requestMetrics();
    // The count is the process's (cl_kernel.h): each run's step on its own.
    auto readsOf = [](ff::Simulation& sim) {
      const long before = sim.backend().hostSyncs().reads;
      sim.step();
      return sim.backend().hostSyncs().reads - before;
    };
    const long da = readsOf(every), db = readsOf(asked);
    if (request) {
      EXPECT_EQ(db, da) << "step " << k;
    } else {
      EXPECT_EQ(db, da - 2) << "step " << k << ": no iou and no shares read back";
    }
    EXPECT_EQ(every.metrics().max_speed, asked.metrics().max_speed) << "step " << k;
  }
  const ff::StepMetrics &a = every.metrics(), &b = asked.metrics();
  EXPECT_GT(a.iou, 0.0);
  EXPECT_EQ(a.iou, b.iou);
  EXPECT_EQ(a.filled, b.filled);
  EXPECT_EQ(a.stray, b.stray);
  EXPECT_EQ(a.tilt, b.tilt);
}

}  // namespace
