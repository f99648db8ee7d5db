// The MuJoCo tasks from the command line as a user tries them: the zoo's entry trained as it is
// (`rlrun train --zoo sac.yml --env HalfCheetah-v4`), evaluation with a trajectory, and the
// model file's `xml_file`: a model from elsewhere cannot make rlrun load a MuJoCo model from an
// arbitrary path unless the user vouches for it.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "runtime/cli_runner.hpp"

using namespace rlrun::testing;

namespace {

std::string tiny_ppo(const std::string& name, const std::string& env_lines) {
  return "run: {name: " + name + ", seed: 1, total_timesteps: 128}\n" + env_lines +
         "algo: {id: PPO, n_steps: 64, batch_size: 32, n_epochs: 1}\n";
}

}  // namespace

TEST_CASE("MuJoCo CLI: the zoo's SAC HalfCheetah-v4 entry trains as it is", "[mujoco][zoo]") {
  TempDir dir("mujoco_zoo");
  std::ofstream(dir / "sac.yml") << "HalfCheetah-v4: &mujoco-defaults\n"
                                    "  n_timesteps: !!float 1e6\n"
                                    "  policy: 'MlpPolicy'\n"
                                    "  learning_starts: 10000\n";
  const CommandResult r =
      run_rlrun("train --zoo " + (dir / "sac.yml") + " --env HalfCheetah-v4 --timesteps 300 " +
                "--set algo.learning_starts=100 --out " + (dir / "runs"));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("SAC on HalfCheetah-v4") != std::string::npos);
}

TEST_CASE("MuJoCo CLI: a model's xml_file is the user's to vouch for", "[mujoco][security]") {
  TempDir dir("mujoco_xml_file");
  const std::string xml = dir / "my_cheetah.xml";
  std::filesystem::copy_file(std::string(RLRUN_SOURCE_DIR) + "/scenarios/mujoco/half_cheetah.xml",
                             xml);
  std::ofstream(dir / "exp.yaml") << tiny_ppo(
      "own_model", "env: {id: HalfCheetah-v4, kwargs: {xml_file: " + xml + "}}\n");
  const CommandResult trained =
      run_rlrun("train " + (dir / "exp.yaml") + " --out " + (dir / "runs"));
  INFO(trained.output);
  REQUIRE(trained.exit_code == 0);
  const std::string model = dir / "runs/own_model/seed1/model.zip";

  // The model file names a file outside rlrun's data: refused, with the --set that vouches.
  const CommandResult refused = run_rlrun("eval --model " + model + " --episodes 1");
  INFO(refused.output);
  CHECK(refused.exit_code != 0);
  CHECK(refused.output.find("xml_file") != std::string::npos);
  CHECK(refused.output.find("--set") != std::string::npos);

  const CommandResult vouched =
      run_rlrun("eval --model " + model + " --episodes 1 --set " + "env.kwargs.xml_file=" + xml +
                " --trajectory " + (dir / "t.csv"));
  INFO(vouched.output);
  CHECK(vouched.exit_code == 0);
  const std::string text = read_text(dir / "t.csv");
  const std::string header = text.substr(0, text.find('\n'));
  CHECK(header.find(",qpos_0,") != std::string::npos);
  CHECK(header.find(",qacc_warmstart_8,action_0,") != std::string::npos);
}
