// scene.h - a scene: the container, the fluid, the parameters, the targets and
// their schedule, and the controlled region. Parsed from JSON (scene_json.cpp).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "core/params.h"
#include "core/vec3.h"
#include "target/target_shape.h"

namespace ff {

struct ContainerDesc {
  Vec3 min{0.0f, 0.0f, 0.0f};
  Vec3 max{0.3f, 0.3f, 0.3f};
};

// A block of fluid particles on a cubic lattice: dims[0] x dims[1] x dims[2]
// particles, the first one at origin + spacing/2, spacing = the rest spacing
// (cube root of mass / rest density) unless given.
struct FluidBlockDesc {
  Vec3 origin{0.0f, 0.0f, 0.0f};
  int dims[3] = {10, 10, 10};
  float spacing = 0.0f;  // 0: rest spacing
  Vec3 velocity{0.0f, 0.0f, 0.0f};
  long count() const { return long(dims[0]) * dims[1] * dims[2]; }
};

// The part of the fluid the user controls (Fig. 2, Fig. 7).
struct RegionDesc {
  enum class Kind { All, Box, Sphere } kind = Kind::All;
  Vec3 min{0.0f, 0.0f, 0.0f}, max{0.0f, 0.0f, 0.0f};  // Box
  Vec3 center{0.0f, 0.0f, 0.0f};                      // Sphere
  float radius = 0.0f;
};

// Where the viewer's camera looks from (`flowform view`; `run` ignores it).
// Every part is optional: a part not given keeps the camera that frames the
// container. Angles in degrees (yaw around +y, 0 = looking along -z; pitch
// above the horizon), distance in metres from `target`, the point orbited.
struct CameraDesc {
  std::optional<float> yaw_deg, pitch_deg, distance, fov_deg;
  std::optional<Vec3> target;
};

struct ScheduleEntry {
  double time = 0.0;  // seconds of simulated time at which this target takes over
  TargetSpec target;
};

struct SceneDesc {
  std::string name = "scene";
  std::string source;  // file it came from ("<built-in default>" for the embedded one)
  std::string preset = "paper";
  Params params;
  ContainerDesc container;
  std::vector<FluidBlockDesc> fluid;
  RegionDesc region;
  std::vector<ScheduleEntry> schedule;  // sorted by time; may be empty (no control)
  double duration = 4.0;                // default run length in seconds
  std::optional<CameraDesc> camera;     // the viewer's camera, when the file gives one

  long fluidCount() const;
};

// Parses a scene file. Mesh paths are resolved here (relative to the file,
// then FLOWFORM_MESH_PATH). Throws ff::Error "FILE: key.path: problem".
SceneDesc loadScene(const std::string& path);
// Parses scene JSON text; `source` names it in messages and `base_dir`
// anchors relative mesh paths ("" = only FLOWFORM_MESH_PATH).
SceneDesc parseScene(const std::string& json_text, const std::string& source, const std::string& base_dir);
// The built-in default scene (scenes/default.json embedded at build time).
SceneDesc defaultScene();

}  // namespace ff
