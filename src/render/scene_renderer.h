// scene_renderer.h - draws a FrameData with OpenGL 3.3 core: screen-space
// fluid (van der Laan et al. 2009; Green 2010) or plain particles, composited
// over a floor and the container, with the control-particle overlay (coloured
// by s_i, as in the paper's Fig. 11), the target ghost and the region box.
//
// Needs a current OpenGL 3.3 core context (a GLFW window or an EGL offscreen
// context) made current before construction and for every call.
#pragma once
#include <memory>
#include <string>

#include "render/camera.h"
#include "render/fluid_mode.h"
#include "render/frame_data.h"

namespace ff::render {

// Overlay colours (rgb, alpha), also shown in the viewer's legend.
inline constexpr float kRegionColor[4] = {1.0f, 0.55f, 0.10f, 1.0f};  // the controlled region's wireframe
inline constexpr float kGhostColor[4] = {0.95f, 0.97f, 1.0f, 0.28f};  // the target ghost
// Control particles by s_i (control_points.frag.glsl): filled, half, empty.
inline constexpr float kControlFilledColor[3] = {0.10f, 0.80f, 0.25f};
inline constexpr float kControlHalfColor[3] = {0.95f, 0.85f, 0.10f};
inline constexpr float kControlEmptyColor[3] = {0.90f, 0.12f, 0.10f};

struct RenderOptions {
  FluidMode mode = FluidMode::ScreenSpace;
  bool show_control = false;     // control particles coloured by s_i
  bool show_ghost = false;       // target shape ghost
  bool show_region = true;       // controlled-region wireframe
  bool show_container = true;    // container edges and floor
  bool show_shadow = true;       // the liquid's soft shadow on the floor
  int smoothing_iterations = 3;  // depth-smoothing passes
  float smoothing_scale = 1.0f;  // Gaussian sigma of the filter in projected particle radii
  float fluid_color[3] = {0.10f, 0.45f, 0.85f};
  float absorption = 15.0f;  // thickness -> tint (Beer-Lambert), 1/m
  // Also time each pass (a glFinish after each, which costs some overlap on a GPU).
  bool profile_passes = false;
};

// Milliseconds the GPU spent on the last draw() (glFinish-bounded CPU timing).
struct RenderTimings {
  double total_ms = 0.0;
  // With RenderOptions::profile_passes (else 0): the passes, in order.
  double background_ms = 0.0;  // floor shadow, sky, floor, walls, edges
  double depth_ms = 0.0;       // sphere depth splats
  double smoothing_ms = 0.0;   // depth smoothing
  double thickness_ms = 0.0;   // thickness splats
  double composite_ms = 0.0;   // composite (or background copy + particle spheres)
  double overlay_ms = 0.0;     // ghost, region, control particles
};

class SceneRenderer {
 public:
  // Compiles the shaders; throws ff::Error with the shader log on failure.
  SceneRenderer();
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // Draws the frame into the framebuffer `target_fbo` (0 = default) of size
  // width x height. Leaves the viewport and target framebuffer bound.
  void draw(const FrameData& frame, const OrbitCamera& camera, const RenderOptions& options, int width,
            int height, unsigned target_fbo = 0);

  const RenderTimings& timings() const { return timings_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  RenderTimings timings_;
};

}  // namespace ff::render
