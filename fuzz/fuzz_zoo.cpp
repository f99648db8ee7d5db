// Fuzz target: `rlrun zoo import` and `rlrun train --zoo` on an arbitrary rl-zoo hyperparameter
// file (zoo files may come from anyone: docs/security.md). The input is the file. Its first line
// may say what to import, as a comment: `#<algo> <env id> [<entry>]` (e.g. `#sac Pendulum-v1`);
// without one it is PPO on CartPole-v1. The entry is read and translated, checked as
// `train --zoo` checks it (the zoo file untrusted), written as `zoo import` writes it, and the
// written text is read back as `rlrun train FILE` reads it.
// Refusing is fine (ConfigError, UsageError, RuntimeFailure: a message naming the zoo file's
// line). Bugs: a crash, a sanitizer report, a hang, any other exception; and written text that
// holds a raw control character other than newlines, a section the import does not write (such
// as `plugins`), or that does not read back as exactly the experiment it was written from (the
// tree, and the resolved config of the checked experiment).
// Left out: envs that start a process to learn their spaces (python:, gymnasium:, the traffic
// envs) are translated and written but not checked, and what fuzz_limits.hpp says.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "../tests/core/yaml_tree.hpp"
#include "fuzz_limits.hpp"
#include "private_file.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/workflows/zoo/experiment_text.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_import.hpp"

using namespace rlrun;

namespace {

struct Selection {
  std::string algorithm = "ppo";
  std::string env_id = "CartPole-v1";
  std::string entry;  // "" : the env's own entry, else `default`
};

// Envs whose spaces are known without starting a process: these are checked too.
const std::set<std::string> kCheckedEnvs{"CartPole-v1",
                                         "Pendulum-v1",
                                         "Acrobot-v1",
                                         "MountainCar-v0",
                                         "MountainCarContinuous-v0",
                                         "BitFlippingEnv-v0",
                                         "LunarLander-v3",
                                         "LunarLander-v2",
                                         "IdentityEnv-v0",
                                         "IdentityEnvBox-v0"};

Selection selection(const std::string& text) {
  Selection s;
  if (text.empty() || text[0] != '#') return s;
  std::istringstream line(text.substr(
      1, text.find('\n') == std::string::npos ? std::string::npos : text.find('\n') - 1));
  std::string algorithm, env, entry;
  line >> algorithm >> env >> entry;
  if (!algorithm.empty()) s.algorithm = algorithm;
  if (!env.empty()) s.env_id = env;
  s.entry = entry;
  return s;
}

[[noreturn]] void fail(const std::string& what, const std::string& written) {
  std::fprintf(stderr, "%s\n--- written:\n%s\n", what.c_str(), written.c_str());
  std::abort();
}

void check_written(const std::string& written, const YAML::Node& tree) {
  for (const char c : written)
    if ((static_cast<unsigned char>(c) < 0x20 && c != '\n') || c == '\r')
      fail("a raw control character in the written file", written);
  const ConfigNode reread = ConfigNode::load_string(written, "imported.yaml");
  for (const std::string& key : reread.keys())
    if (key != "run" && key != "env" && key != "algo" && key != "eval" && key != "checkpoint")
      fail("the written file has a section '" + key + "'", written);
  if (!rlrun::testing::same_yaml_tree(reread.yaml(), tree))
    fail("the written file reads back differently", written);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const Selection pick = selection(text);
  const std::string& path = fuzz::private_file("zoo", "hyperparams.yml");
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
  const Registry& registry = builtin_registry();
  zoo::ZooImport imported;
  std::string written;
  try {
    imported = zoo::translate_zoo_entry(
        zoo::read_zoo_entry(path, pick.env_id, pick.algorithm, pick.entry), registry);
    written = zoo::experiment_text(imported);
  } catch (const ConfigError&) {
    return 0;
  } catch (const UsageError&) {
    return 0;
  }
  check_written(written, zoo::experiment_tree(imported));
  if (!kCheckedEnvs.count(imported.source.env_id) ||
      !fuzz::fuzzable_config(ConfigNode::from_yaml(imported.experiment, path)))
    return 0;
  std::string resolved;
  try {
    resolved = dump_yaml(zoo::check_zoo_experiment(imported, {}, registry).resolved);
  } catch (const ConfigError&) {
    return 0;
  } catch (const UsageError&) {
    return 0;
  } catch (const RuntimeFailure&) {
    return 0;
  }
  // Accepted as the zoo file's: the written file, now the user's own, is the same experiment.
  try {
    const Experiment again =
        parse_experiment(ConfigNode::load_string(written, "imported.yaml"), registry);
    if (dump_yaml(again.resolved) != resolved)
      fail("the written file resolves differently:\n" + dump_yaml(again.resolved) +
               "\n--- checked:\n" + resolved,
           written);
  } catch (const std::exception& e) {
    fail(std::string("the written file does not parse again: ") + e.what(), written);
  }
  return 0;
}
