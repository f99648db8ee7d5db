// The generated sweep.sbatch quotes every value (issue 15, item 8): an out_dir with blanks,
// quotes and $(...) stays one argument and runs nothing; slurm options with newlines or other
// text sbatch would misread are refused, in the sweep file and in a manifest.
#include <yaml-cpp/yaml.h>
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/workflows/sbatch_script.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

// One shell word for the test's own command lines (written here, not taken from rlrun, so a
// bug in rlrun's quoting cannot hide itself).
std::string sh(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\"'\"'") : std::string(1, c);
  return out + "'";
}

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A stand-in for rlrun at `path`: writes its arguments, one per line, to $ARGS_OUT.
void write_fake_binary(const std::string& path) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path) << "#!/bin/sh\nprintf '%s\\n' \"$@\" > \"$ARGS_OUT\"\n";
  fs::permissions(path, fs::perms::owner_all);
}

std::string base_config() { return std::string(RLRUN_SOURCE_DIR) + "/configs/cartpole_ppo.yaml"; }

}  // namespace

TEST_CASE("sweep slurm: an out_dir with blanks, quotes and $(...) is one argument and runs nothing",
          "[sweep]") {
  TempDir dir("sweep_sbatch_quote");
  const std::string out = dir / "out dir 'q' $(touch pwned) `touch pwned2` %A #x";
  std::ofstream(dir / "sweep.yaml")
      << "name: quoted\nbase: " << base_config() << "\nout_dir: \"" << out << "\"\nseeds: [1]\n"
      << "slurm: {time: \"00:05:00\", mem: 1G}\n";
  const auto expand =
      run_command("cd " + sh(dir.str()) + " && " + std::string(RLRUN_BINARY) + " sweep sweep.yaml");
  INFO(expand.output);
  REQUIRE(expand.exit_code == 0);
  const std::string manifest = out + "/manifest.yaml";
  REQUIRE(fs::exists(manifest));
  const auto slurm = run_rlrun("sweep slurm " + sh(manifest));
  INFO(slurm.output);
  REQUIRE(slurm.exit_code == 0);
  const std::string script_path = out + "/sweep.sbatch";
  const std::string script = read_text(script_path);
  INFO(script);

  // bash parses it; sbatch reads the --output path in its own quoting, % doubled.
  CHECK(run_command("bash -n " + sh(script_path)).exit_code == 0);
  CHECK(script.find("#SBATCH --output=\"" + dir.str() +
                    "/out dir 'q' $(touch pwned) `touch pwned2` %%A #x/slurm/\"%A_%a.out\n") !=
        std::string::npos);

  // Run the script's body with rlrun replaced by a stand-in that records its arguments.
  const std::string real = "'" + fs::canonical(RLRUN_BINARY).string() + "'";
  const size_t at = script.find("exec " + real + " ");
  REQUIRE(at != std::string::npos);
  const std::string fake = dir / "fake bin/rl'run $(touch pwned3)";
  write_fake_binary(fake);
  std::string test_script = script;
  test_script.replace(at + 5, real.size(), sh(fake));
  std::ofstream(dir / "task.sh") << test_script;
  const auto task =
      run_command("cd " + sh(dir.str()) + " && SLURM_ARRAY_TASK_ID=0 ARGS_OUT=" + sh(dir / "args") +
                  " bash task.sh");
  INFO(task.output);
  CHECK(task.exit_code == 0);
  CHECK(lines_of(dir / "args") ==
        std::vector<std::string>{"--threads", "1", "sweep", "run", manifest, "--index", "0"});
  for (const char* planted : {"pwned", "pwned2", "pwned3"}) {
    INFO(planted);
    CHECK_FALSE(fs::exists(dir / planted));
    CHECK_FALSE(fs::exists(fs::path(RLRUN_SOURCE_DIR) / planted));
  }
}

TEST_CASE("sweep: slurm values sbatch would misread are refused at the sweep file's line",
          "[sweep]") {
  TempDir dir("sweep_sbatch_values");
  const auto sweep_with = [&](const std::string& slurm) {
    std::ofstream(dir / "sweep.yaml")
        << "name: values\nbase: " << base_config() << "\nout_dir: " << dir / "out"
        << "\nseeds: [1]\nslurm:\n"
        << slurm;
    return run_rlrun("sweep " + dir / "sweep.yaml");
  };
  struct Case {
    std::string slurm, where, says;
  };
  const std::vector<Case> refused = {
      {"  time: \"00:10:00\\ntouch pwned\"\n", "sweep.yaml:6:9", "control character"},
      {"  mem: \"4G\\nrm -rf x\"\n", "sweep.yaml:6:8", "control character"},
      {"  extra: [\"--qos=short\\nid\"]\n", "sweep.yaml:6:11", "control character"},
      {"  extra: [\"--qos=short\", \"--qos short\"]\n", "sweep.yaml:6:26", "not one sbatch option"},
      {"  extra: [\"--comment=a#b\"]\n", "sweep.yaml:6:11", "not one sbatch option"},
      {"  time: \"1 hour\"\n", "sweep.yaml:6:9", "not a Slurm time limit"},
      {"  mem: 4 GB\n", "sweep.yaml:6:8", "not a Slurm memory size"},
      {"  partition: \"a b\"\n", "sweep.yaml:6:14", "not a Slurm partition name"},
      {"  cpus_per_task: 0\n", "sweep.yaml:6:18", "integer >= 1"},
  };
  for (const Case& c : refused) {
    const auto r = sweep_with(c.slurm);
    INFO(c.slurm << r.output);
    CHECK(r.exit_code == 2);
    CHECK(r.output.find(c.where) != std::string::npos);
    CHECK(r.output.find(c.says) != std::string::npos);
    CHECK(r.output.find("\ntouch") == std::string::npos);  // shown escaped, on one line
  }
  const auto fine = sweep_with(
      "  time: \"2-00:00:00\"\n  mem: 500M\n  partition: debug,long\n  cpus_per_task: 2\n"
      "  extra: [\"--qos=short\", \"--exclusive\", \"--gres=gpu:1\"]\n");
  INFO(fine.output);
  REQUIRE(fine.exit_code == 0);
  REQUIRE(run_rlrun("sweep slurm " + dir / "out/manifest.yaml").exit_code == 0);
  const std::string script = read_text(dir / "out/sweep.sbatch");
  CHECK(
      script.find("#SBATCH --time=2-00:00:00\n#SBATCH --mem=500M\n#SBATCH --partition=debug,long\n"
                  "#SBATCH --qos=short\n#SBATCH --exclusive\n#SBATCH --gres=gpu:1\nexec ") !=
      std::string::npos);
}

