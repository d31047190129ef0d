// cmd_view.cpp - `flowform view`: the interactive viewer (docs/VIEWER.md).
#include <omp.h>

#include <memory>
#include <string>

#include "app/commands.h"
#include "app/export_cli.h"
#include "app/kernels_option.h"
#include "core/error.h"
#include "core/resource_limits.h"
#include "viewer/viewer.h"

namespace ff::app {

namespace {

struct ViewCommandOptions {
  std::string scene;
  viewer::ViewerOptions viewer;
  std::string formats = "vtk";
};

int runView(const ViewCommandOptions& o) {
  checkThreadCount(o.viewer.threads, "--threads");
  if (o.viewer.threads > 0) omp_set_num_threads(o.viewer.threads);
  const SceneDesc scene = o.scene.empty() ? defaultScene() : loadScene(o.scene);
  viewer::ViewerOptions vo = o.viewer;
  vo.record.formats = parseExportFormats(o.formats, "--format");
  if (vo.record.dir.empty()) vo.record.dir = "flowform_recordings";
  validateExportOptions(vo.record, "--export");
  return viewer::runViewer(scene, vo);
}

}  // namespace

std::function<int()> addViewCommand(CLI::App& app) {
  auto o = std::make_shared<ViewCommandOptions>();
  CLI::App* view = app.add_subcommand(
      "view", "Interactive viewer: steer the liquid with the mouse (needs a display; docs/VIEWER.md)");
  view->add_option("scene", o->scene, "Scene file (JSON); omitted: the built-in default scene");
  view->add_option("--backend", o->viewer.backend,
                   "auto (an OpenCL GPU if there is one, else the CPU), cpu or opencl")
      ->check(CLI::IsMember({"auto", "cpu", "opencl"}));
  view->add_option("--device", o->viewer.device, "OpenCL device number, as `flowform devices` lists them");
  addKernelsOption(view);
  view->add_option("--threads", o->viewer.threads, "OpenMP threads (default: all cores)")
      ->check(CLI::NonNegativeNumber);
  view->add_option("--script", o->viewer.script,
                   "Replay timed actions from this JSON file (target, region, camera, screenshot, quit...)");
  view->add_option("--width", o->viewer.width, "Window width in pixels (default 1280)")
      ->check(CLI::Range(160, 16384));
  view->add_option("--height", o->viewer.height, "Window height in pixels (default 800)")
      ->check(CLI::Range(120, 16384));
  addExportOptions(view, o->viewer.record, o->formats, true,
                   "Folder for the recordings the E key starts and stops, each in a new take_NNN folder "
                   "(default flowform_recordings)");
  return [o] { return runView(*o); };
}

}  // namespace ff::app
