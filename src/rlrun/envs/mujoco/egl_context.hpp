#pragma once
// An EGL context without a window system, on an EGL device (EGL_EXT_platform_device: a GPU, or
// Mesa's software device), as MuJoCo's Python bindings make one for MUJOCO_GL=egl
// (python/mujoco/egl); opened at run time (gl_library.hpp). Debian's libegl1 (the dispatcher)
// and libegl-mesa0 (Mesa's implementation; a GPU vendor's EGL works as well).
#include <memory>
#include <string>

#include "rlrun/envs/mujoco/offscreen_gl_context.hpp"

namespace rlrun::mujoco {

// Loads libEGL and initializes a display on the first EGL device that has one, once per
// process; false with the reason when that fails.
bool load_egl(std::string& why_not);

// Needs load_egl() to have succeeded. Throws RuntimeFailure when EGL refuses a context.
std::unique_ptr<OffscreenGlContext> make_egl_context();

}  // namespace rlrun::mujoco
