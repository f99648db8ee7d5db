#pragma once
// `--trust`, shared by the subcommands that read a model file (eval, record, export): accept
// what the model's config names for this command, each value printed on stderr first
// (runtime/io/model_trust.hpp). Without it, a refusal names --trust beside the --set that vouches
// for the one value.
#include <CLI/CLI.hpp>

#include "rlrun/runtime/io/model_trust.hpp"

namespace rlrun::cli {

inline constexpr const char* kTrustOption = "--trust";

inline CLI::Option* add_trust_option(CLI::App* sub, bool& trust) {
  return sub->add_flag(kTrustOption, trust,
                       "run what the model file names (its env id's Python code, interpreter, "
                       "SUMO binary, scenario files, plugins) for this command: each is printed "
                       "on stderr first; without it each needs a --set (docs/security.md)");
}

// With --trust: the model's plugin libraries loaded (printed first) when its env needs them.
inline ModelTrust model_trust(bool trust, const std::string& model_path, Registry& registry) {
  const ModelTrust accepted{trust, kTrustOption};
  load_accepted_plugins(model_path, accepted, registry);
  return accepted;
}

}  // namespace rlrun::cli
