// view_framebuffer.h - the framebuffer the 3D view is rendered into (the part
// of the window beside the panel), copied into the window at its place.
#pragma once

namespace ff::viewer {

class ViewFramebuffer {
 public:
  ViewFramebuffer() = default;
  ~ViewFramebuffer();
  ViewFramebuffer(const ViewFramebuffer&) = delete;
  ViewFramebuffer& operator=(const ViewFramebuffer&) = delete;

  // Makes it width x height pixels (RGBA8 + depth/stencil); throws ff::Error
  // when the framebuffer is incomplete.
  void resize(int width, int height);
  unsigned id() const { return fbo_; }
  // Copies it into the window's framebuffer with its lower-left corner at (x, y).
  void blitToWindow(int x, int y) const;

 private:
  void release();
  unsigned fbo_ = 0, color_ = 0, depth_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace ff::viewer
