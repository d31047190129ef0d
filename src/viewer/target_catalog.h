// target_catalog.h - the viewer's target list: "No control", the built-in
// shapes and every mesh file in the folders of FLOWFORM_MESH_PATH; and the
// typed-target field's reader.
#pragma once
#include <string>
#include <vector>

#include "target/target_shape.h"

namespace ff::viewer {

struct TargetChoice {
  std::string label;  // "No control", "sphere", "bunny.obj" (with its folder when the name repeats)
  bool none = false;  // the "No control" entry
  TargetSpec spec;
};

// Mesh files (.obj .ply .stl .off, any letter case) directly inside the
// colon-separated folders of `mesh_path`, folder by folder, each folder sorted
// by name. Missing or unreadable folders are skipped.
std::vector<std::string> meshFilesOnPath(const std::string& mesh_path);

// "No control", sphere, box, torus, capsule, then the meshes of meshFilesOnPath.
std::vector<TargetChoice> targetChoices(const std::string& mesh_path);

// The typed-target field: a built-in name, a mesh path (relative to the current
// directory, then FLOWFORM_MESH_PATH) or a target object in scene syntax
// ({"shape": "box", "size": [2, 1, 1]}). Throws ff::Error saying what is wrong.
TargetSpec parseTypedTarget(const std::string& text);

}  // namespace ff::viewer
