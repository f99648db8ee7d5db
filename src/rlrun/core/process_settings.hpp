#pragma once
// What the user may set for the whole process from outside (environment variables, read only
// by the programs' entry points: apps/common/process_environment.cpp for the rlrun binary, the
// test binary and the Python module), handed to the layers below once, in main() or the
// module's initialisation, before any work starts. No layer below apps/ reads the environment
// (issue 42): a library user (rlrun::Policy::load, a plugin's tests) gets the same behaviour
// whatever variables its process has, and sets what it wants here.
//
// These are facts about the installation and the programs rlrun runs, the same for every run
// of the process; what differs per run (threads) is in ExecutionContext. The kernel path is
// chosen by nn/dense_kernels.hpp's select_kernels() from `kernels`.
#include <string>

namespace rlrun {

struct ProcessSettings {
  // Empty: the default in brackets.
  std::string data_dir;        // RLRUN_DATA_DIR: the shipped data (found beside the binary)
  std::string python;          // RLRUN_PYTHON: what env.python "python3" runs ("python3")
  std::string ffmpeg;          // RLRUN_FFMPEG: the ffmpeg program (`ffmpeg` on PATH)
  std::string libsumo_module;  // RLRUN_LIBSUMO_MODULE: librlrun_libsumo.so (beside the binary)
  std::string sumo_worker;     // RLRUN_SUMO_WORKER: rlrun-sumo-worker (beside the binary)
  std::string kernels;         // RLRUN_KERNELS: auto, avx512, avx2 or baseline (auto)
  std::string mujoco_gl;       // MUJOCO_GL (Gymnasium's name): osmesa or egl, the GL platform
                               // of MuJoCo's renderer (envs/mujoco/offscreen_gl_context.hpp)
};

// The settings in force (all empty until set_process_settings is called).
const ProcessSettings& process_settings();

// Sets them; entry points call it once before any work (tests, to change one for a scope:
// tests/core/scoped_process_settings.hpp). Not for use while other threads run rlrun code.
void set_process_settings(const ProcessSettings& settings);

}  // namespace rlrun
