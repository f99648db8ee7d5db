#pragma once
// An OpenGL context without a window, a display server or a GPU, for MuJoCo's renderer (mjr_*),
// which draws into framebuffer objects of its own (mjFB_OFFSCREEN), so the context needs no
// drawable of any size. Two platforms, as Gymnasium's MUJOCO_GL offers them headless:
//
//   osmesa  Mesa's off-screen rendering (Debian's libosmesa6): software (llvmpipe), needs
//           nothing else; rlrun's default
//   egl     EGL on an EGL device (libegl1 + libegl-mesa0, or a GPU vendor's EGL): a GPU when
//           the driver offers one, else Mesa's software device
//
// One platform per process: MuJoCo's GL loader (gl_library.hpp) binds GL's functions once, from
// the platform it finds at the first mjr_makeContext, for the whole process. It is chosen at
// the first render: MUJOCO_GL=osmesa|egl when set (ProcessSettings::mujoco_gl, read when the
// program starts); else EGL when the process already has EGL among its global symbols
// (MuJoCo's loader would take EGL's functions), else OSMesa, else EGL.
//
// A context is current on one thread at a time. Rendering makes it current for the duration of
// one frame (CurrentGlContext) and leaves no context current, so the next frame may come from
// any thread, and one thread may render several envs in turn.
#include <memory>
#include <string>

namespace rlrun::mujoco {

class OffscreenGlContext {
 public:
  virtual ~OffscreenGlContext() = default;
  // Makes this context the calling thread's current one; throws RuntimeFailure.
  virtual void make_current() = 0;
  // Leaves the calling thread with no current context.
  virtual void release() noexcept = 0;
  // "osmesa" or "egl".
  virtual const char* platform() const = 0;
};

// The context current for a scope.
class CurrentGlContext {
 public:
  explicit CurrentGlContext(OffscreenGlContext& context) : context_(context) {
    context_.make_current();
  }
  ~CurrentGlContext() { context_.release(); }
  CurrentGlContext(const CurrentGlContext&) = delete;
  CurrentGlContext& operator=(const CurrentGlContext&) = delete;

 private:
  OffscreenGlContext& context_;
};

// A new context on the process's platform (chosen at the first call, see above). Throws
// RuntimeFailure naming the Debian packages to install when no platform works.
std::unique_ptr<OffscreenGlContext> make_offscreen_gl_context();

}  // namespace rlrun::mujoco
