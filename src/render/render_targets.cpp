// render_targets.cpp - allocation of the screen-space fluid's textures.
#include "render/render_targets.h"

namespace ff::render {

void RenderTargets::resize(int w, int h) {
  if (shadow.id() == 0) {
    shadow.allocate(kShadowSize, kShadowSize, GL_R16F, GL_RED, GL_FLOAT, true);
    shadow_target.attach("floor shadow", {&shadow}, nullptr);
  }
  if (w == width && h == height) return;
  background_color.allocate(w, h, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, true);
  background_depth.allocate(w, h, GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, false);
  background.attach("background", {&background_color}, &background_depth);
  for (gl::Texture& t : fluid_depth) t.allocate(w, h, GL_RG32F, GL_RG, GL_FLOAT, false);
  fluid_zbuffer.allocate(w, h, GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, false);
  fluid_splat.attach("fluid depth splats", {&fluid_depth[0]}, &fluid_zbuffer);
  fluid_smooth[0].attach("fluid depth smoothing 0", {&fluid_depth[0]}, nullptr);
  fluid_smooth[1].attach("fluid depth smoothing 1", {&fluid_depth[1]}, nullptr);
  thickness.allocate(w, h, GL_R16F, GL_RED, GL_FLOAT, true);
  thickness_target.attach("fluid thickness", {&thickness}, nullptr);
  width = w;
  height = h;
}

}  // namespace ff::render
