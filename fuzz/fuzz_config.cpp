// Fuzz target: the experiment-file loader on arbitrary text — ConfigNode::load_string and
// parse_experiment with the built-in registry, as `rlrun eval` runs them on the config.yaml of
// an untrusted model file. Refusing is fine (ConfigError, UsageError, RuntimeFailure: exit 2 or
// 1 with a message); any other exception, a crash, a sanitizer report or a hang is a bug.
// A config that parses must also parse again from its resolved form (what model files store).
// Left out: what fuzz_limits.hpp says (plugins, huge sizes).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "fuzz_limits.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"

using namespace rlrun;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const Registry& registry = builtin_registry();
  std::string resolved;
  try {
    ConfigNode root = ConfigNode::load_string(text, "fuzz.yaml");
    if (!fuzz::fuzzable_config(root)) return 0;
    // As load_experiment does: a run without a name is named after its file.
    if (root.is_map() && !root.child("run").defined())
      root.yaml()["run"] = YAML::Node(YAML::NodeType::Map);
    if (root.is_map() && root.child("run").is_map() && !root.child("run").child("name").defined())
      root.yaml()["run"]["name"] = "fuzz";
    const Experiment experiment = parse_experiment(root, registry);
    resolved = dump_yaml(experiment.resolved);
  } catch (const ConfigError&) {
    return 0;
  } catch (const UsageError&) {
    return 0;
  } catch (const RuntimeFailure&) {
    return 0;
  }
  try {
    parse_experiment(ConfigNode::load_string(resolved, "resolved.yaml"), registry);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "a resolved config does not parse again: %s\n--- resolved:\n%s\n",
                 e.what(), resolved.c_str());
    std::abort();
  }
  return 0;
}
