#pragma once
// A MuJoCo model (mjModel, compiled from an MJCF file) and its simulation state (mjData), owned
// by smart pointers, and how rlrun finds and loads the model files: the eleven task models ship
// in scenarios/mujoco/ (rlrun's own text of Gymnasium's assets; each compiles to the same model
// as Gymnasium's file, tests/envs/mujoco/test_mujoco_env.cpp), and a user's experiment file
// may name another (`xml_file`, a SimulatorInput: untrusted text may name only shipped files).
#include <mujoco/mujoco.h>

#include <memory>
#include <string>

namespace rlrun::mujoco {

struct ModelDeleter {
  void operator()(const mjModel* m) const { mj_deleteModel(const_cast<mjModel*>(m)); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
// Read-only once compiled: copies of an env may share one.
using ModelPtr = std::shared_ptr<const mjModel>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

// scenarios/mujoco/<file_name> in the shipped data directory.
std::string shipped_model_path(const std::string& file_name);

// The model file of a task's `xml_file` kwarg: "" is the task's own `shipped` file; a bare file
// name of a shipped model ("ant.xml") is that model, as in Gymnasium (mujoco_env.py's
// expand_model_path looks names up in its assets); any other path is taken as given (from the
// working directory when relative).
std::string model_path(const std::string& xml_file, const std::string& shipped);

// Compiles an MJCF file. Throws ConfigError "<path>: MuJoCo cannot load this model: <MuJoCo's
// message>" (MuJoCo names the element, its line and column) for a missing or broken file.
ModelPtr load_model(const std::string& path);

DataPtr make_data(const mjModel& model);

// MuJoCo reports through two process-wide hooks. Its errors (mju_error: a stack overflow, a bad
// argument) would print and exit the process; rlrun's hook throws RuntimeFailure instead. Its
// warnings (mju_warning: instability, too many contacts) would print to stdout and append to
// MUJOCO_LOG.TXT in the working directory; rlrun's hook is silent, because every warning is also
// counted in mjData::warning, which MujocoEnv reads after each step and reports itself. Set once,
// before the first model is loaded (load_model calls it).
void install_error_hooks();

}  // namespace rlrun::mujoco
