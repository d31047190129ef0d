// scene_writer.h - writes a scene in the syntax the strict scene reader
// (scene_json.cpp, scenes/README.md) accepts, so that reading the file back
// gives the same container, fluid, parameters, region, targets and camera.
// The viewer's "Save scene..." goes through here.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "scene/scene.h"

namespace ff {

// The scene as a JSON tree, keys in the order of scenes/README.md. Parameters are written as the preset and
// the keys whose values differ from it. Numbers are written with the fewest digits that read back to the same
// float. A mesh target keeps the path as the user wrote it when that path still finds the same file from
// `base_dir` (the folder of the file being written); otherwise it gets the absolute path of the file that was
// read.
nlohmann::ordered_json sceneToJson(const SceneDesc& scene, const std::string& base_dir);

// Writes the scene to `path`, never over an existing file: when `path`
// exists, throws ff::Error "PATH: ... exists; not overwritten". The file
// appears whole or not at all.
void writeSceneFile(const SceneDesc& scene, const std::string& path);

// `path` when no file has that name; else the first free one of STEM_2.EXT,
// STEM_3.EXT, ... in the same folder.
std::string freeFileName(const std::string& path);

}  // namespace ff
