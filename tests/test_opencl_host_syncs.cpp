// Host synchronisations of the OpenCL step loop: with profiling off (the
// default) a step whose metrics are not requested reads nothing back and
// waits for nothing; a step with metrics reads its sums and the NaN record.
#include <gtest/gtest.h>

#include <memory>

#include "host/backend_opencl.h"
#include "sim/simulation.h"

namespace {

TEST(OpenClHostSyncs, NoBlockingReadInStepsWithoutMetrics) {
  ff::SceneDesc scene = ff::defaultScene();
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
    } else {
      ++without;
      EXPECT_EQ(after.reads, before.reads) << "step " << s << ": no metrics asked, nothing to read";
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

}  // namespace
