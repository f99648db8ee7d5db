#pragma once
// The one place rlrun's programs read their RLRUN_* environment variables
// (core/process_settings.hpp lists them): the rlrun binary's main(), the test binary's main()
// and the Python module's initialisation call apply_process_environment() before any work.
#include "rlrun/core/process_settings.hpp"

namespace rlrun {

// The settings the environment variables give (unset or empty: the default).
ProcessSettings process_settings_from_environment();

// Sets them (set_process_settings) and chooses the network kernels (dense::select_kernels).
// Throws std::runtime_error for an RLRUN_KERNELS value that names no path or one this CPU
// cannot run.
void apply_process_environment();

}  // namespace rlrun
