// scene_renderer.cpp - the passes of a frame:
//   1. floor shadow: the liquid splatted along the light into a map over the floor;
//   2. background: sky, floor, the container's far walls and its edges (colour + depth);
//   3. liquid (screen-space mode): sphere depth splats, bilateral smoothing,
//      additive thickness splats;
//   4. into the target: the composite (normals from depth, Fresnel, refraction
//      with Beer-Lambert tint, sky reflection, specular), or the background
//      and lit sphere impostors in particle mode;
//   5. overlays: the target ghost, the region wireframe, the control particles.
// docs/RENDERING.md describes each pass.
#include "render/scene_renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "render/gl_util.h"
#include "render/render_targets.h"
#include "render/scene_geometry.h"
#include "render/vertex_streams.h"

namespace ff::render {

namespace {

// Unit vector towards the light, world space: high, behind the default view's
// left shoulder, so the liquid's shadow falls towards the viewer.
const Vec3 kLightWorld = Vec3(-0.45f, 1.0f, -0.30f).normalized();
// How much liquid darkens the floor under it, at most.
constexpr float kShadowStrength = 0.45f;
// Refraction: uv offset per metre of thickness per unit of normal tilt, and
// the thickness beyond which it stops growing.
constexpr float kRefraction = 0.6f;
constexpr float kMaxRefractionThickness = 0.08f;
// Taps on each side of a smoothing pass, at most (bounds the cost when the
// camera is very close).
constexpr int kMaxSmoothingHalfWidth = 24;
// Widest gap between liquid pixels the smoothing closes, in taps on each side
// (the shader closes gaps up to a particle diameter; this bounds the search).
constexpr int kMaxGapTaps = 16;
// Colours (rgb, alpha).
constexpr float kWallColor[4] = {0.80f, 0.88f, 0.96f, 0.10f};
constexpr float kEdgeColor[4] = {0.30f, 0.33f, 0.38f, 1.0f};

// What every pass needs to know about the frame's camera and viewport.
struct FrameView {
  int width = 0, height = 0;
  Mat4 view, proj, view_proj;
  Eigen::Matrix3f eye_to_world;  // rotation of the inverse view matrix
  Vec3 eye;
  Vec3 light_eye;    // kLightWorld in eye space
  float radius;      // particle radius, m
  float extent;      // the container's largest side, m
  float line_width;  // pixels

  FrameView(const OrbitCamera& camera, const FrameData& frame, int w, int h) : width(w), height(h) {
    view = camera.view();
    proj = camera.projection(float(w) / float(h));
    view_proj = proj * view;
    const Eigen::Matrix3f rot = view.block<3, 3>(0, 0);
    eye_to_world = rot.transpose();
    eye = camera.eye();
    light_eye = rot * kLightWorld;
    radius = std::max(frame.particle_radius, 1e-5f);
    extent = std::max((frame.container.max - frame.container.min).maxCoeff(), 1e-3f);
    line_width = std::max(1.5f, float(h) / 480.0f);
  }
  // Projected particle radius in pixels at 1 m eye depth.
  float radiusPixelsAt1m() const { return radius * proj(1, 1) * 0.5f * float(height); }
};

void setColor(const gl::Program& p, const char* uniform, const float (&c)[4]) {
  p.set(uniform, c[0], c[1], c[2], c[3]);
}

}  // namespace

struct SceneRenderer::Impl {
  gl::Program sky, floor, walls, lines, floor_shadow, fluid_depth, fluid_thickness, smooth, composite,
      copy_background, particles, control_points, ghost;
  gl::VertexArray empty;  // for the fullscreen triangle
  InstanceStream fluid, control, ghost_faces;
  VertexStream floor_mesh, wall_mesh, edge_lines, region_lines;
  RenderTargets targets;
  float shadow_rect[4] = {0, 0, 0, 0};  // xz rectangle the floor shadow map covers
  float thickness_scale = 1.0f;         // particle volume / sphere volume of this frame

