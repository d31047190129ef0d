// offscreen_context.cpp - an OpenGL 3.3 core context through EGL with no
// surface, drawing into its own framebuffer object. Tries, in order, Mesa's
// surfaceless platform (llvmpipe or a Mesa GPU driver without X), the first
// EGL device (NVIDIA's driver has no surfaceless platform) and the default
// display, and says why each one failed when none works.
#include "render/offscreen_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdio>
#include <cstring>
#include <map>
#include <mutex>

#include "core/error.h"

namespace ff::render {

namespace {

std::string eglErrorText() {
  const EGLint e = eglGetError();
  const char* name = nullptr;
  switch (e) {
    case EGL_SUCCESS:
      return "no EGL error reported";
    case EGL_NOT_INITIALIZED:
      name = "EGL_NOT_INITIALIZED";
      break;
    case EGL_BAD_ACCESS:
      name = "EGL_BAD_ACCESS";
      break;
    case EGL_BAD_ALLOC:
      name = "EGL_BAD_ALLOC";
      break;
    case EGL_BAD_ATTRIBUTE:
      name = "EGL_BAD_ATTRIBUTE";
      break;
    case EGL_BAD_CONFIG:
      name = "EGL_BAD_CONFIG";
      break;
    case EGL_BAD_CONTEXT:
      name = "EGL_BAD_CONTEXT";
      break;
    case EGL_BAD_DISPLAY:
      name = "EGL_BAD_DISPLAY";
      break;
    case EGL_BAD_MATCH:
      name = "EGL_BAD_MATCH";
      break;
    case EGL_BAD_PARAMETER:
      name = "EGL_BAD_PARAMETER";
      break;
    default:
      break;
  }
  if (name) return name;
  char buf[32];
  std::snprintf(buf, sizeof(buf), "EGL error 0x%04x", unsigned(e));
  return buf;
}

bool hasExtension(const char* list, const char* ext) {
  if (!list) return false;
  const size_t n = std::strlen(ext);
  for (const char* p = list; (p = std::strstr(p, ext)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

// eglInitialize is not reference-counted: a display is terminated only when
// the last context this program made on it goes away.
std::mutex g_display_mutex;
std::map<EGLDisplay, int> g_display_users;

void releaseDisplay(EGLDisplay d) {
  std::lock_guard<std::mutex> lock(g_display_mutex);
  if (--g_display_users[d] <= 0) {
    g_display_users.erase(d);
    eglTerminate(d);
  }
}

// Initialises `d` and makes a 3.3 core context current on it with no
// surface. Returns EGL_NO_CONTEXT and sets `why` on failure.
EGLContext makeContext(EGLDisplay d, std::string& why) {
  if (d == EGL_NO_DISPLAY) {
    why = "no display (" + eglErrorText() + ")";
    return EGL_NO_CONTEXT;
  }
  EGLint major = 0, minor = 0;
  if (!eglInitialize(d, &major, &minor)) {
    why = "eglInitialize failed (" + eglErrorText() + ")";
    return EGL_NO_CONTEXT;
  }
  {
    std::lock_guard<std::mutex> lock(g_display_mutex);
    ++g_display_users[d];
  }
  auto fail = [&](const std::string& what) {
    why = what;
    releaseDisplay(d);
    return EGL_NO_CONTEXT;
  };
  const char* exts = eglQueryString(d, EGL_EXTENSIONS);
  if (!hasExtension(exts, "EGL_KHR_surfaceless_context"))
    return fail("the display lacks EGL_KHR_surfaceless_context");
  if (!eglBindAPI(EGL_OPENGL_API)) return fail("desktop OpenGL is not offered (" + eglErrorText() + ")");
  const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                   EGL_NONE};
  EGLConfig config = EGL_NO_CONFIG_KHR;
  EGLint count = 0;
  if (!eglChooseConfig(d, config_attribs, &config, 1, &count) || count < 1) {
    if (!hasExtension(exts, "EGL_KHR_no_config_context") &&
        !hasExtension(exts, "EGL_MESA_configless_context"))
      return fail("no config renders desktop OpenGL");
    config = EGL_NO_CONFIG_KHR;
  }
  const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                    3,
                                    EGL_CONTEXT_MINOR_VERSION,
                                    3,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                    EGL_NONE};
  EGLContext ctx = eglCreateContext(d, config, EGL_NO_CONTEXT, context_attribs);
  if (ctx == EGL_NO_CONTEXT) return fail("no OpenGL 3.3 core context (" + eglErrorText() + ")");
  if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
    const std::string e = eglErrorText();
    eglDestroyContext(d, ctx);
    return fail("the context cannot be made current without a surface (" + e + ")");
  }
  return ctx;
}

}  // namespace

struct OffscreenContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  GLuint fbo = 0, colour = 0, depth = 0;
  int width = 0, height = 0;

