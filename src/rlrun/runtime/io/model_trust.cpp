#include "rlrun/runtime/io/model_trust.hpp"

#include "rlrun/core/errors.hpp"
#include "rlrun/core/trusted_values.hpp"
#include "rlrun/runtime/components/plugin_loader.hpp"
#include "rlrun/runtime/io/model_file.hpp"
#include "rlrun/runtime/io/sb3/sb3_model_file.hpp"

namespace rlrun {

void load_accepted_plugins(const std::string& model_path, const ModelTrust& trust,
                           Registry& registry) {
  // An SB3 file names no plugin (runtime/io/sb3/sb3_model_file.hpp): nothing to load.
  if (!trust.accepted || is_sb3_model_file(model_path)) return;
  const ModelFile header = read_model_header(model_path);  // meta.json and config.yaml, bounded
  ConfigNode root;
  try {
    root = ConfigNode::load_string(header.config_yaml, model_path + ":config.yaml",
                                   ConfigTrust::kAccepted);
  } catch (const ConfigError&) {
    return;  // load_model reports what is wrong with the config
  }
  root.set_trust_option(trust.option);
  const ConfigNode id = root.child("env").child("id");
  const ConfigNode plugins = root.child("plugins");
  if (!id.is_scalar() || registry.find_env(id.yaml().Scalar()) || !plugins.is_sequence()) return;
  for (std::size_t i = 0; i < plugins.size(); ++i) {
    const std::string path = plugins.at(i).as_string();
    require_vouched(plugins.at(i), "a plugin library rlrun loads (it runs the library's code)",
                    path);
    load_plugin(path, registry);
  }
}

}  // namespace rlrun
