// Where the shipped data is found at run time (core/shipped_data.hpp), and that untrusted text
// still names only files inside it (core/trusted_values.hpp) whichever place it was found in.
// scripts/tests/test_install.sh checks an installed, relocated rlrun.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "core/scoped_process_settings.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/shipped_data.hpp"
#include "rlrun/core/trusted_values.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

// RLRUN_DATA_DIR for one scope, as rlrun's main() would pass it on (ProcessSettings::data_dir).
class DataDirOverride {
 public:
  explicit DataDirOverride(const std::string& dir)
      : scope_([&](ProcessSettings& s) { s.data_dir = dir; }) {}

 private:
  test::ScopedProcessSettings scope_;
};

// The value an untrusted model file's config.yaml would give a SimulatorInput ("" = refused).
std::string untrusted_simulator_input(const std::string& path) {
  const ConfigNode node = ConfigNode::load_string("scenario: '" + path + "'\n",
                                                  "model.zip:config.yaml", ConfigTrust::kUntrusted);
  SimulatorInput input;
  try {
    decode(node.child("scenario"), input);
  } catch (const ConfigError&) {
    return "";
  }
  return input.value;
}

void write_file(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

}  // namespace

TEST_CASE("shipped data: found beside the test binary, not through a compiled-in path",
          "[shipped_data]") {
  DataDirOverride none("");
  CHECK(running_binary_dir() == fs::canonical("/proc/self/exe").parent_path());
  // build/tests/rlrun_tests -> build/share/rlrun, whose links lead to the checkout's data.
  const fs::path data = shipped_data_dir();
  CHECK(data == (running_binary_dir() / ".." / "share" / "rlrun").lexically_normal());
  for (const char* dir : {"configs", "scenarios", "sumo_data"})
    CHECK(fs::equivalent(data / dir, fs::path(RLRUN_SOURCE_DIR) / dir));
  CHECK(fs::exists(data / "configs/zoo"));
  CHECK(fs::exists(data / "configs/sweeps/cartpole_ppo_lr.yaml"));

  // A relative data path works from any working directory; an existing one is left alone.
  TempDir dir("shipped_data_cwd");
  const fs::path before = fs::current_path();
  fs::current_path(dir.str());
  CHECK(fs::equivalent(find_data_file("scenarios/grasp/lift.yaml"),
                       fs::path(RLRUN_SOURCE_DIR) / "scenarios/grasp/lift.yaml"));
  write_file(dir / "scenarios/grasp/lift.yaml", "mine\n");
  CHECK(find_data_file("scenarios/grasp/lift.yaml") == "scenarios/grasp/lift.yaml");
  CHECK(find_data_file("scenarios/none.yaml") == "scenarios/none.yaml");
  fs::current_path(before);

  // Untrusted text may name a shipped file through the build tree's links (relative or
  // absolute, by either path), nothing outside.
  const std::string shipped = untrusted_simulator_input("scenarios/single_intersection.yaml");
  CHECK(shipped ==
        fs::canonical(fs::path(RLRUN_SOURCE_DIR) / "scenarios/single_intersection.yaml"));
  CHECK(untrusted_simulator_input(data / "sumo_data/single_intersection/single.sumocfg") != "");
  CHECK(untrusted_simulator_input(std::string(RLRUN_SOURCE_DIR) +
                                  "/sumo_data/single_intersection/single.sumocfg") != "");
  write_file(dir / "evil.sumocfg", "<configuration/>\n");
  CHECK(untrusted_simulator_input(dir / "evil.sumocfg") == "");
  CHECK(untrusted_simulator_input("scenarios/../../../../../../../../" + dir / "evil.sumocfg") ==
        "");
}

TEST_CASE("shipped data: RLRUN_DATA_DIR overrides the lookup, and untrusted text stays inside it",
          "[shipped_data][security]") {
  TempDir dir("shipped_data_override");
  const fs::path data = fs::path(dir.str()) / "my data";
  write_file(data / "scenarios/mine.sumocfg", "<configuration/>\n");
  write_file(data / "sumo_data/net/net.sumocfg", "<configuration/>\n");
  write_file(dir / "outside/evil.sumocfg", "<configuration/>\n");
  fs::create_symlink(dir / "outside/evil.sumocfg", data / "scenarios/link.sumocfg");
  {
    DataDirOverride set(data.string());
    CHECK(shipped_data_dir() == data.string());
    CHECK(find_data_file("scenarios/mine.sumocfg") == (data / "scenarios/mine.sumocfg").string());
    CHECK(untrusted_simulator_input("scenarios/mine.sumocfg") ==
          fs::canonical(data / "scenarios/mine.sumocfg").string());
    CHECK(untrusted_simulator_input((data / "sumo_data/net/net.sumocfg").string()) != "");
    // The binary's own data is no longer trusted, nor a file elsewhere, nor one reached by a
    // link inside the override that leads out of it, nor a directory that is not a file.
    CHECK(untrusted_simulator_input(std::string(RLRUN_SOURCE_DIR) +
                                    "/scenarios/single_intersection.yaml") == "");
    CHECK(untrusted_simulator_input(dir / "outside/evil.sumocfg") == "");
    CHECK(untrusted_simulator_input("scenarios/link.sumocfg") == "");
    CHECK(untrusted_simulator_input("scenarios/../../outside/evil.sumocfg") == "");
    CHECK(untrusted_simulator_input("scenarios") == "");
  }
  {
    // An override without scenarios/ is an error naming it, never silently skipped.
    DataDirOverride set(dir / "outside");
    CHECK_THROWS_WITH(shipped_data_dir(), Catch::Contains("RLRUN_DATA_DIR=" + dir / "outside") &&
                                              Catch::Contains("has no scenarios/"));
    CHECK_THROWS_WITH(untrusted_simulator_input("scenarios/mine.sumocfg"),
                      Catch::Contains("RLRUN_DATA_DIR="));
  }
}
