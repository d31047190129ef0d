// viewer_app.cpp - `flowform view`: the GLFW window (OpenGL 3.3 core), the
// frame loop (input, panel, script, steps, render, screenshots) and the
// script player.
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "render/offscreen_context.h"
#include "viewer/script.h"
#include "viewer/view_framebuffer.h"
#include "viewer/viewer.h"
#include "viewer/viewer_ui.h"

namespace ff::viewer {

namespace {

using Clock = std::chrono::steady_clock;

std::string g_glfw_error;

void onGlfwError(int code, const char* text) {
  g_glfw_error = std::string(text ? text : "unknown error") + " (GLFW error " + std::to_string(code) + ")";
}

double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Owners of GLFW, the window and ImGui, released in reverse order on any exit.
struct GlfwLibrary {
  GlfwLibrary() {
    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit())
      throw Error("flowform view needs a display (X11): " + g_glfw_error +
                  "; use `flowform render` for offscreen frames, or run under xvfb-run");
  }
  ~GlfwLibrary() { glfwTerminate(); }
  GlfwLibrary(const GlfwLibrary&) = delete;
  GlfwLibrary& operator=(const GlfwLibrary&) = delete;
};

struct Window {
  GLFWwindow* handle = nullptr;
  Window(int width, int height, const std::string& title) {
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_DEPTH_BITS, 24);
    handle = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!handle)
      throw Error("flowform view cannot open a window with an OpenGL 3.3 core context: " + g_glfw_error);
    glfwMakeContextCurrent(handle);
    glfwSwapInterval(1);
  }
  ~Window() { glfwDestroyWindow(handle); }
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;
};

struct ImGuiRuntime {
  explicit ImGuiRuntime(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // leave no imgui.ini behind
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
  }
  ~ImGuiRuntime() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  ImGuiRuntime(const ImGuiRuntime&) = delete;
  ImGuiRuntime& operator=(const ImGuiRuntime&) = delete;
};

// The window's key and mouse hooks. Presses go to ImGui and into the viewer's queue.
// ImGui 1.86 samples key states once per frame, so a tap whose release comes
// in the same frame as its press (at a few frames per second, most taps)
// would never be seen down: such releases reach ImGui one frame late.
struct KeyHooks {
  ViewerUi* ui = nullptr;
  std::vector<int> pressed_this_frame;
  struct Release {
    int key, scancode, mods;
  };
  std::vector<Release> deferred;
  // The cursor as of the event being handled (glfwGetCursorPos would give
  // where it is now, after the events still queued).
  double cursor_x = 0.0, cursor_y = 0.0;

  // Call before polling events: the held-back releases happen now.
  void beginFrame(GLFWwindow* window) {
    std::vector<Release> now;
    now.swap(deferred);
    pressed_this_frame.clear();
    for (const Release& r : now) ImGui_ImplGlfw_KeyCallback(window, r.key, r.scancode, GLFW_RELEASE, r.mods);
  }
};

void onKey(GLFWwindow* window, int key, int scancode, int action, int mods) {
  auto* hooks = static_cast<KeyHooks*>(glfwGetWindowUserPointer(window));
  if (!hooks) return ImGui_ImplGlfw_KeyCallback(window, key, scancode, action, mods);
  if (action == GLFW_RELEASE && std::find(hooks->pressed_this_frame.begin(), hooks->pressed_this_frame.end(),
                                          key) != hooks->pressed_this_frame.end()) {
    hooks->deferred.push_back({key, scancode, mods});
    return;
  }
  ImGui_ImplGlfw_KeyCallback(window, key, scancode, action, mods);
  if (action == GLFW_PRESS) hooks->pressed_this_frame.push_back(key);
  if ((action == GLFW_PRESS || action == GLFW_REPEAT) && hooks->ui->keys.size() < 256)
    hooks->ui->keys.push_back({key, mods, action == GLFW_REPEAT});
}

void onCursorPos(GLFWwindow* window, double x, double y) {
  if (auto* hooks = static_cast<KeyHooks*>(glfwGetWindowUserPointer(window))) {
    hooks->cursor_x = x;
    hooks->cursor_y = y;
  }
}

