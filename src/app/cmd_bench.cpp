// cmd_bench.cpp - `flowform bench`: ms per step and phase for the paper's
// Table 1 scenes (its Fig. 8) and the scaling sweeps, on every backend present.
#include <omp.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "app/bench_cases.h"
#include "app/bench_dambreak.h"
#include "app/bench_report.h"
#include "app/bench_runner.h"
#include "app/bench_soak.h"
#include "app/bench_stability.h"
#include "app/commands.h"
#include "app/kernels_option.h"
#include "core/error.h"
#include "core/resource_limits.h"
#ifndef FF_NO_OPENCL
#include "host/cl_context.h"
#endif

namespace ff::app {

namespace {

struct BenchOptions {
  bool table1 = false, fluid_sweep = false, control_sweep = false, dambreak = false;
  std::string solver = "all";     // --dambreak: wcsph, dfsph or all
  double seconds = 1.0;           // --dambreak: simulated seconds
  bool quick = false;             // --dambreak: one small block
  std::string geometry = "peer";  // --dambreak: peer or paper
  std::string backend = "all";
  int device = -1;
  int threads = 0;
  int steps = 200, warmup = 50;
  int sweep_steps = 50, sweep_warmup = 20;
  long max_fluid = 1000000;
  long max_control = 50000;
  double budget_s = 180.0;
  std::string csv;
  bool plot = false;
  int metrics_every = 1;
  bool soak = false;
  SoakOptions soak_options;
  bool stability = false;
  StabilityOptions stability_options;
  std::string stability_scene;  // empty: the built-in bunny
  std::string preset;           // empty: the scene's own parameters
};

// The backends to time: the OpenMP one and every OpenCL device (or the ones asked for).
std::vector<BenchBackend> chooseBackends(const BenchOptions& o) {
  std::vector<BenchBackend> list;
  if (o.backend != "all" && o.backend != "cpu" && o.backend != "opencl")
    throw Error("--backend: '" + o.backend + "' is not one of all, cpu, opencl");
  if (o.backend == "all" || o.backend == "cpu") list.push_back({"cpu", -1, o.threads, o.metrics_every});
  if (o.backend == "all" || o.backend == "opencl") {
#ifdef FF_NO_OPENCL
    if (o.backend == "opencl") throw Error("--backend opencl: this flowform was built without OpenCL");
    std::fprintf(stderr, "bench: built without OpenCL; timing the OpenMP backend only\n");
#else
    std::vector<ClDeviceInfo> devices;
    try {
      devices = listClDevices();
    } catch (const Error& e) {
      if (o.backend == "opencl") throw;
      std::fprintf(stderr, "bench: no OpenCL (%s); timing the OpenMP backend only\n", e.what());
    }
    if (o.device >= 0) {
      if (o.device >= int(devices.size()))
        throw Error("--device " + std::to_string(o.device) + ": there are " + std::to_string(devices.size()) +
                    " OpenCL devices (see `flowform devices`)");
      list.push_back({"opencl", o.device, o.threads, o.metrics_every});
    } else {
      for (const ClDeviceInfo& d : devices) list.push_back({"opencl", d.index, o.threads, o.metrics_every});
    }
#endif
  }
  return list;
}

void validate(const BenchOptions& o) {
  if (o.steps < 1) throw Error("--steps: must be at least 1");
  if (o.sweep_steps < 1) throw Error("--sweep-steps: must be at least 1");
  if (o.warmup < 0 || o.sweep_warmup < 0) throw Error("--warmup/--sweep-warmup: must be >= 0");
  // Upper bounds: a count past them is a typo, and would run for days.
  constexpr long kMostSteps = 100000;
  for (auto [name, v] : {std::pair<const char*, long>{"--steps", o.steps},
                         {"--warmup", o.warmup},
                         {"--sweep-steps", o.sweep_steps},
                         {"--sweep-warmup", o.sweep_warmup},
                         {"--soak-changes", o.soak_options.changes},
                         {"--soak-steps", o.soak_options.steps_between}})
    if (v > kMostSteps)
      throw Error(std::string(name) + ": must be at most " + std::to_string(kMostSteps) + " (got " +
                  std::to_string(v) + ")");
  if (o.stability_options.seconds > 600.0)
    throw Error("--stability-seconds: must be at most 600 simulated seconds per run");
  if (!o.preset.empty()) {
    try {
      presetParams(o.preset);
    } catch (const Error& e) {
      throw Error(std::string("--preset: ") + e.what());
    }
  }
  checkThreadCount(o.threads, "--threads");
  // As `run` refuses them (a negative device timed every device, one with
  // --backend cpu was ignored).
  if (o.device < -1) throw Error("--device: must be >= 0 (got " + std::to_string(o.device) + ")");
  if (o.device >= 0 && o.backend == "cpu")
    throw Error("--device: only applies to the OpenCL backend (--backend opencl or all)");
  if (o.max_fluid < 1000) throw Error("--max-fluid: must be at least 1000");
  if (o.max_control < 100) throw Error("--max-control: must be at least 100");
  if (!(o.seconds > 0.0) || o.seconds > 600.0)
    throw Error("--seconds: must be a number of simulated seconds in (0, 600]");
  dambreakCases(o.geometry, o.max_fluid, o.quick);  // throws naming --geometry
  if (o.solver != "all" && o.solver != "wcsph" && o.solver != "dfsph")
    throw Error("--solver: '" + o.solver + "' is not one of all, wcsph, dfsph");
  if (!(o.budget_s > 0.0)) throw Error("--budget: must be a positive number of seconds");
  if (o.plot && o.csv.empty()) throw Error("--plot: give --csv FILE too (the plots go next to it)");
  if (!o.csv.empty()) {
    // Fail now, not after minutes of timing.
    std::ofstream f(o.csv, std::ios::app);
    if (!f) throw Error(o.csv + ": --csv: cannot write this file (" + std::strerror(errno) + ")");
  }
}

class Bench {
 public:
  explicit Bench(const BenchOptions& o) : o_(o) {}

