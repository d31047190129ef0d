// render_targets.h - the offscreen textures the screen-space fluid passes draw
// into, reallocated when the viewport size changes.
#pragma once
#include "render/gl_util.h"

namespace ff::render {

struct RenderTargets {
  static constexpr int kShadowSize = 256;  // the floor's shadow map (fixed size)

  int width = 0, height = 0;
  // Background: floor, walls and container edges (colour and window depth).
  gl::Texture background_color, background_depth;
  gl::Framebuffer background;
  // Liquid eye depth (red, 0 = none) and coverage (green, see
  // smooth_depth.frag.glsl): splatted into [0] with its own depth test,
  // smoothed back and forth between [0] and [1]; the result ends in [0].
  gl::Texture fluid_depth[2], fluid_zbuffer;
  gl::Framebuffer fluid_splat, fluid_smooth[2];
  // Summed chord lengths of the splats along each pixel's view ray.
  gl::Texture thickness;
  gl::Framebuffer thickness_target;
  // Liquid thickness along the light, over the floor.
  gl::Texture shadow;
  gl::Framebuffer shadow_target;

  // Allocates everything on the first call and the screen-sized textures
  // again whenever (width, height) differs from the last call.
  void resize(int w, int h);
};

}  // namespace ff::render
