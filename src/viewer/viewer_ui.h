// viewer_ui.h - the state of the viewer's window shared by its parts: input
// (viewer_input.cpp), panel (viewer_panel.cpp), edits (viewer_actions.cpp)
// and the frame loop with its script player (viewer_app.cpp).
#pragma once
#include <array>
#include <deque>
#include <string>
#include <vector>

#include "core/params.h"
#include "render/camera.h"
#include "render/frame_data.h"
#include "render/scene_renderer.h"
#include "sim/backend.h"
#include "viewer/recording.h"
#include "viewer/target_catalog.h"
#include "viewer/viewer_session.h"
#include "viewer/viewer_stats.h"

namespace ff::viewer {

enum class PickMode { Camera, BoxSelect, SphereBrush };

struct ViewerUi {
  // Window: sizes in window coordinates (mouse) and framebuffer pixels. The
  // 3D view is the part right of the panel: x from view_x, view_w x view_h
  // (window coordinates); region selection works in view coordinates.
  int win_w = 0, win_h = 0, fb_w = 0, fb_h = 0;
  int view_x = 0, view_w = 0, view_h = 0;
  static constexpr float kPanelWidth = 430.0f;

  render::OrbitCamera camera;
  render::RenderOptions render;
  render::RenderTimings render_timings;  // of the last frame
  bool show_panel = true, show_help = false;

  // Running.
  bool playing = true;
  bool step_once = false;
  int steps_per_frame = 2;
  float frame_budget_ms = 40.0f;  // stop stepping in a frame after this long (at least one step)
  bool reset_request = false, reset_to_scene_request = false;
  bool quit = false;
  bool screenshot_request = false;  // interactive screenshot (P key)
  bool record_request = false;      // start / stop recording (E key, panel button)
  Recording recording;              // frames exported while recording (viewer/recording.h)

  // Key presses since the last frame, in order (GLFW key codes and modifier
  // bits; repeat: held down). Queued by the window's key callback, so that a
  // tap shorter than a frame is not lost.
  struct KeyPress {
    int key = 0, mods = 0;
    bool repeat = false;
  };
  std::vector<KeyPress> keys;
  // Where each mouse button last went down (window coordinates), recorded by
  // the window's callback: a drag starts there even when the mouse moved on
  // before the frame that sees the press.
  float press_x[3] = {0, 0, 0}, press_y[3] = {0, 0, 0};

  // Region selection.
  PickMode mode = PickMode::Camera;
  float brush_radius = 0.04f;
  int drag_button = -1;                    // mouse button of the drag in progress, -1: none
  bool drag_selects = false;               // the left drag draws a selection rectangle
  float drag_x0 = 0, drag_y0 = 0;          // where it started (view coordinates)
  float drag_last_x = 0, drag_last_y = 0;  // where the mouse was last frame
  int hover_particle = -1;                 // sphere brush: particle under the mouse

  // Targets.
  std::vector<TargetChoice> choices;
  int chosen = -1;  // index into choices of the user's pick, -1: none yet (scene schedule)
  char typed[512] = {0};
  char save_path[512] = {0};  // "Save scene..." file name (set from the scene's name at start)

  // Parameters being edited; `params_error` set: the edit was rejected and
  // the panel shows it with the message until fixed or discarded.
  Params edit;
  std::string params_error;

  // What the renderer draws; refreshed when the simulation changes.
  render::FrameData frame;
  bool frame_dirty = true;

  // Statistics.
  History iou{2000}, coverage{2000}, filled{2000}, stray{2000};
  std::array<Smoothed, size_t(Phase::Count)> phase_ms;
  Smoothed step_ms, sim_ms_per_frame, render_ms, frame_ms;
  int steps_last_frame = 0;
  // Simulation::setProfiling: every phase waits for the device, so that the
  // OpenCL backend's phases and stages (each force, the solver's solves) are
  // timed as `run --profile` times them; off, a phase's time on OpenCL is its
  // enqueueing.
  bool profile_phases = false;

  // Messages for the panel (newest last); errors also go to stderr.
  struct Message {
    std::string text;
    bool error = false;
  };
  std::deque<Message> messages;
  std::string target_error;  // last target problem, shown under the target list
  std::string region_error;

  void report(const std::string& text, bool error);
};

// viewer_actions.cpp: edits made by the keys and the panel. Each reports its
// outcome as a message; a rejected edit leaves the simulation as it was.
void pickChoice(ViewerUi& ui, ViewerSession& session, int index);
void pickTypedTarget(ViewerUi& ui, ViewerSession& session);
void applyRegion(ViewerUi& ui, ViewerSession& session, const RegionDesc& region);
void applyParams(ViewerUi& ui, ViewerSession& session, const Params& params);
void resetSimulation(ViewerUi& ui, ViewerSession& session, bool keep_edits);
void toggleMode(ViewerUi& ui, PickMode mode);
// Saves the current scene and camera (ViewerSession::currentScene) to `path`.
// An existing file is never replaced: with pick_free_name the scene goes to
// the next free name (STEM_2.json, ...) and the message says so; without,
// ff::Error is thrown (scripts). Returns the path written.
std::string saveScene(ViewerUi& ui, const ViewerSession& session, const std::string& path,
                      bool pick_free_name);
// The camera as a scene's camera block, and a camera block applied to a camera
// (parts not given stay as they are).
CameraDesc cameraDesc(const render::OrbitCamera& camera);
void applyCamera(render::OrbitCamera& camera, const CameraDesc& desc);
// Starts or stops the recording, reporting where it goes or what it wrote.
void toggleRecording(ViewerUi& ui, ViewerSession& session);
// The camera that shows the whole container in the current view (C key).
render::OrbitCamera homeCamera(const ViewerUi& ui, const ViewerSession& session);
std::string describeRegion(const RegionDesc& region);
// Selection from the current frame: the box around the fluid particles inside
// a rectangle of the view, or the sphere brush at a point of the view (view
// coordinates: pixels from the view's top-left corner).
void selectBox(ViewerUi& ui, ViewerSession& session, float x0, float y0, float x1, float y1);
void brushAt(ViewerUi& ui, ViewerSession& session, float x, float y);
int particleUnder(const ViewerUi& ui, float x, float y);

// viewer_input.cpp: mouse and keys over the 3D view, and the overlays they draw
// (rubber band, brush circle).
void handleInput(ViewerUi& ui, ViewerSession& session);

// viewer_panel.cpp: the ImGui panel and the help window.
void drawPanel(ViewerUi& ui, ViewerSession& session);

}  // namespace ff::viewer
