// param_table.cpp - the ranges and meanings of all run parameters.
//
// The ranges are wide enough for any physical scene at the scale of the paper
// (a few litres of liquid in a box of tens of centimetres up to metres) and
// for the parameter sweeps of docs/, and narrow enough that nothing overflows
// or runs away: counts that multiply work (iterations, cluster sizes,
// substeps) are bounded, and every real is finite. Memory-dependent limits
// (particle counts, voxel counts) are in core/resource_limits.h instead.
#include "core/param_table.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "core/error.h"

namespace ff {

namespace {

using T = ParamInfo::Type;
constexpr bool kMode = true;  // ParamInfo::mode

#define FF_FIELD(member) [](Params& p) -> void* { return &p.member; }

std::string fmt(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

std::string ParamInfo::name() const {
  return std::string("params.") + group + "." + key;
}

std::string ParamInfo::rangeText() const {
  return std::string("in ") + (min_open ? "(" : "[") + fmt(min) + ", " + fmt(max) + "]";
}

bool ParamInfo::inRange(double v) const {
  return (min_open ? v > min : v >= min) && v <= max;
}

double ParamInfo::number(const Params& p) const {
  void* f = field(const_cast<Params&>(p));  // the accessor only reads here
  if (type == Type::Integer) return double(*static_cast<const int*>(f));
  if (type == Type::Real) return double(*static_cast<const float*>(f));
  throw Error(name() + ": not a number parameter");
}

const std::vector<ParamInfo>& paramTable() {
  static const std::vector<ParamInfo> table = {
      // group, key, type, min, max, min_open, doc, field[, kMode]
      {"fluid", "particle_mass", T::Real, 0.0, 1e3, true, "mass of one fluid particle (kg)",
       FF_FIELD(fluid.particle_mass)},
      {"fluid", "particle_radius", T::Real, 0.0, 10.0, true,
       "radius a particle is drawn and exported with (m); no effect on the physics",
       FF_FIELD(fluid.particle_radius)},
      {"fluid", "smoothing_radius", T::Real, 1e-5, 10.0, false, "SPH smoothing radius h (m)",
       FF_FIELD(fluid.smoothing_radius)},
      {"fluid", "rest_density", T::Real, 1e-3, 1e6, false, "rest density rho0 (kg/m^3)",
       FF_FIELD(fluid.rest_density)},
      {"fluid", "gas_constant", T::Real, 0.0, 1e6, false, "k in the equation of state p = k (rho - rho0)",
       FF_FIELD(fluid.gas_constant)},
      {"fluid", "viscosity", T::Real, 0.0, 1e4, false, "viscosity mu (Pa s)", FF_FIELD(fluid.viscosity)},
      {"fluid", "time_step", T::Real, 1e-6, 0.1, false,
       "one step of simulated time (s); giving it turns time_step_fall off", FF_FIELD(fluid.time_step)},
      {"fluid", "gravity", T::Vector, -1e3, 1e3, false, "gravity, each component (m/s^2)",
       FF_FIELD(fluid.gravity)},
      {"fluid", "solver", T::Solver, 0.0, 0.0, false, "the pressure solver by name: \"wcsph\" or \"dfsph\"",
       FF_FIELD(fluid.solver)},
      {"fluid", "density_tolerance", T::Real, 1e-7, 0.1, false,
       "dfsph: the mean compression (units of rho0) at which the density solve stops",
       FF_FIELD(fluid.density_tolerance)},
      {"fluid", "divergence_tolerance", T::Real, 1e-7, 1.0, false,
       "dfsph: the mean compression rate times the substep at which the divergence solve stops",
       FF_FIELD(fluid.divergence_tolerance)},
      {"fluid", "max_iterations", T::Integer, 2, 10000, false,
       "dfsph: the most iterations of one solve (hitting it counts in solver_capped)",
       FF_FIELD(fluid.max_iterations)},
      {"fluid", "max_step_fraction", T::Real, 0.0, 1.0, true,
       "velocity limit: the most a particle moves in one substep, as a fraction of h",
       FF_FIELD(fluid.max_step_fraction)},
      {"fluid", "cfl", T::Real, 0.0, 1.0, true, "CFL number of the automatic substeps", FF_FIELD(fluid.cfl)},
      {"fluid", "max_substeps", T::Integer, 1, 1000, false, "the most CFL substeps per step",
       FF_FIELD(fluid.max_substeps)},
      {"fluid", "substep_carry", T::Integer, 0, 1, false,
       "1: substeps as long as the CFL conditions allow, a frame step's last one ending at or past the frame "
       "(the fluid's clock leads by less than a substep); 0: equal substeps that end on the frame",
       FF_FIELD(fluid.substep_carry), kMode},
      {"fluid", "max_substep", T::Real, 1e-6, 1.0, false,
       "the longest substep (s), whatever the CFL number allows", FF_FIELD(fluid.max_substep)},
      {"fluid", "pressure_cfl", T::Real, 0.0, 1.0, true,
       "dfsph: CFL number on sqrt(p_max / rho0), the speed of the pressure force's own stiffness",
       FF_FIELD(fluid.pressure_cfl)},
      {"fluid", "max_substep_fall", T::Real, 0.0, 100.0, false,
       "> 0: the longest substep is also this many fall times sqrt(h / |g|) of the smoothing radius; "
       "0: max_substep (s) alone",
       FF_FIELD(fluid.max_substep_fall)},
      {"fluid", "time_step_fall", T::Real, 0.0, 10.0, false,
       "> 0: the frame step (time_step) is this many fall times sqrt(h / |g|) of the smoothing radius, "
       "in whole microseconds; 0: time_step in seconds",
       FF_FIELD(fluid.time_step_fall)},
      {"fluid", "divergence_min_iterations", T::Integer, 0, 10, false,
       "dfsph: the fewest iterations of the divergence solve; 0: it stops at its first test (after the warm "
       "start) where that meets divergence_tolerance",
       FF_FIELD(fluid.divergence_min_iterations)},

      {"control", "radius", T::Real, 1e-5, 10.0, false, "influence radius of a control particle (m)",
       FF_FIELD(control.radius)},
      {"control", "radius_spacings", T::Real, 0.0, 100.0, false,
       "> 0: the radius in control particle spacings (the target's voxel), set at every target; "
       "0: radius in metres",
       FF_FIELD(control.radius_spacings)},
      {"control", "attraction", T::Real, 0.0, 1e6, false, "w_a, weight of the attraction force (eq. 4)",
       FF_FIELD(control.attraction)},
      {"control", "velocity", T::Real, 0.0, 1e6, false, "w_v, weight of the velocity force (eq. 6)",
       FF_FIELD(control.velocity)},
      {"control", "feedback", T::Real, 0.0, 1.0, false,
       "fluid feedback: how far a control particle's velocity moves towards the fluid's per step",
       FF_FIELD(control.feedback)},
      {"control", "gravity_compensation", T::Real, 0.0, 1.0, false,
       "share of gravity the control particles carry for the fluid they hold",
       FF_FIELD(control.gravity_compensation)},
      {"control", "recapture", T::Real, 0.0, 10.0, false,
       "recapture of fluid out of the control's reach: speed in units of sqrt(g r) (0 = off)",
       FF_FIELD(control.recapture)},
      {"control", "units", T::Units, 0.0, 0.0, false,
       "how eq. 4 and 6 act: \"acceleration\", \"force_density\" or \"force\"", FF_FIELD(control.units)},
      {"control", "normalise", T::Integer, 0, 1, false,
       "1: eq. 4 and 6 normalised by the local control weight (attraction_g, velocity_rate; units unused); "
       "0: as the paper writes them (attraction, velocity, units)",
       FF_FIELD(control.normalise), kMode},
      {"control", "adaptive", T::Integer, 0, 1, false,
       "1: each control particle's radius in eq. 5 follows the target's local thickness and clusters follow "
       "limbs (thin features); 0: one radius, cube clusters (the paper)",
       FF_FIELD(control.adaptive), kMode},
      {"control", "attraction_g", T::Real, 0.0, 1e3, false,
       "normalised attraction (normalise = 1): its most, in units of gravity",
       FF_FIELD(control.attraction_g)},
      {"control", "velocity_rate", T::Real, 0.0, 1e3, false,
       "normalised velocity force (normalise = 1): relaxation rate in units of sqrt(g / radius)",
       FF_FIELD(control.velocity_rate)},
      {"control", "auto_count", T::Integer, 0, 100000000, false,
       "> 0: a target without control_count or voxel_size gets at most this many control particles for the "
       "scene's whole fluid (a region its share by volume), whatever the particle count; 0: one per 1.55 "
       "fluid spacings",
       FF_FIELD(control.auto_count)},

      {"shape_matching", "stiffness", T::Real, 0.0, 1.0, false, "alpha of eq. 7", FF_FIELD(shape.stiffness)},
      {"shape_matching", "time_step", T::Real, 1e-6, 1.0, false,
       "the shape-matching clock (s); at most 1000 shape-matching steps per fluid step; giving it "
       "turns time_step_fall off",
       FF_FIELD(shape.time_step)},
      {"shape_matching", "cluster_stride", T::Integer, 1, 64, false,
       "a cluster is centred on every N-th reference voxel", FF_FIELD(shape.cluster_stride)},
      {"shape_matching", "cluster_half_width", T::Integer, 1, 64, false,
       "a cluster holds the control particles within N voxels (a cube)", FF_FIELD(shape.cluster_half_width)},
      {"shape_matching", "rotation_iterations", T::Integer, 1, 100, false,
       "warm-started quaternion iterations per shape-matching step", FF_FIELD(shape.rotation_iterations)},
      {"shape_matching", "damping", T::Real, 0.0, 1.0, false,
       "how far a control particle's velocity moves towards its clusters' mean per step",
       FF_FIELD(shape.damping)},
      {"shape_matching", "anchor", T::Integer, 0, 2, false,
       "2: the control set never rises above where its rest shape stands on the floor and is righted at "
       "sqrt(g / its centre's height); 1: its height and up axis stay where it was placed, both ways, "
       "relaxing back at the stiffness; 0: they follow the fluid (the paper)",
       FF_FIELD(shape.anchor), kMode},
      {"shape_matching", "blend", T::Real, 0.0, 100.0, false,
       "rest-shape blend at a target change, in fall times sqrt(2 d / g) over the largest distance d a "
       "rest position moves (0 = off: the new rest shape at once)",
       FF_FIELD(shape.blend)},
      {"shape_matching", "time_step_fall", T::Real, 0.0, 10.0, false,
       "> 0: the shape-matching step in units of sqrt(radius / g), set at every target; "
       "0: time_step in seconds",
       FF_FIELD(shape.time_step_fall)},
      {"shape_matching", "blend_first", T::Real, 0.0, 100.0, false,
       "rest-shape blend of a run's first target, from where placement puts it, over blend_first "
       "sqrt(2 radius / g) (0 = off: the rest shape at once)",
       FF_FIELD(shape.blend_first)},
      {"shape_matching", "coarse_clusters", T::Integer, 0, 16, false,
       ">= 2: a second level of clusters this many times the stride and half-width, so that a long thin "
       "part does not bend under its fluid; 0 or 1: one level",
       FF_FIELD(shape.coarse_clusters)},
      {"shape_matching", "coarse_bars", T::Integer, 0, 1, false,
       "1: the coarse clusters only around a bar that joins two lumps of the shape, never on a limb "
       "(a shape without such a bar keeps one level, but one with a closed loop and no limbs gets it "
       "everywhere, as does one whose strokes meet at a junction of three or more branches and that has no "
       "limbs); 0: over the whole shape",
       FF_FIELD(shape.coarse_bars), kMode},
  };
  return table;
}

const std::vector<std::string>& paramGroups() {
  static const std::vector<std::string> groups = {"fluid", "control", "shape_matching"};
  return groups;
}

void setRealParam(const ParamInfo& info, Params& p, float v) {
  void* f = info.field(p);
  if (f == static_cast<void*>(&p.fluid.time_step))
    p.fluid.setTimeStep(v);
  else if (f == static_cast<void*>(&p.shape.time_step))
    p.shape.setTimeStep(v);
  else
    *static_cast<float*>(f) = v;
}

const std::vector<OverrideRule>& overrideRules() {
  using When = OverrideRule::When;
  static const std::vector<OverrideRule> rules = {
      // group, key, by, sets, when, note
      {"fluid", "time_step", "time_step_fall", true, When::Positive,
       "it sets the frame step from the smoothing radius"},
      {"control", "radius", "radius_spacings", true, When::Positive, "it sets the radius at every target"},
      {"control", "attraction", "normalise", false, When::One, "attraction_g and velocity_rate act instead"},
      {"control", "velocity", "normalise", false, When::One, "attraction_g and velocity_rate act instead"},
      {"control", "units", "normalise", false, When::One, "attraction_g and velocity_rate act instead"},
      {"control", "attraction_g", "normalise", false, When::Zero,
       "attraction, velocity and units act instead"},
      {"control", "velocity_rate", "normalise", false, When::Zero,
       "attraction, velocity and units act instead"},
      {"shape_matching", "time_step", "time_step_fall", true, When::Positive,
       "it sets the step from the control radius at every target"},
  };
  return rules;
}

const char* OverrideRule::condition() const {
  return when == When::Positive ? "> 0" : when == When::One ? "is 1" : "is 0";
}

bool OverrideRule::holds(const Params& p) const {
  const auto it = std::find_if(paramTable().begin(), paramTable().end(), [this](const ParamInfo& i) {
    return std::strcmp(i.group, group) == 0 && std::strcmp(i.key, by) == 0;
  });
  if (it == paramTable().end()) throw Error(std::string("override rule: no parameter ") + group + "." + by);
  const double v = it->number(p);
  // A mode is an integer: 1 is "not 0" (normalise is 0 or 1).
  return when == When::Positive ? v > 0.0 : when == When::One ? v != 0.0 : v == 0.0;
}

const OverrideRule* overriddenBy(const ParamInfo& info, const Params& p) {
  for (const OverrideRule& r : overrideRules())
    if (std::strcmp(r.group, info.group) == 0 && std::strcmp(r.key, info.key) == 0 && r.holds(p)) return &r;
  return nullptr;
}

std::string whyNoEffect(const ParamInfo& info, const Params& p) {
  const OverrideRule* r = overriddenBy(info, p);
  if (!r) return "";
  return std::string("while params.") + r->group + "." + r->by + " " + r->condition() + " (" + r->note + ")";
}

bool paramActs(const ParamInfo& info, const Params& p) {
  return overriddenBy(info, p) == nullptr;
}

bool setByAnother(const ParamInfo& info, const Params& p) {
  const OverrideRule* r = overriddenBy(info, p);
  return r != nullptr && r->sets;
}

}  // namespace ff