void onMouseButton(GLFWwindow* window, int button, int action, int mods) {
  ImGui_ImplGlfw_MouseButtonCallback(window, button, action, mods);
  auto* hooks = static_cast<KeyHooks*>(glfwGetWindowUserPointer(window));
  if (hooks && action == GLFW_PRESS && button >= 0 && button < 3) {
    hooks->ui->press_x[button] = float(hooks->cursor_x);
    hooks->ui->press_y[button] = float(hooks->cursor_y);
  }
}

// The default framebuffer's back buffer (what the next swap shows) as a PNG.
void saveScreenshot(const std::string& path, int width, int height) {
  std::vector<uint8_t> pixels(size_t(width) * size_t(height) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  const GLenum err = glGetError();
  if (err != GL_NO_ERROR)
    throw Error(path + ": reading the window's pixels failed (GL error " + std::to_string(err) + ")");
  // OpenGL rows run bottom-up; PNG rows top-down. The window is opaque.
  std::vector<uint8_t> rgba(pixels.size());
  const size_t row = size_t(width) * 4;
  for (int y = 0; y < height; ++y)
    std::copy_n(pixels.begin() + long(size_t(height - 1 - y) * row), row,
                rgba.begin() + long(size_t(y) * row));
  for (size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(parent, ec);
  }
  render::writePng(path, width, height, rgba);
}

std::string nextScreenshotName() {
  for (int i = 1; i < 100000; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "flowform_%04d.png", i);
    std::error_code ec;
    if (!std::filesystem::exists(name, ec)) return name;
  }
  return "flowform_screenshot.png";
}

// What the due script actions asked of the frame being drawn.
struct FrameRequests {
  std::vector<const ScriptAction*> screenshots;
  bool quit = false;
  bool hold() const { return quit || !screenshots.empty(); }  // no steps: show the state at `at`
};

void runAction(const ScriptAction& a, ViewerUi& ui, ViewerSession& session, FrameRequests& req) {
  std::printf("flowform view: script t=%.3f s: %s\n", session.sim().time(), actionName(a.kind));
  try {
    switch (a.kind) {
      case ScriptAction::Kind::Target:
        session.chooseTarget(a.target);
        ui.chosen = -1;
        ui.frame_dirty = true;
        break;
      case ScriptAction::Kind::NoTarget:
        session.chooseNoTarget();
        ui.chosen = 0;
        ui.frame_dirty = true;
        break;
      case ScriptAction::Kind::Region:
        session.setRegion(a.region);
        ui.frame_dirty = true;
        break;
      case ScriptAction::Kind::Camera:
        applyCamera(ui.camera, a.camera);
        break;
      case ScriptAction::Kind::Params: {
        Params p = session.params();
        applyParamsAction(a, p);
        session.setParams(p);
        ui.params_error.clear();
        break;
      }
      case ScriptAction::Kind::Render:
        if (a.render.particles)
          ui.render.mode =
              *a.render.particles ? render::FluidMode::Particles : render::FluidMode::ScreenSpace;
        if (a.render.control) ui.render.show_control = *a.render.control;
        if (a.render.ghost) ui.render.show_ghost = *a.render.ghost;
        if (a.render.region) ui.render.show_region = *a.render.region;
        break;
      case ScriptAction::Kind::Panel:
        ui.show_panel = a.panel;
        break;
      case ScriptAction::Kind::Screenshot:
        req.screenshots.push_back(&a);
        break;
      case ScriptAction::Kind::Save:
        saveScene(ui, session, a.save, false);
        break;
      case ScriptAction::Kind::Pause:
        ui.playing = false;
        break;
      case ScriptAction::Kind::Play:
        ui.playing = true;
        break;
      case ScriptAction::Kind::Quit:
        req.quit = true;
        break;
    }
  } catch (const Error& e) {
    throw Error(a.where + " (" + actionName(a.kind) + "): " + e.what());
  }
}

