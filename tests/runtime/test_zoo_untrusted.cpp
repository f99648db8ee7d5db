// rl-zoo hyperparameter files are data from anyone (docs/security.md, docs/zoo.md): what a
// crafted one can and cannot do to `rlrun zoo import` and `rlrun train --zoo`. Its text cannot
// add lines or keys to the written experiment (a `plugins:` line would load a library when the
// user trains the file), its env_kwargs cannot name a program to run, a file to write or a
// scenario unless the user's own `--set` vouches, and its size or nesting cannot make an error
// message hundreds of kilobytes long.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "core/yaml_tree.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/workflows/zoo/experiment_text.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_import.hpp"
#include "runtime/cli_runner.hpp"
#include "runtime/marker_library.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

std::string write_file(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// What the written file must be: no raw control character but newlines, the sections the
// import writes and no others, and read back (as `rlrun train FILE` reads it) the tree it was
// written from.
void check_written(const zoo::ZooImport& imported) {
  const std::string text = zoo::experiment_text(imported);
  INFO(text);
  CHECK(std::none_of(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) < 0x20 && c != '\n') || c == 0x7f;
  }));
  const ConfigNode reread = ConfigNode::load_string(text, "written.yaml");
  for (const std::string& key : reread.keys())
    CHECK((key == "run" || key == "env" || key == "algo" || key == "eval" || key == "checkpoint"));
  CHECK_FALSE(reread.has("plugins"));
  CHECK(same_yaml_tree(reread.yaml(), zoo::experiment_tree(imported)));
}

// Text that would end a comment, start a line, a key, a document, a merge or a flow collection
// in YAML (plain, or to a reader that breaks lines at \r, NEL or U+2028), or clear a terminal.
const std::vector<std::string> kHostile{"x\nplugins: [/tmp/evil.so]\n#",
                                        "x\rplugins: [/tmp/evil.so]",
                                        "x\r\nplugins: [e.so]",
                                        "x\xc2\x85plugins: [e.so]",
                                        "x\xe2\x80\xa8plugins: [e.so]",
                                        "# comment",
                                        "---",
                                        "...",
                                        "--- !!python/object/apply:os.system ['id']",
                                        "a: b",
                                        "[x]",
                                        "{a: 1}",
                                        "'",
                                        "\"",
                                        "\x1b[2J",
                                        "<<",
                                        "null",
                                        "~",
                                        "",
                                        " lead",
                                        "\t",
                                        "*alias",
                                        "&anchor",
                                        "!tag",
                                        "%YAML 1.1",
                                        "|",
                                        ">",
                                        "x\x7f"};

}  // namespace

TEST_CASE("zoo import: text from the zoo file cannot add lines or keys to the written file",
          "[zoo][security]") {
  TempDir dir("zoo_injection");
  Registry registry = make_builtin_registry();
  for (const std::string& hostile : kHostile) {
    INFO("hostile text: " + hostile);
    const std::string q = yaml_double_quoted(hostile);
    // A Python literal's string has no escapes and ends at its quote.
    const std::string replay_buffer_kwargs =
        hostile.find_first_of("'\\") == std::string::npos
            ? "  replay_buffer_kwargs: " +
                  yaml_double_quoted("{'" + hostile + "': '" + hostile + "'}") + "\n"
            : "";
    // In class names (they reach the header's notes), entry names, env_kwargs and
    // replay_buffer_kwargs keys and values (they reach the experiment).
    const std::string file =
        write_file(dir / "dqn.yml",
                   "CartPole-v1:\n"
                   "  n_timesteps: 1000\n"
                   "  policy: 'MlpPolicy'\n"
                   "  env_wrapper:\n"
                   "    - " +
                       yaml_double_quoted(hostile + ".TimeLimit") +
                       ": {max_episode_steps: 900}\n"
                       "  callback:\n"
                       "    - " +
                       yaml_double_quoted(hostile + ".CheckpointCallback") +
                       ":\n"
                       "        save_freq: 100\n"
                       "        save_path: " +
                       q +
                       "\n"
                       "  env_kwargs: {" +
                       q + ": " + q + ", k: [" + q + "]}\n" + replay_buffer_kwargs + q +
                       ":\n  n_timesteps: 10\n  policy: 'MlpPolicy'\n");
    const zoo::ZooImport imported =
        zoo::translate_zoo_entry(zoo::read_zoo_entry(file, "CartPole-v1", ""), registry);
    CHECK(imported.notes.size() == 2);  // TimeLimit above the registered limit, save_path
    check_written(imported);
    // The entry named on the command line, and env ids (the command line's).
    if (!hostile.empty())
      check_written(zoo::translate_zoo_entry(zoo::read_zoo_entry(file, "CartPole-v1", "", hostile),
                                             registry));
    const std::string no_entry = write_file(dir / "ppo.yml", "default:\n  n_timesteps: 10\n");
    check_written(zoo::translate_zoo_entry(zoo::read_zoo_entry(no_entry, hostile, ""), registry));
  }
}

