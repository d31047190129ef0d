// vertex_streams.h - vertex arrays with one buffer each, for the renderer's
// two kinds of geometry: per-instance data (particles, ghost faces) drawn as
// instanced quads, and plain vertex lists (floor, walls, lines).
#pragma once
#include <vector>

#include "render/gl_util.h"

namespace ff::render {

// 4 floats per instance: attribute 0 = all four (xyz, w), attribute 1 = w alone.
struct InstanceStream {
  gl::VertexArray vao;
  gl::Buffer vbo;
  GLsizei count = 0;

  void create();
  void upload(const std::vector<float>& data);
  // A 4-vertex triangle strip per instance (the shader places the corners
  // from gl_VertexID).
  void drawQuads() const;
};

// `floats` floats per vertex: attribute 0 = xyz, attribute 1 = a normal (when 6).
struct VertexStream {
  gl::VertexArray vao;
  gl::Buffer vbo;
  GLsizei count = 0;
  int floats = 3;

  void create(int floats_per_vertex);
  void upload(const std::vector<float>& data);
  void draw(GLenum mode) const;
};

}  // namespace ff::render
