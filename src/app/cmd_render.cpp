// cmd_render.cpp - `flowform render`: runs a scene and writes PNG frames drawn
// offscreen (EGL, no X server), optionally joined into a video by ffmpeg.
#include <omp.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/export_cli.h"
#include "app/kernels_option.h"
#include "app/progress.h"
#include "core/error.h"
#include "core/resource_limits.h"
#include "host/backend_factory.h"
#include "render/camera.h"
#include "render/frame_data.h"
#include "render/offscreen_context.h"
#include "render/scene_renderer.h"
#include "sim/export_frame.h"
#include "sim/simulation.h"

extern char** environ;

namespace ff::app {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr int kMinSize = 16, kMaxSize = 8192;

struct RenderCmdOptions {
  std::string scene;
  long frames = 0;
  std::string out;
  int width = 1280, height = 720;
  long every = 0;
  bool every_given = false;  // else from --fps
  double fps = 30.0;
  double start = 0.0;
  std::string backend = "auto";
  int device = -1;
  int threads = 0;
  std::string mode = "fluid";
  bool control = false, ghost = false, no_region = false, profile = false;
  int smoothing = 0;
  bool smoothing_given = false;  // else the renderer's default
  std::string camera;
  std::string video;
  ExportOptions exports;  // with exports.dir: every rendered frame is also exported
  std::string formats = "vtk";
};

// "yaw,pitch,distance[,x,y,z]": degrees, degrees, metres, and the point
// looked at (default: the container's framing). Returns whether a point was given.
bool parseCamera(const std::string& text, render::OrbitCamera& cam) {
  const std::string usage = "--camera '" + text +
                            "': expected yaw,pitch,distance or yaw,pitch,distance,x,y,z (degrees, degrees, "
                            "metres, a point in metres), e.g. 35,25,0.8";
  std::vector<float> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const float x = std::strtof(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(x)) throw Error(usage);
    v.push_back(x);
  }
  if ((v.size() != 3 && v.size() != 6) || text.empty() || text.back() == ',') throw Error(usage);
  if (std::abs(v[1]) >= 89.0f) throw Error(usage + " (the pitch must lie strictly between -89 and 89)");
  if (!(v[2] > 0.0f) || v[2] > 0.5f * cam.z_far)
    throw Error(usage + " (the distance must be above 0 and at most " +
                std::to_string(int(0.5f * cam.z_far)) + " m)");
  cam.yaw = v[0] * kPi / 180.0f;
  cam.pitch = v[1] * kPi / 180.0f;
  cam.distance = v[2];
  if (v.size() == 6) cam.target = Vec3(v[3], v[4], v[5]);
  return v.size() == 6;
}

// The full path of an executable `name` on PATH, or "" when there is none.
std::string findOnPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::stringstream ss(path);
  std::string dir;
  while (std::getline(ss, dir, ':')) {
    const std::string candidate = (dir.empty() ? std::string(".") : dir) + "/" + name;
    struct stat st {};
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
  }
  return "";
}

// Creates `dir` (and its parents) and checks that files can be written in it.
void prepareOutputFolder(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw Error("--out " + dir + ": exists and is not a folder");
  fs::create_directories(dir, ec);
  if (ec) throw Error("--out " + dir + ": cannot create the output folder: " + ec.message());
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw Error("--out " + dir + ": no permission to write files in this folder");
}

// Runs ffmpeg on the frames; throws ff::Error when it cannot start or fails.
void makeVideo(const std::string& ffmpeg, const std::string& dir, double fps, const std::string& video) {
  char rate[32];
  std::snprintf(rate, sizeof(rate), "%g", fps);
  const std::string pattern = dir + "/frame_%05d.png";
  std::vector<std::string> args = {ffmpeg,       "-hide_banner", "-loglevel", "error", "-y",
                                   "-framerate", rate,           "-i",        pattern, "-pix_fmt",
                                   "yuv420p",    "-c:v",         "libx264",   video};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::printf("flowform: making %s with %s\n", video.c_str(), ffmpeg.c_str());
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, ffmpeg.c_str(), nullptr, nullptr, argv.data(), environ);
  if (rc != 0)
    throw Error("--video " + video + ": cannot start " + ffmpeg + ": " + std::strerror(rc) +
                " (the PNG frames are in " + dir + ")");
  int status = 0;
  if (waitpid(pid, &status, 0) < 0)
    throw Error("--video " + video + ": lost track of ffmpeg (the PNG frames are in " + dir + ")");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string how = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                              : "killed by signal " + std::to_string(WTERMSIG(status));
    throw Error("--video " + video + ": ffmpeg failed (" + how +
                ", its messages are above); the PNG frames are in " + dir);
  }
}

double msSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

int renderScene(const RenderCmdOptions& o) {
  // Every argument is checked before any work is done.
  if (o.frames < 1) throw Error("--frames: must be at least 1 (got " + std::to_string(o.frames) + ")");
  if (o.out.empty()) throw Error("--out: the output folder is missing");
  for (auto [name, v] : {std::pair<const char*, int>{"--width", o.width}, {"--height", o.height}})
    if (v < kMinSize || v > kMaxSize)
      throw Error(std::string(name) + ": must be between " + std::to_string(kMinSize) + " and " +
                  std::to_string(kMaxSize) + " pixels (got " + std::to_string(v) + ")");
  if (!(o.fps > 0.0) || !std::isfinite(o.fps) || o.fps > 1000.0)
    throw Error("--fps: must be a number above 0 and at most 1000");
  if (o.every_given && o.every < 1)
    throw Error("--every: must be at least 1 step (got " + std::to_string(o.every) + ")");
  if (!(o.start >= 0.0) || !std::isfinite(o.start)) throw Error("--start: must be 0 or more seconds");
  checkThreadCount(o.threads, "--threads");
  if (o.smoothing_given && (o.smoothing < 0 || o.smoothing > 64))
    throw Error("--smoothing: must be between 0 and 64 iterations (got " + std::to_string(o.smoothing) + ")");
  if (!render::fluidModeByName(o.mode))
    throw Error("--mode: '" + o.mode + "' is not one of fluid (or screen_space), particles");
  render::OrbitCamera camera;
  bool camera_target = false;  // checked now, applied once the scene is known
  if (!o.camera.empty()) camera_target = parseCamera(o.camera, camera);
  std::string ffmpeg;
  if (!o.video.empty()) {
    if (o.width % 2 || o.height % 2)
      throw Error("--video: H.264 in yuv420p needs an even width and height (got " + std::to_string(o.width) +
                  "x" + std::to_string(o.height) + ")");
    const std::filesystem::path parent = std::filesystem::absolute(o.video).parent_path();
    if (::access(parent.c_str(), W_OK | X_OK) != 0)
      throw Error("--video " + o.video + ": cannot write into the folder " + parent.string() + ": " +
                  std::strerror(errno));
    ffmpeg = findOnPath("ffmpeg");
    if (ffmpeg.empty())
      throw Error(
          "--video needs ffmpeg; install it with apt-get install ffmpeg, or drop --video to keep the "
          "PNG frames");
  }
  prepareOutputFolder(o.out);

  if (o.threads > 0) omp_set_num_threads(o.threads);
  SceneDesc scene = o.scene.empty() ? defaultScene() : loadScene(o.scene);
  const double dt = scene.params.fluid.frameStep();
  const long every = o.every_given ? o.every : std::max(1L, long(std::lround(1.0 / (o.fps * dt))));
  const long start_steps = o.start > 0.0 ? runSteps(o.start, dt, "--start") : 0;

  std::string note;
  auto backend = makeBackend(o.backend, o.device, o.threads, &note);
  if (!note.empty()) std::printf("flowform: %s\n", note.c_str());
  Simulation sim(scene, std::move(backend));
  std::unique_ptr<FrameExporter> exporter;
  if (!o.exports.dir.empty()) {
    ExportOptions eo = o.exports;
    eo.formats = parseExportFormats(o.formats, "--format");
    exporter = std::make_unique<FrameExporter>(eo);
  }

  render::OffscreenContext context(o.width, o.height);
  render::SceneRenderer renderer;
  const render::OrbitCamera framing = render::OrbitCamera::framing(scene.container.min, scene.container.max);
  if (o.camera.empty()) {
    camera = framing;
  } else {
    const render::OrbitCamera chosen = camera;
    camera = framing;
    camera.yaw = chosen.yaw, camera.pitch = chosen.pitch, camera.distance = chosen.distance;
    if (camera_target) camera.target = chosen.target;
  }
  render::RenderOptions ro;
  ro.mode = *render::fluidModeByName(o.mode);
  ro.show_control = o.control;
  ro.show_ghost = o.ghost;
  ro.show_region = !o.no_region;
  if (o.smoothing_given) ro.smoothing_iterations = o.smoothing;
  ro.profile_passes = o.profile;

  std::printf(
      "flowform: scene '%s' (%s), %zu fluid particles, backend %s (%s); %ld frame(s) of %dx%d, %ld step(s) "
      "(%.4g s) apart, from t = %.3f s; renderer %s\n",
      scene.name.c_str(), scene.source.c_str(), size_t(scene.fluidCount()), sim.backend().name().c_str(),
      sim.backend().device().c_str(), o.frames, o.width, o.height, every, double(every) * dt,
      double(start_steps) * dt, context.renderer().c_str());

  // One progress line over every step: the lead-in to --start, then the frames.
  Progress progress("  render", start_steps + (o.frames - 1) * every, dt, sim.time());
  long steps_done = 0;
  if (start_steps > 0) {
    const auto t = std::chrono::steady_clock::now();
    for (long s = 0; s < start_steps; ++s) {
      sim.step();
      progress.update(++steps_done, sim.time());
    }
    progress.interrupt();
    std::printf("  simulated to t = %.3f s before the first frame (%.1f s)\n", sim.time(),
                msSince(t) / 1000.0);
  }

  const auto t_all = std::chrono::steady_clock::now();
  double sim_total = 0.0, draw_total = 0.0, draw_after_first = 0.0, write_total = 0.0;
  render::RenderTimings passes;  // summed over frames 2.. (with --profile)
  long sim_frames = 0;
  for (long f = 0; f < o.frames; ++f) {
    const auto t_frame = std::chrono::steady_clock::now();
    double sim_ms = 0.0;
    if (f > 0) {
      for (long s = 0; s < every; ++s) {
        sim.step();
        progress.update(++steps_done, sim.time());
      }
      sim_ms = msSince(t_frame);
      sim_total += sim_ms;
      ++sim_frames;
    }
    const render::FrameData frame = render::captureFrame(sim);
    if (exporter) exportFrameNow(sim, *exporter);
    renderer.draw(frame, camera, ro, o.width, o.height, context.framebuffer());
    const double draw_ms = renderer.timings().total_ms;
    draw_total += draw_ms;
    if (f > 0) {
      const render::RenderTimings& t = renderer.timings();
      draw_after_first += draw_ms;
      passes.background_ms += t.background_ms, passes.depth_ms += t.depth_ms;
      passes.smoothing_ms += t.smoothing_ms, passes.thickness_ms += t.thickness_ms;
      passes.composite_ms += t.composite_ms, passes.overlay_ms += t.overlay_ms;
    }
    const auto t_write = std::chrono::steady_clock::now();
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%05ld.png", f);
    render::writePng(o.out + "/" + name, o.width, o.height, context.readPixels());
    const double write_ms = msSince(t_write);
    write_total += write_ms;
    const double elapsed = msSince(t_all) / 1000.0;
    const double eta = elapsed / double(f + 1) * double(o.frames - f - 1);
    progress.interrupt();
    std::printf("  frame %ld/%ld  t=%.3f s  sim %.1f ms  render %.1f ms (+%.1f ms read+PNG)  ETA %s\n", f + 1,
                o.frames, sim.time(), sim_ms, draw_ms, write_ms, clockText(eta).c_str());
  }

  progress.finish(steps_done, sim.time());
  std::printf("summary: %ld frame(s) of %dx%d in %.1f s, %zu fluid particles\n", o.frames, o.width, o.height,
              msSince(t_all) / 1000.0, size_t(scene.fluidCount()));
  if (sim_frames > 0)
    std::printf("  simulation: %.1f ms per frame (%ld steps of %.4g s each)\n",
                sim_total / double(sim_frames), every, dt);
  if (o.frames > 1)
    std::printf(
        "  render:     %.1f ms per frame (frames 2..%ld; the first, with shader compilation, took %.1f ms)\n",
        draw_after_first / double(o.frames - 1), o.frames, draw_total - draw_after_first);
  else
    std::printf("  render:     %.1f ms (one frame, shader compilation included)\n", draw_total);
  if (o.profile && o.frames > 1) {
    const double n = double(o.frames - 1);
    std::printf(
        "  render passes (ms per frame, frames 2..%ld): background %.1f, depth splats %.1f, smoothing %.1f, "
        "thickness %.1f, composite %.1f, overlays %.1f\n",
        o.frames, passes.background_ms / n, passes.depth_ms / n, passes.smoothing_ms / n,
        passes.thickness_ms / n, passes.composite_ms / n, passes.overlay_ms / n);
  }
  std::printf("  read-back and PNG: %.1f ms per frame\n", write_total / double(o.frames));
  std::printf("  GL renderer: %s\n", context.renderer().c_str());
  std::printf("  frames in %s/frame_00000.png .. frame_%05ld.png\n", o.out.c_str(), o.frames - 1);
  if (exporter)
    std::printf("  exported %ld frames (%s%s) into %s: %s\n", exporter->frames(), o.formats.c_str(),
                o.exports.surface.enabled ? ", surface" : "", o.exports.dir.c_str(),
                exporter->costReport().c_str());

  if (!o.video.empty()) {
    makeVideo(ffmpeg, o.out, o.fps, o.video);
    std::printf("flowform: wrote %s\n", o.video.c_str());
  }
  return 0;
}

}  // namespace

