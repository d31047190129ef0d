// viewer_session.cpp - the viewer's Simulation and the edits a reset keeps.
#include "viewer/viewer_session.h"

#include <utility>

#include "core/error.h"
#include "core/fluid_state.h"
#include "host/backend_factory.h"

namespace ff::viewer {

namespace {

std::unique_ptr<Simulation> build(SceneDesc scene, const BackendChoice& b, std::string* note) {
  scene.schedule.clear();  // the session plays the schedule itself
  return std::make_unique<Simulation>(std::move(scene), makeBackend(b.kind, b.device, b.threads, note));
}

}  // namespace

ViewerSession::ViewerSession(const SceneDesc& scene, const BackendChoice& backend)
    : scene_(scene), backend_(backend) {
  sim_ = build(scene_, backend_, &note_);
  applyDueSchedule();
}

void ViewerSession::applyDueSchedule() {
  if (!follow_schedule_) return;
  const auto& schedule = scene_.schedule;
  while (next_schedule_ < schedule.size() && schedule[next_schedule_].time <= sim_->time() + 1e-9) {
    // Move on first: a scheduled target that fails is reported once, not every step.
    const TargetSpec& spec = schedule[next_schedule_++].target;
    sim_->setTarget(spec);
    active_ = spec;
  }
}

void ViewerSession::chooseTarget(const TargetSpec& spec) {
  sim_->setTarget(spec);  // throws before changing anything when the shape cannot be built
  active_ = spec;
  follow_schedule_ = false;
  chose_none_ = false;
  chosen_ = spec;
}

void ViewerSession::chooseNoTarget() {
  sim_->clearTarget();
  follow_schedule_ = false;
  chose_none_ = true;
}

std::string ViewerSession::targetLabel() const {
  return sim_->target() ? sim_->target()->label : std::string("none");
}

void ViewerSession::setRegion(const RegionDesc& region) {
  FluidState fluid;
  sim_->backend().readFluid(fluid);
  long inside = 0;
  for (size_t i = 0; i < fluid.size(); ++i) {
    const Vec3 p(fluid.x[i], fluid.y[i], fluid.z[i]);
    if (region.kind == RegionDesc::Kind::Box)
      inside += (p.array() >= region.min.array()).all() && (p.array() <= region.max.array()).all();
    else if (region.kind == RegionDesc::Kind::Sphere)
      inside += (p - region.center).squaredNorm() <= region.radius * region.radius;
    else
      ++inside;
  }
  if (inside == 0) throw Error("the region holds no fluid particles; the region is unchanged");
  // The target is rebuilt from all the fluid inside the new region (the
  // Simulation alone would keep to the part that forms the current shape).
  const bool controlled = sim_->target() != nullptr;
  if (controlled) sim_->clearTarget();
  sim_->setRegion(region);
  if (controlled) sim_->setTarget(active_);
}

void ViewerSession::setParams(const Params& params) {
  validateParams(params, "");
  sim_->setParams(params);  // new clusters or adaptive control re-place the control particles
}

SceneDesc ViewerSession::currentScene() const {
  SceneDesc s = scene_;
  s.params = params();
  s.region = region();
  s.camera.reset();
  if (!follow_schedule_) {
    s.schedule.clear();
    if (!chose_none_) s.schedule.push_back({0.0, chosen_});
  }
  return s;
}

void ViewerSession::step() {
  applyDueSchedule();
  sim_->step();
}

std::string ViewerSession::reset(bool keep_edits) {
  SceneDesc s = scene_;
  if (keep_edits) {
    s.params = sim_->scene().params;
    s.region = sim_->scene().region;
  }
  std::string note;
  std::unique_ptr<Simulation> fresh = build(s, backend_, &note);
  sim_ = std::move(fresh);
  note_ = note;
  if (!keep_edits) {
    follow_schedule_ = true;
    chose_none_ = false;
  }
  next_schedule_ = 0;
  std::string warning;
  try {
    if (follow_schedule_)
      applyDueSchedule();
    else if (!chose_none_) {
      sim_->setTarget(chosen_);
      active_ = chosen_;
    }
  } catch (const Error& e) {
    warning = std::string("reset: the target was not applied: ") + e.what();
  }
  return warning;
}

}  // namespace ff::viewer
