// bench_stability.cpp - the parameter sweep of `flowform bench --stability`.
#include "app/bench_stability.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "core/error.h"
#include "core/param_table.h"
#include "host/backend_factory.h"
#include "sim/simulation.h"

namespace ff::app {

namespace {

// "control.attraction" for the table's entry (group "shape_matching" is "shape_matching").
std::string shortName(const ParamInfo& p) {
  return std::string(p.group) + "." + p.key;
}

// The parameters the sweep scales: the numbers of the control and
// shape-matching groups that act with the scene's parameters (not the force
// units, a choice of units; with normalise on, attraction_g and velocity_rate
// instead of attraction and velocity; with radius_spacings on, it instead of
// the radius it sets; with time_step_fall on, it instead of the time_step it
// sets), and the modes (normalise, adaptive, anchor), each run once in each
// other mode; not a number that is 0 (off), which no factor changes.
std::vector<const ParamInfo*> sweptParams(const std::vector<std::string>& names, const Params& params) {
  std::vector<const ParamInfo*> out;
  for (const ParamInfo& p : paramTable()) {
    const std::string g = p.group, k = p.key;
    const bool number = p.type == ParamInfo::Type::Real || p.type == ParamInfo::Type::Integer;
    // overrideRules: radius_spacings or time_step_fall at 0 (off) is left by the zero rule below.
    const bool inactive = !paramActs(p, params);
    // A number at 0 (off, e.g. the paper preset's blend and auto_count) stays 0 at every factor.
    const bool zero = number && !p.mode && p.number(params) == 0.0;
    if (names.empty() && number && !inactive && !zero && (g == "control" || g == "shape_matching"))
      out.push_back(&p);
  }
  for (const std::string& n : names) {
    const auto it = std::find_if(paramTable().begin(), paramTable().end(),
                                 [&](const ParamInfo& p) { return shortName(p) == n; });
    if (it == paramTable().end() ||
        (it->type != ParamInfo::Type::Real && it->type != ParamInfo::Type::Integer))
      throw Error(
          "--stability-params: '" + n +
          "' is not a number parameter (GROUP.KEY, e.g. control.attraction or shape_matching.stiffness)");
    out.push_back(&*it);
  }
  return out;
}

// Sets p to base * factor, kept in its range (integers rounded); returns the value set.
double setScaled(const ParamInfo& p, Params& params, double base, double factor, bool& clipped) {
  double v = base * factor;
  if (p.type == ParamInfo::Type::Integer) v = std::round(v);
  const double lo =
      p.min_open ? (p.type == ParamInfo::Type::Integer ? p.min + 1 : p.min * (1 + 1e-6)) : p.min;
  clipped = v < lo || v > p.max;
  v = std::clamp(v, lo, p.max);
  if (p.type == ParamInfo::Type::Integer)
    *static_cast<int*>(p.field(params)) = int(v);
  else
    setRealParam(p, params, float(v));  // a step scaled in seconds turns its *_fall off
  return v;
}

// The factor as printed: "0.25" (after `prefix`), or "switched" for an on/off parameter.
std::string factor(const StabilityRun& r, const char* prefix = "") {
  char f[32] = "switched";
  if (!r.switched) std::snprintf(f, sizeof f, "%s%g", prefix, r.factor);
  return f;
}

// One run of `seconds`; `at_start`, where given, gets the parameters the run
// took at its start: the frame step, control radius and shape-matching step
// that time_step_fall, radius_spacings and shape_matching.time_step_fall set.
StabilityRun runOne(const SceneDesc& scene, const BenchBackend& b, double seconds, double explode_speed,
                    Params* at_start = nullptr) {
  const auto t0 = std::chrono::steady_clock::now();
  StabilityRun r;
  r.ran = true;
  std::string note;
  Simulation sim(scene, makeBackend(b.kind, b.device, b.threads, &note));
  if (at_start) *at_start = sim.scene().params;
  const long steps = std::max(1L, std::lround(seconds / double(sim.scene().params.fluid.time_step)));
  for (long s = 0; s < steps; ++s) {
    try {
      sim.step();
    } catch (const Error& e) {
      r.nan = e.what();
      r.exploded = true;
      break;
    }
    const StepMetrics& m = sim.metrics();
    r.max_speed = std::max(r.max_speed, m.max_speed);
    r.max_density_error = std::max(r.max_density_error, m.max_density_error);
    r.clamps += m.velocity_clamps;
    r.clamped_steps += m.velocity_clamps > 0;
    r.final_iou = m.iou, r.final_stray = m.stray;
    ++r.steps;
  }
  r.exploded = r.exploded || r.max_speed > explode_speed;
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace

std::vector<StabilityPlan> stabilityPlan(const Params& params, const StabilityOptions& o) {
  std::vector<StabilityPlan> plan;
  for (const ParamInfo* p : sweptParams(o.params, params)) {
    StabilityPlan q{p, p->mode, o.factors};
    if (q.mode) {
      q.factors.clear();
      const double v0 = p->number(params);
      for (int m = int(p->min); m <= int(p->max); ++m)
        if (double(m) != v0) q.factors.push_back(double(m));
    }
    plan.push_back(q);
  }
  return plan;
}

double explosionSpeed(const SceneDesc& scene) {
  const Vec3 ext = scene.container.max - scene.container.min;
  const float* g = scene.params.fluid.gravity;
  const double gm =
      std::max(9.81, std::sqrt(double(g[0]) * g[0] + double(g[1]) * g[1] + double(g[2]) * g[2]));
  return 2.0 * std::sqrt(2.0 * gm * double(ext.maxCoeff()));
}

std::vector<StabilityRun> runStability(const SceneDesc& scene, const StabilityOptions& o,
                                       const BenchBackend& b) {
  if (!(o.seconds > 0.0)) throw Error("--stability-seconds: must be a positive number of seconds");
  if (o.factors.empty()) throw Error("--stability-factors: give at least one factor");
  for (double f : o.factors)
    if (!(f > 0.0) || !std::isfinite(f))
      throw Error("--stability-factors: each factor must be a positive number");
  const std::vector<StabilityPlan> plan = stabilityPlan(scene.params, o);
  const double vx = explosionSpeed(scene);
  std::vector<StabilityRun> runs;
  auto report = [&](const StabilityRun& r) {
    std::fprintf(stderr, "bench stability: %-34s %-9s = %-10g %s", r.param.c_str(), factor(r, "x").c_str(),
                 r.value, r.exploded ? "EXPLODED" : (r.nan.empty() ? "stable" : r.nan.c_str()));
    if (r.ran)
      std::fprintf(stderr, ", %ld clamps, max speed %.2f m/s, iou %.3f, %.0f s", r.clamps, r.max_speed,
                   r.final_iou, r.wall_s);
    std::fprintf(stderr, "\n");
  };
  // Each parameter is scaled from the value the unscaled run took: a step or
  // radius that another parameter sets (overrideRules) from the one it set
  // (on water, shape_matching.time_step from its fall time), not from the
  // scene's value that it overrides.
  Params taken;
  StabilityRun base = runOne(scene, b, o.seconds, vx, &taken);
  base.param = "(none)";
  report(base);
  runs.push_back(base);
  for (const StabilityPlan& q : plan) {
    const ParamInfo* p = q.param;
    const double v0 = p->number(taken);
    for (double f : q.factors) {
      SceneDesc s = scene;
      bool clipped = false;
      const double v =
          q.mode ? setScaled(*p, s.params, f, 1.0, clipped) : setScaled(*p, s.params, v0, f, clipped);
      StabilityRun r;
      const std::string why = whyNoEffect(*p, s.params);
      try {
        validateParams(s.params, "bench --stability");
        if (why.empty())
          r = runOne(s, b, o.seconds, vx);
        else  // a named parameter that another overrides: its runs would all be the unscaled run
          r.nan = "no effect " + why;
      } catch (const Error& e) {  // a combination validateParams refuses (e.g. the shape clock)
        r.nan = std::string("refused: ") + e.what();
      }
      r.param = shortName(*p), r.factor = f, r.value = v, r.clipped = clipped, r.switched = q.mode;
      report(r);
      runs.push_back(r);
    }
  }
  return runs;
}

void printStability(std::FILE* out, const SceneDesc& scene, const std::vector<StabilityRun>& runs) {
  std::fprintf(out, "\n### Stability sweep: %s (preset %s), %ld steps per run, explosion above %.2f m/s\n\n",
               scene.name.c_str(), scene.preset.c_str(), runs.empty() ? 0L : runs.front().steps,
               explosionSpeed(scene));
  std::fprintf(
      out,
      "| parameter | factor | value | result | velocity clamps | steps with clamps | max speed (m/s) | "
      "max density error | iou at end | stray at end |\n");
  std::fprintf(out, "|---|---|---|---|---|---|---|---|---|---|\n");
  for (const StabilityRun& r : runs) {
    std::string result = r.exploded ? (r.nan.empty() ? "EXPLODED (speed)" : "NaN: " + r.nan)
                                    : (r.nan.empty() ? "stable" : r.nan);
    char value[64] = "-";
    if (r.param != "(none)")
      std::snprintf(value, sizeof value, "%g%s", r.value, r.clipped ? " (range limit)" : "");
    // A run that did not run (no effect, refused) measured nothing: "-".
    char figures[160] = "- | - | - | - | - | -";
    if (r.ran)
      std::snprintf(figures, sizeof figures, "%ld | %ld | %.3f | %.3f | %.3f | %.3f", r.clamps,
                    r.clamped_steps, r.max_speed, r.max_density_error, r.final_iou, r.final_stray);
    std::fprintf(out, "| %s | %s | %s | %s | %s |\n", r.param.c_str(), factor(r).c_str(), value,
                 result.c_str(), figures);
  }
}

}  // namespace ff::app