  // Deletes the framebuffer and the context (also after a failed start).
  void release() {
    if (context == EGL_NO_CONTEXT) return;
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context);
    if (fbo) glDeleteFramebuffers(1, &fbo);
    if (colour) glDeleteRenderbuffers(1, &colour);
    if (depth) glDeleteRenderbuffers(1, &depth);
    fbo = colour = depth = 0;
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, context);
    releaseDisplay(display);
    context = EGL_NO_CONTEXT;
  }
};

OffscreenContext::OffscreenContext(int width, int height) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  const bool platform_base = hasExtension(client, "EGL_EXT_platform_base");
  std::string tried;
  auto attempt = [&](const char* label, EGLDisplay d, const std::string& unavailable) {
    if (m.context != EGL_NO_CONTEXT) return;
    std::string why = unavailable;
    if (why.empty()) {
      EGLContext c = makeContext(d, why);
      if (c != EGL_NO_CONTEXT) {
        m.display = d;
        m.context = c;
        return;
      }
    }
    tried += std::string(tried.empty() ? "" : "; ") + label + ": " + why;
  };

  if (platform_base && hasExtension(client, "EGL_MESA_platform_surfaceless"))
    attempt("surfaceless Mesa platform",
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr), "");
  else
    attempt("surfaceless Mesa platform", EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless is not offered");

  if (m.context == EGL_NO_CONTEXT) {
    if (platform_base && hasExtension(client, "EGL_EXT_platform_device") &&
        (hasExtension(client, "EGL_EXT_device_enumeration") || hasExtension(client, "EGL_EXT_device_base"))) {
      EGLDeviceEXT device = nullptr;
      EGLint devices = 0;
      if (eglQueryDevicesEXT(1, &device, &devices) && devices > 0)
        attempt("EGL device platform", eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr),
                "");
      else
        attempt("EGL device platform", EGL_NO_DISPLAY, "no EGL device found");
    } else {
      attempt("EGL device platform", EGL_NO_DISPLAY, "EGL_EXT_platform_device is not offered");
    }
  }
  if (m.context == EGL_NO_CONTEXT) attempt("default display", eglGetDisplay(EGL_DEFAULT_DISPLAY), "");
  if (m.context == EGL_NO_CONTEXT)
    throw Error("cannot create an offscreen OpenGL 3.3 core context through EGL (" + tried + ")");

  GLint max_size = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (width < 1 || height < 1 || width > max_size || height > max_size) {
    m.release();
    throw Error("offscreen framebuffer " + std::to_string(width) + " x " + std::to_string(height) +
                ": each side must be between 1 and " + std::to_string(max_size) + " pixels on this GPU");
  }
  m.width = width;
  m.height = height;
  glGenRenderbuffers(1, &m.colour);
  glBindRenderbuffer(GL_RENDERBUFFER, m.colour);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glGenRenderbuffers(1, &m.depth);
  glBindRenderbuffer(GL_RENDERBUFFER, m.depth);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glGenFramebuffers(1, &m.fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, m.fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m.colour);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, m.depth);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char buf[128];
    std::snprintf(buf, sizeof(buf), "offscreen framebuffer is incomplete (status 0x%04x)", unsigned(status));
    m.release();
    throw Error(buf);
  }
  glViewport(0, 0, width, height);
}

OffscreenContext::~OffscreenContext() {
  impl_->release();
}

int OffscreenContext::width() const {
  return impl_->width;
}
int OffscreenContext::height() const {
  return impl_->height;
}
unsigned OffscreenContext::framebuffer() const {
  return impl_->fbo;
}

std::string OffscreenContext::renderer() const {
  const GLubyte* r = glGetString(GL_RENDERER);
  return r ? reinterpret_cast<const char*>(r) : "unknown renderer";
}

std::vector<uint8_t> OffscreenContext::readPixels() const {
  const Impl& m = *impl_;
  const size_t row = size_t(m.width) * 4;
  std::vector<uint8_t> bottom_up(row * size_t(m.height));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, m.fbo);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, m.width, m.height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  std::vector<uint8_t> top_down(bottom_up.size());
  for (int y = 0; y < m.height; ++y)
    std::memcpy(&top_down[size_t(y) * row], &bottom_up[size_t(m.height - 1 - y) * row], row);
  return top_down;
}

}  // namespace ff::render
