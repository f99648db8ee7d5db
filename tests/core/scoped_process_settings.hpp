#pragma once
// Changes the process settings (core/process_settings.hpp) for one scope, as a user's
// RLRUN_* variable would for a whole run, and restores them after.
#include <functional>

#include "rlrun/core/process_settings.hpp"

namespace rlrun::test {

class ScopedProcessSettings {
 public:
  explicit ScopedProcessSettings(const std::function<void(ProcessSettings&)>& change)
      : saved_(process_settings()) {
    ProcessSettings changed = saved_;
    change(changed);
    set_process_settings(changed);
  }
  ~ScopedProcessSettings() { set_process_settings(saved_); }
  ScopedProcessSettings(const ScopedProcessSettings&) = delete;
  ScopedProcessSettings& operator=(const ScopedProcessSettings&) = delete;

 private:
  ProcessSettings saved_;
};

}  // namespace rlrun::test
