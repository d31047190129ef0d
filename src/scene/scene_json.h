// scene_json.h - pieces of the strict scene reader for other files that embed
// scene syntax (the viewer's scripts). Every error is an ff::Error
// "SOURCE: PATH: problem", PATH being the key path given here.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "scene/scene.h"

namespace ff {

// Parses JSON text; duplicate keys and numbers out of range are errors naming
// their key path, syntax errors give line:column.
nlohmann::json parseJsonStrict(const std::string& text, const std::string& source);
// A target in scene syntax ("sphere", "bunny.obj", {"shape": ...}); mesh paths
// resolve against base_dir, then FLOWFORM_MESH_PATH.
TargetSpec parseTargetSpec(const nlohmann::json& j, const std::string& source, const std::string& path,
                           const std::string& base_dir);
// A region in scene syntax: "all", {"box": ...} or {"sphere": ...}.
RegionDesc parseRegionDesc(const nlohmann::json& j, const std::string& source, const std::string& path);
// A camera in scene syntax: {"yaw": deg, "pitch": deg, "distance": m,
// "fov": deg, "target": [x, y, z]}, each key optional but at least one given.
CameraDesc parseCameraDesc(const nlohmann::json& j, const std::string& source, const std::string& path);
// A "params" object in scene syntax, written over `params` (only the keys
// given). Types are checked here; ranges are validateParams' job.
void parseParamsOverlay(const nlohmann::json& j, const std::string& source, const std::string& path,
                        Params& params);

}  // namespace ff
