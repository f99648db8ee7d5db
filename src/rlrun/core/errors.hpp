#pragma once
// Error types mapped to exit codes in main (DESIGN.md §6):
//   ConfigError / UsageError -> 2 (the user's input is wrong: fix the file or the command line)
//   RuntimeFailure           -> 1 (env, I/O, simulator failed while running)
#include <stdexcept>
#include <string>

namespace rlrun {

// Bad YAML or bad values in an experiment file; the message names file:line:col and key path.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bad command-line usage (unknown flag, missing file, incompatible options).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Something failed while running: I/O, an environment, a simulator, a NaN in training.
class RuntimeFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr int kExitOk = 0;
inline constexpr int kExitRuntime = 1;
inline constexpr int kExitUsage = 2;

}  // namespace rlrun
