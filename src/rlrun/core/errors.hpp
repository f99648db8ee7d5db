#pragma once
// Error types mapped to exit codes in main (docs/commands.md):
//   ConfigError / UsageError -> 2 (the user's input is wrong: fix the file or the command line)
//   RuntimeFailure           -> 1 (env, I/O, simulator failed while running)
//   Interrupted              -> 128 + the signal (130 for Ctrl-C), as a shell reports it
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

// A Ctrl-C (SIGINT) or SIGTERM that stopped rlrun where it could not wait for a safe point: a
// worker that has not started or does not answer (core/worker_wait.hpp). Not a RuntimeFailure,
// so that code turning failures into other errors (an env that cannot be built is a config
// error) lets it through to main().
class Interrupted : public std::runtime_error {
 public:
  Interrupted(const std::string& what, int signal)
      : std::runtime_error(what), signal_(signal > 0 ? signal : 2) {}
  int signal() const { return signal_; }  // SIGINT (2) or SIGTERM (15)

 private:
  int signal_;
};

inline constexpr int kExitOk = 0;
inline constexpr int kExitRuntime = 1;
inline constexpr int kExitUsage = 2;

}  // namespace rlrun
