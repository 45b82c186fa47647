#pragma once
// EglContext: an OpenGL 4.5 core context with no window system, for headless rendering.
//
// Display selection (first that initialises wins):
//   1. EGL_MESA_platform_surfaceless through eglGetPlatformDisplayEXT (Mesa llvmpipe on CPU-only
//      machines, or Mesa's GPU drivers),
//   2. EGL_DEFAULT_DISPLAY (vendor EGL on GPU workstations, e.g. NVIDIA's EGL device platform).
// The context is created without a surface (EGL_KHR_surfaceless_context); all rendering goes into
// framebuffer objects. GL entry points are the GL_GLEXT_PROTOTYPES symbols of the GLVND libGL /
// libOpenGL dispatch library, which routes them to whichever vendor owns the current EGL context.
#include <string>

namespace crowdlab::stimuli {

class EglContext {
 public:
  /// Creates the display and a 4.5 core context and makes it current on the calling thread.
  /// Throws RuntimeError with the EGL error code when no suitable display/context exists.
  EglContext();
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  /// Makes the context current on the calling thread (a no-op when it already is). Several contexts
  /// may coexist; each Renderer call makes its own current first.
  void make_current();
  /// GL_RENDERER and GL_VERSION strings, e.g. "llvmpipe (LLVM 15.0.6, 256 bits) / 4.5 (Core Profile)
  /// Mesa 22.3.6".
  const std::string& renderer_description() const { return description_; }

 private:
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  std::string description_;
};

}  // namespace crowdlab::stimuli