  void table1(const std::vector<BenchBackend>& backends) {
    std::vector<BenchCase> cases = table1Cases();
    if (!o_.preset.empty())  // the same scenes with this preset's parameters (scenes/water/ for "water")
      for (BenchCase& c : cases) c.scene.params = presetParams(o_.preset), c.scene.preset = o_.preset;
    std::vector<BenchResult> out;
    for (const BenchCase& c : cases)
      for (const BenchBackend& b : backends) out.push_back(run(c, b, o_.warmup, o_.steps));
    printMarkdown(stdout, "Table 1 scenes (paper Fig. 8)", out);
  }

  // Runs the cases in order while the next one is expected to fit in the
  // budget (its cost estimated from the last one's, scaled by `size`).
  void sweep(const std::string& title, const std::vector<BenchCase>& cases,
             const std::vector<BenchBackend>& backends, long (*size)(const BenchCase&)) {
    std::vector<BenchResult> out;
    for (const BenchBackend& b : backends) {
      double spent = 0.0, last_wall = 0.0;
      long last_size = 0;
      for (const BenchCase& c : cases) {
        if (last_size > 0) {
          const double estimate = last_wall * double(size(c)) / double(last_size);
          if (spent + estimate > o_.budget_s) {
            std::fprintf(stderr,
                         "bench: %s on %s stops before %ld: it would take about %.0f s, past the --budget of "
                         "%.0f s\n",
                         title.c_str(), b.kind.c_str(), size(c), estimate, o_.budget_s);
            break;
          }
        }
        out.push_back(run(c, b, o_.sweep_warmup, o_.sweep_steps));
        last_wall = out.back().wall_s;
        last_size = size(c);
        spent += last_wall;
      }
    }
    printMarkdown(stdout, title, out);
  }

  void finish() {
    if (o_.plot)
      for (const std::string& f : plotBenchCsv(o_.csv)) std::fprintf(stderr, "bench: wrote %s\n", f.c_str());
  }

 private:
  BenchResult run(const BenchCase& c, const BenchBackend& b, int warmup, int steps) {
    std::fprintf(stderr, "bench: %s, %ld fluid, %ld control, on %s%s ...", c.name.c_str(), c.fluid, c.control,
                 b.kind.c_str(), b.kind == "opencl" ? (" device " + std::to_string(b.device)).c_str() : "");
    std::fflush(stderr);
    BenchResult r = runBenchCase(c, b, warmup, steps);
    std::fprintf(stderr, " %.2f ms/step (%s), %.0f s\n", r.total.median, r.device.c_str(), r.wall_s);
    std::printf(
        "host syncs per step (%s, %s): %d steps with metrics: %.2f blocking reads, %.2f waits; %d "
        "without: %.2f blocking reads, %.2f waits (profiling on: one wait per phase)\n",
        c.name.c_str(), r.backend.c_str(), r.steps_with, r.reads_with, r.waits_with, r.steps_without,
        r.reads_without, r.waits_without);
    all_.push_back(r);
    // Rewritten after every case: an interrupted bench keeps what it measured.
    if (!o_.csv.empty()) writeBenchCsv(o_.csv, all_);
    return r;
  }

