// gl_util.h - small RAII owners of OpenGL objects (shader programs, textures,
// framebuffers, buffers, vertex arrays) and a shader loader that reads the
// GLSL files embedded from src/render/shaders/.
//
// Every object needs the context it was created in to be current when it is
// destroyed.
#pragma once
#include <epoxy/gl.h>

#include <string>
#include <vector>

#include "render/camera.h"

namespace ff::render::gl {

// Throws ff::Error "OpenGL error in WHERE: GL_INVALID_..." if glGetError reports one.
void checkError(const char* where);

// Owns one GL name and deletes it with `Deleter` (a function of one GLuint).
template <void (*Deleter)(GLuint)>
class Handle {
 public:
  Handle() = default;
  explicit Handle(GLuint id) : id_(id) {}
  ~Handle() { reset(); }
  Handle(Handle&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = o.id_;
      o.id_ = 0;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  GLuint id() const { return id_; }
  void reset() {
    if (id_) Deleter(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

void deleteTexture(GLuint id);
void deleteFramebuffer(GLuint id);
void deleteBuffer(GLuint id);
void deleteVertexArray(GLuint id);
void deleteProgram(GLuint id);

using Buffer = Handle<deleteBuffer>;
using VertexArray = Handle<deleteVertexArray>;

Buffer makeBuffer();
VertexArray makeVertexArray();

// A linked shader program. Each stage is a list of embedded files under
// src/render/shaders/ ("common.glsl", "sphere.vert.glsl", ...) that are
// concatenated after a "#version 330 core" line; compile and link errors throw
// ff::Error naming the program, the stage, the files and the driver's log.
class Program {
 public:
  Program() = default;
  Program(const std::string& name, const std::vector<std::string>& vertex,
          const std::vector<std::string>& fragment, const std::vector<std::string>& geometry = {});

  void use() const { glUseProgram(handle_.id()); }
  GLuint id() const { return handle_.id(); }
  const std::string& name() const { return name_; }

  // Uniform setters for the program in use; unknown names (optimised away) are ignored.
  void set(const char* uniform, int v) const;
  void set(const char* uniform, float v) const;
  void set(const char* uniform, float x, float y) const;
  void set(const char* uniform, float x, float y, float z) const;
  void set(const char* uniform, float x, float y, float z, float w) const;
  void set(const char* uniform, const Vec3& v) const;
  void set(const char* uniform, const Mat4& m) const;
  void set(const char* uniform, const Eigen::Matrix3f& m) const;

 private:
  std::string name_;
  Handle<deleteProgram> handle_;
};

// A 2D texture with nearest or linear filtering and clamp-to-edge wrapping.
class Texture {
 public:
  // (Re)allocates the storage, e.g. (GL_R32F, GL_RED, GL_FLOAT) or
  // (GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT).
  void allocate(int width, int height, GLenum internal_format, GLenum format, GLenum type, bool linear);
  void bind(int unit) const;
  GLuint id() const { return handle_.id(); }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  Handle<deleteTexture> handle_;
  int width_ = 0, height_ = 0;
};

// A framebuffer object over textures the caller owns.
class Framebuffer {
 public:
  // Attaches `colour` (each may be null) to GL_COLOR_ATTACHMENT0.. and `depth`
  // (may be null) as the depth attachment, enables the colour draw buffers,
  // and throws ff::Error naming `name` when the result is incomplete.
  void attach(const std::string& name, const std::vector<const Texture*>& colour, const Texture* depth);
  void bind() const { glBindFramebuffer(GL_FRAMEBUFFER, handle_.id()); }
  GLuint id() const { return handle_.id(); }

 private:
  Handle<deleteFramebuffer> handle_;
};

}  // namespace ff::render::gl
