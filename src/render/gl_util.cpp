// gl_util.cpp - OpenGL object owners and the embedded-shader loader.
#include "render/gl_util.h"

#include <algorithm>
#include <sstream>

#include "core/embedded.h"
#include "core/error.h"

namespace ff::render::gl {

namespace {

const char* errorName(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    default:
      return "unknown GL error";
  }
}

const char* stageName(GLenum stage) {
  switch (stage) {
    case GL_VERTEX_SHADER:
      return "vertex";
    case GL_FRAGMENT_SHADER:
      return "fragment";
    case GL_GEOMETRY_SHADER:
      return "geometry";
    default:
      return "shader";
  }
}

std::string joined(const std::vector<std::string>& files) {
  std::string s;
  for (const std::string& f : files) s += (s.empty() ? "" : " + ") + f;
  return s;
}

// Compiles one stage from embedded files. Each file starts with a
// `#line 1 N` directive, so the driver's log reports "N:LINE" (or "N(LINE)")
// with N the file's position in the list, which the error message spells out.
GLuint compileStage(const std::string& program, GLenum stage, const std::vector<std::string>& files) {
  std::string text = "#version 330 core\n";
  for (size_t i = 0; i < files.size(); ++i) {
    text += "#line 1 " + std::to_string(i) + "\n";
    text += embeddedFile("src/render/shaders/" + files[i]);
    text += "\n";
  }
  const GLuint s = glCreateShader(stage);
  const char* src = text.c_str();
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = GL_FALSE;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (ok == GL_TRUE) return s;
  GLint len = 0;
  glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
  std::string log(size_t(std::max(len, 1)), '\0');
  glGetShaderInfoLog(s, GLsizei(log.size()), nullptr, log.data());
  glDeleteShader(s);
  std::ostringstream os;
  os << "shader program '" << program << "': the " << stageName(stage) << " shader (" << joined(files)
     << ") does not compile; in the log below, source string N is file N of that list (from 0):\n"
     << log.c_str();
  throw Error(os.str());
}

}  // namespace

void checkError(const char* where) {
  const GLenum e = glGetError();
  if (e == GL_NO_ERROR) return;
  while (glGetError() != GL_NO_ERROR) {
  }
  throw Error(std::string("OpenGL error in ") + where + ": " + errorName(e));
}

void deleteTexture(GLuint id) {
  glDeleteTextures(1, &id);
}
void deleteFramebuffer(GLuint id) {
  glDeleteFramebuffers(1, &id);
}
void deleteBuffer(GLuint id) {
  glDeleteBuffers(1, &id);
}
void deleteVertexArray(GLuint id) {
  glDeleteVertexArrays(1, &id);
}
void deleteProgram(GLuint id) {
  glDeleteProgram(id);
}

Buffer makeBuffer() {
  GLuint id = 0;
  glGenBuffers(1, &id);
  return Buffer(id);
}

VertexArray makeVertexArray() {
  GLuint id = 0;
  glGenVertexArrays(1, &id);
  return VertexArray(id);
}

Program::Program(const std::string& name, const std::vector<std::string>& vertex,
                 const std::vector<std::string>& fragment, const std::vector<std::string>& geometry)
    : name_(name) {
  std::vector<GLuint> stages;
  try {
    stages.push_back(compileStage(name, GL_VERTEX_SHADER, vertex));
    if (!geometry.empty()) stages.push_back(compileStage(name, GL_GEOMETRY_SHADER, geometry));
    stages.push_back(compileStage(name, GL_FRAGMENT_SHADER, fragment));
  } catch (...) {
    for (GLuint s : stages) glDeleteShader(s);
    throw;
  }
  const GLuint p = glCreateProgram();
  for (GLuint s : stages) glAttachShader(p, s);
  glLinkProgram(p);
  for (GLuint s : stages) {
    glDetachShader(p, s);
    glDeleteShader(s);
  }
  GLint ok = GL_FALSE;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint len = 0;
    glGetProgramiv(p, GL_INFO_LOG_LENGTH, &len);
    std::string log(size_t(std::max(len, 1)), '\0');
    glGetProgramInfoLog(p, GLsizei(log.size()), nullptr, log.data());
    glDeleteProgram(p);
    throw Error("shader program '" + name + "' (" + joined(vertex) + ", " + joined(fragment) +
                ") does not link:\n" + log.c_str());
  }
  handle_ = Handle<deleteProgram>(p);
}

void Program::set(const char* uniform, int v) const {
  glUniform1i(glGetUniformLocation(id(), uniform), v);
}
void Program::set(const char* uniform, float v) const {
  glUniform1f(glGetUniformLocation(id(), uniform), v);
}
void Program::set(const char* uniform, float x, float y) const {
  glUniform2f(glGetUniformLocation(id(), uniform), x, y);
}
void Program::set(const char* uniform, float x, float y, float z) const {
  glUniform3f(glGetUniformLocation(id(), uniform), x, y, z);
}
void Program::set(const char* uniform, float x, float y, float z, float w) const {
  glUniform4f(glGetUniformLocation(id(), uniform), x, y, z, w);
}
void Program::set(const char* uniform, const Vec3& v) const {
  set(uniform, v.x(), v.y(), v.z());
}
void Program::set(const char* uniform, const Mat4& m) const {
  glUniformMatrix4fv(glGetUniformLocation(id(), uniform), 1, GL_FALSE, m.data());
}
void Program::set(const char* uniform, const Eigen::Matrix3f& m) const {
  glUniformMatrix3fv(glGetUniformLocation(id(), uniform), 1, GL_FALSE, m.data());
}

void Texture::allocate(int width, int height, GLenum internal_format, GLenum format, GLenum type,
                       bool linear) {
  if (!handle_.id()) {
    GLuint id = 0;
    glGenTextures(1, &id);
    handle_ = Handle<deleteTexture>(id);
  }
  glBindTexture(GL_TEXTURE_2D, handle_.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GLint(internal_format), width, height, 0, format, type, nullptr);
  const GLint filter = linear ? GL_LINEAR : GL_NEAREST;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
  width_ = width;
  height_ = height;
  checkError("texture allocation");
}

void Texture::bind(int unit) const {
  glActiveTexture(GLenum(GL_TEXTURE0 + unit));
  glBindTexture(GL_TEXTURE_2D, handle_.id());
}

void Framebuffer::attach(const std::string& name, const std::vector<const Texture*>& colour,
                         const Texture* depth) {
  if (!handle_.id()) {
    GLuint id = 0;
    glGenFramebuffers(1, &id);
    handle_ = Handle<deleteFramebuffer>(id);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, handle_.id());
  std::vector<GLenum> buffers;
  for (size_t i = 0; i < colour.size(); ++i) {
    const GLenum att = GLenum(GL_COLOR_ATTACHMENT0 + i);
    glFramebufferTexture2D(GL_FRAMEBUFFER, att, GL_TEXTURE_2D, colour[i] ? colour[i]->id() : 0, 0);
    buffers.push_back(colour[i] ? att : GL_NONE);
  }
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth ? depth->id() : 0, 0);
  if (buffers.empty()) {
    glDrawBuffer(GL_NONE);
  } else {
    glDrawBuffers(GLsizei(buffers.size()), buffers.data());
  }
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    std::ostringstream os;
    os << "framebuffer '" << name << "' is incomplete (status 0x" << std::hex << status << ")";
    throw Error(os.str());
  }
  checkError(name.c_str());
}

}  // namespace ff::render::gl
