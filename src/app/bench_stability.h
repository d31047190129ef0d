// bench_stability.h - `flowform bench --stability`: every control and
// shape-matching parameter scaled one at a time (x0.25, x0.5, x2, x4 by
// default; the modes, ParamInfo::mode, run in each other mode) on one scene, each a short run,
// reporting NaN, explosions and the velocity clamps (docs/RESULTS.md, "Stability sweep").
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "app/bench_runner.h"
#include "core/param_table.h"
#include "scene/scene.h"

namespace ff::app {

struct StabilityOptions {
  double seconds = 1.5;                              // simulated time per run
  std::vector<double> factors{0.25, 0.5, 2.0, 4.0};  // applied to each parameter in turn
  std::vector<std::string> params;  // "group.key"; empty: every control and shape-matching number
};

struct StabilityRun {
  std::string param;  // "control.attraction", or "(none)" for the unscaled run
  double factor = 1.0;
  double value = 0.0;     // the value run (scaled, then kept in the parameter's range)
  bool clipped = false;   // the scaled value fell outside the range and was clipped to it
  bool switched = false;  // a mode parameter, run in another mode (value; factor unused)
  // Whether it ran: not where the parameter has no effect (another overrides
  // it) or validateParams refused the values (`nan` says which); the figures
  // below are then not measured.
  bool ran = false;
  long steps = 0;
  std::string nan;  // empty, or where a value became NaN or Inf
  double max_speed = 0.0, max_density_error = 0.0;
  long clamps = 0;         // velocity clamps over the run
  long clamped_steps = 0;  // steps with at least one clamp
  double final_iou = 0.0, final_stray = 0.0;
  bool exploded = false;  // NaN, or faster than the explosion speed
  double wall_s = 0.0;
};

// One parameter of the sweep and what it is run at: a number at each factor
// of the options, a mode (ParamInfo::mode) in each of its other modes.
struct StabilityPlan {
  const ParamInfo* param = nullptr;
  bool mode = false;
  std::vector<double> factors;  // the factors; for a mode, the modes
};
// The sweep's parameters for a scene with `params` (options.params, or every
// control and shape-matching number that acts), in the table's order.
std::vector<StabilityPlan> stabilityPlan(const Params& params, const StabilityOptions& options);

// The speed (m/s) above which a run counts as exploded: twice the speed of a
// free fall through the container's tallest extent, sqrt(2 g L).
double explosionSpeed(const SceneDesc& scene);

// Runs the unscaled scene, then each parameter at each factor, on one backend;
// progress on stderr.
std::vector<StabilityRun> runStability(const SceneDesc& scene, const StabilityOptions& options,
                                       const BenchBackend& backend);
// A Markdown table of the runs.
void printStability(std::FILE* out, const SceneDesc& scene, const std::vector<StabilityRun>& runs);

}  // namespace ff::app
