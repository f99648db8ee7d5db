#include "rlrun/envs/mujoco/gl_library.hpp"

#include <dlfcn.h>

#include "rlrun/core/errors.hpp"

namespace rlrun::mujoco {

void* open_gl_library(std::initializer_list<const char*> names, std::string& error) {
  for (const char* name : names) {
    if (void* library = dlopen(name, RTLD_NOW | RTLD_GLOBAL)) return library;
    const char* message = dlerror();
    error = message ? message : std::string("cannot load ") + name;
  }
  return nullptr;
}

void* gl_symbol(void* library, const char* library_name, const char* name) {
  void* symbol = dlsym(library, name);
  if (!symbol)
    throw RuntimeFailure(std::string(library_name) + " has no function " + name +
                         ": it is not the library MuJoCo's renderer needs");
  return symbol;
}

bool globally_visible(const char* name) {
  // dlopen(NULL) is the program itself; dlsym on it searches the global scope: the program, the
  // libraries it links, and those opened RTLD_GLOBAL (what MuJoCo's loader searches).
  void* program = dlopen(nullptr, RTLD_NOW);
  if (!program) return false;
  const bool found = dlsym(program, name) != nullptr;
  dlclose(program);
  return found;
}

}  // namespace rlrun::mujoco
