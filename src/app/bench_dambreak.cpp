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

SceneDesc dambreakScene(int nx, int ny, int nz, const std::string& solver) {
  const PressureSolverKind kind = solverByName(solver);
  SceneDesc s;
  s.preset = solver == "dfsph" ? "water" : "paper";
  s.params = presetParams(s.preset);
  s.params.fluid.solver = kind;
  s.name = "dambreak-" + solver;
  s.source = "<flowform bench --dambreak>";
  const float sp = s.params.fluid.restSpacing();
  s.container.min = Vec3(0.0f, 0.0f, 0.0f);
  s.container.max = Vec3(4.0f * float(nx) * sp, 2.5f * float(ny) * sp, float(nz) * sp);
  FluidBlockDesc b;
  b.origin = Vec3(0.0f, 0.0f, 0.0f);
  b.dims[0] = nx, b.dims[1] = ny, b.dims[2] = nz;
  s.fluid.push_back(b);
  return s;
}

std::vector<std::array<int, 3>> dambreakSizes(long max_fluid, bool quick) {
  if (quick) return {{10, 20, 8}};
  std::vector<std::array<int, 3>> sizes;
  for (const std::array<int, 3>& d : {std::array<int, 3>{20, 40, 15}, std::array<int, 3>{40, 80, 31}})
    if (long(d[0]) * d[1] * d[2] <= max_fluid || sizes.empty()) sizes.push_back(d);
  return sizes;
}

DambreakResult runDambreak(const std::array<int, 3>& size, const std::string& solver, const BenchBackend& b,
                           double sim_seconds) {
  const auto t0 = std::chrono::steady_clock::now();
  DambreakResult d;
  d.solver = solver;
  BenchResult& r = d.timing;
  r.fluid = long(size[0]) * size[1] * size[2];
  std::string note;
  std::unique_ptr<Backend> backend = makeBackend(b.kind, b.device, b.threads, &note);
  r.backend = backend->name();
  r.device = backend->device();
  std::unique_ptr<Simulation> sim;
  SceneDesc scene;
  try {
    scene = dambreakScene(size[0], size[1], size[2], solver);
    d.preset = scene.preset;
    r.scene = scene.name;
    sim = std::make_unique<Simulation>(scene, std::move(backend));
  } catch (const Error& e) {
    d.skipped = e.what();
    return d;
  }
  sim->setProfiling(true);
  const double frame = double(scene.params.fluid.time_step);
  const int steps = std::max(1, int(std::lround(sim_seconds / frame)));
  // One untimed frame step first: an OpenCL runtime compiles kernels at their
  // first launch (PoCL: about 2 s), which is setup, not simulation.
  sim->step();
  double derr = 0.0, iterations = 0.0;
  timeSteps(*sim, steps, r, [&](const Simulation& s) {
    const StepMetrics& m = s.metrics();
    derr += m.density_error;
    iterations += double(m.solver_iterations);
    d.max_density_error = std::max(d.max_density_error, m.max_density_error);
    d.capped += m.solver_capped;
  });
  d.sim_seconds = double(steps) * frame;  // timed, after the first frame step
  d.wall_per_sim_s = r.sum_ms * 1e-3 / d.sim_seconds;
  d.ms_per_step = r.sum_ms / double(steps);
  d.iterations_per_step = iterations / double(steps);
  d.mean_density_error = derr / double(steps);
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
               "| solver | preset | backend | device | fluid | sim s | frame steps | **wall s / sim s** | "
               "ms / step | substeps / step | iterations / step | mean density error | max density error | "
               "capped solves | escaped |\n");
  std::fprintf(out, "|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const DambreakResult& d : results) {
    if (!d.skipped.empty()) continue;
    const BenchResult& r = d.timing;
    std::fprintf(
        out,
        "| %s | %s | %s | %s | %ld | %.3f | %d | **%.3f** | %.3f | %.2f | %.1f | %.6f | %.6f | %ld | %ld |\n",
        d.solver.c_str(), d.preset.c_str(), r.backend.c_str(), r.device.c_str(), r.fluid, d.sim_seconds,
        r.steps, d.wall_per_sim_s, d.ms_per_step, r.mean_substeps, d.iterations_per_step,
        d.mean_density_error, d.max_density_error, d.capped, d.escaped);
  }
  for (const DambreakResult& d : results)
    if (!d.skipped.empty())
      std::fprintf(out, "\nnot run: %s on %s (%s, %ld fluid): %s\n", d.solver.c_str(),
                   d.timing.backend.c_str(), d.timing.device.c_str(), d.timing.fluid, d.skipped.c_str());
  std::fflush(out);
}

}  // namespace ff::app