TEST_CASE("zoo import: a class name cannot add a plugins line that `rlrun train` then loads",
          "[zoo][security][cli]") {
  TempDir dir("zoo_injection_cli");
  const std::string marker = dir / "code_ran";
  build_marker_library(dir, marker);
  const std::string file = write_file(dir / "dqn.yml",
                                      "CartPole-v1:\n"
                                      "  n_timesteps: 1000\n"
                                      "  policy: 'MlpPolicy'\n"
                                      "  callback:\n"
                                      "    - \"x\\nplugins: [" +
                                          dir / "libevil.so" +
                                          "]\\n#.CheckpointCallback\":\n"
                                          "        save_freq: 100\n"
                                          "        save_path: logs\n");
  const std::string written = dir / "cartpole_dqn.yaml";
  const auto imported = run_rlrun("zoo import " + file + " CartPole-v1 -o " + written);
  INFO(imported.output);
  REQUIRE(imported.exit_code == 0);
  INFO(read_text(written));
  CHECK(read_text(written).find("\nplugins:") == std::string::npos);
  const auto trained =
      run_rlrun("train " + written + " --timesteps 64 --set eval.freq=0 --out " + dir.str());
  INFO(trained.output);
  CHECK(trained.exit_code == 0);
  CHECK_FALSE(fs::exists(marker));
}

