#pragma once
// The OpenGL platform libraries (libOSMesa, libEGL) are opened at the first render, never linked:
// an rlrun or a deployed policy that never renders loads no GL, and a machine without them still
// trains. MuJoCo's own GL loader (glad inside libmujoco; MuJoCo 2.2's src/render/glad/glad.c,
// mjGlad_open_gl) finds GL by looking up a platform's *GetProcAddress among the process's global
// symbols, eglGetProcAddress first, then OSMesaGetProcAddress, then glXGetProcAddressARB; so the
// library of the context rlrun makes is opened RTLD_GLOBAL, and that order decides which
// platform rlrun may use (offscreen_gl_context.cpp).
#include <initializer_list>
#include <string>

namespace rlrun::mujoco {

// dlopen()s the first of `names` that loads, RTLD_NOW | RTLD_GLOBAL, and never closes it (MuJoCo
// keeps pointers to its functions for the life of the process). nullptr when none loads; then
// `error` holds the loader's message for the last name.
void* open_gl_library(std::initializer_list<const char*> names, std::string& error);

// The address of `name` in `library`; throws RuntimeFailure naming both when it is missing.
void* gl_symbol(void* library, const char* library_name, const char* name);

template <class Function>
Function gl_function(void* library, const char* library_name, const char* name) {
  return reinterpret_cast<Function>(gl_symbol(library, library_name, name));
}

// Whether `name` is among the process's global symbols, where MuJoCo's loader looks first.
bool globally_visible(const char* name);

}  // namespace rlrun::mujoco