  void drawFullscreen() const {
    glBindVertexArray(empty.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  void floorShadowPass(const FrameData& frame, const FrameView& v, bool enabled);
  void backgroundPass(const FrameData& frame, const FrameView& v, bool container);
  void liquidDepthPass(const FrameView& v);
  void smoothingPasses(const std::vector<float>& fluid_instances, const FrameView& v,
                       const RenderOptions& options);
  void thicknessPass(const FrameData& frame, const FrameView& v);
  void compositePass(const FrameView& v, const RenderOptions& options);
  void particlePass(const FrameView& v, const RenderOptions& options);
  void overlayPasses(const FrameData& frame, const FrameView& v, const RenderOptions& options);
};

void SceneRenderer::Impl::floorShadowPass(const FrameData& frame, const FrameView& v, bool enabled) {
  // Thickness of liquid along the light over a rectangle around the container
  // (wide enough for shadows cast from its top).
  const ContainerDesc& box = frame.container;
  const float margin = 0.5f * v.extent + (box.max.y() - box.min.y()) *
                                             std::hypot(kLightWorld.x(), kLightWorld.z()) / kLightWorld.y();
  shadow_rect[0] = box.min.x() - margin, shadow_rect[1] = box.min.z() - margin;
  shadow_rect[2] = box.max.x() + margin, shadow_rect[3] = box.max.z() + margin;
  targets.shadow_target.bind();
  glViewport(0, 0, RenderTargets::kShadowSize, RenderTargets::kShadowSize);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  if (!enabled || fluid.count == 0) return;
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  floor_shadow.use();
  floor_shadow.set("u_light_world", kLightWorld);
  floor_shadow.set("u_floor_y", box.min.y());
  floor_shadow.set("u_rect", shadow_rect[0], shadow_rect[1], shadow_rect[2], shadow_rect[3]);
  floor_shadow.set("u_radius", 2.0f * v.radius);  // twice the particle radius: a softer shadow
  fluid.drawQuads();
  glDisable(GL_BLEND);
}

void SceneRenderer::Impl::backgroundPass(const FrameData& frame, const FrameView& v, bool container) {
  const ContainerDesc& box = frame.container;
  targets.background.bind();
  glViewport(0, 0, v.width, v.height);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  sky.use();
  sky.set("u_proj", v.proj);
  sky.set("u_eye_to_world", v.eye_to_world);
  drawFullscreen();
  if (!container) return;
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);

  floor_mesh.upload(floorQuad(box, 12.0f * v.extent));
  floor.use();
  floor.set("u_view", v.view);
  floor.set("u_proj", v.proj);
  floor.set("u_tile", floorTile(box));
  floor.set("u_center", Vec3(0.5f * (box.min + box.max)));
  floor.set("u_fade_distance", 6.0f * v.extent);
  floor.set("u_eye_world", v.eye);
  floor.set("u_light_world", kLightWorld);
  floor.set("u_shadow", 0);
  floor.set("u_shadow_rect", shadow_rect[0], shadow_rect[1], shadow_rect[2], shadow_rect[3]);
  floor.set("u_shadow_strength", kShadowStrength);
  targets.shadow.bind(0);
  floor_mesh.draw(GL_TRIANGLES);

  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  wall_mesh.upload(containerWalls(box));
  walls.use();
  walls.set("u_view", v.view);
  walls.set("u_proj", v.proj);
  walls.set("u_eye_world", v.eye);
  setColor(walls, "u_color", kWallColor);
  wall_mesh.draw(GL_TRIANGLES);
  glDisable(GL_BLEND);

  edge_lines.upload(boxEdges(box.min, box.max));
  lines.use();
  lines.set("u_view", v.view);
  lines.set("u_proj", v.proj);
  lines.set("u_viewport", float(v.width), float(v.height));
  lines.set("u_width", v.line_width);
  setColor(lines, "u_color", kEdgeColor);
  edge_lines.draw(GL_LINES);
  glDisable(GL_DEPTH_TEST);
}

void SceneRenderer::Impl::liquidDepthPass(const FrameView& v) {
  targets.fluid_splat.bind();
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (fluid.count == 0) return;
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  fluid_depth.use();
  fluid_depth.set("u_view", v.view);
  fluid_depth.set("u_proj", v.proj);
  fluid_depth.set("u_radius", v.radius);
  fluid.drawQuads();
  glDisable(GL_DEPTH_TEST);
}

void SceneRenderer::Impl::smoothingPasses(const std::vector<float>& fluid_instances, const FrameView& v,
                                          const RenderOptions& options) {
  const int iterations = std::clamp(options.smoothing_iterations, 0, 64);
  const float scale = std::max(options.smoothing_scale, 0.0f);
  if (iterations == 0 || scale <= 0.0f || fluid.count == 0) return;
  targets.fluid_smooth[1].bind();  // pixels outside the scissor rectangle stay empty
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  // Only the pixels the liquid can cover (plus the filter's reach) are worth filtering.
  const PixelRect r = projectedBounds(fluid_instances, v.view_proj, v.radius, v.width, v.height, 2);
  glEnable(GL_SCISSOR_TEST);
  glScissor(r.x, r.y, r.w, r.h);
  smooth.use();
  smooth.set("u_depth", 0);
  smooth.set("u_radius_px_1m", v.radiusPixelsAt1m());
  smooth.set("u_scale", scale);
  smooth.set("u_range", 2.0f * v.radius);
  smooth.set("u_max_half_width", kMaxSmoothingHalfWidth);
  // The widest gap closed is a particle's diameter at the nearest particle.
  const float diameter_px = r.nearest > 0.0f ? 2.0f * v.radiusPixelsAt1m() / r.nearest : float(kMaxGapTaps);
  smooth.set("u_gap_taps", std::clamp(int(std::ceil(diameter_px)), 1, kMaxGapTaps));
  // Each iteration is two separable passes, [0] -> [1] -> [0]; odd iterations
  // run along the diagonals, so that the separable passes' leftovers do not
  // all line up with the pixel rows and columns.
  const float tx = 1.0f / float(v.width), ty = 1.0f / float(v.height);
  for (int it = 0; it < iterations; ++it) {
    const bool diagonal = it % 2 == 1;
    smooth.set("u_step_pixels", diagonal ? 1.41421356f : 1.0f);
    targets.fluid_smooth[1].bind();
    targets.fluid_depth[0].bind(0);
    smooth.set("u_step", tx, diagonal ? ty : 0.0f);
    drawFullscreen();
    targets.fluid_smooth[0].bind();
    targets.fluid_depth[1].bind(0);
    smooth.set("u_step", diagonal ? tx : 0.0f, diagonal ? -ty : ty);
    drawFullscreen();
  }
  glDisable(GL_SCISSOR_TEST);
}

void SceneRenderer::Impl::thicknessPass(const FrameData& frame, const FrameView& v) {
  const float sphere_volume = 4.18879f * v.radius * v.radius * v.radius;
  thickness_scale = frame.particle_volume > 0.0f ? frame.particle_volume / sphere_volume : 1.0f;
  targets.thickness_target.bind();
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  if (fluid.count == 0) return;
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  fluid_thickness.use();
  fluid_thickness.set("u_view", v.view);
  fluid_thickness.set("u_proj", v.proj);
  fluid_thickness.set("u_radius", v.radius);
  fluid_thickness.set("u_scale", thickness_scale);
  fluid.drawQuads();
  glDisable(GL_BLEND);
}

void SceneRenderer::Impl::compositePass(const FrameView& v, const RenderOptions& options) {
  composite.use();
  composite.set("u_background", 0);
  composite.set("u_background_depth", 1);
  composite.set("u_fluid_depth", 2);
  composite.set("u_thickness", 3);
  targets.background_color.bind(0);
  targets.background_depth.bind(1);
  targets.fluid_depth[0].bind(2);
  targets.thickness.bind(3);
  composite.set("u_proj", v.proj);
  composite.set("u_eye_to_world", v.eye_to_world);
  composite.set("u_texel", 1.0f / float(v.width), 1.0f / float(v.height));
  composite.set("u_fluid_color", options.fluid_color[0], options.fluid_color[1], options.fluid_color[2]);
  composite.set("u_absorption", std::max(options.absorption, 0.0f));
  composite.set("u_light_eye", v.light_eye);
  composite.set("u_refraction", kRefraction);
  composite.set("u_max_thickness", kMaxRefractionThickness);
  // A particle's volume spread over its cross-section (4/3 r, scaled like the splats).
  composite.set("u_min_thickness", 1.3333f * v.radius * thickness_scale);
  composite.set("u_occlusion_slack", 2.0f * v.radius);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_ALWAYS);  // writes every pixel's depth (liquid or background)
  drawFullscreen();
  glDepthFunc(GL_LESS);
}

void SceneRenderer::Impl::particlePass(const FrameView& v, const RenderOptions& options) {
  copy_background.use();
  copy_background.set("u_background", 0);
  copy_background.set("u_background_depth", 1);
  targets.background_color.bind(0);
  targets.background_depth.bind(1);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_ALWAYS);
  drawFullscreen();
  glDepthFunc(GL_LESS);
  if (fluid.count == 0) return;
  particles.use();
  particles.set("u_view", v.view);
  particles.set("u_proj", v.proj);
  particles.set("u_eye_to_world", v.eye_to_world);
  particles.set("u_radius", v.radius);
  particles.set("u_color", options.fluid_color[0], options.fluid_color[1], options.fluid_color[2]);
  particles.set("u_light_eye", v.light_eye);
  fluid.drawQuads();
}

