// bench_dambreak.h - `flowform bench --dambreak`: uncontrolled dam breaks
// timed from rest over a few simulated seconds, per pressure solver and
// backend: wall seconds per simulated second, ms per frame step, substeps,
// solver iterations and the density error. Two geometries: `peer`, the
// SPlisHSPlasH DamBreakModel the anchor was measured on (a 1 m cube
// in a corner of a 4 x 3 x 1.5 m tank, docs/PERFORMANCE.md), and `paper`, a
// block twice as high as long at the paper's 6.3 mm spacing in a slab four
// blocks long.
#pragma once
#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "app/bench_runner.h"
#include "scene/scene.h"

namespace ff::app {

// One dam break's geometry.
struct DambreakCase {
  std::string geometry;     // "peer" or "paper"
  std::array<int, 3> dims;  // the block's particles along x, y, z
  float spacing = 0.0f;     // the particle spacing (m); 0: the preset's (paper geometry)
  long count() const { return long(dims[0]) * dims[1] * dims[2]; }
};

// The dam break of `c` with the solver's preset ("paper" for wcsph, "water"
// for dfsph). `peer`: an n^3 block of spacing 1 / (n + 1) m in the low corner
// of a 4 x 3 x 1.5 m tank; only the particle size changes with it (the mass
// rho0 spacing^3, the support in the preset's ratio to the spacing), every
// other constant stays the preset's. `paper`: the block fills the slab's
// depth (nz) at its low-x end; the slab is 4 nx long and 2.5 ny high. Throws
// ff::Error when this build has no such solver or preset.
SceneDesc dambreakScene(const DambreakCase& c, const std::string& solver);

// The cases of `geometry` ("peer" or "paper"; else ff::Error naming
// --geometry) up to `max_fluid` (at least the first): peer 12 167 (23^3) and
// 103 823 (47^3) particles, paper 12k (20 x 40 x 15) and 99.2k
// (40 x 80 x 31); `quick`: one small block (peer 11^3, paper 10 x 20 x 8),
// for tests.
std::vector<DambreakCase> dambreakCases(const std::string& geometry, long max_fluid, bool quick);

struct DambreakResult {
  BenchResult timing;    // phases per frame step (scene "dambreak-<solver>")
  std::string solver;    // "wcsph", "dfsph"
  std::string preset;    // the parameter preset
  std::string geometry;  // DambreakCase::geometry
  double spacing = 0.0;  // the particle spacing (m)
  std::string skipped;   // non-empty: why this solver did not run on this backend
  double sim_seconds = 0.0;
  double wall_per_sim_s = 0.0;       // the steps' phases (setup excluded) per simulated second
  double ms_per_step = 0.0;          // mean over the frame steps
  double iterations_per_step = 0.0;  // solver iterations (both solves, every substep)
  double mean_density_error = 0.0;   // time mean of the metrics' density_error (surface deficit included)
  double mean_compression = 0.0;     // time mean of the metrics' compression (no free-surface deficit)
  double max_density_error = 0.0;    // largest max_density_error over the run
  long capped = 0;                   // solves that stopped at max_iterations
  long escaped = 0;                  // particles lost at the end: outside the container or NaN/Inf
};

// Runs one dam break with the solver called `solver` on `backend`: one
// untimed frame step (kernel compilation on OpenCL), then `sim_seconds` of
// timed frame steps. A solver the backend cannot run (or this build lacks)
// comes back with `skipped` set (the message).
DambreakResult runDambreak(const DambreakCase& c, const std::string& solver, const BenchBackend& backend,
                           double sim_seconds);

// The markdown table of the results (skipped ones listed below it).
void printDambreak(std::FILE* out, const std::vector<DambreakResult>& results);

}  // namespace ff::app