std::function<int()> addRenderCommand(CLI::App& app) {
  auto o = std::make_shared<RenderCmdOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Run a scene and write PNG frames rendered offscreen (no window or X server needed). Writes "
      "OUT/frame_00000.png, frame_00001.png, ... and overwrites files of those names.");
  cmd->add_option("scene", o->scene, "Scene file (JSON); omitted: the built-in default scene");
  cmd->add_option("--frames", o->frames, "Number of frames to write (required)")->required();
  cmd->add_option("--out", o->out, "Folder for the frames (created if missing) (required)")->required();
  cmd->add_option("--width", o->width, "Image width in pixels (16..8192)")->capture_default_str();
  cmd->add_option("--height", o->height, "Image height in pixels (16..8192)")->capture_default_str();
  CLI::Option* every =
      cmd->add_option("--every", o->every,
                      "Simulation steps between frames (default: as many as make 1/FPS seconds, e.g. 8 steps "
                      "of 4 ms at 30 fps, so the video plays at about real time)");
  cmd->add_option("--fps", o->fps, "Frame rate of --video, which also sets the default --every")
      ->capture_default_str();
  cmd->add_option("--start", o->start, "Simulated seconds to run before the first frame")
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "OpenMP threads (default: all cores)");
  cmd->add_option("--backend", o->backend,
                  "auto (an OpenCL GPU if there is one, else the CPU), cpu or opencl")
      ->check(CLI::IsMember({"auto", "cpu", "opencl"}));
  cmd->add_option("--device", o->device, "OpenCL device number, as `flowform devices` lists them");
  addKernelsOption(cmd);
  cmd->add_option("--mode", o->mode,
                  "fluid (screen-space liquid surface; also screen_space, as in viewer scripts) or particles "
                  "(plain spheres)")
      ->capture_default_str();
  cmd->add_flag("--control", o->control,
                "Show the control particles, coloured by s_i (green filled .. red empty)");
  cmd->add_flag("--ghost", o->ghost, "Show the target shape as a translucent ghost");
  cmd->add_flag("--no-region", o->no_region, "Hide the controlled region's wireframe");
  CLI::Option* smoothing =
      cmd->add_option("--smoothing", o->smoothing, "Depth-smoothing iterations (default 3; 0 = none)");
  cmd->add_option("--camera", o->camera,
                  "yaw,pitch,distance[,x,y,z]: the orbit angles in degrees, the distance in metres and "
                  "the point looked at (default: the container's middle; without --camera, a view of the "
                  "whole container)");
  cmd->add_flag("--profile", o->profile,
                "Also time each render pass (with a glFinish after each) and print the means");
  cmd->add_option("--video", o->video, "Also join the frames into this video (needs ffmpeg on PATH)");
  addExportOptions(cmd, o->exports, o->formats, false,
                   "Also export every rendered frame into this folder, as `flowform run --export` does "
                   "(refused if it holds another run's frames, see --overwrite)");
  return [o, smoothing, every] {
    o->smoothing_given = smoothing->count() > 0;
    o->every_given = every->count() > 0;
    return renderScene(*o);
  };
}

}  // namespace ff::app
