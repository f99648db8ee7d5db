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

// The [key, value] pairs of a file rl-zoo writes with yaml.dump of an OrderedDict (config.yml,
// args.yml): `!!python/object/apply:collections.OrderedDict` over the call's one argument, a list
// of pairs. Read as untrusted text (core/config_node.hpp's bounds), never through a link; an
// undefined node when the file is absent or not of that form (a note says so when unreadable).
ConfigNode ordered_dict_pairs(const std::string& file, ZooRunFolder& folder) {
  ConfigNode root;
  try {
    const FileDescriptor fd = open_regular_file(AT_FDCWD, file, O_RDONLY, file);
    if (!fd) return {};
    root = ConfigNode::load_string(read_bounded(fd.get(), kMaxConfigBytes, file), file,
                                   ConfigTrust::kUntrusted);
  } catch (const std::runtime_error&) {  // a link, a FIFO, too long, not YAML
    folder.notes.push_back("note: " + file + " is not a file rlrun reads; its settings are unread");
    return {};
  }
  if (!root.is_sequence() || root.size() != 1 || !root.at(0).is_sequence()) return {};
  return root.at(0);
}

// Calls `use(key, value)` for each well-formed pair with a defined value.
template <class Use>
void for_each_pair(const ConfigNode& pairs, Use use) {
  if (!pairs.defined()) return;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const ConfigNode pair = pairs.at(i);
    if (!pair.is_sequence() || pair.size() != 2 || !pair.at(0).is_scalar()) continue;
    if (pair.at(1).defined()) use(pair.at(0).yaml().Scalar(), pair.at(1));
  }
}

// The zoo's hyperparameters that change the env the model saw (config.yml): env_wrapper is
// translated into `folder.env_section` as `rlrun zoo import` translates it, frame_stack by
// add_frame_stack.
void read_zoo_config(const std::string& config_file, int registered_limit, bool normalized,
                     ZooRunFolder& folder) {
  ConfigNode frame_stack;
  for_each_pair(ordered_dict_pairs(config_file, folder), [&](const std::string& key,
                                                             const ConfigNode& value) {
    if (key == "frame_stack") {
      frame_stack = value;  // applied after env_wrapper's, as rl-zoo stacks last
    } else if (key == "env_wrapper") {
      try {
        translate_env_wrappers(value, folder.env_section, registered_limit, folder.notes);
      } catch (const ConfigError& e) {
        folder.notes.push_back(std::string("note: env_wrapper not applied: ") + e.what());
        folder.env_section = YAML::Node(YAML::NodeType::Map);
      }
    }
  });
  if (frame_stack.defined()) add_frame_stack(frame_stack, normalized, config_file, folder);
}

// The env's keyword arguments the run was trained with (args.yml's env_kwargs, the command
// line's --env-kwargs), which rl_zoo3/enjoy.py passes to the env it evaluates: env.kwargs. They
// are the model's untrusted config like the rest (a value that names a program or file needs
// --set or --trust), and the env's own Config checks them.
void read_zoo_args(const std::string& args_file, ZooRunFolder& folder) {
  for_each_pair(
      ordered_dict_pairs(args_file, folder), [&](const std::string& key, const ConfigNode& value) {
        if (key != "env_kwargs" || value.yaml().IsNull()) return;
        if (!value.is_map()) {
          folder.notes.push_back("note: " + args_file + ": env_kwargs is not a map; not applied");
          return;
        }
        if (value.size() == 0) return;
        folder.env_section["kwargs"] = YAML::Clone(value.yaml());
        folder.notes.push_back("note: " + args_file +
                               ": its env_kwargs are the env's kwargs (env.kwargs), as "
                               "rl_zoo3.enjoy passes them");
      });
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
  read_zoo_args((folder / zoo_env / "args.yml").string(), out);
  return out;
}

}  // namespace rlrun::zoo
