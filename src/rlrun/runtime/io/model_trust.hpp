#pragma once
// `--trust` (eval, record, export) and `rlrun.load(path, trust=True)`: the user accepts a model
// file's config as a whole for one command, instead of vouching with a --set (or --plugin) for
// each env id that names Python code, interpreter, program, scenario or output file, and
// plugin library it names. The config is then read as ConfigTrust::kAccepted: every such value
// is printed on stderr before rlrun runs or opens it (core/trusted_values.hpp), and rlrun
// runs what the file says. Without --trust a refusal names both ways (docs/security.md,
// "Vouching for a value").
#include <string>

#include "rlrun/core/config_node.hpp"
#include "rlrun/runtime/components/registry.hpp"

namespace rlrun {

struct ModelTrust {
  bool accepted = false;  // --trust given
  std::string option;     // how the command spells it ("--trust", "trust=True"); "" = none
  ConfigTrust config_trust() const {
    return accepted ? ConfigTrust::kAccepted : ConfigTrust::kUntrusted;
  }
};

// With trust accepted and the model's env id unknown to `registry`: loads the plugin libraries
// its config lists (`plugins:`, absolute paths as training wrote them), each printed first, as
// --plugin would. Otherwise does nothing (nothing is read without trust). Throws
// RuntimeFailure for a damaged model file, UsageError for a library that does not load.
void load_accepted_plugins(const std::string& model_path, const ModelTrust& trust,
                           Registry& registry);

}  // namespace rlrun
