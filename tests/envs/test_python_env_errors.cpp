// What goes wrong in a Python env is reported, never hangs or crashes rlrun: each case runs
// the real binary on an env of tests/python_envs/rlrun_test_envs/broken.py and checks the exit
// code (1: a runtime failure; 2: a bad config) and that the message names the env and says what
// happened, where.
#include <catch2/catch.hpp>

#include <initializer_list>
#include <string>

#include "envs/python_env_runner.hpp"

using namespace rlrun::testing;

namespace {

struct Expected {
  int exit_code;
  std::initializer_list<const char*> texts;
};

// Training with one env (several crashing at once interleave their Python stacks).
void check_training_fails(const std::string& env_id, const Expected& expected,
                          const std::string& env_extra = "", const std::string& args = "") {
  TempDir dir("python_error");
  const auto r = run_rlrun_python(
      "train " +
      python_experiment(dir.str(), "broken", env_id, "id: PPO, n_steps: 16", 64, 1, env_extra) +
      args);
  INFO(r.output);
  CHECK(r.exit_code == expected.exit_code);
  for (const char* text : expected.texts) CHECK(r.output.find(text) != std::string::npos);
}

const std::string kBroken = "python:rlrun_test_envs.broken:";

}  // namespace

TEST_CASE("a Python env that raises: its traceback, the env id and the step", "[python]") {
  check_training_fails(
      kBroken + "RaisesInStep",
      {1,
       {"python:rlrun_test_envs.broken:RaisesInStep", "failed in step() at step 5 of episode 1",
        "Traceback (most recent call last)", "in compute_reward",
        "ValueError: the reward table has no entry for state 42"}});
}

TEST_CASE("a Python env that crashes the interpreter or is killed", "[python]") {
  check_training_fails(
      kBroken + "CrashesInStep",
      {1,
       {"python:rlrun_test_envs.broken:CrashesInStep",
        "was killed by signal 11 (Segmentation fault) in step()", "(step 5 of episode 1)",
        // faulthandler's Python stack, printed by the dying worker
        "Fatal Python error: Segmentation fault", "in go_wrong"}});
  check_training_fails(kBroken + "KilledInStep",
                       {1, {"was killed by signal 9 (Killed) in step() (step 5 of episode 1)"}});
}

TEST_CASE("Python envs whose observations do not fit their space, or are NaN", "[python]") {
  check_training_fails(
      kBroken + "WrongShape",
      {1, {"WrongShape", "at step 5", "has shape (4,), but observation_space has shape (3,)"}});
  check_training_fails(
      kBroken + "WrongDtype",
      {1,
       {"WrongDtype", "has dtype float64, but observation_space is a Box of float32",
        "astype(np.float32)"}});
  check_training_fails(kBroken + "NanObservation",
                       {1, {"NanObservation", "holds nan at flat index 1", "must be finite"}});
  check_training_fails(kBroken + "OldGymApi",
                       {1, {"OldGymApi", "returned 4 values", "old gym API"}});
}

TEST_CASE("Python envs that cannot be built", "[python]") {
  check_training_fails("python:no_such_module:Env",
                       {2,
                        {"cannot import module 'no_such_module' with /usr/bin/python3",
                         "ModuleNotFoundError", "env.python"}});
  check_training_fails(kBroken + "NoSuchClass",
                       {2, {"has no 'NoSuchClass'", "it defines:", "RaisesInStep"}});
  check_training_fails(
      kBroken + "NotAnEnv",
      {2, {"built a rlrun_test_envs.broken.NotAnEnv, which is not a Gymnasium env"}});
  check_training_fails(
      kBroken + "FailsInInit",
      {2, {"could not be built", "RuntimeError: cannot open the simulator config for size 7"}},
      ", kwargs: {size: 7}");
  check_training_fails(kBroken + "TupleSpace",
                       {2, {"observation_space is a Tuple space", "Box, Discrete, MultiDiscrete"}});
  check_training_fails("python:not a valid id",
                       {2, {"is not a Python env id: write python:<module>:<Class>"}});
  check_training_fails(
      kBroken + "RaisesInStep",
      {2, {"cannot run the Python interpreter '/no/such/python'", "apt install python3"}}, "",
      " --set env.python=/no/such/python");
}

TEST_CASE("A Python env whose __init__ hangs is stopped after env.startup_timeout", "[python]") {
  // The message names the env and the setting; exit code 2: an env that cannot be built is the
  // experiment's problem, said at its env.id (runtime/experiment/env_factory.cpp).
  check_training_fails(kBroken + "HangsInInit",
                       {2,
                        {"HangsInInit", "has not finished starting within 1 s",
                         "(env.startup_timeout)", "Raise env.startup_timeout"}},
                       ", startup_timeout: 1");
}

TEST_CASE("A Python env's Discrete space too large for a policy is refused at its creation",
          "[python]") {
  // Was "layer sizes must be positive, got 0" (2^62 cast to int) when the network was built.
  check_training_fails(kBroken + "HugeDiscrete",
                       {2,
                        {"HugeDiscrete",
                         "its action_space: Discrete(4611686018427387904) has "
                         "too many values",
                         "at most 16777216 (2^24)"}});
}