void SceneRenderer::Impl::overlayPasses(const FrameData& frame, const FrameView& v,
                                        const RenderOptions& options) {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  if (options.show_ghost && !frame.ghost.empty() && frame.ghost_voxel > 0.0f) {
    ghost_faces.upload(ghostFaceInstances(frame));
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    ghost.use();
    ghost.set("u_view", v.view);
    ghost.set("u_proj", v.proj);
    ghost.set("u_rotation", frame.ghost_rotation);
    ghost.set("u_voxel", frame.ghost_voxel);
    ghost.set("u_eye_world", v.eye);
    ghost.set("u_light_world", kLightWorld);
    setColor(ghost, "u_color", kGhostColor);
    ghost_faces.drawQuads();
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
  }
  if (options.show_region) {
    region_lines.upload(regionWireframe(frame.region));
    if (region_lines.count > 0) {
      lines.use();
      lines.set("u_view", v.view);
      lines.set("u_proj", v.proj);
      lines.set("u_viewport", float(v.width), float(v.height));
      lines.set("u_width", v.line_width);
      setColor(lines, "u_color", kRegionColor);
      region_lines.draw(GL_LINES);
    }
  }
  if (options.show_control && !frame.cx.empty()) {
    // Drawn over everything else (the control particles sit inside the
    // liquid), depth-tested among themselves only.
    glClear(GL_DEPTH_BUFFER_BIT);
    control.upload(controlInstances(frame));
    control_points.use();
    control_points.set("u_view", v.view);
    control_points.set("u_proj", v.proj);
    control_points.set("u_radius", frame.ghost_voxel > 0.0f ? 0.3f * frame.ghost_voxel : 0.5f * v.radius);
    control_points.set("u_light_eye", v.light_eye);
    control.drawQuads();
  }
}

