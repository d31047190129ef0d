// bench_dambreak.cpp - the dam breaks of `flowform bench --dambreak`.
#include "app/bench_dambreak.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "app/fluid_census.h"
#include "core/error.h"
#include "core/fluid_state.h"
#include "host/backend_factory.h"
#include "sim/simulation.h"

namespace ff::app {

SceneDesc dambreakScene(const DambreakCase& c, const std::string& solver) {
  const PressureSolverKind kind = solverByName(solver);
  SceneDesc s;
  s.preset = solver == "dfsph" ? "water" : "paper";
  s.params = presetParams(s.preset);
  s.params.fluid.solver = kind;
  s.name = "dambreak-" + solver;
  s.source = "<flowform bench --dambreak>";
  FluidParams& f = s.params.fluid;
  if (c.spacing > 0.0f) {  // the preset's particle, resized
    const float ratio = c.spacing / f.restSpacing();
    f.particle_mass = f.rest_density * c.spacing * c.spacing * c.spacing;
    f.smoothing_radius *= ratio, f.particle_radius *= ratio;
  }
  const float sp = f.restSpacing();
  const int nx = c.dims[0], ny = c.dims[1], nz = c.dims[2];
  s.container.min = Vec3(0.0f, 0.0f, 0.0f);
  s.container.max = c.geometry == "peer" ? Vec3(4.0f, 3.0f, 1.5f)
                                         : Vec3(4.0f * float(nx) * sp, 2.5f * float(ny) * sp, float(nz) * sp);
  FluidBlockDesc b;
  b.origin = Vec3(0.0f, 0.0f, 0.0f);
  b.dims[0] = nx, b.dims[1] = ny, b.dims[2] = nz;
  s.fluid.push_back(b);
  return s;
}

std::vector<DambreakCase> dambreakCases(const std::string& geometry, long max_fluid, bool quick) {
  std::vector<DambreakCase> all;
  if (geometry == "peer") {  // SPlisHSPlasH: particle radius 1 / (2 (n + 1)) m
    for (int n : quick ? std::vector<int>{11} : std::vector<int>{23, 47})
      all.push_back({geometry, {n, n, n}, 1.0f / float(n + 1)});
  } else if (geometry == "paper") {
    const std::vector<std::array<int, 3>> dims =
        quick ? std::vector<std::array<int, 3>>{{10, 20, 8}}
              : std::vector<std::array<int, 3>>{{20, 40, 15}, {40, 80, 31}};
    for (const std::array<int, 3>& d : dims) all.push_back({geometry, d, 0.0f});
  } else {
    throw Error("--geometry: '" + geometry + "' is not one of peer, paper");
  }
  std::vector<DambreakCase> cases;
  for (const DambreakCase& c : all)
    if (c.count() <= max_fluid || cases.empty()) cases.push_back(c);
  return cases;
}

DambreakResult runDambreak(const DambreakCase& c, const std::string& solver, const BenchBackend& b,
                           double sim_seconds) {
  const auto t0 = std::chrono::steady_clock::now();
  DambreakResult d;
  d.solver = solver;
  BenchResult& r = d.timing;
  d.geometry = c.geometry;
  r.fluid = c.count();
  std::string note;
  std::unique_ptr<Backend> backend = makeBackend(b.kind, b.device, b.threads, &note);
  r.backend = backend->name();
  r.device = backend->device();
  std::unique_ptr<Simulation> sim;
  SceneDesc scene;
  try {
    scene = dambreakScene(c, solver);
    d.preset = scene.preset;
    d.spacing = double(scene.params.fluid.restSpacing());
    r.scene = scene.name;
    sim = std::make_unique<Simulation>(scene, std::move(backend));
  } catch (const Error& e) {
    d.skipped = e.what();
    return d;
  }
  sim->setProfiling(true);
  const double frame = double(sim->scene().params.fluid.time_step);
  const int steps = std::max(1, int(std::lround(sim_seconds / frame)));
  // One untimed frame step first: an OpenCL runtime compiles kernels at their
  // first launch (PoCL: about 2 s), which is setup, not simulation.
  sim->step();
  const double timed_from = sim->time();
  double derr = 0.0, iterations = 0.0, compression = 0.0;
  timeSteps(*sim, steps, r, [&](const Simulation& s) {
    const StepMetrics& m = s.metrics();
    compression += m.compression;  // the solvers' measure: no free-surface deficit
    derr += m.density_error;
    iterations += double(m.solver_iterations);
    d.max_density_error = std::max(d.max_density_error, m.max_density_error);
    d.capped += m.solver_capped;
  });
  // Timed, after the first frame step: the fluid's clock, which runs ahead
  // of the frames by less than a substep where substeps carry over them.
  d.sim_seconds = sim->time() - timed_from;
  d.wall_per_sim_s = r.sum_ms * 1e-3 / d.sim_seconds;
  d.ms_per_step = r.sum_ms / double(steps);
  d.iterations_per_step = iterations / double(steps);
  d.mean_density_error = derr / double(steps);
  d.mean_compression = compression / double(steps);
  FluidState end;
  sim->backend().readFluid(end);
  d.escaped = countLostFluid(end, scene.container).lost();
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return d;
}

void printDambreak(std::FILE* out, const std::vector<DambreakResult>& results) {
  if (results.empty()) return;
  std::fprintf(
      out,
      "\n### Dam break, no control (wall s per simulated s: the timed frame steps' phases, after one untimed "
      "step)\n\n");
  std::fprintf(out,
               "| solver | preset | geometry | spacing m | backend | device | fluid | sim s | frame steps | "
               "**wall s / sim s** | "
               "ms / step | substeps / step | iterations / step | mean density error | mean compression | "
               "max density error | capped solves | escaped |\n");
  std::fprintf(out,
               "|---|---|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const DambreakResult& d : results) {
    if (!d.skipped.empty()) continue;
    const BenchResult& r = d.timing;
    std::fprintf(out,
                 "| %s | %s | %s | %.5f | %s | %s | %ld | %.3f | %d | **%.3f** | %.3f | %.2f | %.1f | %.6f | "
                 "%.6f | %.6f | %ld | %ld |\n",
                 d.solver.c_str(), d.preset.c_str(), d.geometry.c_str(), d.spacing, r.backend.c_str(),
                 r.device.c_str(), r.fluid, d.sim_seconds, r.steps, d.wall_per_sim_s, d.ms_per_step,
                 r.mean_substeps, d.iterations_per_step, d.mean_density_error, d.mean_compression,
                 d.max_density_error, d.capped, d.escaped);
  }
  for (const DambreakResult& d : results)
    if (!d.skipped.empty())
      std::fprintf(out, "\nnot run: %s on %s (%s, %ld fluid): %s\n", d.solver.c_str(),
                   d.timing.backend.c_str(), d.timing.device.c_str(), d.timing.fluid, d.skipped.c_str());
  std::fflush(out);
}

}  // namespace ff::app
