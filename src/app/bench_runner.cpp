// bench_runner.cpp - one timed run of a bench case.
#include "app/bench_runner.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "core/error.h"
#include "host/backend_factory.h"
#include "sim/simulation.h"

namespace ff::app {

PhaseStats summarise(std::vector<double>& v) {
  PhaseStats s;
  if (v.empty()) return s;
  const size_t n = v.size();
  std::nth_element(v.begin(), v.begin() + long(n / 2), v.end());
  double med = v[n / 2];
  if (n % 2 == 0) med = 0.5 * (med + *std::max_element(v.begin(), v.begin() + long(n / 2)));
  s.median = med;
  s.min = *std::min_element(v.begin(), v.end());
  s.max = *std::max_element(v.begin(), v.end());
  return s;
}

void timeSteps(Simulation& sim, int steps, BenchResult& r,
               const std::function<void(const Simulation&)>& each) {
  constexpr size_t kPhases = size_t(Phase::Count);
  std::array<std::vector<double>, kPhases> samples;
  std::vector<double> totals;
  totals.reserve(size_t(steps));
  double substeps = 0.0;
  for (int i = 0; i < steps; ++i) {
    const Backend::HostSyncs before = sim.backend().hostSyncs();
    sim.step();
    const Backend::HostSyncs after = sim.backend().hostSyncs();
    const double reads = double(after.reads - before.reads), waits = double(after.waits - before.waits);
    if (sim.metricsFresh())
      r.reads_with += reads, r.waits_with += waits, ++r.steps_with;
    else
      r.reads_without += reads, r.waits_without += waits, ++r.steps_without;
    double total = 0.0;
    for (size_t p = 0; p < kPhases; ++p) {
      samples[p].push_back(sim.lastStepMs()[p]);
      total += sim.lastStepMs()[p];
    }
    totals.push_back(total);
    r.sum_ms += total;
    substeps += sim.metrics().substeps;
    addStages(r.stages, sim.lastStepStageMs());
    if (each) each(sim);
  }
  for (StageTime& s : r.stages) s.ms /= double(std::max(1, steps));
  for (size_t p = 0; p < kPhases; ++p) r.phase[p] = summarise(samples[p]);
  r.total = summarise(totals);
  r.steps = steps;
  r.mean_substeps = substeps / double(steps);
  r.control = sim.metrics().control_count;
  r.memory_bytes = sim.backend().memoryBytes();
  r.final_iou = sim.metrics().iou;
  if (r.steps_with > 0) r.reads_with /= r.steps_with, r.waits_with /= r.steps_with;
  if (r.steps_without > 0) r.reads_without /= r.steps_without, r.waits_without /= r.steps_without;
}

BenchResult runBenchCase(const BenchCase& c, const BenchBackend& b, int warmup, int steps) {
  if (steps < 1) throw Error("bench: --steps must be at least 1");
  const auto t0 = std::chrono::steady_clock::now();
  std::string note;
  auto backend = makeBackend(b.kind, b.device, b.threads, &note);
  BenchResult r;
  r.scene = c.name;
  r.backend = backend->name();
  r.device = backend->device();
  Simulation sim(c.scene, std::move(backend));
  sim.setProfiling(true);
  sim.setMetricsEvery(b.metrics_every);
  for (int i = 0; i < warmup; ++i) sim.step();
  timeSteps(sim, steps, r, nullptr);
  r.fluid = c.fluid;
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace ff::app
