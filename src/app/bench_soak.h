// bench_soak.h - `flowform bench --soak`: hundreds of target changes, each
// with a change of the controlled region, on one backend, checking after
// every change that no value is NaN or Inf and no particle has left the
// container, and sampling the resident memory (docs/PERFORMANCE.md).
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "app/bench_runner.h"

namespace ff::app {

struct SoakOptions {
  int changes = 300;            // target changes (each with a region change)
  int steps_between = 4;        // steps after each change
  int fluid_side = 14;          // the fluid block is fluid_side^3 particles
  double max_growth_mb = 32.0;  // resident memory may grow this much after the first 10% of changes
};

struct SoakResult {
  std::string backend, device;
  long fluid = 0;
  int changes = 0;
  long steps = 0;
  double sim_time = 0.0;
  long nonfinite = 0;                           // particle values that were NaN or Inf, over all checks
  long outside = 0;                             // particle positions outside the container, over all checks
  long min_controlled = 0, max_controlled = 0;  // controlled fluid particles after the changes
  size_t cache_entries = 0;                     // target shapes held by the Simulation's cache at the end
  double rss_start_mb = 0.0, rss_warm_mb = 0.0, rss_end_mb = 0.0, hwm_mb = 0.0;
  double wall_s = 0.0;
  std::string failure;  // empty: every check held
  bool ok() const { return failure.empty(); }
};

// Runs the soak on one backend; prints progress on stderr.
SoakResult runSoak(const SoakOptions& options, const BenchBackend& backend);
// A Markdown table of the results.
void printSoak(std::FILE* out, const std::vector<SoakResult>& results);

// This process's resident set now and its peak (VmRSS, VmHWM of
// /proc/self/status), in MiB; 0 where the file cannot be read.
double residentMb();
double peakResidentMb();

}  // namespace ff::app
