// viewer_actions.cpp - the edits the keys, the panel and scripts make: target
// picks, region selection, parameters, reset. Problems become messages in the
// panel (and on stderr); the simulation keeps running.
#include <algorithm>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "scene/scene_writer.h"
#include "viewer/region_pick.h"
#include "viewer/viewer_ui.h"

namespace ff::viewer {

namespace {

constexpr float kPi = 3.14159265358979f;

std::string fmt3(const Vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%.3f, %.3f, %.3f]", double(v.x()), double(v.y()), double(v.z()));
  return buf;
}

}  // namespace

void ViewerUi::report(const std::string& text, bool error) {
  std::fprintf(error ? stderr : stdout, "flowform view: %s%s\n", error ? "error: " : "", text.c_str());
  messages.push_back({text, error});
  while (messages.size() > 8) messages.pop_front();
}

std::string describeRegion(const RegionDesc& r) {
  switch (r.kind) {
    case RegionDesc::Kind::All:
      return "all fluid";
    case RegionDesc::Kind::Box:
      return "box " + fmt3(r.min) + " - " + fmt3(r.max);
    case RegionDesc::Kind::Sphere: {
      char buf[48];
      std::snprintf(buf, sizeof buf, ", r %.3f", double(r.radius));
      return "sphere " + fmt3(r.center) + buf;
    }
  }
  return "?";
}

void pickChoice(ViewerUi& ui, ViewerSession& session, int index) {
  if (index < 0 || index >= int(ui.choices.size())) return;
  const TargetChoice& c = ui.choices[size_t(index)];
  try {
    if (c.none)
      session.chooseNoTarget();
    else
      session.chooseTarget(c.spec);
    ui.chosen = index;
    ui.target_error.clear();
    ui.frame_dirty = true;
    ui.report("target: " + session.targetLabel(), false);
  } catch (const Error& e) {
    ui.target_error = std::string(c.label) + ": " + e.what();
    ui.report(ui.target_error, true);
  }
}

void pickTypedTarget(ViewerUi& ui, ViewerSession& session) {
  try {
    const TargetSpec spec = parseTypedTarget(ui.typed);
    session.chooseTarget(spec);
    ui.chosen = -1;
    ui.target_error.clear();
    ui.frame_dirty = true;
    ui.report("target: " + session.targetLabel(), false);
  } catch (const Error& e) {
    ui.target_error = e.what();
    ui.report(ui.target_error, true);
  }
}

void toggleRecording(ViewerUi& ui, ViewerSession& session) {
  if (ui.recording.active()) return ui.report(ui.recording.stop(), false);
  try {
    const std::string folder = ui.recording.start(session.sim());
    ui.report("recording into " + folder + " (E stops)", false);
  } catch (const Error& e) {
    ui.report(std::string("cannot record: ") + e.what(), true);
  }
}

void applyRegion(ViewerUi& ui, ViewerSession& session, const RegionDesc& region) {
  try {
    session.setRegion(region);
    ui.region_error.clear();
    ui.frame_dirty = true;
    ui.report("region: " + describeRegion(region), false);
  } catch (const Error& e) {
    ui.region_error = e.what();
    ui.report(ui.region_error, true);
  }
}

void applyParams(ViewerUi& ui, ViewerSession& session, const Params& params) {
  try {
    session.setParams(params);
    ui.params_error.clear();
  } catch (const Error& e) {
    ui.params_error = std::string("not applied: ") + e.what();
    ui.report(ui.params_error, true);
  }
}

void resetSimulation(ViewerUi& ui, ViewerSession& session, bool keep_edits) {
  try {
    const std::string warning = session.reset(keep_edits);
    if (!keep_edits) ui.chosen = -1;
    ui.iou.clear();
    ui.coverage.clear();
    ui.filled.clear();
    ui.stray.clear();
    ui.params_error.clear();
    ui.frame_dirty = true;
    ui.report(keep_edits ? "reset (edits kept)" : "reset to the scene as loaded", false);
    if (!warning.empty()) ui.report(warning, true);
  } catch (const Error& e) {
    ui.report(std::string("reset failed: ") + e.what(), true);
  }
}

