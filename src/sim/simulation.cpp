#include "sim/simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <sstream>
#include <utility>
#include <vector>

#include "control/placement.h"
#include "control/shape_matching.h"
#include "core/error.h"
#include "core/resource_limits.h"
#include "scene/scene_state.h"

namespace ff {

namespace {
// The fewest control particles a target that asks for neither a size nor a
// count gets (a shape 4 voxels across), unless its fluid has fewer particles.
constexpr double kMinAutoControls = 64.0;

// The voxel size of a target that asks for neither a size nor a count, for
// `fluid_volume` of controlled fluid in a scene whose whole fluid has the rest
// volume `scene_volume`: 1.55 fluid spacings (a control particle per 3.7 fluid
// particles), but with `control.auto_count` never finer than the scene's
// fluid cut into that many voxels, a length that does not change with the
// particle count (at 2x the particles in the same volume the control set
// stays as it was); for a small region, finer, down to one fluid spacing, so
// that it still gets min(fluid particles, kMinAutoControls) control particles
// (docs/CONTROL_UNITS.md, "How many control particles").
float defaultVoxelSize(const Params& p, double scene_volume, double fluid_volume) {
  const FluidParams& fp = p.fluid;
  float voxel = 1.55f * fp.restSpacing();
  if (p.control.auto_count > 0 && scene_volume > 0.0) {
    const double coarse = std::cbrt(scene_volume / double(p.control.auto_count));
    if (coarse > double(voxel)) voxel = float(coarse);
  }
  const double v = double(voxel), fluid = fluid_volume / double(fp.restVolume());
  const double wanted = std::min(fluid, kMinAutoControls);
  if (!(fluid_volume > 0.0) || fluid_volume / (v * v * v) >= wanted) return voxel;
  return float(std::max(double(fp.restSpacing()), std::cbrt(fluid_volume / wanted)));
}
// The most control particles per controlled fluid particle: a voxel of a
// quarter of the fluid's rest spacing. Denser control particles carry no more
// information about the shape than the fluid can follow, only work.
constexpr double kMaxControlPerFluid = 64.0;

// Before voxelising: how many control particles the spec asks for, against
// the fluid that will fill them.
void checkControlCount(const TargetSpec& spec, long fluid, double fluid_volume, float default_voxel) {
  const double volume = spec.volume > 0.0f ? double(spec.volume) : fluid_volume;
  const double voxel = spec.voxel_size > 0.0f ? double(spec.voxel_size) : double(default_voxel);
  const double controls =
      spec.control_count > 0 ? double(spec.control_count) : volume / (voxel * voxel * voxel);
  if (!(controls <= kMaxControlPerFluid * double(fluid))) {
    const char* key = spec.control_count > 0   ? "control_count"
                      : spec.voxel_size > 0.0f ? "voxel_size"
                                               : "volume";
    std::ostringstream os;
    os.precision(3);
    os << spec.where(key) << ": about " << controls << " control particles for " << fluid
       << " controlled fluid particles; at most " << kMaxControlPerFluid << " per fluid particle";
    throw Error(os.str());
  }
}

// The clusters of `controls` control particles must fit in memory.
void checkClusterMemory(const ShapeMatchParams& sm, size_t controls, const std::string& where) {
  const double per = sm.clustersPerParticle();
  std::ostringstream what;
  what.precision(3);
  what << double(controls) << " control particles in up to " << per << " clusters each";
  checkMemory(double(controls) * (per * kBytesPerClusterMembership + kBytesPerControlParticle), where,
              "params.shape_matching.cluster_half_width", what.str());
}

}  // namespace

Simulation::Simulation(SceneDesc scene, std::unique_ptr<Backend> backend)
    : scene_(std::move(scene)), backend_(std::move(backend)) {
  validateParams(scene_.params, scene_.source);
  scene_.params.fluid.setFrameStep();
  double particles = 0.0;  // in double: dims of scenes made in code are not checked yet
  for (const FluidBlockDesc& b : scene_.fluid) particles += double(b.dims[0]) * b.dims[1] * b.dims[2];
  checkFluidCount(particles, scene_.source, "fluid");
  backend_->init(scene_.params, scene_.container, makeFluid(scene_));
  applySchedule();
}

Simulation::Simulation(SceneDesc scene, std::unique_ptr<Backend> backend, StateReader& r)
    : scene_(std::move(scene)), backend_(std::move(backend)) {
  validateParams(scene_.params, r.source());
  scene_.params.fluid.setFrameStep();
  backend_->init(scene_.params, scene_.container, makeFluid(scene_));
  r.tag("SIMU");
  r.pod(step_), r.pod(time_), r.pod(lead_), r.pod(metrics_);
  r.check(std::isfinite(lead_) && lead_ >= 0.0, "its substeps' lead is not a finite time >= 0");
  const uint64_t next = r.pod<uint64_t>();
  r.check(next <= scene_.schedule.size(), "the schedule position is past the schedule's end");
  next_schedule_ = size_t(next);
  r.pod(has_target_), r.pod(controlled_), r.pod(target_volume_);
  r.pod(metrics_requested_), r.pod(metrics_fresh_), r.pod(unchecked_from_);
  r.vec(controlled_by_id_);
  r.check(controlled_by_id_.empty() || controlled_by_id_.size() == makeFluid(scene_).size(),
          "the controlled fluid's flags do not match the fluid");
  if (has_target_) {
    target_spec_ = readTargetState(r);
    target_ = &cache_.get(target_spec_, target_volume_,
                          defaultVoxelSize(scene_.params, sceneFluidVolume(), target_volume_));
    scene_.params = withControlRadius(scene_.params, target_->grid.voxel);
    backend_->setParams(scene_.params);
  }
  backend_->loadState(r);
  backend_->setMetricsTarget(target_);
  backend_->setControlledFluid(controlled_by_id_);
  r.check(r.atEnd(), "there are bytes after the end of the state");
}

void Simulation::saveState(StateWriter& w) const {
  w.tag("SIMU");
  w.pod(step_), w.pod(time_), w.pod(lead_), w.pod(metrics_);
  w.pod(uint64_t(next_schedule_));
  w.pod(has_target_), w.pod(controlled_), w.pod(target_volume_);
  w.pod(metrics_requested_), w.pod(metrics_fresh_), w.pod(unchecked_from_);
  w.vec(controlled_by_id_);
  if (has_target_) writeTargetState(w, target_spec_);
  backend_->saveState(w);
}

double Simulation::sceneFluidVolume() const {
  double particles = 0.0;
  for (const FluidBlockDesc& b : scene_.fluid) particles += double(b.dims[0]) * b.dims[1] * b.dims[2];
  return particles * double(scene_.params.fluid.restVolume());
}

FluidState Simulation::makeFluid(const SceneDesc& scene) {
  FluidState s;
  const float rest = scene.params.fluid.restSpacing();
  for (const FluidBlockDesc& b : scene.fluid) {
    const float sp = b.spacing > 0.0f ? b.spacing : rest;
    for (int k = 0; k < b.dims[2]; ++k)
      for (int j = 0; j < b.dims[1]; ++j)
        for (int i = 0; i < b.dims[0]; ++i)
          s.push(b.origin.x() + (float(i) + 0.5f) * sp, b.origin.y() + (float(j) + 0.5f) * sp,
                 b.origin.z() + (float(k) + 0.5f) * sp, b.velocity.x(), b.velocity.y(), b.velocity.z());
  }
  return s;
}

template <class F>
void Simulation::timed(Phase p, F&& f) {
  auto t0 = std::chrono::steady_clock::now();
  f();
  auto t1 = std::chrono::steady_clock::now();
  const double ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  phase_ms_[size_t(p)] += ms;
  last_step_ms_[size_t(p)] += ms;
}

void Simulation::check(long step, double time, int substeps) {
  int substep = 0;
  const Phase p = backend_->firstNonFinite(&substep);
  if (p == Phase::Count) return;
  std::ostringstream os;
  if (unchecked_from_ < step) os << "steps " << unchecked_from_ << " to ";
  os << "step " << step << " (t = " << time << " s";
  if (substeps > 1) os << ", substep " << substep + 1 << " of " << substeps;
  os << "): a value became NaN or Inf in phase '" << phaseName(p) << "'";
  throw Error(os.str());
}

void Simulation::applySchedule() {
  const auto& sch = scene_.schedule;
  while (next_schedule_ < sch.size() && sch[next_schedule_].time <= time_ + 1e-9) {
    setTarget(sch[next_schedule_].target);
    ++next_schedule_;
  }
}

void Simulation::step() {
  last_step_ms_.fill(0.0);
  applySchedule();
  const FluidParams& fp = scene_.params.fluid;
  // Substeps from the CFL condition, with last step's highest pressure and speed.
  const SubstepPlan plan = fp.substepPlan(lead_, metrics_.max_pressure, metrics_.max_speed);
  const int n = plan.count;
  const float dt = plan.dt;
  for (int k = 0; k < n; ++k) {
    timed(Phase::Grid, [&] { backend_->buildGrid(); });
    timed(Phase::Density, [&] { backend_->computeDensity(); });
    timed(Phase::Forces, [&] { backend_->computeForces(dt); });
    timed(Phase::ControlScale, [&] { backend_->computeControlScale(); });
    timed(Phase::ControlForces, [&] { backend_->applyControlForces(dt); });
    timed(Phase::Pressure, [&] { backend_->solvePressure(dt); });
    timed(Phase::Integrate, [&] { backend_->integrate(dt); });
    timed(Phase::ShapeMatching, [&] { backend_->shapeMatching(dt); });
  }
  last_stage_ms_ = backend_->takeStageMs();
  addStages(stage_ms_, last_stage_ms_);
  // One check per step with metrics (on OpenCL one int read back): the phase
  // that first wrote a NaN or Inf since the last check, in phase and substep order.
  const long step = step_;
  const double time = time_;
  ++step_;
  // The fluid's clock, and how far it runs ahead of the frames.
  time_ += plan.advance;
  lead_ = plan.lead;
  const bool want = metrics_requested_ || step_ % metrics_every_ == 0;
  const bool with_shape = !shape_on_request_ || metrics_requested_;
  metrics_requested_ = false;
  metrics_fresh_ = want;
  if (want) {
    // The pressure that sets DFSPH's substeps is held: the larger of this
    // step's highest and the last one's, halved every 0.1 s. A column's
    // highest pressure swings by half between steps as it settles, and one
    // long substep taken at a low swing kicks it (measured, docs/PRESETS.md).
    // It decays over the steps since the last metrics (one step unless
    // --metrics-every skipped some), so its half-life is 0.1 s for any K.
    const double since = double(step_ - unchecked_from_);
    const double held = metrics_.max_pressure * std::exp2(-since * double(fp.time_step) / 0.1);
    const StepMetrics last = metrics_;
    timed(Phase::Metrics, [&] { metrics_ = backend_->computeMetrics(with_shape); });
    if (!with_shape) metrics_.copyShapeMetrics(last);
    metrics_.max_pressure = std::max(metrics_.max_pressure, held);
    check(step, time, unchecked_from_ < step ? 0 : n);
    unchecked_from_ = step_;
  }
  metrics_.step = step_;
  metrics_.time = time_;
  metrics_.substeps = n;
  metrics_.max_density_error = (metrics_.max_density - double(fp.rest_density)) / double(fp.rest_density);
  for (double v : {metrics_.iou, metrics_.coverage, metrics_.max_speed, metrics_.density_error,
                   metrics_.kinetic_energy, metrics_.max_density, metrics_.compression})
    if (!std::isfinite(v))
      throw Error("step " + std::to_string(step_) + ": a metric became NaN or Inf in phase 'metrics'");
}

void Simulation::makeTarget(const TargetSpec& spec, bool reselect) {
  FluidState s;
  backend_->readFluid(s);
  const RegionDesc& r = scene_.region;
  // With a target already active, the new shape is placed over the fluid that
  // forms the current shape: inside its voxels (dilated by one voxel), where
  // the control particles have carried it. Fluid that fell out of the shape
  // onto the floor does not stretch the new target's bounding box. With the
  // recapture on, which brings that fluid back, it still counts in the new
  // target's volume: the controlled fluid stays the same particles (by
  // identity) and the control set's volume does not shrink from one change to
  // the next. Without it, the new target holds only the fluid of the current
  // shape.
  const bool keep = target_ != nullptr && !reselect && scene_.params.control.recapture > 0.0f;
  std::function<bool(const Vec3&)> inCurrentShape = [](const Vec3&) { return true; };
  ControlSet cur;
  if (target_) {
    ControlFields unused;
    backend_->readControl(cur, unused);
  }
  ff_quat q = FF_Q(0.0f, 0.0f, 0.0f, 1.0f);
  float c[3] = {0, 0, 0};
  if (target_ && cur.size() > 0) {
    bestFitFrame(cur, q, c, 50);
    const ff_mat3 rot = ff_quat_to_mat3(q);
    const VoxelGrid& g = target_->grid;
    const Vec3 rest_c(cur.rest_cx, cur.rest_cy, cur.rest_cz), centre(c[0], c[1], c[2]);
    inCurrentShape = [&g, rot, rest_c, centre](const Vec3& p) {
      const Vec3 d = p - centre;  // world offset; rotate back with R^T
      const Vec3 x0 =
          Vec3(FF_DOT(rot.c0, FF_F3(d.x(), d.y(), d.z())), FF_DOT(rot.c1, FF_F3(d.x(), d.y(), d.z())),
               FF_DOT(rot.c2, FF_F3(d.x(), d.y(), d.z()))) +
          rest_c;
      const int i = int(std::floor((x0.x() - g.origin.x()) / g.voxel));
      const int j = int(std::floor((x0.y() - g.origin.y()) / g.voxel));
      const int k = int(std::floor((x0.z() - g.origin.z()) / g.voxel));
      for (int dk = -1; dk <= 1; ++dk)
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int a = i + di, b = j + dj, e = k + dk;
            if (a >= 0 && b >= 0 && e >= 0 && a < g.nx && b < g.ny && e < g.nz && g.inside[g.index(a, b, e)])
              return true;
          }
      return false;
    };
  }
  const std::vector<uint8_t> was_controlled = controlled_by_id_;  // empty: all the fluid
  auto inRegion = [&](size_t i) {
    if (keep) return was_controlled.empty() || was_controlled[s.id[i]] != 0;
    const Vec3 p(s.x[i], s.y[i], s.z[i]);
    if (r.kind == RegionDesc::Kind::Box)
      return (p.array() >= r.min.array()).all() && (p.array() <= r.max.array()).all();
    if (r.kind == RegionDesc::Kind::Sphere) return (p - r.center).squaredNorm() <= r.radius * r.radius;
    return true;
  };
  std::vector<float> px, py, pz;
  auto collect = [&](bool shape_only) {
    px.clear(), py.clear(), pz.clear();
    for (size_t i = 0; i < s.size(); ++i) {
      Vec3 p(s.x[i], s.y[i], s.z[i]);
      if (!inRegion(i) || (shape_only && !inCurrentShape(p))) continue;
      px.push_back(p.x()), py.push_back(p.y()), pz.push_back(p.z());
    }
  };
  collect(false);
  const long in_region = long(px.size());
  collect(true);
  if (px.empty()) collect(false);  // the current shape holds no fluid: start from the region
  const long count = keep ? in_region : long(px.size());
  if (count == 0) throw Error(scene_.source + ": region: the controlled region holds no fluid particles");
  // The region's bounding box, robust to the few droplets a splash throws far
  // away: the 1st to 99th percentile of the particles along each axis (all of
  // them for small regions). Otherwise one droplet on the far side of the
  // container stretches the new shape over the whole floor.
  auto range = [&](std::vector<float>& v, float& lo, float& hi) {
    const size_t n = v.size(), k = n >= 200 ? n / 100 : 0;
    std::nth_element(v.begin(), v.begin() + long(k), v.end());
    lo = v[k];
    std::nth_element(v.begin(), v.begin() + long(n - 1 - k), v.end());
    hi = v[n - 1 - k];
  };
  Vec3 lo, hi;
  range(px, lo.x(), hi.x());
  range(py, lo.y(), hi.y());
  range(pz, lo.z(), hi.z());
  const FluidParams& fp = scene_.params.fluid;
  const double volume = double(count) * fp.restVolume();
  const float default_voxel = defaultVoxelSize(scene_.params, sceneFluidVolume(), volume);
  checkControlCount(spec, count, volume, default_voxel);
  // The current shape stays in the cache (the backend still uses it) until
  // the new one is accepted.
  const TargetShape& shape = cache_.get(spec, volume, default_voxel, target_);
  checkClusterMemory(scene_.params.shape, shape.reference.size(), scene_.source);
  // Placed before any state changes: if placement throws, the simulation and
  // the backend keep the previous target, which the cache still holds.
  const Params params = withControlRadius(scene_.params, shape.grid.voxel);
  // Anchored standing on the floor at every target; placed standing on the
  // region's floor, unstretched, at a change only (placement.h, Standing).
  Standing standing = standingFor(fp.gravity);
  standing.unstretched = target_ != nullptr;
  standing.reach = params.control.radius;
  ControlSet placed =
      placeControlParticles(shape, lo, hi, params.shape, scene_.container.min, scene_.container.max,
                            adaptiveControl(params.control, shape.grid.voxel, fp.restSpacing()), standing);
  // The rest shape morphs from where the particles start into the new
  // target: at a change over `blend` fall times of the distance it moves, at
  // the first target (stretched over the picked fluid) over `blend_first`
  // fall times of the control radius.
  if (target_)
    startBlend(placed, params.shape.blend, fp.gravity);
  else
    startBlendOver(placed, params.shape.firstBlendTime(params.control.radius, fp.gravity));
  // The derived radius and shape-matching step take effect (with the radius
  // in metres and time_step_fall > 0 only the step changes, at the first target).
  if (params.control.radius != scene_.params.control.radius ||
      params.shape.time_step != scene_.params.shape.time_step) {
    scene_.params = params;
    backend_->setParams(scene_.params);
  }
  target_ = &shape;
  target_volume_ = volume;
  target_spec_ = spec;
  has_target_ = true;
  controlled_ = count;
  // The controlled fluid of the metrics: the region's fluid (by identity).
  controlled_by_id_.clear();
  if (r.kind != RegionDesc::Kind::All) {
    controlled_by_id_.assign(s.size(), 0);
    for (size_t i = 0; i < s.size(); ++i) controlled_by_id_[s.id[i]] = inRegion(i) ? 1 : 0;
  }
  backend_->setControl(std::move(placed));
  backend_->setMetricsTarget(target_);
  backend_->setControlledFluid(controlled_by_id_);
}

