// cmd_run.cpp - `flowform run`: a headless simulation with metrics and export.
#include <omp.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <memory>
#include <string>

#include "app/commands.h"
#include "app/export_cli.h"
#include "app/kernels_option.h"
#include "app/progress.h"
#include "app/run_checkpoints.h"
#include "core/error.h"
#include "core/resource_limits.h"
#include "host/backend_factory.h"
#include "io/metrics_csv.h"
#include "sim/checkpoint.h"
#include "sim/export_frame.h"
#include "sim/simulation.h"

namespace ff::app {

namespace {

struct RunOptions {
  std::string scene;
  double seconds = 0.0;
  long steps = 0;
  bool seconds_given = false, steps_given = false;
  int threads = 0;
  std::string backend = "auto";
  int device = -1;
  std::string metrics;
  ExportOptions exports;  // used when exports.dir is set
  std::string formats = "vtk";
  int print_every = 0;
  int metrics_every = 1;
  bool profile = false;
  double checkpoint_every = 0.0;
  std::string checkpoint_dir = "checkpoints";
  std::string resume;
};

int runScene(const RunOptions& o) {
  checkThreadCount(o.threads, "--threads");
  if (o.threads > 0) omp_set_num_threads(o.threads);
  if (!o.resume.empty() && !o.scene.empty())
    throw Error("--resume: give a scene or a checkpoint, not both (the checkpoint holds its scene)");
  std::string note;
  auto backend = makeBackend(o.backend, o.device, o.threads, &note);
  if (!note.empty()) std::printf("flowform: %s\n", note.c_str());
  if (o.checkpoint_every > 0.0 && !backend->writesCheckpoints())
    throw Error("--checkpoint-every: the " + backend->name() +
                " backend cannot write checkpoints; run with --backend cpu");
  std::unique_ptr<Simulation> simp =
      o.resume.empty() ? std::make_unique<Simulation>(o.scene.empty() ? defaultScene() : loadScene(o.scene),
                                                      std::move(backend))
                       : loadCheckpoint(o.resume, std::move(backend));
  Simulation& sim = *simp;
  const SceneDesc& scene = sim.scene();
  // --seconds and --steps count from the start of the run, also when resuming.
  const double dt = scene.params.fluid.time_step;
  if (o.steps_given && !(o.steps >= 1 && double(o.steps) <= kMaxRunSteps))
    throw Error("--steps: must be in [1, " + std::to_string(long(kMaxRunSteps)) + "] (got " +
                std::to_string(o.steps) + ")");
  const long end = o.steps_given     ? o.steps
                   : o.seconds_given ? runSteps(o.seconds, dt, "--seconds")
                                     : runSteps(scene.duration, dt, scene.source + ": duration");
  const long first = sim.stepCount();
  const long steps = end - first;
  if (steps <= 0)
    throw Error("--resume " + o.resume + ": the checkpoint is at step " + std::to_string(first) +
                " (t = " + std::to_string(sim.time()) + " s), at or past the end of the run (step " +
                std::to_string(end) + "); ask for more with --seconds or --steps");
  // A resumed run's export starts at its first step, numbered from 0.
  std::unique_ptr<FrameExporter> exporter;
  if (!o.exports.dir.empty()) {
    ExportOptions eo = o.exports;
    eo.formats = parseExportFormats(o.formats, "--format");
    exporter = std::make_unique<FrameExporter>(eo);
  }

  if (!o.resume.empty())
    std::printf("flowform: resuming %s at step %ld (t = %.3f s)\n", o.resume.c_str(), first, sim.time());
  std::printf("flowform: scene '%s' (%s), %zu fluid particles, backend %s (%s), %ld steps of %.4g s\n",
              scene.name.c_str(), scene.source.c_str(), size_t(scene.fluidCount()),
              sim.backend().name().c_str(), sim.backend().device().c_str(), steps, dt);

  MetricsCsv csv;
  std::vector<std::string> columns;
  for (const MetricColumn& c : kMetricColumns) columns.push_back(c.name);
  if (!o.metrics.empty() && first > 0)
    csv.resume(o.metrics, columns, double(first));
  else if (!o.metrics.empty())
    csv.open(o.metrics, columns);
  const int print_every = o.print_every > 0 ? o.print_every : std::max(1L, long(std::lround(0.5 / dt)));
  auto t0 = std::chrono::steady_clock::now();
  if (exporter) exportFrameIfDue(sim, *exporter);
  Progress progress("  run", steps, dt, sim.time());
  const bool can_checkpoint = sim.backend().writesCheckpoints();
  Checkpoints checkpoints(o.checkpoint_dir, o.checkpoint_every, sim.time());
  StopSignals stop;
  sim.setProfiling(o.profile);
  sim.setMetricsEvery(o.metrics_every);
  // Without --metrics the target's metrics are computed only in the steps
  // that print them (the physics is the same).
  sim.setShapeMetricsOnRequest(!csv.isOpen());
  for (long s = first; s < end; ++s) {
    const bool print = (s + 1) % print_every == 0 || s + 1 == end;
    if (print) sim.requestMetrics();
    sim.step();
    const StepMetrics& m = sim.metrics();
    progress.update(s + 1 - first, m.time);
    if (csv.isOpen() && sim.metricsFresh()) {
      const auto row = metricValues(m);
      csv.row(std::vector<double>(row.begin(), row.end()));
    }
    if (exporter) exportFrameIfDue(sim, *exporter);
    if (print) {
      progress.interrupt();
      std::printf(
          "  t=%6.3f s  iou=%.3f  coverage=%.3f  filled=%.3f  stray=%.3f  max_speed=%.3f m/s  "
          "density_error=%.3f  target=%s\n",
          m.time, m.iou, m.coverage, m.filled, m.stray, m.max_speed, m.density_error,
          sim.target() ? sim.target()->label.c_str() : "none");
    }
    const std::string saved = checkpoints.due(sim);
    if (!saved.empty()) {
      progress.interrupt();
      std::printf("  checkpoint %s (t = %.3f s)\n", saved.c_str(), sim.time());
    }
    if (stop.caught() && s + 1 < end) {
      const char* signal_name = stop.caught() == SIGINT ? "SIGINT" : "SIGTERM";
      progress.interrupt();
      if (!can_checkpoint) {
        std::printf(
            "flowform: stopped by %s at step %ld (t = %.3f s); no checkpoint: the %s backend cannot "
            "write checkpoints (--backend cpu can)\n",
            signal_name, sim.stepCount(), sim.time(), sim.backend().name().c_str());
        return 128 + stop.caught();
      }
      const std::string last = saved.empty() ? checkpoints.write(sim) : saved;
      std::printf(
          "flowform: stopped by %s at step %ld (t = %.3f s); checkpoint %s\n"
          "  resume with: flowform run --resume %s\n",
          signal_name, sim.stepCount(), sim.time(), last.c_str(), last.c_str());
      return 128 + stop.caught();
    }
  }
  progress.finish(steps, sim.time());
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto& ms = sim.phaseMs();
  double total = 0.0;
  std::printf(
      "ms per step by phase (%ld steps, %.2f s wall%s):\n", steps, wall,
      o.profile ? "" : "; on OpenCL without --profile a phase's device time counts where it is waited for");
  for (int p = 0; p < int(Phase::Count); ++p) {
    total += ms[size_t(p)];
    std::printf("  %-15s %8.3f\n", phaseName(Phase(p)), ms[size_t(p)] / double(std::max(1L, steps)));
    for (const StageTime& s : sim.stageMs())  // the phase's named stages
      if (s.phase == phaseName(Phase(p)))
        std::printf("    %-30s %8.3f\n", s.name.c_str(), s.ms / double(std::max(1L, steps)));
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
  // Ranges are checked in runScene (CLI11's PositiveNumber lets NaN through).
  auto* sec = run->add_option("--seconds", o->seconds, "Simulated seconds (default: the scene's duration)");
  auto* st = run->add_option("--steps", o->steps, "Number of steps");
  sec->excludes(st);
  run->add_option("--threads", o->threads, "OpenMP threads (default: all cores)")
      ->check(CLI::NonNegativeNumber);
  run->add_option("--backend", o->backend,
                  "auto (an OpenCL GPU if there is one, else the CPU), cpu or opencl")
      ->check(CLI::IsMember({"auto", "cpu", "opencl"}));
  run->add_option("--device", o->device, "OpenCL device number, as `flowform devices` lists them");
  addKernelsOption(run);
  run->add_option("--metrics", o->metrics, "Write per-step metrics to this CSV file");
  addExportOptions(
      run, o->exports, o->formats, true,
      "Write frames into this folder (refused if it holds another run's frames, see --overwrite)");
  run->add_option("--print-every", o->print_every,
                  "Print metrics every K steps (default 0: every half simulated second)")
      ->check(CLI::NonNegativeNumber);
  run->add_option("--metrics-every", o->metrics_every,
                  "Compute the metrics (and the NaN check) every K steps (default 1; --metrics writes those "
                  "rows); other steps read nothing back from an OpenCL device")
      ->check(CLI::PositiveNumber);
  run->add_flag("--profile", o->profile,
                "Time each phase exactly (every OpenCL phase waits for its kernels), and on OpenCL "
                "each force plug-in and solver stage too");
  run->add_option("--checkpoint-every", o->checkpoint_every, "Write a checkpoint every T simulated seconds")
      ->check(CLI::PositiveNumber);
  run->add_option("--checkpoint", o->checkpoint_dir,
                  "Folder for checkpoints (default: checkpoints); SIGINT/SIGTERM also write one there");
  run->add_option("--resume", o->resume,
                  "Continue the run saved in this checkpoint (--seconds/--steps count from its start)");
  return [o, sec, st] {
    o->seconds_given = sec->count() > 0;
    o->steps_given = st->count() > 0;
    return runScene(*o);
  };
}

}  // namespace ff::app
