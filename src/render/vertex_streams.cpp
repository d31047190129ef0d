// vertex_streams.cpp - vertex array setup, upload and draw calls.
#include "render/vertex_streams.h"

namespace ff::render {

namespace {

void uploadFloats(const gl::Buffer& vbo, const std::vector<float>& data) {
  glBindBuffer(GL_ARRAY_BUFFER, vbo.id());
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(float)), data.data(), GL_STREAM_DRAW);
}

}  // namespace

void InstanceStream::create() {
  vao = gl::makeVertexArray();
  vbo = gl::makeBuffer();
  glBindVertexArray(vao.id());
  glBindBuffer(GL_ARRAY_BUFFER, vbo.id());
  const GLsizei stride = 4 * sizeof(float);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, stride, nullptr);
  glVertexAttribDivisor(0, 1);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(3 * sizeof(float)));
  glVertexAttribDivisor(1, 1);
  glBindVertexArray(0);
}

void InstanceStream::upload(const std::vector<float>& data) {
  uploadFloats(vbo, data);
  count = GLsizei(data.size() / 4);
}

void InstanceStream::drawQuads() const {
  if (count == 0) return;
  glBindVertexArray(vao.id());
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, count);
}

void VertexStream::create(int floats_per_vertex) {
  floats = floats_per_vertex;
  vao = gl::makeVertexArray();
  vbo = gl::makeBuffer();
  glBindVertexArray(vao.id());
  glBindBuffer(GL_ARRAY_BUFFER, vbo.id());
  const GLsizei stride = GLsizei(floats * sizeof(float));
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
  if (floats == 6) {
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(3 * sizeof(float)));
  }
  glBindVertexArray(0);
}

void VertexStream::upload(const std::vector<float>& data) {
  uploadFloats(vbo, data);
  count = GLsizei(data.size() / size_t(floats));
}

void VertexStream::draw(GLenum mode) const {
  if (count == 0) return;
  glBindVertexArray(vao.id());
  glDrawArrays(mode, 0, count);
}

}  // namespace ff::render
