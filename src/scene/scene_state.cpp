#include "scene/scene_state.h"

namespace ff {

void writeTargetState(StateWriter& w, const TargetSpec& t) {
  w.pod(t.kind);
  w.str(t.mesh), w.str(t.resolved_path);
  w.vec3(t.box_size);
  w.pod(t.torus_major), w.pod(t.torus_minor), w.pod(t.capsule_radius), w.pod(t.capsule_length);
  w.vec3(t.rotation_deg);
  w.pod(t.control_count), w.pod(t.voxel_size), w.pod(t.volume);
}

TargetSpec readTargetState(StateReader& r) {
  TargetSpec t;
  r.pod(t.kind);
  r.check(int(t.kind) >= int(TargetKind::Mesh) && int(t.kind) <= int(TargetKind::Capsule), "a target's kind");
  t.mesh = r.str(), t.resolved_path = r.str();
  t.box_size = r.vec3();
  r.pod(t.torus_major), r.pod(t.torus_minor), r.pod(t.capsule_radius), r.pod(t.capsule_length);
  t.rotation_deg = r.vec3();
  r.pod(t.control_count), r.pod(t.voxel_size), r.pod(t.volume);
  return t;
}

void writeSceneState(StateWriter& w, const SceneDesc& s) {
  w.tag("SCEN");
  w.str(s.name), w.str(s.source), w.str(s.preset);
  w.pod(s.params);
  w.vec3(s.container.min), w.vec3(s.container.max);
  w.pod(uint64_t(s.fluid.size()));
  for (const FluidBlockDesc& b : s.fluid) {
    w.vec3(b.origin);
    w.pod(b.dims), w.pod(b.spacing);
    w.vec3(b.velocity);
  }
  w.pod(s.region.kind);
  w.vec3(s.region.min), w.vec3(s.region.max), w.vec3(s.region.center);
  w.pod(s.region.radius);
  w.pod(uint64_t(s.schedule.size()));
  for (const ScheduleEntry& e : s.schedule) {
    w.pod(e.time);
    writeTargetState(w, e.target);
  }
  w.pod(s.duration);
}

SceneDesc readSceneState(StateReader& r) {
  r.tag("SCEN");
  SceneDesc s;
  s.name = r.str(), s.source = r.str(), s.preset = r.str();
  r.pod(s.params);
  s.container.min = r.vec3(), s.container.max = r.vec3();
  const uint64_t blocks = r.pod<uint64_t>();
  r.check(blocks <= 4096, "the scene has " + std::to_string(blocks) + " fluid blocks");
  for (uint64_t i = 0; i < blocks; ++i) {
    FluidBlockDesc b;
    b.origin = r.vec3();
    r.pod(b.dims), r.pod(b.spacing);
    b.velocity = r.vec3();
    r.check(b.dims[0] >= 0 && b.dims[1] >= 0 && b.dims[2] >= 0, "a fluid block's dims");
    s.fluid.push_back(b);
  }
  r.pod(s.region.kind);
  r.check(int(s.region.kind) >= 0 && int(s.region.kind) <= int(RegionDesc::Kind::Sphere),
          "the region's kind");
  s.region.min = r.vec3(), s.region.max = r.vec3(), s.region.center = r.vec3();
  r.pod(s.region.radius);
  const uint64_t entries = r.pod<uint64_t>();
  r.check(entries <= 100000, "the schedule has " + std::to_string(entries) + " entries");
  for (uint64_t i = 0; i < entries; ++i) {
    ScheduleEntry e;
    r.pod(e.time);
    e.target = readTargetState(r);
    s.schedule.push_back(e);
  }
  r.pod(s.duration);
  return s;
}

}  // namespace ff