TEST_CASE("sweep: negative seeds are refused at their line, in a sweep file and a manifest",
          "[sweep]") {
  TempDir dir("sweep_seed_range");
  std::ofstream(dir / "sweep.yaml")
      << "name: seeds\nbase: " << base_config() << "\nout_dir: " << dir / "out"
      << "\nseeds: [1, -1]\n";
  const auto r = run_rlrun("sweep " + dir / "sweep.yaml");
  INFO(r.output);
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("sweep.yaml:4:12") != std::string::npos);
  CHECK(r.output.find("seeds are integers from 0 to 2^63 - 1, got -1") != std::string::npos);

  std::ofstream(dir / "sweep.yaml")
      << "name: seeds\nbase: " << base_config() << "\nout_dir: " << dir / "out"
      << "\nseeds: [1]\n";
  REQUIRE(run_rlrun("sweep " + dir / "sweep.yaml").exit_code == 0);
  const std::string manifest = dir / "out/manifest.yaml";
  YAML::Node node = YAML::LoadFile(manifest);
  node["runs"][0]["seed"] = -1;
  std::ofstream(manifest) << YAML::Dump(node) << "\n";
  const auto status = run_rlrun("sweep status " + manifest);
  INFO(status.output);
  CHECK(status.exit_code == 2);
  CHECK(status.output.find("seeds are integers from 0 to 2^63 - 1") != std::string::npos);
}

TEST_CASE("sweep slurm: a manifest carrying a newline in a slurm value is refused", "[sweep]") {
  TempDir dir("sweep_sbatch_manifest");
  std::ofstream(dir / "sweep.yaml")
      << "name: edited\nbase: " << base_config() << "\nout_dir: " << dir / "out"
      << "\nseeds: [1]\n";
  REQUIRE(run_rlrun("sweep " + dir / "sweep.yaml").exit_code == 0);
  const std::string manifest = dir / "out/manifest.yaml";
  for (const char* key : {"time", "mem", "partition"}) {
    YAML::Node node = YAML::LoadFile(manifest);
    node["slurm"][key] = "1\ntouch " + dir / "pwned";
    std::ofstream(manifest) << YAML::Dump(node) << "\n";
    const auto r = run_rlrun("sweep slurm " + manifest);
    INFO(key << ": " << r.output);
    CHECK(r.exit_code == 2);
    CHECK(r.output.find("manifest.yaml:") != std::string::npos);
    CHECK(r.output.find("control character") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "out/sweep.sbatch"));
    node["slurm"][key] = key == std::string("time") ? "01:00:00" : "";
    std::ofstream(manifest) << YAML::Dump(node) << "\n";
  }
  YAML::Node node = YAML::LoadFile(manifest);
  node["slurm"]["extra"].push_back("--qos=a\n#SBATCH --wrap=id");
  std::ofstream(manifest) << YAML::Dump(node) << "\n";
  const auto r = run_rlrun("sweep slurm " + manifest);
  INFO(r.output);
  CHECK(r.exit_code == 2);
  CHECK_FALSE(fs::exists(dir / "out/sweep.sbatch"));
  CHECK_FALSE(fs::exists(dir / "pwned"));
}

TEST_CASE("shell_quote: any text comes back unchanged from bash, paths with newlines refused",
          "[sweep]") {
  TempDir dir("shell_quote");
  const std::vector<std::string> texts = {
      "plain",      "",       "it's",
      "'",          "a b\tc", "$(touch x) `y` $HOME ${Z} \\ \" ! * ? ~ # ; & | < >",
      "two\nlines", "''\\''"};
  for (const std::string& text : texts) {
    std::ofstream(dir / "q.sh") << "printf '%s' " << shell_quote(text);
    const auto r = run_command("cd " + sh(dir.str()) + " && bash q.sh");
    CHECK(r.exit_code == 0);
    CHECK(r.output == text);
  }
  CHECK_FALSE(fs::exists(dir / "x"));

  Sweep sweep;
  sweep.name = "n";
  sweep.manifest = dir / "m/manifest.yaml";
  sweep.runs.resize(2);
  CHECK(slurm_script(sweep, "/usr/bin/rlrun").find("exec '/usr/bin/rlrun' --threads 1") !=
        std::string::npos);
  CHECK_THROWS_AS(slurm_script(sweep, "/opt/rl\nrun"), UsageError);
  sweep.manifest = dir / "m\n/manifest.yaml";
  CHECK_THROWS_AS(slurm_script(sweep, "/usr/bin/rlrun"), UsageError);
  sweep.manifest = dir / "m/manifest.yaml";
  sweep.slurm.extra = {"--qos=x\ntouch y"};
  CHECK_THROWS_AS(slurm_script(sweep, "/usr/bin/rlrun"), UsageError);
}