  const BenchOptions& o_;
  std::vector<BenchResult> all_;
};

long fluidSize(const BenchCase& c) {
  return c.fluid;
}
long controlSize(const BenchCase& c) {
  return c.control;
}

// --soak: the target-change soak on every backend; exit 1 if a check failed.
int runSoaks(const BenchOptions& o) {
  std::vector<SoakResult> results;
  for (const BenchBackend& b : chooseBackends(o)) {
    results.push_back(runSoak(o.soak_options, b));
    if (!results.back().ok())
      std::fprintf(stderr, "bench soak: FAILED: %s\n", results.back().failure.c_str());
  }
  printSoak(stdout, results);
  for (const SoakResult& r : results)
    if (!r.ok()) return 1;
  return 0;
}

// --stability: the parameter sweep on every backend; exit 1 if a run exploded.
int runStabilitySweep(const BenchOptions& o) {
  SceneDesc scene = o.stability_scene.empty() ? table1Cases().front().scene : loadScene(o.stability_scene);
  if (!o.preset.empty()) {
    scene.params = presetParams(o.preset);
    scene.preset = o.preset;
  }
  if (o.threads > 0) omp_set_num_threads(o.threads);
  int rc = 0;
  for (const BenchBackend& b : chooseBackends(o)) {
    const std::vector<StabilityRun> runs = runStability(scene, o.stability_options, b);
    std::printf("\nbackend %s\n", b.kind.c_str());
    printStability(stdout, scene, runs);
    for (const StabilityRun& r : runs) rc |= r.exploded ? 1 : 0;
  }
  return rc;
}

// --dambreak: every solver asked for on every backend, 12k and 100k.
void runDambreaks(const BenchOptions& o, const std::vector<BenchBackend>& backends) {
  std::vector<std::string> solvers;
  for (const char* k : {"wcsph", "dfsph"})
    if (o.solver == "all" || o.solver == k) solvers.push_back(k);
  std::vector<DambreakResult> out;
  for (const DambreakCase& c : dambreakCases(o.geometry, o.max_fluid, o.quick))
    for (const std::string& k : solvers)
      for (const BenchBackend& b : backends) {
        std::fprintf(stderr, "bench: dam break (%s), %ld fluid, %s on %s ...", c.geometry.c_str(), c.count(),
                     k.c_str(), b.kind.c_str());
        std::fflush(stderr);
        out.push_back(runDambreak(c, k, b, o.seconds));
        const DambreakResult& d = out.back();
        if (d.skipped.empty())
          std::fprintf(stderr, " %.2f s per simulated s (%s)\n", d.wall_per_sim_s, d.timing.device.c_str());
        else
          std::fprintf(stderr, " not run: %s\n", d.skipped.c_str());
      }
  printDambreak(stdout, out);
  std::vector<BenchResult> timed;
  for (const DambreakResult& d : out)
    if (d.skipped.empty()) timed.push_back(d.timing);
  printMarkdown(stdout, "Dam break phases", timed);
  if (!o.csv.empty()) writeBenchCsv(o.csv, timed);
}

int runBench(BenchOptions o) {
  validate(o);
  if (o.soak) return runSoaks(o);
  if (o.stability) return runStabilitySweep(o);
  if (o.dambreak) {
    if (o.threads > 0) omp_set_num_threads(o.threads);
    std::printf("flowform bench --dambreak: %d OpenMP threads, %g simulated s per run\n",
                o.threads > 0 ? o.threads : omp_get_max_threads(), o.seconds);
    runDambreaks(o, chooseBackends(o));
    return 0;
  }
  if (!o.table1 && !o.fluid_sweep && !o.control_sweep) o.table1 = o.fluid_sweep = o.control_sweep = true;
  if (o.threads > 0) omp_set_num_threads(o.threads);
  const std::vector<BenchBackend> backends = chooseBackends(o);
  // Fail on a missing mesh before timing anything.
  if (o.table1) table1Cases();
  std::printf(
      "flowform bench: %d OpenMP threads; Table 1: median of %d steps after %d warm-up steps; sweeps: "
      "median of %d steps after %d\n",
      o.threads > 0 ? o.threads : omp_get_max_threads(), o.steps, o.warmup, o.sweep_steps, o.sweep_warmup);
  Bench bench(o);
  if (o.table1) bench.table1(backends);
  if (o.fluid_sweep)
    bench.sweep("Fluid-count sweep (sphere target, control = 0.266 x fluid)", fluidSweepCases(o.max_fluid),
                backends, fluidSize);
  if (o.control_sweep)
    bench.sweep("Control-count sweep (12k fluid, sphere target)", controlSweepCases(o.max_control), backends,
                controlSize);
  bench.finish();
  return 0;
}

}  // namespace

std::function<int()> addBenchCommand(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand(
      "bench",
      "Time every phase: the paper's Table 1 scenes (12k fluid; bunny, teapot, runner, dragon meshes from "
      "FLOWFORM_MESH_PATH) and scaling sweeps, on every backend present. With no --table1/--fluid-sweep/"
      "--control-sweep, runs all three.");
  cmd->add_flag("--table1", o->table1, "Time the Table 1 scenes");
  cmd->add_flag("--fluid-sweep", o->fluid_sweep, "Time 12k .. --max-fluid fluid particles");
  cmd->add_flag("--control-sweep", o->control_sweep,
                "Time 500 .. --max-control control particles at 12k fluid");
  cmd->add_flag(
      "--dambreak", o->dambreak,
      "Instead: uncontrolled dam breaks of 12k and 100k fluid particles (up to --max-fluid) on each "
      "solver and backend, from rest over --seconds: wall s per simulated s, ms per frame step, "
      "substeps, solver iterations, density error");
  cmd->add_option("--solver", o->solver, "--dambreak: wcsph, dfsph or all (default)");
  cmd->add_option("--seconds", o->seconds, "--dambreak: simulated seconds per run (default 1)");
  cmd->add_flag("--quick", o->quick, "--dambreak: one small block instead (a check, not a benchmark)");
  cmd->add_option("--geometry", o->geometry,
                  "--dambreak: peer (default: SPlisHSPlasH's DamBreakModel, a 1 m cube of 23^3 / 47^3 "
                  "particles in a 4 x 3 x 1.5 m tank) or paper (the paper's 6.3 mm spacing, 12k / 99.2k)");
  cmd->add_option("--backend", o->backend,
                  "all (default), cpu or opencl (every OpenCL device unless --device)");
  cmd->add_option("--device", o->device, "OpenCL device index (see `flowform devices`)");
  addKernelsOption(cmd);
  cmd->add_option("--threads", o->threads, "OpenMP threads (default: OpenMP's default)");
  cmd->add_option("--steps", o->steps, "Timed steps per Table 1 case (default 200)");
  cmd->add_option("--warmup", o->warmup, "Untimed steps before (default 50)");
  cmd->add_option("--sweep-steps", o->sweep_steps, "Timed steps per sweep case (default 50)");
  cmd->add_option("--sweep-warmup", o->sweep_warmup, "Untimed steps per sweep case (default 20)");
  cmd->add_option("--max-fluid", o->max_fluid, "Largest fluid count of the sweep (default 1000000)");
  cmd->add_option("--max-control", o->max_control, "Largest control count of the sweep (default 50000)");
  cmd->add_option(
      "--budget", o->budget_s,
      "Seconds each sweep may take per backend; it stops before a size that would not fit (default "
      "180)");
  cmd->add_option(
      "--csv", o->csv,
      "Write scene,backend,device,fluid,control,phase,ms_median,ms_min,ms_max (a row per phase, a total, "
      "then a row per named stage, phase PHASE/STAGE, its mean ms per step as ms_median)");
  cmd->add_flag("--plot", o->plot, "Write PNG plots next to the CSV (python3-matplotlib)");
  cmd->add_option("--metrics-every", o->metrics_every,
                  "Metrics every K steps (default 1); the host-sync count separates steps with and without")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--soak", o->soak,
                "Soak instead of timing: --soak-changes target changes, each with a region change, on every "
                "backend; checks for NaN and particles outside the box and that memory stays flat "
                "(peak RSS reported); exit 1 if a check fails");
  cmd->add_option("--soak-changes", o->soak_options.changes, "Target changes of the soak (default 300)");
  cmd->add_option("--soak-steps", o->soak_options.steps_between,
                  "Steps after each change of the soak (default 4)");
  cmd->add_flag(
      "--stability", o->stability,
      "Stability sweep instead of timing: every control and shape-matching parameter scaled one at a "
      "time by each --stability-factors, a short run each on the bunny (or --stability-scene); "
      "reports NaN, explosions (faster than twice a free fall through the container) and velocity "
      "clamps; exit 1 if a run exploded");
  cmd->add_option("--stability-scene", o->stability_scene,
                  "Scene of the sweep (default: the built-in bunny)");
  cmd->add_option("--stability-seconds", o->stability_options.seconds,
                  "Simulated seconds per sweep run (default 1.5)");
  cmd->add_option("--stability-factors", o->stability_options.factors,
                  "Factors, comma-separated (default 0.25,0.5,2,4)")
      ->delimiter(',');
  cmd->add_option(
         "--stability-params", o->stability_options.params,
         "Parameters, comma-separated as GROUP.KEY (default: every control and shape_matching number)")
      ->delimiter(',');
  cmd->add_option("--preset", o->preset,
                  "--table1 and --stability: this preset's parameters instead of the scenes' own");
  return [o] { return runBench(*o); };
}

}  // namespace ff::app
