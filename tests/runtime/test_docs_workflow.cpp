// docs/workflow.md promises that every YAML snippet on it runs as written. This test keeps
// that promise: each ```yaml block is put into configs/cartpole_ppo.yaml (its top-level
// sections replace the file's sections of the same name, as the page tells readers to do)
// and trained for 2048 steps with the real binary. A renamed key or wrapper parameter then
// fails here instead of in a reader's terminal.
#include <yaml-cpp/yaml.h>
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

const std::string kSource = RLRUN_SOURCE_DIR;

// The bodies of the ```yaml fenced blocks of a Markdown file, in order.
std::vector<std::string> yaml_blocks(const std::string& markdown_path) {
  std::ifstream in(markdown_path);
  std::vector<std::string> blocks;
  std::string line, block;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!inside && line.rfind("```yaml", 0) == 0) {
      inside = true;
      block.clear();
    } else if (inside && line.rfind("```", 0) == 0) {
      inside = false;
      blocks.push_back(block);
    } else if (inside) {
      block += line + "\n";
    }
  }
  return blocks;
}

// The output a section should leave in the run directory, so that a snippet that parses but
// never fires (e.g. a freq above the test's 2048 steps) is noticed too.
std::vector<std::string> expected_outputs(const YAML::Node& snippet) {
  std::vector<std::string> out{"model.zip"};
  if (snippet["eval"]) out.push_back("evaluations.csv");
  if (snippet["checkpoint"]) out.push_back("checkpoints");
  if (snippet["obs_log"]) out.push_back("obs_log");
  if (snippet["video"]) out.push_back("videos");
  return out;
}

}  // namespace

TEST_CASE("docs/workflow.md: every YAML example trains", "[cli][docs]") {
  const std::vector<std::string> blocks = yaml_blocks(kSource + "/docs/workflow.md");
  REQUIRE(blocks.size() >= 15);  // 6 callback and 12 wrapper examples when this was written
  TempDir dir("docs_workflow");
  for (size_t i = 0; i < blocks.size(); ++i) {
    INFO("example " << i + 1 << ":\n" << blocks[i]);
    const YAML::Node snippet = YAML::Load(blocks[i]);
    REQUIRE(snippet.IsMap());
    YAML::Node config = YAML::LoadFile(kSource + "/configs/cartpole_ppo.yaml");
    for (const auto& section : snippet) config[section.first.as<std::string>()] = section.second;
    config["run"]["name"] = "example" + std::to_string(i + 1);
    const std::string path = dir / ("example" + std::to_string(i + 1) + ".yaml");
    {
      std::ofstream out(path);
      out << YAML::Dump(config) << "\n";
    }
    const auto r =
        run_rlrun("--threads 1 train " + path + " --timesteps 2048 --out " + dir / "runs");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const std::string run_dir = dir / ("runs/example" + std::to_string(i + 1) + "/seed1");
    for (const std::string& file : expected_outputs(snippet)) {
      INFO(file);
      CHECK(fs::exists(run_dir + "/" + file));
    }
  }
}
