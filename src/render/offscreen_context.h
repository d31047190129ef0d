// offscreen_context.h - an OpenGL 3.3 core context with no window and no X
// server (EGL, surfaceless Mesa platform: llvmpipe on a machine without a GPU),
// rendering into its own framebuffer object.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace ff::render {

class OffscreenContext {
 public:
  // Creates the context and a width x height RGBA8 + depth framebuffer and
  // makes it current. Throws ff::Error saying what EGL or GL refused.
  OffscreenContext(int width, int height);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  int width() const;
  int height() const;
  unsigned framebuffer() const;  // the FBO to pass to SceneRenderer::draw
  std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"

  // The framebuffer's pixels, RGBA8, top row first.
  std::vector<uint8_t> readPixels() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes RGBA8 pixels (top row first) as a PNG (stb_image_write from libstb).
// Throws ff::Error naming the file when it cannot be written.
void writePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba);

}  // namespace ff::render