// Steps for one frame: steps_per_frame of them (one for a single step), fewer
// when the frame budget runs out (never none) or a script action falls due.
void stepFrame(ViewerUi& ui, ViewerSession& session, const ScriptCursor* script) {
  const int want = ui.step_once ? 1 : ui.steps_per_frame;
  const auto t0 = Clock::now();
  int n = 0;
  while (n < want) {
    if (script && script->due(session.sim().time())) break;  // it runs at the start of the next frame
    const auto s0 = Clock::now();
    try {
      session.step();
    } catch (const Error& e) {
      if (script && !script->done())
        throw Error(std::string("the simulation failed while the script ran: ") + e.what());
      ui.playing = false;
      ui.report(std::string("simulation stopped: ") + e.what() + " (R resets)", true);
      break;
    }
    ++n;
    ui.step_ms.add(msSince(s0));
    try {
      ui.recording.afterStep(session.sim());
    } catch (const Error& e) {
      ui.report(std::string("recording stopped: ") + e.what(), true);
    }
    const Simulation& sim = session.sim();
    for (size_t p = 0; p < size_t(Phase::Count); ++p) ui.phase_ms[p].add(sim.lastStepMs()[p]);
    ui.iou.push(float(sim.metrics().iou));
    ui.coverage.push(float(sim.metrics().coverage));
    ui.filled.push(float(sim.metrics().filled));
    ui.stray.push(float(sim.metrics().stray));
    ui.frame_dirty = true;
    if (msSince(t0) >= double(ui.frame_budget_ms)) break;
  }
  ui.steps_last_frame = n;
  if (n > 0) ui.sim_ms_per_frame.add(msSince(t0));
}

void initUi(ViewerUi& ui, const ViewerSession& session, const ViewerOptions& options) {
  const char* mesh_path = std::getenv("FLOWFORM_MESH_PATH");
  ui.choices = targetChoices(mesh_path ? mesh_path : "");
  const ContainerDesc& c = session.scene().container;
  ui.brush_radius = 0.15f * (c.max - c.min).maxCoeff();
  ui.render.show_region = true;
  ui.edit = session.params();
  ui.recording.configure(options.record);
  // The first frame's view (window coordinates may differ on high-DPI screens;
  // C re-frames with the actual view).
  ui.view_x = int(std::min(ViewerUi::kPanelWidth, 0.5f * float(options.width)));
  ui.view_w = options.width - ui.view_x;
  ui.view_h = options.height;
  ui.camera = homeCamera(ui, session);
  if (session.scene().camera) applyCamera(ui.camera, *session.scene().camera);
  const std::string stem = std::filesystem::path(session.scene().source).stem().string();
  const std::string name = (stem.empty() || stem[0] == '<' ? session.scene().name : stem) + "_saved.json";
  std::snprintf(ui.save_path, sizeof ui.save_path, "%s", name.c_str());
}

}  // namespace

