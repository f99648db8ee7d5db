#pragma once
// Config values that make rlrun start a program, write a file, or hand a file to a simulator
// that may do either (a SUMO configuration can name output files). The user's own experiment
// files and `--set` values may set them freely. Text rlrun does not trust (the config.yaml
// inside a model file or checkpoint, a run directory's config.yaml, a sweep manifest's
// configs, a zoo hyperparameter file; docs/security.md) may not: there such a field must keep its default, and a
// SimulatorInput may also name a file shipped with rlrun. Anything else is refused with the
// `--set` that vouches for the value (or `--trust`, which accepts a model file's config as a
// whole and prints each such value), so opening a model file from elsewhere never runs code
// or writes outside the run unasked (docs/security.md; SB3's pickled model files do run code on
// load).
#include <string>

#include "rlrun/core/config_node.hpp"
#include "rlrun/core/shipped_data.hpp"

namespace rlrun {

// A program rlrun starts (e.g. the sumo binary).
struct ProgramPath {
  std::string value;
  bool operator==(const ProgramPath&) const = default;
};
// A file rlrun or a simulator writes besides the run directory's own files.
struct OutputPath {
  std::string value;
  bool operator==(const OutputPath&) const = default;
};
// A file handed to an external simulator (a traffic scenario: its SUMO configuration may name
// output files and more). Untrusted text may name only files inside shipped_data_dir().
struct SimulatorInput {
  std::string value;
  bool operator==(const SimulatorInput&) const = default;
};

// A value `n` holds that makes rlrun run code, start a program, or write or hand over a file;
// `what` says which ("a program to run"). Returns when the text is the user's own. When the
// user accepted the whole text (ConfigTrust::kAccepted, `--trust`), prints on stderr first
//   trusting <origin> (--trust): <path> = <value>: <what>
// (the value with control characters escaped, so the line shows exactly what will be used).
// Otherwise throws ConfigError saying how to vouch for it: `--set <path>=<value>`, and the
// text's trust option when the command has one.
void require_vouched(const ConfigNode& n, const std::string& what, const std::string& value);
// " Or pass --trust to accept everything <origin> names (each printed first)." when the text
// has a trust option, else "": for refusals that name another way to vouch (--plugin).
std::string trust_alternative(const ConfigNode& n);

// Each decode keeps `out` (the default) unless the node is trusted or the value is allowed.
void decode(const ConfigNode& n, ProgramPath& out);
void decode(const ConfigNode& n, OutputPath& out);
void decode(const ConfigNode& n, SimulatorInput& out);
inline YAML::Node encode(const ProgramPath& v) { return YAML::Node(v.value); }
inline YAML::Node encode(const OutputPath& v) { return YAML::Node(v.value); }
inline YAML::Node encode(const SimulatorInput& v) { return YAML::Node(v.value); }

}  // namespace rlrun
