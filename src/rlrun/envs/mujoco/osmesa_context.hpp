#pragma once
// An OSMesa context (Mesa's off-screen rendering: software OpenGL on llvmpipe, Debian's
// libosmesa6), opened at run time (gl_library.hpp).
#include <memory>
#include <string>

#include "rlrun/envs/mujoco/offscreen_gl_context.hpp"

namespace rlrun::mujoco {

// Loads libOSMesa once per process; false with the reason when it cannot be loaded.
bool load_osmesa(std::string& why_not);

// Needs load_osmesa() to have succeeded. Throws RuntimeFailure when Mesa refuses a context.
std::unique_ptr<OffscreenGlContext> make_osmesa_context();

}  // namespace rlrun::mujoco
