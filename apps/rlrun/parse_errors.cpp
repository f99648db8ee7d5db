#include "parse_errors.hpp"

#include <vector>

#include "rlrun/core/config_node.hpp"

namespace rlrun::cli {

namespace {

std::vector<std::string> command_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  return names;
}

std::string joined(const std::vector<std::string>& words, const std::string& separator) {
  std::string text;
  for (const std::string& word : words) {
    if (!text.empty()) text += separator;
    text += word;
  }
  return text;
}

// The first word of argv that is neither an option nor the value of the global --threads:
// what the user meant as the command.
std::optional<std::string> first_word(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--threads") {
      ++i;  // its value
      continue;
    }
    if (!arg.empty() && arg[0] == '-') continue;
    return arg;
  }
  return std::nullopt;
}

// The command line's deepest parsed subcommand, and its path as typed ("rlrun sweep run").
const CLI::App* deepest_command(const CLI::App& app, std::string& path) {
  const CLI::App* at = &app;
  path = "rlrun";
  while (!at->get_subcommands().empty()) {
    at = at->get_subcommands().front();
    path += " " + at->get_name();
  }
  return at;
}

// `rlrun sweep rnu m.yaml`: the word after a command that has commands of its own, when it
// is a near miss of one of them ("" otherwise).
std::string mistyped_subcommand(const CLI::App& command, int argc, char** argv) {
  const std::vector<std::string> names = command_names(command);
  if (names.empty()) return "";
  int at = 1;
  while (at < argc && command.get_name() != argv[at]) ++at;
  for (++at; at < argc; ++at) {
    const std::string word = argv[at];
    if (word.empty() || word[0] == '-') continue;
    const std::string close = closest_name(word, names);
    if (close.empty() || close == word) return "";
    return "unknown command '" + word + "'; did you mean '" + close + "'?";
  }
  return "";
}

}  // namespace

std::optional<std::string> describe_parse_error(const CLI::App& app, const CLI::ParseError& error,
                                                int argc, char** argv) {
  const std::vector<std::string> commands = command_names(app);
  if (app.get_subcommands().empty() && (dynamic_cast<const CLI::RequiredError*>(&error) ||
                                        dynamic_cast<const CLI::ExtrasError*>(&error))) {
    const std::optional<std::string> word = first_word(argc, argv);
    if (!word)
      return "a command is required: " + joined(commands, ", ") + " (rlrun --help says more)";
    const std::string close = closest_name(*word, commands);
    return "unknown command '" + *word + "'; " +
           (close.empty() ? "the commands are " + joined(commands, ", ")
                          : "did you mean '" + close + "'?");
  }
  if (dynamic_cast<const CLI::ExtrasError*>(&error)) {
    // Every level's leftovers in the order they were typed (ExtrasError joins them reversed);
    // an unknown option given after a subcommand is left over at its parent (fallthrough).
    std::string path;
    const CLI::App* command = deepest_command(app, path);
    const std::string mistyped = mistyped_subcommand(*command, argc, argv);
    if (!mistyped.empty()) return path + ": " + mistyped;
    const std::vector<std::string> extras = app.remaining(true);
    if (extras.empty()) return std::nullopt;
    return path + ": unexpected " +
           (extras.size() == 1 ? "argument '" + extras.front() + "'"
                               : "arguments: " + joined(extras, " ")) +
           " (" + path + " --help lists its options)";
  }
  return std::nullopt;
}

}  // namespace rlrun::cli
