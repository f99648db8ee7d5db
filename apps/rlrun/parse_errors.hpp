#pragma once
// Command-line mistakes said the way rlrun says errors, where CLI11's own words mislead:
//
//   rlrun trian ...            CLI11: "A subcommand is required"
//                              here:  "unknown command 'trian'; did you mean 'train'?"
//   rlrun sweep s.yaml -x DIR  CLI11 2.1: "The following arguments were not expected: DIR -x"
//                              (its ExtrasError joins them in reverse order)
//                              here:  "rlrun sweep: unexpected arguments: -x DIR"
//
// Other parse errors keep CLI11's message.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace rlrun::cli {

// The message for `error` raised while `app` (rlrun's top-level app) parsed argv, or nullopt
// when CLI11's own message is the right one.
std::optional<std::string> describe_parse_error(const CLI::App& app, const CLI::ParseError& error,
                                                int argc, char** argv);

}  // namespace rlrun::cli
