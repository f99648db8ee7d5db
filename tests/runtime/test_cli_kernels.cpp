// RLRUN_KERNELS: which vector instructions run the networks changes the speed of a run, never its
// result (nn/dense_kernels.hpp). Short runs of PPO (tanh and GELU), DQN, TD3 and SAC on the AVX2
// and the AVX-512 kernels give byte-equal models; a bad value is a usage error.
#include <catch2/catch.hpp>
#include <fstream>

#include "rlrun/nn/dense_kernels.hpp"
#include "runtime/cli_runner.hpp"
#include "runtime/same_tensors.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;

TEST_CASE("cli: the AVX2 and AVX-512 kernels train byte-equal models", "[cli][kernels]") {
  if (!dense::kernel_path_available(dense::KernelPath::kAvx512)) {
    WARN(
        "this CPU has no AVX-512: only the AVX2 path ran (the kernel-level test still compares "
        "AVX2 with the baseline)");
    return;
  }
  TempDir dir("kernels");
  for (const auto& [name, algo, env, extra] :
       {std::tuple{"PPO", "PPO", "CartPole-v1", "n_steps: 128, batch_size: 64, n_epochs: 3"},
        {"DQN", "DQN", "CartPole-v1", "learning_starts: 200, batch_size: 64"},
        {"TD3", "TD3", "Pendulum-v1",
         "learning_starts: 200, batch_size: 100, policy: {net_arch: [64, 64]}"},
        {"SAC", "SAC", "Pendulum-v1", "learning_starts: 200, batch_size: 256"},
        // GELU's erf-based kernels (rl-zoo's PPO CarRacing policy_kwargs, on Pendulum).
        {"PPO_gelu", "PPO", "Pendulum-v1",
         "n_steps: 128, batch_size: 64, n_epochs: 3, use_sde: true, policy: {activation_fn: "
         "gelu, log_std_init: -2, ortho_init: false, net_arch: {pi: [64], vf: [64]}}"}}) {
    INFO(name);
    const std::string config = dir / (std::string(name) + ".yaml");
    std::ofstream(config) << "run: {name: " << name
                          << ", seed: 5, total_timesteps: 1500, out_dir: " << dir.str()
                          << "/runs}\n"
                          << "env: {id: " << env << ", n_envs: 2}\n"
                          << "algo: {id: " << algo << ", " << extra << "}\n";
    const auto wide =
        run_command("RLRUN_KERNELS=avx512 " + std::string(RLRUN_BINARY) + " train " + config);
    INFO(wide.output);
    REQUIRE(wide.exit_code == 0);
    const auto narrow =
        run_command("RLRUN_KERNELS=avx2 " + std::string(RLRUN_BINARY) + " train " + config);
    INFO(narrow.output);
    REQUIRE(narrow.exit_code == 0);
    check_same_tensors(dir / ("runs/" + std::string(name) + "/seed5/model.zip"),
                       dir / ("runs/" + std::string(name) + "/seed5_2/model.zip"));
  }
}

TEST_CASE("cli: RLRUN_KERNELS names a path or is a usage error", "[cli][kernels]") {
  const auto bad = run_command("RLRUN_KERNELS=sse9 " + std::string(RLRUN_BINARY) + " list");
  CHECK(bad.exit_code == 2);
  CHECK(bad.output.find("RLRUN_KERNELS=sse9: expected auto, avx512, avx2 or baseline") !=
        std::string::npos);
  const auto base = run_command("RLRUN_KERNELS=baseline " + std::string(RLRUN_BINARY) + " list");
  CHECK(base.exit_code == 0);
  const auto version = run_rlrun("--version");
  CHECK(version.output.find(std::string("network kernels: ") +
                            dense::kernel_path_name(dense::best_kernel_path())) !=
        std::string::npos);
}
