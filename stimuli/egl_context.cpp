#include "stimuli/egl_context.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <cstdio>

#include "framework/core/error.hpp"

namespace crowdlab::stimuli {
namespace {

thread_local const EglContext* t_current = nullptr;  // the context current on this thread

std::string egl_error_text() {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%04x", static_cast<unsigned>(eglGetError()));
  return buf;
}

EGLDisplay open_display() {
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (get_platform_display) {
    EGLDisplay d = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major = 0, minor = 0;
    if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) return d;
  }
  EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  EGLint major = 0, minor = 0;
  if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) return d;
  throw RuntimeError("EGL: no display could be initialised (surfaceless or default), error " +
                     egl_error_text());
}

}  // namespace

EglContext::EglContext() {
  EGLDisplay display = open_display();
  display_ = display;
  if (!eglBindAPI(EGL_OPENGL_API))
    throw RuntimeError("EGL: eglBindAPI(OpenGL) failed, error " + egl_error_text());
  const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                   EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  eglChooseConfig(display, config_attribs, &config, 1, &count);
  const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                    4,
                                    EGL_CONTEXT_MINOR_VERSION,
                                    5,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                    EGL_NONE};
  EGLContext ctx =
      eglCreateContext(display, count > 0 ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, context_attribs);
  if (ctx == EGL_NO_CONTEXT) {
    eglTerminate(display);
    throw RuntimeError("EGL: could not create an OpenGL 4.5 core context, error " + egl_error_text());
  }
  context_ = ctx;
  make_current();
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  description_ = std::string(renderer ? renderer : "?") + " / " + (version ? version : "?");
}

EglContext::~EglContext() {
  auto display = static_cast<EGLDisplay>(display_);
  if (t_current == this) {
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    t_current = nullptr;
  }
  eglDestroyContext(display, static_cast<EGLContext>(context_));
  // No eglTerminate: the display handle is shared by every context of the process (EGL returns the
  // same EGLDisplay for the same platform and native display), and terminating it would invalidate
  // the other renderers' contexts.
}

void EglContext::make_current() {
  if (t_current == this) return;
  if (!eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE,
                      static_cast<EGLContext>(context_)))
    throw RuntimeError("EGL: eglMakeCurrent failed, error " + egl_error_text());
  t_current = this;
}

}  // namespace crowdlab::stimuli
