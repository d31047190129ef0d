// bench_dambreak.h - `flowform bench --dambreak`: uncontrolled dam breaks (a
// block of water twice as high as long, in the corner of a slab four blocks
// long) timed from rest over a few simulated seconds, per pressure solver and
// backend: wall seconds per simulated second, ms per frame step, substeps,
// solver iterations and the density error.
#pragma once
#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "app/bench_runner.h"
#include "scene/scene.h"

namespace ff::app {

// A dam break of nx x ny x nz particles: the block fills the slab's depth
// (nz) at its low-x end; the slab is 4 nx long and 2.5 ny high. The solver's
// preset: "paper" for wcsph, "water" for dfsph (the same particle spacing).
// Throws ff::Error when this build has no such solver or preset.
SceneDesc dambreakScene(int nx, int ny, int nz, const std::string& solver);

// The block sizes: 12k (20 x 40 x 15) and 99.2k (40 x 80 x 31) particles up to
// `max_fluid`; `quick`: one 1.6k block (10 x 20 x 8), for tests.
std::vector<std::array<int, 3>> dambreakSizes(long max_fluid, bool quick);

struct DambreakResult {
  BenchResult timing;   // phases per frame step (scene "dambreak-<solver>")
  std::string solver;   // "wcsph", "dfsph"
  std::string preset;   // the parameter preset
  std::string skipped;  // non-empty: why this solver did not run on this backend
  double sim_seconds = 0.0;
  double wall_per_sim_s = 0.0;       // the steps' phases (setup excluded) per simulated second
  double ms_per_step = 0.0;          // mean over the frame steps
  double iterations_per_step = 0.0;  // solver iterations (both solves, every substep)
  double mean_density_error = 0.0;   // time mean of the metrics' density_error
  double max_density_error = 0.0;    // largest max_density_error over the run
  long capped = 0;                   // solves that stopped at max_iterations
  long escaped = 0;                  // particles lost at the end: outside the container or NaN/Inf
};

// Runs one dam break with the solver called `solver` on `backend`: one
// untimed frame step (kernel compilation on OpenCL), then `sim_seconds` of
// timed frame steps. A solver the backend cannot run (or this build lacks)
// comes back with `skipped` set (the message).
DambreakResult runDambreak(const std::array<int, 3>& size, const std::string& solver,
                           const BenchBackend& backend, double sim_seconds);

// The markdown table of the results (skipped ones listed below it).
void printDambreak(std::FILE* out, const std::vector<DambreakResult>& results);

}  // namespace ff::app