void Simulation::clearTarget() {
  backend_->setControl(ControlSet());
  backend_->setMetricsTarget(nullptr);
  controlled_by_id_.clear();
  backend_->setControlledFluid(controlled_by_id_);
  target_ = nullptr;
  has_target_ = false;
}

void Simulation::setRegion(const RegionDesc& region) {
  scene_.region = region;
  if (has_target_) makeTarget(target_spec_, true);
}

void Simulation::setParams(const Params& params) {
  validateParams(params, "parameters");
  if (target_) checkClusterMemory(params.shape, target_->reference.size(), "parameters");
  const Params before = scene_.params;
  scene_.params = withControlRadius(params, target_ ? target_->grid.voxel : 0.0f);
  scene_.params.fluid.setFrameStep();
  backend_->setParams(scene_.params);
  // Clusters and the adaptive radii are made when control particles are
  // placed: re-placed, so that a new cluster size, coarse level, adaptive
  // control or (with it) radius takes effect now. The radius compared is the
  // one that acts (radius_spacings may set it).
  const bool same =
      before.shape.sameClusters(scene_.params.shape) && before.control.samePlacement(scene_.params.control);
  if (target_ && !same) makeTarget(target_spec_, false);
}

Params Simulation::withControlRadius(Params params, float voxel) {
  if (voxel > 0.0f) {
    params.control.radius = params.control.radiusFor(voxel);
    params.shape.time_step = params.shape.timeStepFor(params.control.radius, params.fluid.gravity);
  }
  return params;
}

}  // namespace ff
