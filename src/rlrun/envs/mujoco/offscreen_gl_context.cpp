#include "rlrun/envs/mujoco/offscreen_gl_context.hpp"

#include "rlrun/core/errors.hpp"
#include "rlrun/core/process_settings.hpp"
#include "rlrun/envs/mujoco/egl_context.hpp"
#include "rlrun/envs/mujoco/gl_library.hpp"
#include "rlrun/envs/mujoco/osmesa_context.hpp"

namespace rlrun::mujoco {

namespace {

enum class Platform { osmesa, egl };

constexpr const char* kOsmesaPackage = "Debian's libosmesa6";
constexpr const char* kEglPackages = "Debian's libegl1 and libegl-mesa0";

Platform need_egl(const std::string& reason) {
  std::string why_not;
  if (load_egl(why_not)) return Platform::egl;
  throw RuntimeFailure("MuJoCo rendering: " + reason + ", but EGL does not work: " + why_not +
                       ". Install " + kEglPackages + " (or a GPU driver's EGL)");
}

Platform need_osmesa() {
  std::string why_not;
  if (load_osmesa(why_not)) return Platform::osmesa;
  throw RuntimeFailure("MuJoCo rendering with MUJOCO_GL=osmesa needs " +
                       std::string(kOsmesaPackage) + " (" + why_not + ")");
}

// The rules of offscreen_gl_context.hpp. MuJoCo's loader takes eglGetProcAddress over
// OSMesaGetProcAddress when both are global, so OSMesa is usable only while EGL is not.
Platform choose_platform() {
  const bool egl_is_global = globally_visible("eglGetProcAddress");
  const std::string& choice = process_settings().mujoco_gl;
  if (choice == "egl") return need_egl("MUJOCO_GL=egl");
  if (choice == "osmesa") {
    if (egl_is_global)
      throw RuntimeFailure(
          "MuJoCo rendering with MUJOCO_GL=osmesa: this process has already loaded EGL, whose "
          "functions MuJoCo's OpenGL loader would take; set MUJOCO_GL=egl");
    return need_osmesa();
  }
  if (!choice.empty())
    throw RuntimeFailure("MUJOCO_GL=" + choice +
                         ": rlrun renders MuJoCo offscreen with osmesa or egl (unset MUJOCO_GL to "
                         "let rlrun choose)");
  if (egl_is_global) return need_egl("this process has already loaded EGL");
  std::string osmesa_missing, egl_missing;
  if (load_osmesa(osmesa_missing)) return Platform::osmesa;
  if (load_egl(egl_missing)) return Platform::egl;
  throw RuntimeFailure("MuJoCo rendering needs an offscreen OpenGL: install " +
                       std::string(kOsmesaPackage) + " (" + osmesa_missing + "), or " +
                       kEglPackages + " (" + egl_missing + ")");
}

}  // namespace

std::unique_ptr<OffscreenGlContext> make_offscreen_gl_context() {
  // Chosen once (a throw leaves it unchosen: the next render tries again).
  static const Platform platform = choose_platform();
  return platform == Platform::osmesa ? make_osmesa_context() : make_egl_context();
}

}  // namespace rlrun::mujoco
