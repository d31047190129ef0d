// params.h - every physical and numerical parameter of a run. Defaults are the
// paper's appendix values (the `paper` preset).
#pragma once
#include <string>

namespace ff {

// How eq. 4 and eq. 6 turn into the fluid's motion. The paper leaves the units
// of f_a and f_v open; docs/CONTROL_UNITS.md records the measurement that chose
// the default.
enum class ControlForceUnits {
  Acceleration,  // dv/dt = f_a + f_v
  ForceDensity,  // dv/dt = (f_a + f_v) / rho_e, like the SPH pressure force
  Force,         // dv/dt = (f_a + f_v) / m_e, a force on the particle
};

// The pressure solver (params.fluid.solver; by name in scenes, solverName).
// Each backend owns its implementation (src/cpu/pressure_solver.h).
enum class PressureSolverKind {
  Wcsph,  // "wcsph": p = k (rho - rho0), Mueller et al. 2003
  Dfsph,  // "dfsph": divergence-free SPH, Bender & Koschier 2015, 2017
};
const char* solverName(PressureSolverKind k);
// The solver called `name`; throws ff::Error "params.fluid.solver: ..." for another.
PressureSolverKind solverByName(const std::string& name);

// A frame step's substeps: `count` of `dt` s each, which advance the
// fluid's clock by `advance` s, after which it leads the frame clock by
// `lead` s (0 <= lead < dt).
struct SubstepPlan {
  int count = 1;
  float dt = 0.0f;
  double advance = 0.0;
  double lead = 0.0;
};

struct FluidParams {
  float particle_mass = 0.0002f;
  float particle_radius = 0.0059f;  // used for rendering and export only
  float smoothing_radius = 0.012f;  // h
  float rest_density = 800.0f;
  float gas_constant = 0.5f;  // k in p = k (rho - rho0)
  float viscosity = 0.02f;    // mu
  float time_step = 0.004f;
  float gravity[3] = {0.0f, -9.81f, 0.0f};
  // Stability without tuning. Each step of `time_step` is split into as many
  // equal substeps as the CFL condition dt <= cfl * h / (c + v_max) asks for,
  // where c = sqrt(k) is the sound speed of p = k (rho - rho0) (0 for dfsph,
  // which has pressure_cfl below instead) and h the smoothing radius (up to
  // max_substeps).
  float cfl = 0.4f;
  int max_substeps = 16;
  // 1: each substep is as long as the CFL conditions and the cap allow (at
  // most the frame step), and a frame step's last substep may end past the
  // frame's end. The fluid's clock then leads the frame clock by less than
  // one substep, and the next frame step is that much shorter (substepPlan).
  // Equal substeps that end on the frame take ceil(time_step / dt) of them,
  // up to one more per frame step than the fluid needs (12 % of the peer dam
  // break's substeps, docs/PRESETS.md, "Substeps that carry over the frame").
  // 0: a frame step's substeps are equal and end on the frame (the paper).
  int substep_carry = 0;
  // The longest substep (s), whatever the CFL condition allows.
  float max_substep = 0.1f;
  // > 0: the longest substep is also max_substep_fall times the fall time
  // sqrt(h / |g|) of the smoothing radius h, which scales with the scene as
  // its clock does (docs/PRESETS.md); 0 = max_substep (s) alone.
  float max_substep_fall = 0.0f;
  // > 0: the frame step is time_step_fall times the fall time sqrt(h / |g|)
  // of the smoothing radius h, rounded to whole microseconds, and sets
  // time_step (setFrameStep), so that a scene c times as large steps sqrt(c)
  // times as long, the same on its own clock (docs/PRESETS.md, "Frame step
  // in fall times"); 0 = time_step in seconds.
  float time_step_fall = 0.0f;
  // DFSPH: the substep also keeps dt <= pressure_cfl * h / sqrt(p_max / rho0),
  // p_max the last step's highest pressure: the pressure force's own
  // stiffness, which the solve leaves explicit (substepsFor, docs/PRESETS.md).
  float pressure_cfl = 0.3f;
  // Last safeguard: no particle moves more than this fraction of h in one
  // substep (a velocity limit).
  float max_step_fraction = 0.5f;
  PressureSolverKind solver = PressureSolverKind::Wcsph;
  // DFSPH: each solve stops once the mean compression it leaves is at most
  // its tolerance, after at least 2 (density) or 1 (divergence) iterations
  // and at most max_iterations (hitting it counts in metrics solver_capped).
  // density_tolerance is in units of rho0; divergence_tolerance is the mean
  // compression rate times the substep, also in units of rho0.
  float density_tolerance = 0.0005f;
  float divergence_tolerance = 0.001f;
  int max_iterations = 100;
  // DFSPH: the fewest iterations of the divergence solve (SPlisHSPlasH: 1);
  // 0 lets it stop at its first test, after the warm start, where that
  // already meets divergence_tolerance (docs/PRESETS.md).
  int divergence_min_iterations = 1;

