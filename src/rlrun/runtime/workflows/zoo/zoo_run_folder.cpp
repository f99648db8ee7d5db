#include "rlrun/runtime/workflows/zoo/zoo_run_folder.hpp"

#include <fcntl.h>

#include <cctype>
#include <filesystem>
#include <stdexcept>

#include "rlrun/core/config_node.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/quoted_text.hpp"
#include "rlrun/core/regular_file.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_file.hpp"

namespace rlrun::zoo {

namespace {

// "CartPole-v1_1" -> "CartPole-v1"; "" when the name does not end in _<digits>.
std::string env_of_folder_name(const std::string& name) {
  const auto underscore = name.rfind('_');
  if (underscore == std::string::npos || underscore == 0 || underscore + 1 == name.size())
    return "";
  for (size_t i = underscore + 1; i < name.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(name[i]))) return "";
  return name.substr(0, underscore);
}

// The zoo's hyperparameters that change the env the model saw and that rlrun does not apply to
// an SB3 file (the observation check then refuses a model they changed). The file is the
// zoo's yaml.dump of an OrderedDict: `!!python/object/apply:collections.OrderedDict` over the
// call's one argument, a list of [key, value] pairs; read as untrusted text
// (core/config_node.hpp's bounds), never through a link.
std::vector<std::string> unapplied_settings(const std::string& config_file) {
  std::vector<std::string> notes;
  ConfigNode root;
  try {
    const FileDescriptor fd = open_regular_file(AT_FDCWD, config_file, O_RDONLY, config_file);
    if (!fd) return notes;
    root = ConfigNode::load_string(read_bounded(fd.get(), kMaxConfigBytes, config_file),
                                   config_file, ConfigTrust::kUntrusted);
  } catch (const std::runtime_error&) {  // a link, a FIFO, too long, not YAML
    return {"note: " + config_file + " is not a file rlrun reads; its settings are unread"};
  }
  if (!root.is_sequence() || root.size() != 1 || !root.at(0).is_sequence()) return notes;
  const ConfigNode pairs = root.at(0);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const ConfigNode pair = pairs.at(i);
    if (!pair.is_sequence() || pair.size() != 2 || !pair.at(0).is_scalar()) continue;
    const std::string key = pair.at(0).yaml().Scalar();
    const YAML::Node value = pair.at(1).yaml();
    if ((key == "env_wrapper" || key == "frame_stack") && value.IsDefined() && !value.IsNull())
      notes.push_back("note: " + config_file + " sets " + key +
                      ", which rlrun does not apply to SB3 model files yet (docs/sb3_models.md)");
  }
  return notes;
}

}  // namespace

ZooRunFolder find_zoo_run_folder(const std::string& dir, bool best) {
  std::filesystem::path folder(dir);
  if (folder.filename().empty()) folder = folder.parent_path();  // a trailing '/'
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec))
    throw UsageError("--zoo-model " + quoted_text(dir) + ": no such directory");
  const std::string zoo_env = env_of_folder_name(folder.filename().string());
  if (zoo_env.empty())
    throw UsageError("--zoo-model " + quoted_text(dir) +
                     ": a zoo run folder is named <env>_<n> (e.g. ppo/CartPole-v1_1)");
  ZooRunFolder out;
  const std::filesystem::path model = folder / (best ? "best_model.zip" : zoo_env + ".zip");
  if (!std::filesystem::is_regular_file(model, ec))
    throw UsageError("--zoo-model " + quoted_text(dir) + ": no " + model.filename().string() +
                     " in it");
  out.model_path = model.string();
  out.env_id = current_env_id(zoo_env);
  out.notes = unapplied_settings((folder / zoo_env / "config.yml").string());
  return out;
}

}  // namespace rlrun::zoo
