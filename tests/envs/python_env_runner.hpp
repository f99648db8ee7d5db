#pragma once
// Running the real rlrun binary on the Python envs of tests/python_envs/ (rlrun_test_envs),
// with Debian's interpreter: env.python is /usr/bin/python3 (the one with python3-numpy,
// whatever `python3` is first on PATH) unless a test checks the default.
#include <fstream>
#include <string>

#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

namespace rlrun::testing {

inline const std::string kSourceDir = RLRUN_SOURCE_DIR;
inline const std::string kPython = "/usr/bin/python3";

// `rlrun ARGS` with the test envs importable (PYTHONPATH), from the source directory.
inline CommandResult run_rlrun_python(const std::string& args) {
  return run_command("cd " + kSourceDir + " && PYTHONPATH=" + kSourceDir + "/tests/python_envs " +
                     RLRUN_BINARY + " " + args);
}

inline std::string write_file(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

// An experiment file for a Python env; `algo` is the YAML of the algo section's body.
inline std::string python_experiment(const std::string& dir, const std::string& name,
                                     const std::string& env_id, const std::string& algo,
                                     long long steps, int n_envs = 1,
                                     const std::string& env_extra = "",
                                     const std::string& extra = "") {
  return write_file(dir + "/" + name + ".yaml",
                    "run: {name: " + name + ", seed: 1, total_timesteps: " + std::to_string(steps) +
                        ", out_dir: " + dir + "/runs}\n" + "env: {id: \"" + env_id +
                        "\", n_envs: " + std::to_string(n_envs) + ", python: " + kPython +
                        env_extra + "}\n" + "algo: {" + algo + "}\n" + extra);
}

}  // namespace rlrun::testing
