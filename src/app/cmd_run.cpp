// cmd_run.cpp - `flowform run`: a headless simulation with metrics and export.
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "app/commands.h"
#include "app/export_cli.h"
#include "app/kernels_option.h"
#include "app/progress.h"
#include "core/error.h"
#include "host/backend_factory.h"
#include "io/metrics_csv.h"
#include "sim/export_frame.h"
#include "sim/simulation.h"

namespace ff::app {

namespace {

struct RunOptions {
  std::string scene;
  double seconds = 0.0;
  long steps = 0;
  int threads = 0;
  std::string backend = "auto";
  int device = -1;
  std::string metrics;
  ExportOptions exports;  // used when exports.dir is set
  std::string formats = "vtk";
  int print_every = 0;
};

int runScene(const RunOptions& o) {
  if (o.threads < 0) throw Error("--threads: must be >= 0");
  if (o.threads > 0) omp_set_num_threads(o.threads);
  SceneDesc scene = o.scene.empty() ? defaultScene() : loadScene(o.scene);
  long steps = 0;
  const double dt = scene.params.fluid.time_step;
  if (o.steps > 0)
    steps = o.steps;
  else
    steps = long(std::ceil((o.seconds > 0.0 ? o.seconds : scene.duration) / dt - 1e-9));
  std::unique_ptr<FrameExporter> exporter;
  if (!o.exports.dir.empty()) {
    ExportOptions eo = o.exports;
    eo.formats = parseExportFormats(o.formats, "--format");
    exporter = std::make_unique<FrameExporter>(eo);
  }

  std::string note;
  auto backend = makeBackend(o.backend, o.device, o.threads, &note);
  if (!note.empty()) std::printf("flowform: %s\n", note.c_str());
  Simulation sim(scene, std::move(backend));
  std::printf("flowform: scene '%s' (%s), %zu fluid particles, backend %s (%s), %ld steps of %.4g s\n",
              scene.name.c_str(), scene.source.c_str(), size_t(scene.fluidCount()),
              sim.backend().name().c_str(), sim.backend().device().c_str(), steps, dt);

  MetricsCsv csv;
  if (!o.metrics.empty())
    csv.open(o.metrics, {"step", "time", "iou", "coverage", "max_speed", "density_error", "kinetic_energy",
                         "control_count", "max_density", "substeps"});
  const int print_every = o.print_every > 0 ? o.print_every : std::max(1L, long(std::lround(0.5 / dt)));
  auto t0 = std::chrono::steady_clock::now();
  if (exporter) exportFrameIfDue(sim, *exporter);
  Progress progress("  run", steps, dt, sim.time());
  for (long s = 0; s < steps; ++s) {
    sim.step();
    const StepMetrics& m = sim.metrics();
    progress.update(s + 1, m.time);
    if (csv.isOpen())
      csv.row({double(m.step), m.time, m.iou, m.coverage, m.max_speed, m.density_error, m.kinetic_energy,
               double(m.control_count), m.max_density, double(m.substeps)});
    if (exporter) exportFrameIfDue(sim, *exporter);
    if ((s + 1) % print_every == 0 || s + 1 == steps) {
      progress.interrupt();
      std::printf("  t=%6.3f s  iou=%.3f  coverage=%.3f  max_speed=%.3f m/s  density_error=%.3f  target=%s\n",
                  m.time, m.iou, m.coverage, m.max_speed, m.density_error,
                  sim.target() ? sim.target()->label.c_str() : "none");
    }
  }
  progress.finish(steps, sim.time());
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto& ms = sim.phaseMs();
  double total = 0.0;
  std::printf("ms per step by phase (%ld steps, %.2f s wall):\n", steps, wall);
  for (int p = 0; p < int(Phase::Count); ++p) {
    total += ms[size_t(p)];
    std::printf("  %-15s %8.3f\n", phaseName(Phase(p)), ms[size_t(p)] / double(std::max(1L, steps)));
  }
  std::printf("  %-15s %8.3f\n", "total", total / double(std::max(1L, steps)));
  const StepMetrics& m = sim.metrics();
  if (exporter)
    std::printf("exported %ld frames (%s%s) into %s: %s\n", exporter->frames(), o.formats.c_str(),
                o.exports.surface.enabled ? ", surface" : "", o.exports.dir.c_str(),
                exporter->costReport().c_str());
  std::printf("final: t=%.3f s iou=%.4f coverage=%.4f max_speed=%.4f density_error=%.4f\n", m.time, m.iou,
              m.coverage, m.max_speed, m.density_error);
  return 0;
}

}  // namespace

std::function<int()> addRunCommand(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* run = app.add_subcommand("run", "Run a scene headless (the default scene if none is given)");
  run->add_option("scene", o->scene, "Scene file (JSON); omitted: the built-in default scene");
  auto* sec = run->add_option("--seconds", o->seconds, "Simulated seconds (default: the scene's duration)")
                  ->check(CLI::PositiveNumber);
  auto* st = run->add_option("--steps", o->steps, "Number of steps")->check(CLI::PositiveNumber);
  sec->excludes(st);
  run->add_option("--threads", o->threads, "OpenMP threads (default: all cores)")
      ->check(CLI::NonNegativeNumber);
  run->add_option("--backend", o->backend,
                  "auto (an OpenCL GPU if there is one, else the CPU), cpu or opencl")
      ->check(CLI::IsMember({"auto", "cpu", "opencl"}));
  run->add_option("--device", o->device, "OpenCL device number, as `flowform devices` lists them");
  addKernelsOption(run);
  run->add_option("--metrics", o->metrics, "Write per-step metrics to this CSV file");
  addExportOptions(run, o->exports, o->formats, true);
  run->add_option("--print-every", o->print_every, "Print metrics every K steps");
  return [o] { return runScene(*o); };
}

}  // namespace ff::app
