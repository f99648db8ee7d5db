#include "rlrun/core/process_settings.hpp"

namespace rlrun {

namespace {

ProcessSettings& settings() {
  static ProcessSettings instance;
  return instance;
}

}  // namespace

const ProcessSettings& process_settings() { return settings(); }

void set_process_settings(const ProcessSettings& value) { settings() = value; }

}  // namespace rlrun
