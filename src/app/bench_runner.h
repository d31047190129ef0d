// bench_runner.h - times one bench case on one backend: warm-up steps, then
// per-step milliseconds of every phase, summarised as median / min / max.
#pragma once
#include <array>
#include <functional>
#include <memory>
#include <string>

#include "app/bench_cases.h"
#include "sim/backend.h"
#include "sim/simulation.h"

namespace ff::app {

// What one backend configuration is: kind for makeBackend and the device index.
struct BenchBackend {
  std::string kind;       // "cpu" or "opencl"
  int device = -1;        // OpenCL device index
  int threads = 0;        // OpenMP threads (0: default)
  int metrics_every = 1;  // Simulation::setMetricsEvery
};

struct PhaseStats {
  double median = 0.0, min = 0.0, max = 0.0;  // ms per step
};

struct BenchResult {
  std::string scene, backend, device;
  long fluid = 0;
  long control = 0;  // control particles actually placed
  int steps = 0;     // timed steps
  double mean_substeps = 0.0;
  std::array<PhaseStats, size_t(Phase::Count)> phase{};
  PhaseStats total;
  size_t memory_bytes = 0;  // the backend's particle, grid and control buffers
  double final_iou = 0.0;
  double wall_s = 0.0;  // whole run, warm-up and setup included
  // Host synchronisations per timed step, in steps with and without metrics
  // (Backend::hostSyncs: blocking reads, queue waits), and how many of each.
  double reads_with = 0.0, waits_with = 0.0, reads_without = 0.0, waits_without = 0.0;
  int steps_with = 0, steps_without = 0;
  double sum_ms = 0.0;            // the timed steps' phases, summed
  std::vector<StageTime> stages;  // the named stages inside phases, mean ms per timed step
};

// Median, minimum and maximum of the samples (which it reorders).
PhaseStats summarise(std::vector<double>& samples);

// Runs `steps` timed steps of `sim` into r (phases, total, substeps, host
// syncs, memory); `each`, when set, sees the simulation after every step.
void timeSteps(Simulation& sim, int steps, BenchResult& r,
               const std::function<void(const Simulation&)>& each);

// Runs `warmup` untimed steps and `steps` timed ones.
BenchResult runBenchCase(const BenchCase& bench_case, const BenchBackend& backend, int warmup, int steps);

}  // namespace ff::app