int runViewer(const SceneDesc& scene, const ViewerOptions& options) {
  if (options.width < 160 || options.height < 120 || options.width > 16384 || options.height > 16384)
    throw Error("--width/--height: the window must be between 160x120 and 16384x16384 (got " +
                std::to_string(options.width) + "x" + std::to_string(options.height) + ")");
  std::unique_ptr<ScriptCursor> script;
  if (!options.script.empty()) script = std::make_unique<ScriptCursor>(loadScript(options.script));

  GlfwLibrary glfw;
  ViewerSession session(scene, BackendChoice{options.backend, options.device, options.threads});
  if (!session.backendNote().empty()) std::printf("flowform: %s\n", session.backendNote().c_str());
  std::printf("flowform view: scene '%s' (%s), %ld fluid particles, backend %s (%s)\n", scene.name.c_str(),
              scene.source.c_str(), scene.fluidCount(), session.sim().backend().name().c_str(),
              session.sim().backend().device().c_str());

  Window window(options.width, options.height, "flowform view: " + scene.name);
  ImGuiRuntime imgui(window.handle);
  render::SceneRenderer renderer;
  auto glText = [](GLenum name) {
    const GLubyte* text = glGetString(name);
    return std::string(text ? reinterpret_cast<const char*>(text) : "unknown");
  };
  const std::string gl_renderer = glText(GL_RENDERER);
  std::printf("flowform view: OpenGL %s, %s\n", glText(GL_VERSION).c_str(), gl_renderer.c_str());

  ViewerUi ui;
  initUi(ui, session, options);
  KeyHooks hooks;
  hooks.ui = &ui;
  glfwSetWindowUserPointer(window.handle, &hooks);
  glfwSetKeyCallback(window.handle, onKey);  // these replace ImGui's callbacks, and call them
  glfwSetMouseButtonCallback(window.handle, onMouseButton);
  glfwSetCursorPosCallback(window.handle, onCursorPos);  // ImGui 1.86 polls the cursor; no callback to chain
  struct DetachHooks {
    GLFWwindow* w;
    ~DetachHooks() { glfwSetWindowUserPointer(w, nullptr); }
  } detach{window.handle};
  ViewFramebuffer view;
  auto last_frame = Clock::now();
  while (!glfwWindowShouldClose(window.handle) && !ui.quit) {
    hooks.beginFrame(window.handle);
    glfwPollEvents();
    glfwGetWindowSize(window.handle, &ui.win_w, &ui.win_h);
    glfwGetFramebufferSize(window.handle, &ui.fb_w, &ui.fb_h);
    if (ui.fb_w <= 0 || ui.fb_h <= 0 || ui.win_w <= 0 || ui.win_h <= 0) {  // minimised
      glfwWaitEventsTimeout(0.1);
      continue;
    }

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();

    // Script actions first, so that the frame drawn shows them. A screenshot
    // (or quit) ends this frame's actions: the ones after it run next frame,
    // before any step, so each screenshot shows exactly the actions before it.
    FrameRequests req;
    while (script && script->due(session.sim().time()) && !req.hold())
      runAction(script->take(), ui, session, req);
    if (script && script->done() && !req.hold()) {  // (req points into the script)
      std::printf("flowform view: script %s done; the viewer stays open\n", script->script().source.c_str());
      script.reset();
    }

    // The panel on the left, the 3D view beside it (the whole window without the panel).
    ui.view_x = ui.show_panel ? int(std::min(ViewerUi::kPanelWidth, 0.5f * float(ui.win_w))) : 0;
    ui.view_w = ui.win_w - ui.view_x;
    ui.view_h = ui.win_h;
    const float to_fb = float(ui.fb_w) / float(ui.win_w);
    const int view_fb_x = int(std::lround(float(ui.view_x) * to_fb));
    const int view_fb_w = std::max(1, ui.fb_w - view_fb_x);

    handleInput(ui, session);
    drawPanel(ui, session);
    if ((ui.reset_to_scene_request || ui.reset_request) && ui.recording.active())
      ui.report(ui.recording.stop() + " (stopped by the reset)", false);
    if (ui.reset_to_scene_request || ui.reset_request)
      resetSimulation(ui, session, !ui.reset_to_scene_request);
    if (ui.record_request) toggleRecording(ui, session);
    ui.record_request = false;
    ui.reset_request = ui.reset_to_scene_request = false;

    if (!req.hold() && (ui.playing || ui.step_once)) stepFrame(ui, session, script.get());
    ui.step_once = false;

    if (ui.frame_dirty) {
      ui.frame = render::captureFrame(session.sim());
      ui.frame_dirty = false;
    }
    view.resize(view_fb_w, ui.fb_h);
    renderer.draw(ui.frame, ui.camera, ui.render, view_fb_w, ui.fb_h, view.id());
    ui.render_timings = renderer.timings();
    ui.render_ms.add(ui.render_timings.total_ms);

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, ui.fb_w, ui.fb_h);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(0.08f, 0.08f, 0.09f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    view.blitToWindow(view_fb_x, 0);
    ImGui::Render();
    glViewport(0, 0, ui.fb_w, ui.fb_h);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

    for (const ScriptAction* shot : req.screenshots) {
      try {
        saveScreenshot(shot->screenshot, ui.fb_w, ui.fb_h);
      } catch (const Error& e) {
        throw Error(shot->where + " (screenshot): " + e.what());
      }
      std::printf("flowform view: wrote %s (%dx%d)\n", shot->screenshot.c_str(), ui.fb_w, ui.fb_h);
    }
    if (ui.screenshot_request) {
      ui.screenshot_request = false;
      const std::string path = nextScreenshotName();
      try {
        saveScreenshot(path, ui.fb_w, ui.fb_h);
        ui.report("wrote " + path, false);
      } catch (const Error& e) {
        ui.report(e.what(), true);
      }
    }
    glfwSwapBuffers(window.handle);
    ui.frame_ms.add(msSince(last_frame), 0.1);
    last_frame = Clock::now();
    if (req.quit) return 0;
  }
  return 0;
}

}  // namespace ff::viewer
