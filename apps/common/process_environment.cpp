#include "process_environment.hpp"

#include <cstdlib>

#include "rlrun/nn/dense_kernels.hpp"

namespace rlrun {

namespace {

std::string variable(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

}  // namespace

ProcessSettings process_settings_from_environment() {
  ProcessSettings s;
  s.data_dir = variable("RLRUN_DATA_DIR");
  s.python = variable("RLRUN_PYTHON");
  s.ffmpeg = variable("RLRUN_FFMPEG");
  s.libsumo_module = variable("RLRUN_LIBSUMO_MODULE");
  s.sumo_worker = variable("RLRUN_SUMO_WORKER");
  s.kernels = variable("RLRUN_KERNELS");
  s.mujoco_gl = variable("MUJOCO_GL");
  return s;
}

void apply_process_environment() {
  const ProcessSettings settings = process_settings_from_environment();
  set_process_settings(settings);
  dense::select_kernels(settings.kernels);
}

}  // namespace rlrun