void toggleMode(ViewerUi& ui, PickMode mode) {
  ui.mode = ui.mode == mode ? PickMode::Camera : mode;
  ui.drag_button = -1;
  ui.hover_particle = -1;
}

CameraDesc cameraDesc(const render::OrbitCamera& camera) {
  CameraDesc d;
  d.yaw_deg = camera.yaw * 180.0f / kPi;
  d.pitch_deg = camera.pitch * 180.0f / kPi;
  d.distance = camera.distance;
  d.fov_deg = camera.fov_y_deg;
  d.target = camera.target;
  return d;
}

void applyCamera(render::OrbitCamera& camera, const CameraDesc& desc) {
  if (desc.yaw_deg) camera.yaw = *desc.yaw_deg * kPi / 180.0f;
  if (desc.pitch_deg) camera.pitch = *desc.pitch_deg * kPi / 180.0f;
  if (desc.distance) camera.distance = *desc.distance;
  if (desc.fov_deg) camera.fov_y_deg = *desc.fov_deg;
  if (desc.target) camera.target = *desc.target;
}

std::string saveScene(ViewerUi& ui, const ViewerSession& session, const std::string& path,
                      bool pick_free_name) {
  if (path.empty()) throw Error("save scene: no file name given");
  SceneDesc scene = session.currentScene();
  scene.camera = cameraDesc(ui.camera);
  const std::string target = pick_free_name ? freeFileName(path) : path;
  writeSceneFile(scene, target);
  if (target != path)
    ui.report(path + " exists and was left alone; the scene was saved as " + target, false);
  else
    ui.report("scene saved to " + target, false);
  return target;
}

render::OrbitCamera homeCamera(const ViewerUi& ui, const ViewerSession& session) {
  const ContainerDesc& c = session.scene().container;
  render::OrbitCamera cam = render::OrbitCamera::framing(c.min, c.max);
  // framing() fits the container's bounding sphere vertically; a view narrower
  // than it is tall needs the horizontal field of view to fit it instead.
  const float aspect = float(std::max(ui.view_w, 1)) / float(std::max(ui.view_h, 1));
  if (aspect < 1.0f) cam.distance /= aspect;
  return cam;
}

void selectBox(ViewerUi& ui, ViewerSession& session, float x0, float y0, float x1, float y1) {
  const render::FrameData& f = ui.frame;
  const std::vector<int> chosen =
      particlesInRect(ui.camera, ui.view_w, ui.view_h, f.x, f.y, f.z, {x0, y0, x1, y1});
  if (chosen.empty()) {
    ui.region_error = "no fluid particle inside the rectangle; the region is unchanged";
    ui.report(ui.region_error, true);
    return;
  }
  // Grow the box by half a particle spacing so that the particles on its
  // faces are safely inside.
  const float pad = 0.5f * session.params().fluid.restSpacing();
  applyRegion(ui, session, boxAroundParticles(f.x, f.y, f.z, chosen, pad));
}

int particleUnder(const ViewerUi& ui, float x, float y) {
  Vec3 origin, dir;
  ui.camera.ray(x - 0.5f, y - 0.5f, ui.view_w, ui.view_h, origin, dir);
  const render::FrameData& f = ui.frame;
  return pickParticleOnRay(origin, dir, f.x, f.y, f.z, 1.5f * f.particle_radius);
}

void brushAt(ViewerUi& ui, ViewerSession& session, float x, float y) {
  const int hit = particleUnder(ui, x, y);
  if (hit < 0) {
    ui.region_error = "the brush is not over the fluid; the region is unchanged";
    ui.report(ui.region_error, true);
    return;
  }
  const size_t i = size_t(hit);
  applyRegion(ui, session, sphereRegion(Vec3(ui.frame.x[i], ui.frame.y[i], ui.frame.z[i]), ui.brush_radius));
}

}  // namespace ff::viewer
