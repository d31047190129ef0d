// viewer.h - the interactive viewer: a GLFW window with an OpenGL 3.3 core
// context, the scene renderer and a Dear ImGui control panel.
#pragma once
#include <string>

#include "io/export_options.h"
#include "scene/scene.h"

namespace ff::viewer {

struct ViewerOptions {
  std::string backend = "auto";  // auto | cpu | opencl
  int device = -1;               // OpenCL device index, -1 = default
  int threads = 0;               // OpenMP threads, 0 = default
  std::string script;            // timed actions to replay (empty: none)
  int width = 1280, height = 800;
  ExportOptions record;  // what the E key records, and where (record.dir: the folder of the takes)
};

// Runs the viewer until the window closes (or the script quits). Returns the
// process exit code. Throws ff::Error for bad input (scene, script, no display).
int runViewer(const SceneDesc& scene, const ViewerOptions& options);

}  // namespace ff::viewer