  float restVolume() const { return particle_mass / rest_density; }
  float restSpacing() const;  // cube root of the rest volume
  // Substeps the CFL condition asks for, given the highest pressure (Pa)
  // and speed of the last step.
  // The longest substep (s): max_substep, or max_substep_fall's fall-time
  // multiple where that is shorter.
  double substepCap() const;
  // The fall time sqrt(h / |g|) of the smoothing radius (s; |g| 9.81 where g is 0).
  double fallTime() const;
  // The frame step (s): time_step, or time_step_fall's fall-time multiple.
  float frameStep() const;
  // time_step = frameStep(): called once the scene's params are final.
  void setFrameStep() { time_step = frameStep(); }
  // A frame step given in seconds: time_step = seconds, and time_step_fall
  // off, which would override it. Every place that sets the step in seconds
  // (a scene's or script's params, the viewer, bench --stability) calls this.
  void setTimeStep(float seconds) { time_step = seconds, time_step_fall = 0.0f; }
  int substepsFor(double max_pressure, double max_speed) const;
  // The longest substep the CFL conditions and the cap allow (s).
  double substepLimit(double max_pressure, double max_speed) const;
  // The substeps of the next frame step, the fluid's clock `lead` s ahead of
  // the frame clock: equal ones that end on the frame (substep_carry 0), or
  // ones as long as substepLimit allows that end at or past it.
  SubstepPlan substepPlan(double lead, double max_pressure, double max_speed) const;
};

struct ControlParams {
  float radius = 0.03f;  // influence radius of a control particle
  // The radius in control particle spacings (the target's voxel): > 0 sets
  // `radius` to radius_spacings voxels at every target, so that it scales
  // with the scene and not with the fluid's particle count (docs/CONTROL_UNITS.md,
  // "Radius in control spacings"); 0 = `radius` in metres, as the paper.
  float radius_spacings = 0.0f;
  // The radius for control particles `voxel` apart.
  float radiusFor(float voxel) const { return radius_spacings > 0.0f ? radius_spacings * voxel : radius; }
  float attraction = 0.00008f;  // w_a
  float velocity = 0.00005f;    // w_v
  float feedback = 0.02f;       // fluid feedback coefficient
  // Share of gravity that the control particles carry for the fluid they hold
  // (after Thuerey et al. 2006, who scale gravity down where control acts).
  // 0 = none (the paper's text), 1 = full inside the target shape.
  float gravity_compensation = 1.0f;
  ControlForceUnits units = ControlForceUnits::Acceleration;
  // Recapture of the fluid out of the control's reach (0 = off, the paper's
  // text): it flies back to the target's unfilled part at
  // recapture * sqrt(g r) (g: gravity's magnitude, r: the radius), its
  // velocity relaxing at sqrt(g / r) per second, with its gravity switched off.
  float recapture = 1.0f;
  // The recapture's speed and relaxation rate for gravity g (9.81 m/s^2 when g is 0).
  float recaptureSpeed(const float g[3]) const;
  float recaptureRate(const float g[3]) const;
  // Normalised pull (docs/CONTROL_UNITS.md, "Normalised pull"): 0 = eq. 4
  // and 6 as the paper writes them, with attraction and velocity (w_a, w_v)
  // in `units`; 1 = normalised by the local control weight, so that the pull
  // does not depend on the control particles' density, with the constants
  // below relative to gravity g and the control radius r. The defaults equal
  // the paper's w_a and w_v for the bunny's control spacing (9.8 mm).
  int normalise = 0;
  float attraction_g = 8.7f;   // most attraction, in units of g
  float velocity_rate = 2.9f;  // the velocity force's relaxation rate, in units of sqrt(g / r)
  // Adaptive control (docs/CONTROL_UNITS.md, "Thin features"): 1 = each control
  // particle's radius follows the target's local thickness (at most `radius`)
  // and clusters hold only particles connected to each other inside them;
  // 0 = one radius and cube clusters, as the paper (the default: measured,
  // docs/RESULTS.md, "Thin features").
  int adaptive = 0;
  // Whether `o` places the same control particles: the fields read as they
  // are placed (adaptive; with it on, the radius, which each particle's
  // radius_scale is a share of). A change re-places the control particles at
  // once (Simulation::setParams), as a change of the clusters does.
  bool samePlacement(const ControlParams& o) const {
    return adaptive == o.adaptive && (adaptive == 0 || radius == o.radius);
  }
  // Derived control count (docs/CONTROL_UNITS.md, "How many control
  // particles"): > 0 caps the control particles a target without
  // control_count or voxel_size gets at this many for the scene's whole fluid
  // (a region its share by volume): the control spacing is at least
  // cbrt(V / auto_count), V the scene's fluid volume, a length that does not
  // change with the particle count; 0 = 1.55 fluid spacings at any count.
  int auto_count = 0;
  // The constants eq. 4 and 6 are multiplied by (w_a, w_v, or their normalised
  // forms g attraction_g and sqrt(g / r) velocity_rate), and the scale mode
  // of ff_pull_scale (kernels/common/ff_control.h).
  float pullAttraction(const float g[3]) const;
  float pullVelocity(const float g[3]) const;
  int pullMode() const;
};

struct ShapeMatchParams {
  float stiffness = 0.3f;    // alpha of eq. 7
  float time_step = 0.005f;  // the shape-matching clock, independent of the fluid's
  // Clusters: one centred on every `cluster_stride`-th reference voxel, holding
  // the control particles within `cluster_half_width` voxels (a cube), so that
  // neighbouring clusters overlap.
  int cluster_stride = 2;
  int cluster_half_width = 2;
  int rotation_iterations = 8;  // warm-started quaternion iterations per step
  // Damping of the control particles' deformation: each shape-matching step
  // moves a particle's velocity this fraction towards the mean velocity of its
  // clusters. Rigid motion is untouched. Plain shape matching with stiffness
  // < 1 is an undamped oscillator; this makes it converge.
  float damping = 0.1f;
  // The anchor (docs/CONTROL_UNITS.md, "Anchor"; kernels/common/ff_anchor.h):
  // 2 = standing (the `default`/`water` presets): the control set never rises
  // above where its rigid rest shape stands on the floor (free below it) and
  // a tilt is righted at sqrt(g / l), l its rest centre's height; 1 = hold:
  // its height and its up axis stay where the placement put them, both ways
  // (its rigid velocity along up and its turning about the horizontal axes
  // relax them back at eq. 7's stiffness); 0 = they follow the fluid, as the
  // paper (the `paper` preset).
  int anchor = 0;
  // Rest-shape blend at a target change (docs/CONTROL_UNITS.md, "Rest-shape
  // blend"): the rest shape morphs from where placement puts the control
  // particles (the new shape spread over the fluid as it stands) into the new
  // target over `blend` times the time the fluid takes to fall the largest
  // distance a rest position moves, sqrt(2 d / g). 0 = off (the paper: the
  // new rest shape at once). A run's first target: `blend_first`.
  float blend = 0.0f;
  // The shape-matching step in units of sqrt(r / g), r the control radius
  // (docs/CONTROL_UNITS.md, "Shape-matching clock"): > 0 sets `time_step`
  // at every target, so that eq. 7's stiffness, the damping and the feedback
  // (each a fraction per step) act on the scene's own fall time and a scene
  // scaled by c forms on a clock sqrt(c) times slower, as its fluid falls;
  // 0 = `time_step` in seconds, as the paper.
  float time_step_fall = 0.0f;
  // The shape-matching step for control radius `radius` under gravity `g`.
  float timeStepFor(float radius, const float g[3]) const;
  // A shape-matching step given in seconds: time_step = seconds, and
  // time_step_fall off, which would override it at every target. Every place
  // that sets the step in seconds (a scene's or script's params, the Python
  // module's set_params, the viewer, bench --stability) calls this.
  void setTimeStep(float seconds) { time_step = seconds, time_step_fall = 0.0f; }
  // The rest-shape blend of a run's first target (docs/CONTROL_UNITS.md,
  // "Rest-shape blend"): its rest shape morphs from where placement puts the
  // control particles (the target stretched over the picked fluid) into the
  // target over `blend_first` times sqrt(2 r / g), r the control radius, so
  // that the first forming does not ring the control set's slow deformation
  // mode. A time of the scene's own clock, not of how far the particles move
  // (`blend`): a tall shape squashed over its fluid would form late. 0 = off
  // (the paper: the rest shape at once).
  float blend_first = 0.0f;
  // Coarse clusters (docs/CONTROL_UNITS.md, "Coarse clusters"): k >= 2 adds
  // a second level of clusters k times the stride and half-width, so that a
  // long thin part does not bend under the fluid it holds; 0 or 1 (every
  // preset): one level, as the paper.
  int coarse_clusters = 0;
  // Where the coarse level acts (docs/CONTROL_UNITS.md, "Coarse clusters on
  // bars"): 1, only around a bar that joins two lumps of the shape
  // (shapeParts), a limb never; a shape without such a bar keeps one level,
  // except one with no limbs and a closed loop ("Coarse clusters on loops")
  // or a junction of three or more strokes ("Coarse clusters on crossings"),
  // which gets it everywhere.
  // 0: over the whole shape (the paper has no coarse level).
  int coarse_bars = 0;
  // The first target's blend time (s) for control radius `radius` under gravity `g`.
  float firstBlendTime(float radius, const float g[3]) const;
  // Whether `o` builds the same clusters: the fields read when the clusters
  // are built, as the control particles are placed (cluster_stride,
  // cluster_half_width, coarse_clusters, coarse_bars). A change of any of them re-places
  // the control particles at once (Simulation::setParams), so that it does
  // not wait for the next target. A new cluster field is added here.
  bool sameClusters(const ShapeMatchParams& o) const {
    return cluster_stride == o.cluster_stride && cluster_half_width == o.cluster_half_width &&
           coarse_clusters == o.coarse_clusters && coarse_bars == o.coarse_bars;
  }

  // The most clusters one control particle belongs to: the lattice points
  // (multiples of the stride) within half_width voxels, per axis
  // floor(2 half_width / stride) + 1. Work and memory of shape matching grow
  // with it.
  double clustersPerParticle() const;
};

struct Params {
  FluidParams fluid;
  ControlParams control;
  ShapeMatchParams shape;
};

// Named parameter sets. Throws ff::Error for an unknown name.
Params presetParams(const std::string& name);

// Checks every field for NaN, Inf and values outside its range in the
// parameter table (core/param_table.h), and that the shape-matching clock
// makes at most kMaxShapeStepsPerStep steps per fluid step. `where` prefixes
// the message (e.g. the scene file). Throws ff::Error naming the field.
void validateParams(const Params& p, const std::string& where);

}  // namespace ff
