// Integers in experiment files (and in the config.yaml of untrusted model files) that do not
// fit the setting's C++ type are refused, not wrapped.
#include <catch2/catch.hpp>

#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"

using namespace rlrun;

namespace {

std::string parse_error(const std::string& text) {
  try {
    parse_experiment(ConfigNode::load_string(text, "x.yaml"), builtin_registry());
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("config: integers beyond int are refused", "[core][config]") {
  const std::string base = "run: {total_timesteps: 8}\n";
  CHECK(parse_error(base + "env: {id: CartPole-v1, n_envs: 4294967297}\nalgo: {id: PPO}\n")
            .find("expected an integer in [") != std::string::npos);
  CHECK(parse_error(base + "env: {id: CartPole-v1}\nalgo: {id: PPO, n_steps: -4294967296}\n")
            .find("expected an integer in [") != std::string::npos);
  // Values that fit are fine, infinities included where a setting allows them.
  CHECK(parse_error(base + "env: {id: CartPole-v1, n_envs: 2}\nalgo: {id: PPO, gamma: 0.5}\n")
            .empty());
  // A list or map used as a key (YAML allows it) is a config error, not an escaped exception.
  CHECK(parse_error("run: {[a]: 1}\n").find("a key must be a plain name") != std::string::npos);
}