TEST_CASE("zoo files name no program, output file or scenario without the user's --set",
          "[zoo][security][cli]") {
  TempDir dir("zoo_trust");
  const std::string marker = dir / "code_ran";
  // A script that would leave the marker, then run SUMO (so a vouched run works).
  write_file(dir / "evil.sh", "#!/bin/sh\ntouch " + marker + "\nexec sumo \"$@\"\n");
  fs::permissions(dir / "evil.sh", fs::perms::owner_all);
  const std::string elsewhere = dir / "elsewhere/x.xml";
  fs::create_directories(dir / "elsewhere");
  write_file(dir / "evil.sumocfg", "<configuration/>\n");
  const std::string entry =
      "TrafficSignal-v0:\n  n_timesteps: 20\n  policy: 'MlpPolicy'\n"
      "  learning_starts: 10\n  env_kwargs:\n";
  const std::string sumo_binary =
      write_file(dir / "dqn.yml", entry + "    sumo_binary: " + dir / "evil.sh\n");
  fs::create_directories(dir / "tripinfo");
  const std::string tripinfo =
      write_file(dir / "tripinfo/dqn.yml", entry + "    tripinfo_output: " + elsewhere + "\n");
  fs::create_directories(dir / "scenario");
  const std::string scenario =
      write_file(dir / "scenario/dqn.yml", entry + "    scenario: " + dir / "evil.sumocfg\n");
  const std::string train =
      "train --set eval.freq=0 --out " + dir / "runs" + " --env TrafficSignal-v0 --zoo ";
  const std::string import = " TrafficSignal-v0 -o " + dir / "imported.yaml";
  const std::vector<std::pair<std::string, std::string>> cases{
      {sumo_binary, "env.kwargs.sumo_binary: a program to run"},
      {tripinfo, "env.kwargs.tripinfo_output: an output file"},
      {scenario, "env.kwargs.scenario: a simulator input file"}};
  for (const auto& [file, message] : cases) {
    INFO(file);
    for (const std::string& command : {train + file, "zoo import " + file + import}) {
      const auto r = run_rlrun(command);
      INFO(r.output);
      CHECK(r.exit_code == 2);
      CHECK_THAT(r.output, Catch::Contains(file + ":6:") && Catch::Contains(message) &&
                               Catch::Contains("zoo files") &&
                               Catch::Contains("--set env.kwargs."));
    }
  }
  CHECK_FALSE(fs::exists(marker));
  CHECK_FALSE(fs::exists(elsewhere));
  CHECK_FALSE(fs::exists(dir / "imported.yaml"));

  // The user's --set vouches: train runs the named program, import writes the value.
  setenv("SUMO_HOME", "/usr/share/sumo", 0);
  const auto vouched =
      run_rlrun(train + sumo_binary + " --set env.kwargs.sumo_binary=" + dir / "evil.sh");
  INFO(vouched.output);
  CHECK(vouched.exit_code == 0);
  CHECK(fs::exists(marker));
  const auto written = run_rlrun("zoo import " + tripinfo + import +
                                 " --set env.kwargs.tripinfo_output=" + elsewhere);
  INFO(written.output);
  REQUIRE(written.exit_code == 0);
  const std::string text = read_text(dir / "imported.yaml");
  CHECK_THAT(text,
             Catch::Contains("tripinfo_output: " + elsewhere) &&
                 Catch::Contains("# Set on the command line: --set env.kwargs.tripinfo_output="));
}

TEST_CASE("zoo files: deep nesting and long text give a short error, not a 200 KB line",
          "[zoo][security]") {
  TempDir dir("zoo_bounds");
  Registry registry = make_builtin_registry();
  const std::string head = "CartPole-v1:\n  n_timesteps: 1000\n  policy: 'MlpPolicy'\n";
  auto error = [&](const std::string& body) {
    const std::string file = write_file(dir / "ppo.yml", head + body);
    try {
      zoo::load_zoo_experiment(file, "CartPole-v1", "", {}, registry);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  auto longest_line = [](const std::string& text) {
    std::size_t longest = 0, start = 0;
    while (start <= text.size()) {
      const std::size_t end = std::min(text.find('\n', start), text.size());
      longest = std::max(longest, end - start);
      start = end + 1;
    }
    return longest;
  };
  const std::string deep_literal = error("  policy_kwargs: \"" + std::string(60000, '[') + "\"\n");
  CHECK_THAT(deep_literal, Catch::Contains("nested too deeply"));
  CHECK(deep_literal.size() < 1000);
  std::string nested = "1";
  for (int i = 0; i < 100; ++i) nested = "{a: " + nested + "}";
  const std::string deep_yaml = error("  env_kwargs: " + nested + "\n");
  CHECK_THAT(deep_yaml,
             Catch::Contains("ppo.yml:") && Catch::Contains("nests deeper than 16 levels"));
  CHECK(deep_yaml.size() < 1000);
  const std::string long_key = error("  ? " + std::string(60000, 'k') + "\n  : 1\n");
  CHECK_THAT(long_key, Catch::Contains("no hyperparameter"));
  CHECK(longest_line(long_key) <= 1000);
  const std::string lines = error("  policy: \"" + std::string(50000, '\x1b') + "\"\n");
  CHECK(lines.size() < 2000);
  // Aliases that repeat a value many times: the entry's text is bounded with them expanded.
  std::string many = "  env_kwargs: {";
  for (int i = 0; i < 2000; ++i) many += (i ? ", k" : "k") + std::to_string(i) + ": *big";
  const std::string aliased = error("  big: &big " + std::string(1000, 'b') + "\n" + many + "}\n");
  CHECK_THAT(aliased, Catch::Contains("more than 64 KiB"));
}
