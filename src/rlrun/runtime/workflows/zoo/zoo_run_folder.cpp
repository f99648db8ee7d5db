#include "rlrun/runtime/workflows/zoo/zoo_run_folder.hpp"

#include <fcntl.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>

#include "rlrun/core/config_node.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/quoted_text.hpp"
#include "rlrun/core/regular_file.hpp"
#include "rlrun/runtime/io/sb3/rl_zoo_folder_name.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_file.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_wrappers.hpp"

namespace rlrun::zoo {

namespace {

// rl-zoo's `frame_stack: N`: VecFrameStack over the whole stack, as FrameStack's sb3 layout
// (wrappers/frame_stack.hpp), last in env.wrappers. Not with VecNormalize statistics: rl-zoo
// stacks normalised observations (VecFrameStack outside VecNormalize), and rlrun's
// env.normalize sits outside its wrappers (as `rlrun zoo import` refuses the same).
void add_frame_stack(const ConfigNode& value, bool normalized, const std::string& config_file,
                     ZooRunFolder& folder) {
  if (normalized) {
    folder.notes.push_back("note: " + config_file +
                           " sets frame_stack over VecNormalize's statistics, which rlrun does "
                           "not apply (it would stack before normalising; docs/sb3_models.md)");
    return;
  }
  int n_stack = 0;
  if (!value.is_scalar() || !YAML::convert<int>::decode(value.yaml(), n_stack) || n_stack < 1 ||
      n_stack > 1000) {
    folder.notes.push_back("note: " + config_file +
                           ": frame_stack is not a number of frames (1-1000); not applied");
    return;
  }
  YAML::Node wrapper(YAML::NodeType::Map);
  wrapper["id"] = "FrameStack";
  wrapper["n_stack"] = n_stack;
  wrapper["layout"] = "sb3";
  folder.env_section["wrappers"].push_back(wrapper);
}

// The zoo's hyperparameters that change the env the model saw: env_wrapper is translated into
// `folder.env_section` as `rlrun zoo import` translates it, frame_stack by add_frame_stack. The
// file is the zoo's yaml.dump of an OrderedDict: `!!python/object/apply:collections.OrderedDict`
// over the call's one argument, a list of [key, value] pairs; read as untrusted text
// (core/config_node.hpp's bounds), never through a link.
void read_zoo_config(const std::string& config_file, int registered_limit, bool normalized,
                     ZooRunFolder& folder) {
  ConfigNode root;
  try {
    const FileDescriptor fd = open_regular_file(AT_FDCWD, config_file, O_RDONLY, config_file);
    if (!fd) return;
    root = ConfigNode::load_string(read_bounded(fd.get(), kMaxConfigBytes, config_file),
                                   config_file, ConfigTrust::kUntrusted);
  } catch (const std::runtime_error&) {  // a link, a FIFO, too long, not YAML
    folder.notes.push_back("note: " + config_file +
                           " is not a file rlrun reads; its settings are unread");
    return;
  }
  if (!root.is_sequence() || root.size() != 1 || !root.at(0).is_sequence()) return;
  const ConfigNode pairs = root.at(0);
  ConfigNode frame_stack;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const ConfigNode pair = pairs.at(i);
    if (!pair.is_sequence() || pair.size() != 2 || !pair.at(0).is_scalar()) continue;
    const std::string key = pair.at(0).yaml().Scalar();
    const ConfigNode value = pair.at(1);
    if (!value.defined()) continue;
    if (key == "frame_stack") {
      frame_stack = value;  // applied after env_wrapper's wrappers, as rl-zoo stacks last
    } else if (key == "env_wrapper") {
      try {
        translate_env_wrappers(value, folder.env_section, registered_limit, folder.notes);
      } catch (const ConfigError& e) {
        folder.notes.push_back(std::string("note: env_wrapper not applied: ") + e.what());
        folder.env_section = YAML::Node(YAML::NodeType::Map);
      }
    }
  }
  if (frame_stack.defined()) add_frame_stack(frame_stack, normalized, config_file, folder);
}

// rl_model_<N>_steps.zip -> N; 0 for any other name.
int64_t checkpoint_steps(const std::string& name) {
  const std::string prefix = "rl_model_", suffix = "_steps.zip";
  if (name.size() <= prefix.size() + suffix.size() || !name.starts_with(prefix) ||
      !name.ends_with(suffix))
    return 0;
  const std::string digits =
      name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.size() > 18) return 0;
  for (const char c : digits)
    if (!std::isdigit(static_cast<unsigned char>(c))) return 0;
  return std::stoll(digits);
}

// The file name of the chosen model in `folder`.
std::string chosen_model(const std::filesystem::path& folder, const std::string& zoo_env,
                         const ZooModelChoice& choice, const std::string& dir) {
  if (choice.best) return "best_model.zip";
  if (choice.checkpoint > 0) return "rl_model_" + std::to_string(choice.checkpoint) + "_steps.zip";
  if (!choice.last_checkpoint) return zoo_env + ".zip";
  int64_t last = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec))
    if (entry.is_regular_file(ec)) last = std::max(last, checkpoint_steps(entry.path().filename()));
  if (last == 0)
    throw UsageError("--zoo-model " + quoted_text(dir) +
                     ": --load-last-checkpoint finds no rl_model_<N>_steps.zip in it");
  return "rl_model_" + std::to_string(last) + "_steps.zip";
}

}  // namespace

ZooRunFolder find_zoo_run_folder(const std::string& dir, const ZooModelChoice& choice,
                                 const Registry& registry) {
  std::filesystem::path folder(dir);
  if (folder.filename().empty()) folder = folder.parent_path();  // a trailing '/'
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec))
    throw UsageError("--zoo-model " + quoted_text(dir) + ": no such directory");
  const std::string zoo_env = rl_zoo_folder_env(folder.filename().string());
  if (zoo_env.empty())
    throw UsageError("--zoo-model " + quoted_text(dir) +
                     ": a zoo run folder is named <env>_<n> (e.g. ppo/CartPole-v1_1)");
  ZooRunFolder out;
  const std::filesystem::path model = folder / chosen_model(folder, zoo_env, choice, dir);
  if (!std::filesystem::is_regular_file(model, ec))
    throw UsageError("--zoo-model " + quoted_text(dir) + ": no " + model.filename().string() +
                     " in it");
  out.model_path = model.string();
  out.env_id = current_env_id(zoo_env);
  out.env_section = YAML::Node(YAML::NodeType::Map);
  const EnvEntry* env = registry.find_env(out.env_id);
  const bool normalized = std::filesystem::exists(folder / zoo_env / "vecnormalize.pkl", ec);
  read_zoo_config((folder / zoo_env / "config.yml").string(), env ? env->max_episode_steps : 0,
                  normalized, out);
  return out;
}

}  // namespace rlrun::zoo
