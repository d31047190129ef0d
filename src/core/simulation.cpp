#include "core/simulation.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "control/placement.h"
#include "core/error.h"

namespace ff {

Simulation::Simulation(SceneDesc scene, std::unique_ptr<Backend> backend)
    : scene_(std::move(scene)), backend_(std::move(backend)) {
  validateParams(scene_.params, scene_.source);
  backend_->init(scene_.params, scene_.container, makeFluid(scene_));
  applySchedule();
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
  phase_ms_[size_t(p)] += std::chrono::duration<double, std::milli>(t1 - t0).count();
  check(p);
}

void Simulation::check(Phase p) {
  if (backend_->finiteAfter(p)) return;
  std::ostringstream os;
  os << "step " << step_ << " (t = " << time_ << " s): a value became NaN or Inf in phase '" << phaseName(p)
     << "'";
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
  applySchedule();
  const FluidParams& fp = scene_.params.fluid;
  // Substeps from the CFL condition, with last step's highest density and speed.
  const int n = fp.substepsFor(metrics_.max_density, metrics_.max_speed);
  const float dt = fp.time_step / float(n);
  for (int k = 0; k < n; ++k) {
    timed(Phase::Grid, [&] { backend_->buildGrid(); });
    timed(Phase::Density, [&] { backend_->computeDensity(); });
    timed(Phase::Forces, [&] { backend_->computeForces(); });
    timed(Phase::ControlScale, [&] { backend_->computeControlScale(); });
    timed(Phase::ControlForces, [&] { backend_->applyControlForces(dt); });
    timed(Phase::Integrate, [&] { backend_->integrate(dt); });
    timed(Phase::ShapeMatching, [&] { backend_->shapeMatching(dt); });
  }
  ++step_;
  time_ += double(fp.time_step);
  timed(Phase::Metrics, [&] { metrics_ = backend_->computeMetrics(); });
  metrics_.step = step_;
  metrics_.time = time_;
  metrics_.substeps = n;
  for (double v : {metrics_.iou, metrics_.coverage, metrics_.max_speed, metrics_.density_error,
                   metrics_.kinetic_energy, metrics_.max_density})
    if (!std::isfinite(v))
      throw Error("step " + std::to_string(step_) + ": a metric became NaN or Inf in phase 'metrics'");
}

void Simulation::setTarget(const TargetSpec& spec) {
  FluidState s;
  backend_->readFluid(s);
  const RegionDesc& r = scene_.region;
  Vec3 lo(1e30f, 1e30f, 1e30f), hi(-1e30f, -1e30f, -1e30f);
  long count = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    Vec3 p(s.x[i], s.y[i], s.z[i]);
    bool in = true;
    if (r.kind == RegionDesc::Kind::Box)
      in = (p.array() >= r.min.array()).all() && (p.array() <= r.max.array()).all();
    else if (r.kind == RegionDesc::Kind::Sphere)
      in = (p - r.center).squaredNorm() <= r.radius * r.radius;
    if (!in) continue;
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    ++count;
  }
  if (count == 0) throw Error(scene_.source + ": region: the controlled region holds no fluid particles");
  const FluidParams& fp = scene_.params.fluid;
  const double volume = double(count) * fp.restVolume();
  const float default_voxel = 1.55f * fp.restSpacing();
  target_ = &cache_.get(spec, volume, default_voxel);
  target_spec_ = spec;
  has_target_ = true;
  controlled_ = count;
  backend_->setControl(placeControlParticles(*target_, lo, hi, scene_.params.shape, scene_.container.min,
                                             scene_.container.max));
  backend_->setMetricsTarget(target_);
}

void Simulation::clearTarget() {
  backend_->setControl(ControlSet());
  backend_->setMetricsTarget(nullptr);
  target_ = nullptr;
  has_target_ = false;
}

void Simulation::setRegion(const RegionDesc& region) {
  scene_.region = region;
  if (has_target_) setTarget(target_spec_);
}

void Simulation::setParams(const Params& params) {
  validateParams(params, "parameters");
  scene_.params = params;
  backend_->setParams(params);
}

}  // namespace ff