SceneRenderer::SceneRenderer() : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  const std::vector<std::string> fullscreen = {"common.glsl", "fullscreen.vert.glsl"};
  const std::vector<std::string> impostor = {"sphere_impostor.vert.glsl"};
  auto impostorFrag = [](const char* file) {
    return std::vector<std::string>{"common.glsl", "sphere_hit.glsl", file};
  };
  m.sky = gl::Program("sky", fullscreen, {"common.glsl", "sky.frag.glsl"});
  m.floor = gl::Program("floor", {"world.vert.glsl"}, {"common.glsl", "floor.frag.glsl"});
  m.walls = gl::Program("walls", {"world.vert.glsl"}, {"walls.frag.glsl"});
  m.lines = gl::Program("lines", {"lines.vert.glsl"}, {"lines.frag.glsl"}, {"lines.geom.glsl"});
  m.floor_shadow = gl::Program("floor shadow", {"floor_shadow.vert.glsl"}, {"floor_shadow.frag.glsl"});
  m.fluid_depth = gl::Program("fluid depth", impostor, impostorFrag("fluid_depth.frag.glsl"));
  m.fluid_thickness = gl::Program("fluid thickness", impostor, impostorFrag("fluid_thickness.frag.glsl"));
  m.smooth = gl::Program("depth smoothing", fullscreen, {"smooth_depth.frag.glsl"});
  m.composite = gl::Program("composite", fullscreen, {"common.glsl", "composite.frag.glsl"});
  m.copy_background = gl::Program("copy background", fullscreen, {"copy_background.frag.glsl"});
  m.particles = gl::Program("particles", impostor, impostorFrag("particles.frag.glsl"));
  m.control_points = gl::Program("control points", impostor, impostorFrag("control_points.frag.glsl"));
  m.ghost = gl::Program("ghost", {"ghost.vert.glsl"}, {"ghost.frag.glsl"});
  m.empty = gl::makeVertexArray();
  m.fluid.create();
  m.control.create();
  m.ghost_faces.create();
  m.floor_mesh.create(6);
  m.wall_mesh.create(6);
  m.edge_lines.create(3);
  m.region_lines.create(3);
  gl::checkError("SceneRenderer setup");
}

SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::draw(const FrameData& frame, const OrbitCamera& camera, const RenderOptions& options,
                         int width, int height, unsigned target_fbo) {
  const auto t0 = std::chrono::steady_clock::now();
  timings_ = RenderTimings();
  if (width <= 0 || height <= 0) return;  // a minimised window: nothing to draw
  auto last = t0;
  // Adds the time since the previous mark to `slot` (only when profiling).
  auto mark = [&](double& slot) {
    if (!options.profile_passes) return;
    glFinish();
    const auto now = std::chrono::steady_clock::now();
    slot += std::chrono::duration<double, std::milli>(now - last).count();
    last = now;
  };
  Impl& m = *impl_;
  m.targets.resize(width, height);
  const FrameView v(camera, frame, width, height);
  const std::vector<float> fluid = fluidInstances(frame);
  m.fluid.upload(fluid);

  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);

  m.floorShadowPass(frame, v, options.show_container && options.show_shadow);
  m.backgroundPass(frame, v, options.show_container);
  mark(timings_.background_ms);

  const bool screen_space = options.mode == FluidMode::ScreenSpace;
  if (screen_space) {
    m.liquidDepthPass(v);
    mark(timings_.depth_ms);
    m.smoothingPasses(fluid, v, options);
    mark(timings_.smoothing_ms);
    m.thicknessPass(frame, v);
    mark(timings_.thickness_ms);
  }

  glBindFramebuffer(GL_FRAMEBUFFER, target_fbo);
  glViewport(0, 0, width, height);
  if (screen_space)
    m.compositePass(v, options);
  else
    m.particlePass(v, options);
  mark(timings_.composite_ms);

  m.overlayPasses(frame, v, options);
  glBindVertexArray(0);
  glUseProgram(0);
  glActiveTexture(GL_TEXTURE0);
  gl::checkError("SceneRenderer::draw");
  mark(timings_.overlay_ms);
  glFinish();
  timings_.total_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace ff::render
