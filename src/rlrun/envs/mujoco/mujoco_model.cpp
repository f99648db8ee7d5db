#include "rlrun/envs/mujoco/mujoco_model.hpp"

#include <array>
#include <filesystem>
#include <mutex>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/shipped_data.hpp"

namespace rlrun::mujoco {

namespace {

// mju_user_error must not return (MuJoCo's state is undefined after the error): it throws.
// MuJoCo is C, but Debian builds it with unwind tables (x86-64 and arm64 defaults), so the
// exception passes through its frames; MuJoCo's Python bindings rely on the same.
void throw_mujoco_error(const char* message) {
  throw RuntimeFailure(std::string("MuJoCo error: ") + message);
}

void ignore_mujoco_warning(const char*) {}

}  // namespace

void install_error_hooks() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = throw_mujoco_error;
    mju_user_warning = ignore_mujoco_warning;
  });
}

std::string shipped_model_path(const std::string& file_name) {
  return (std::filesystem::path(shipped_data_dir()) / "scenarios" / "mujoco" / file_name).string();
}

std::string model_path(const std::string& xml_file, const std::string& shipped) {
  if (xml_file.empty()) return shipped_model_path(shipped);
  if (xml_file.find('/') == std::string::npos && !std::filesystem::exists(xml_file)) {
    const std::string in_data = shipped_model_path(xml_file);
    if (std::filesystem::is_regular_file(in_data)) return in_data;
  }
  return xml_file;
}

ModelPtr load_model(const std::string& path) {
  install_error_hooks();
  if (!std::filesystem::is_regular_file(path))
    throw ConfigError(path + ": no such MuJoCo model file (MJCF XML)");
  std::array<char, 1024> error{};
  mjModel* model = mj_loadXML(path.c_str(), nullptr, error.data(), static_cast<int>(error.size()));
  if (!model) {
    throw ConfigError(path + ": MuJoCo cannot load this model: " + std::string(error.data()));
  }
  return ModelPtr(model, ModelDeleter{});
}

DataPtr make_data(const mjModel& model) {
  mjData* data = mj_makeData(&model);
  if (!data) throw RuntimeFailure("MuJoCo could not allocate the simulation state (mj_makeData)");
  return DataPtr(data);
}

}  // namespace rlrun::mujoco
