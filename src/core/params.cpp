// params.cpp - parameter presets and range checks.
#include "core/params.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/param_table.h"
#include "core/resource_limits.h"
#include "ff_control.h"

namespace ff {

namespace {
float gravityScale(const float g[3]) {
  const float m = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  return m > 0.0f ? m : 9.81f;
}
// The fall time sqrt(L / |g|) (s) of a length L (m): the clock of a scene of
// size L, sqrt(c) times as long in a scene c times as large. T is the
// precision the division and the root round in (float or double).
template <class T>
T fallTime(T length, const float g[3]) {
  return std::sqrt(length / T(gravityScale(g)));
}
}  // namespace

float FluidParams::restSpacing() const {
  return std::cbrt(particle_mass / rest_density);
}

double FluidParams::fallTime() const {
  return ff::fallTime(double(smoothing_radius), gravity);
}

double FluidParams::substepCap() const {
  // max_substep_fall: a multiple of the fall time sqrt(h / g) of the smoothing
  // radius, so that a scene c times as large gets a cap sqrt(c) times as
  // long, the same on its own clock; max_substep (s) stays an upper bound.
  const double cap = double(max_substep);
  if (max_substep_fall <= 0.0f) return cap;
  return std::min(cap, double(max_substep_fall) * fallTime());
}

float FluidParams::frameStep() const {
  if (!(time_step_fall > 0.0f)) return time_step;
  // Whole microseconds: the water preset's 0.11161 fall times is the paper's
  // 4 ms frame exactly at the paper's spacing, so that its scenes' steps
  // land on their schedule's and the metrics' times as before.
  return float(std::round(double(time_step_fall) * fallTime() * 1e6) * 1e-6);
}

namespace {

// The substeps of at most `longest` s each that `span` s takes, 1 to `most`.
int substepCount(double span, double longest, int most) {
  const double n = std::ceil(span / longest - 1e-9);
  return int(std::clamp(n, 1.0, double(std::max(1, most))));
}

}  // namespace

int FluidParams::substepsFor(double max_pressure, double max_speed) const {
  return substepCount(double(time_step), substepLimit(max_pressure, max_speed), max_substeps);
}

SubstepPlan FluidParams::substepPlan(double lead, double max_pressure, double max_speed) const {
  SubstepPlan plan;
  if (!substep_carry) {
    plan.count = substepsFor(max_pressure, max_speed);
    plan.dt = time_step / float(plan.count);
    plan.advance = double(time_step);  // the frame step, whatever the rounding of count x dt
    plan.lead = lead;
    return plan;
  }
  const double frame = double(time_step);
  // What is left of this frame step for the fluid; a frame step made shorter
  // than the lead (the viewer's slider) starts the frame clock afresh.
  const double rest = lead < frame ? frame - lead : frame;
  const double longest = std::min(substepLimit(max_pressure, max_speed), frame);
  plan.count = substepCount(rest, longest, max_substeps);
  plan.dt = float(std::max(longest, rest / double(plan.count)));
  plan.advance = double(plan.count) * double(plan.dt);
  plan.lead = std::max(0.0, plan.advance - rest);
  return plan;
}

double FluidParams::substepLimit(double max_pressure, double max_speed) const {
  // WCSPH: the sound speed of p = k (rho - rho0), sqrt(k), adds to the speed.
  const double c = solver == PressureSolverKind::Wcsph ? std::sqrt(std::max(0.0, double(gas_constant))) : 0.0;
  double dt_cfl = std::min(double(cfl) * double(smoothing_radius) / (c + max_speed + 1e-12), substepCap());
  // DFSPH: its pressure force, V sum_j g (p_i + p_j) / rho0 r_ij, pushes a
  // particle down the gradient of its neighbours' kernel sum with a stiffness
  // proportional to p itself. No solve constrains that motion (the density
  // is one number per particle, its motion three), so the step integrates it
  // explicitly, and symplectic Euler holds it only while dt sqrt(p / rho0)
  // stays below about 0.6 spacings (measured on a resting water column,
  // docs/PRESETS.md): a CFL condition on the speed sqrt(p / rho0), sqrt(g h)
  // under a column of height h, with the last step's highest pressure.
  if (solver == PressureSolverKind::Dfsph && max_pressure > 0.0)
    dt_cfl = std::min(dt_cfl, double(pressure_cfl) * double(smoothing_radius) /
                                  std::sqrt(max_pressure / double(rest_density)));
  return dt_cfl;
}

float ControlParams::recaptureSpeed(const float g[3]) const {
  return recapture * std::sqrt(gravityScale(g) * radius);
}

float ControlParams::recaptureRate(const float g[3]) const {
  return std::sqrt(gravityScale(g) / radius);
}

float ControlParams::pullAttraction(const float g[3]) const {
  return normalise ? attraction_g * gravityScale(g) : attraction;
}

float ControlParams::pullVelocity(const float g[3]) const {
  return normalise ? velocity_rate * std::sqrt(gravityScale(g) / radius) : velocity;
}

int ControlParams::pullMode() const {
  if (normalise) return FF_PULL_NORMALISED;
  return units == ControlForceUnits::ForceDensity ? FF_PULL_PER_DENSITY : FF_PULL_UNITS;
}

float ShapeMatchParams::timeStepFor(float radius, const float g[3]) const {
  return time_step_fall > 0.0f ? time_step_fall * fallTime(radius, g) : time_step;
}

float ShapeMatchParams::firstBlendTime(float radius, const float g[3]) const {
  return blend_first > 0.0f ? blend_first * fallTime(2.0f * radius, g) : 0.0f;
}

double ShapeMatchParams::clustersPerParticle() const {
  const double per_axis =
      std::floor(2.0 * double(cluster_half_width) / double(std::max(1, cluster_stride))) + 1.0;
  return per_axis * per_axis * per_axis * (coarse_clusters >= 2 ? 2.0 : 1.0);
}

const char* solverName(PressureSolverKind k) {
  switch (k) {
    case PressureSolverKind::Wcsph:
      return "wcsph";
    case PressureSolverKind::Dfsph:
      return "dfsph";
  }
  return "?";
}

PressureSolverKind solverByName(const std::string& name) {
  if (name == "wcsph") return PressureSolverKind::Wcsph;
  if (name == "dfsph") return PressureSolverKind::Dfsph;
  throw Error("params.fluid.solver: must be \"wcsph\" or \"dfsph\" (got \"" + name + "\")");
}

namespace {

// Water (docs/PRESETS.md): rho0 = 1000 and DFSPH at the paper's particle
// spacing, so a scene has the same particle count on both presets; the
// support is 2 spacings, as SPlisHSPlasH's cubic spline.
Params waterParams() {
  Params p;
  FluidParams& f = p.fluid;
  const float volume = f.restVolume();  // the paper's rest volume: spacing 6.3 mm
  f.rest_density = 1000.0f;
  f.particle_mass = f.rest_density * volume;
  f.smoothing_radius = 2.0f * std::cbrt(volume);
  f.solver = PressureSolverKind::Dfsph;
  f.cfl = 0.2f;  // two fifths of a spacing per substep at the largest speed (docs/PRESETS.md)
  // Substeps as long as the CFL conditions allow, carried over the frame's
  // end (docs/PRESETS.md, "Substeps that carry over the frame").
  f.substep_carry = 1;
  // The longest substep is 0.112 fall times sqrt(h / g) of the support, the
  // same on every scene's own clock (docs/PRESETS.md, "Substep cap in fall
  // times"): 4.01 ms at the paper's spacing, so one substep per 4 ms frame
  // where the CFL conditions allow (0.0625, 2 substeps, before).
  f.max_substep_fall = 0.112f;
  // The frame step is in fall times too (docs/PRESETS.md, "Frame step in
  // fall times"): 0.11161 sqrt(h / g) is 4.000 ms at the paper's spacing, so
  // that a scene scaled by c steps on its own clock, sqrt(c) times as long.
  f.time_step_fall = 0.11161f;
  f.setFrameStep();
  f.viscosity = 0.1f;  // docs/PRESETS.md: damps the settling of the cubic lattice
  // The divergence solve stops at its first test where the warm start already
  // meets its tolerance (docs/PRESETS.md, "The divergence solve's floor"):
  // on the peer dam break it always does.
  f.divergence_min_iterations = 0;
  // The pull that does not depend on the control particles' density
  // (docs/CONTROL_UNITS.md, "Normalised pull"); the paper preset keeps eq. 4
  // and 6 raw and the radius in metres.
  p.control.normalise = 1;
  // Half the paper's velocity force (docs/CONTROL_UNITS.md, "Thin features"):
  // eq. 6 ties the fluid to the control particles, and at 2.9 it held the
  // fluid in a thin figure's legs (1.4 times their volume at 3 s) while its
  // head stayed half empty (stick figure 0.77, runner with the derived count
  // 0.81; 0.91 and 0.91 at 1.45). At 0.725 a standing disc drains (0.53).
  p.control.velocity_rate = 1.45f;
  // The radius scales with the scene: 3.06 control spacings is the paper's
  // 0.03 m at the bunny's 3197 control particles (9.8 mm apart), and 0.0299 m
  // at the default voxel of 1.55 fluid spacings.
  p.control.radius_spacings = 3.06f;
  // Target changes: the rest shape morphs into the new one over 8 fall times
  // (docs/RESULTS.md, "Rest-shape blend at target changes": shorter blends
  // still ring the control set's slow deformation mode).
  p.shape.blend = 8.0f;
  // The first target morphs in over 2 fall times of the control radius
  // (docs/RESULTS.md, "The first target's overshoots"): the default scene's
  // sphere and Fig. 12's bunny settle with at most one overshoot.
  p.shape.blend_first = 2.0f;
  // The shape-matching clock follows the fall time sqrt(r / g), not the
  // second (docs/CONTROL_UNITS.md, "Shape-matching clock"): 0.0904 of it is
  // the paper's 5 ms at the paper's 0.03 m radius.
  p.shape.time_step_fall = 0.0904f;
  // The derived control count follows the scene's fluid volume, not its
  // particle count (docs/CONTROL_UNITS.md, "How many control particles"):
  // 12,000 / 1.55^3 = 3222 control particles, the default voxel's count for
  // the Table 1 scenes' 12,000 fluid particles, so that scenes of up to
  // 12,013 fluid particles keep one per 1.55 fluid spacings and finer ones
  // keep the control set of 12,000.
  p.control.auto_count = 3226;
  // Shapes do not climb off the floor or tip (docs/CONTROL_UNITS.md,
  // "Anchor": the standing anchor; docs/RESULTS.md, "Standing anchor").
  p.shape.anchor = 2;
  // A bar between two lumps is matched with its ends by clusters 3 times as
  // wide, so that it does not bend under its fluid; limbs and shapes without
  // such a bar keep one level (docs/CONTROL_UNITS.md, "Coarse clusters on
  // bars").
  p.shape.coarse_clusters = 3;
  p.shape.coarse_bars = 1;
  // The recapture at twice sqrt(g r), so that fluid climbs a tall thin
  // figure within 3 s (on main: figure_spread18 0.695 -> 0.935 at 3 s, the
  // runner 0.912 -> 0.968; docs/CONTROL_UNITS.md, "Recapture at twice
  // sqrt(g r)").
  p.control.recapture = 2.0f;
  return p;
}

}  // namespace

Params presetParams(const std::string& name) {
  // The paper's appendix values; params.h holds them as the defaults.
  if (name == "paper") return Params{};
  // The engine's recommended set: the incompressible water (issue 9,
  // docs/PRESETS.md).
  if (name == "default" || name == "water") return waterParams();
  throw Error("unknown parameter preset '" + name + "' (known: paper, default, water)");
}

namespace {

std::string formatValue(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

[[noreturn]] void fail(const std::string& where, const std::string& field, const std::string& problem) {
  std::string prefix = where.empty() ? std::string() : where + ": ";
  throw Error(prefix + field + ": " + problem);
}

void checkValue(const std::string& where, const ParamInfo& info, const std::string& field, double v) {
  if (!info.inRange(v) || !std::isfinite(v))
    fail(where, field, "must be " + info.rangeText() + " (got " + formatValue(v) + ")");
}

}  // namespace

void validateParams(const Params& p, const std::string& where) {
  Params& fields = const_cast<Params&>(p);  // the table's accessors only read here
  for (const ParamInfo& info : paramTable()) {
    void* f = info.field(fields);
    switch (info.type) {
      case ParamInfo::Type::Real:
        checkValue(where, info, info.name(), *static_cast<const float*>(f));
        break;
      case ParamInfo::Type::Integer: {
        const int v = *static_cast<const int*>(f);
        if (!info.inRange(v))
          fail(where, info.name(), "must be " + info.rangeText() + " (got " + std::to_string(v) + ")");
        break;
      }
      case ParamInfo::Type::Vector:
        for (int i = 0; i < 3; ++i)
          checkValue(where, info, info.name() + "[" + std::to_string(i) + "]",
                     static_cast<const float*>(f)[i]);
        break;
      case ParamInfo::Type::Solver:
        if (*static_cast<const PressureSolverKind*>(f) != PressureSolverKind::Wcsph &&
            *static_cast<const PressureSolverKind*>(f) != PressureSolverKind::Dfsph)
          fail(where, info.name(), "must be \"wcsph\" or \"dfsph\"");
        break;
      case ParamInfo::Type::Units: {
        const ControlForceUnits u = *static_cast<const ControlForceUnits*>(f);
        if (u != ControlForceUnits::Acceleration && u != ControlForceUnits::ForceDensity &&
            u != ControlForceUnits::Force)
          fail(where, info.name(), "must be acceleration, force_density or force");
        break;
      }
    }
  }
  // The frame step time_step_fall sets must be a valid time_step.
  const float frame = p.fluid.frameStep();
  if (p.fluid.time_step_fall > 0.0f && !(frame >= 1e-6f && frame <= 0.1f))
    fail(where, "params.fluid.time_step_fall",
         formatValue(p.fluid.time_step_fall) + " fall times sqrt(h / |g|) = " +
             formatValue(p.fluid.fallTime()) + " s make a frame step of " + formatValue(frame) +
             " s; it must be in [1e-06, 0.1] s (or set time_step_fall 0 to give time_step in seconds)");
  // Work per step: every fluid step runs time_step / shape_matching.time_step
  // shape-matching steps.
  const double shape_steps = double(frame) / double(p.shape.time_step);
  if (shape_steps > kMaxShapeStepsPerStep)
    fail(where, "params.shape_matching.time_step",
         "must be at least params.fluid.time_step / " + formatValue(kMaxShapeStepsPerStep) + " = " +
             formatValue(double(frame) / kMaxShapeStepsPerStep) + " s (got " +
             formatValue(p.shape.time_step) + " s, which would make " +
             formatValue(std::ceil(shape_steps - 1e-3)) + " shape-matching steps per fluid step)");
  const double clusters = p.shape.clustersPerParticle();
  if (clusters > kMaxClustersPerParticle)
    fail(where, "params.shape_matching.cluster_half_width",
         formatValue(p.shape.cluster_half_width) + " voxels at cluster_stride " +
             formatValue(p.shape.cluster_stride) + " puts every control particle in " +
             formatValue(clusters) + " clusters; at most " + formatValue(kMaxClustersPerParticle) +
             " (lower cluster_half_width or raise cluster_stride)");
}

}  // namespace ff
