#pragma once
// The experiment file `rlrun zoo import` writes: a header comment (where the experiment came
// from, notes) and the experiment, both through yaml-cpp's emitter, never by pasting text
// together, because the zoo file may come from anyone (docs/security.md). Its text cannot add
// lines or keys to the written file: each comment line is quoted_text (escapes visible, one
// line), each key and value an emitted scalar, double-quoted wherever a plain scalar would
// change on reading (a control character: yaml-cpp 0.7 writes a carriage return raw in a plain
// scalar, which YAML readers take as a line break; the merge key `<<`), and everything past
// ASCII escaped. The text reads back as exactly experiment_tree() (tests/runtime/
// test_zoo_untrusted.cpp, fuzz/fuzz_zoo.cpp).
#include <string>

#include <yaml-cpp/yaml.h>

#include "rlrun/runtime/workflows/zoo/zoo_import.hpp"

namespace rlrun::zoo {

// The experiment as written: sections run, env, algo, eval and checkpoint in that order, without
// the zoo file's tags (!!float) and aliases, counts as integers, lists in flow style.
YAML::Node experiment_tree(const ZooImport& imported);

// The file's text. Throws ConfigError when it would be larger than rlrun reads an experiment
// file (kMaxConfigBytes; aliases in the zoo file can repeat a value many times).
std::string experiment_text(const ZooImport& imported);

}  // namespace rlrun::zoo
