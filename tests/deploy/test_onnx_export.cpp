// `rlrun export --format onnx` and `--format c` (deploy/): the exported file, run by a real ONNX Runtime (the
// npm package onnxruntime-node, installed by scripts/setup.sh) and checked by Debian's
// python3-onnx checker, acts as `rlrun eval` does: on the observations of real evaluation
// episodes (`rlrun eval --trajectory`), discrete actions equal and continuous ones within 1e-5,
// for every algorithm, Dict / Discrete / MultiBinary observations, MultiDiscrete and
// MultiBinary actions, normalised observations and action wrappers; the C export, compiled with
// cc -std=c99 -Wall -Werror, likewise. The graph evaluator
// (evaluate_graph, the reference for the other exports) is checked against the same actions.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "envs/python_env_runner.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "rlrun/nn/policy_graph.hpp"
#include "rlrun/policy.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/io/model_graph.hpp"
#include "rlrun/runtime/io/model_loader.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

struct Trajectory {
  int obs_dim = 0, act_dim = 0;
  Eigen::MatrixXf obs, actions;  // a column per step
  std::vector<float> starts;     // 1 where an episode starts (its step 0)
};

// The first `limit` steps of an `rlrun eval --trajectory` file.
Trajectory read_trajectory(const std::string& path, int limit) {
  std::ifstream in(path);
  std::string line;
  REQUIRE(std::getline(in, line));
  std::vector<std::string> header;
  std::stringstream hs(line);
  for (std::string cell; std::getline(hs, cell, ',');) header.push_back(cell);
  Trajectory t;
  for (const std::string& h : header) {
    t.obs_dim += h.rfind("obs_", 0) == 0;
    t.act_dim += h.rfind("action_", 0) == 0;
  }
  std::vector<std::vector<float>> rows;
  while (static_cast<int>(rows.size()) < limit && std::getline(in, line)) {
    std::vector<float> row;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');)
      row.push_back(std::strtof(cell.c_str(), nullptr));
    REQUIRE(row.size() == header.size());
    rows.push_back(std::move(row));
  }
  const auto n = static_cast<Eigen::Index>(rows.size());
  t.obs.resize(t.obs_dim, n);
  t.actions.resize(t.act_dim, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    t.starts.push_back(rows[j][1] == 0.0f ? 1.0f : 0.0f);
    for (int i = 0; i < t.obs_dim; ++i) t.obs(i, j) = rows[j][2 + i];
    for (int i = 0; i < t.act_dim; ++i) t.actions(i, j) = rows[j][2 + t.obs_dim + i];
  }
  return t;
}

// The graph's inputs from flat observations (Dict keys are consecutive runs of the flat order).
std::vector<Eigen::MatrixXf> split_inputs(const PolicyGraph& graph, const Eigen::MatrixXf& obs) {
  std::vector<Eigen::MatrixXf> inputs;
  Eigen::Index row = 0;
  for (const GraphInput& in : graph.inputs()) {
    inputs.push_back(obs.middleRows(row, in.width));
    row += in.width;
  }
  REQUIRE(row == obs.rows());
  return inputs;
}

// Runs the ONNX file with onnxruntime-node; returns the parsed output JSON. With `starts`, a
// recurrent graph runs one step at a time, its state zeroed where an episode starts
// (tests/deploy/onnx_run.js).
nlohmann::json run_onnxruntime(const std::string& model, const PolicyGraph& graph,
                               const Eigen::MatrixXf& obs, const TempDir& dir,
                               const std::vector<float>* starts = nullptr) {
  nlohmann::json request;
  request["batch"] = obs.cols();
  if (starts) {
    request["starts"] = *starts;
    request["state_width"] = graph.state_width();
  }
  const std::vector<Eigen::MatrixXf> inputs = split_inputs(graph, obs);
  for (size_t k = 0; k < inputs.size(); ++k) {
    // Row-major [batch, width]: rlrun's column-major width x batch, read in memory order.
    const Eigen::MatrixXf& m = inputs[k];
    request["inputs"][graph.inputs()[k].name] = std::vector<float>(m.data(), m.data() + m.size());
  }
  const std::string in_path = dir / "ort_in.json", out_path = dir / "ort_out.json";
  std::ofstream(in_path) << request.dump();
  const char* modules = std::getenv("RLRUN_ONNXRUNTIME_NODE_MODULES");
  const std::string node_path = modules ? modules : RLRUN_TEST_NODE_MODULES;
  const std::string command = "NODE_PATH='" + node_path + "' node '" + RLRUN_SOURCE_DIR +
                              "/tests/deploy/onnx_run.js' '" + model + "' '" + in_path + "' '" +
                              out_path + "' 2>&1";
  const CommandResult r = run_command(command);
  INFO("onnxruntime-node (scripts/setup.sh installs it into " << node_path << "): " << r.output);
  REQUIRE(r.exit_code == 0);
  std::ifstream out(out_path);
  return nlohmann::json::parse(out);
}

// Discrete actions equal; continuous within 1e-5 (relative to the action's size beyond 1).
void check_actions(const Eigen::MatrixXf& got, const Eigen::MatrixXf& expected, bool discrete) {
  REQUIRE(got.rows() == expected.rows());
  REQUIRE(got.cols() == expected.cols());
  for (Eigen::Index j = 0; j < got.cols(); ++j)
    for (Eigen::Index i = 0; i < got.rows(); ++i) {
      INFO("step " << j << " action " << i);
      if (discrete)
        REQUIRE(got(i, j) == expected(i, j));
      else
        REQUIRE(std::abs(got(i, j) - expected(i, j)) <=
                1e-5f * std::max(1.0f, std::abs(expected(i, j))));
    }
}

// Exports the model as C99, compiles it with a small driver (tests/deploy/c_policy_main.c) under
// -std=c99 -Wall -Wextra -Werror -pedantic and runs it on `obs`; returns its actions. A recurrent
// policy's steps are each preceded by their episode-start flag (`starts`).
Eigen::MatrixXf run_c_export(const std::string& model, const Eigen::MatrixXf& obs, int action_dim,
                             const TempDir& dir, const std::vector<float>* starts = nullptr) {
  const std::string c_dir = dir / "c_policy";
  const auto x = run_rlrun("export --model " + model + " --format c --output " + c_dir);
  INFO(x.output);
  REQUIRE(x.exit_code == 0);
  const std::string binary = dir / "c_policy_run";
  const CommandResult cc = run_command(
      "cc -std=c99 -O2 -Wall -Wextra -Werror -pedantic -I'" + c_dir + "' '" + RLRUN_SOURCE_DIR +
      "/tests/deploy/c_policy_main.c' '" + c_dir + "/policy.c' -lm -o '" + binary + "' 2>&1");
  INFO(cc.output);
  REQUIRE(cc.exit_code == 0);
  const std::string in_path = dir / "obs.f32", out_path = dir / "actions.f32";
  Eigen::MatrixXf steps = obs;
  if (starts) {
    steps.resize(obs.rows() + 1, obs.cols());
    steps.row(0) = Eigen::Map<const Eigen::RowVectorXf>(starts->data(), obs.cols());
    steps.bottomRows(obs.rows()) = obs;
  }
  std::ofstream(in_path, std::ios::binary)
      .write(reinterpret_cast<const char*>(steps.data()),
             static_cast<std::streamsize>(steps.size() * sizeof(float)));
  const CommandResult run =
      run_command("'" + binary + "' '" + in_path + "' '" + out_path + "' 2>&1");
  INFO(run.output);
  REQUIRE(run.exit_code == 0);
  Eigen::MatrixXf actions(action_dim, obs.cols());
  std::ifstream out(out_path, std::ios::binary);
  out.read(reinterpret_cast<char*>(actions.data()),
           static_cast<std::streamsize>(actions.size() * sizeof(float)));
  REQUIRE(out.gcount() == static_cast<std::streamsize>(actions.size() * sizeof(float)));
  return actions;
}

Eigen::MatrixXf from_json(const nlohmann::json& tensor, Eigen::Index batch) {
  const std::vector<float> data = tensor["data"].get<std::vector<float>>();
  REQUIRE(tensor["dims"][0].get<Eigen::Index>() == batch);
  const Eigen::Index width = tensor["dims"][1].get<Eigen::Index>();
  REQUIRE(static_cast<Eigen::Index>(data.size()) == width * batch);
  return Eigen::Map<const Eigen::MatrixXf>(data.data(), width, batch);
}

struct Case {
  const char* name;
  int timesteps;
  const char* config;  // the experiment's env and algo sections
  int episodes;        // evaluation episodes to record (enough for 1000 steps; those are used)
  bool discrete;
  bool python = false;  // a Python env of tests/python_envs (trained and evaluated with it)
  bool value = true;    // the algorithm has a value to export (ARS has none)
};

// A trained model, its evaluation's first 1000 steps and its ONNX export (with the value).
struct Exported {
  std::string model, onnx;
  Trajectory steps;
};

Exported train_and_export(const Case& c, const TempDir& dir) {
  const std::string config = dir / "exp.yaml";
  std::ofstream(config) << "run: {name: m, seed: 3, total_timesteps: " << c.timesteps
                        << ", out_dir: " << dir.str() << "/runs}\n"
                        << c.config;
  auto rlrun = [&](const std::string& args) {
    return c.python ? run_rlrun_python(args) : run_rlrun(args);
  };
  const auto t = rlrun("train " + config + " --set run.console_interval=1e9");
  INFO(t.output);
  REQUIRE(t.exit_code == 0);
  const std::string model = dir / "runs/m/seed3/model.zip";
  const std::string trajectory = dir / "steps.csv";
  const auto e = rlrun("eval --model " + model + " --episodes " + std::to_string(c.episodes) +
                       " --seed 11 --trajectory " + trajectory + (c.python ? " --trust" : ""));
  INFO(e.output);
  REQUIRE(e.exit_code == 0);
  const Trajectory steps = read_trajectory(trajectory, 1000);
  REQUIRE(steps.obs.cols() == 1000);

  const std::string onnx = dir / "policy.onnx";
  const auto x =
      run_rlrun("export --model " + model + " --format onnx --output " + onnx + " --with-value");
  INFO(x.output);
  REQUIRE(x.exit_code == 0);
  return {model, onnx, steps};
}

// Debian's onnx checker, with shape inference, accepts the graph.
void check_onnx_file(const std::string& onnx) {
  const CommandResult check =
      run_command("/usr/bin/python3 -c \"import onnx; m = onnx.load('" + onnx +
                  "'); onnx.checker.check_model(m, full_check=True); "
                  "print(m.opset_import[0].version, {p.key: p.value for p in "
                  "m.metadata_props}['env_id'])\" 2>&1");
  INFO(check.output);
  REQUIRE(check.exit_code == 0);
  CHECK(check.output.find("13 ") == 0);
}

void check_case(const Case& c) {
  INFO(c.name);
  TempDir dir(std::string("onnx_") + c.name);
  const auto [model, onnx, steps] = train_and_export(c, dir);

  // The graph evaluator: the same actions.
  // As `rlrun export` loads it: the spaces only, no env built (so no Python started).
  const LoadedModel loaded = load_model(model, builtin_registry(), {}, {}, ModelEnv::kSpacesOnly);
  const PolicyGraph graph = build_model_graph(loaded, /*with_value=*/true);
  const auto values = evaluate_graph(graph, split_inputs(graph, steps.obs));
  check_actions(values.at(graph.action()), steps.actions, c.discrete);

  // ONNX Runtime: the same actions, and the value output as the evaluator computes it.
  const nlohmann::json ort = run_onnxruntime(onnx, graph, steps.obs, dir);
  check_actions(from_json(ort["action"], steps.obs.cols()), steps.actions, c.discrete);
  CHECK(ort.contains("value") == c.value);
  if (c.value) {
    const Eigen::MatrixXf value = from_json(ort["value"], steps.obs.cols());
    const Eigen::MatrixXf& expected_value = values.at(graph.value());
    REQUIRE(value.rows() == expected_value.rows());
    CHECK(((value - expected_value).array().abs() <= 1e-4f * expected_value.array().abs().max(1.0f))
              .all());
  }

  // rlrun::Policy (the embeddable library), one observation at a time and as one batch.
  const Policy policy = Policy::load(model);
  REQUIRE(policy.observation_size() == static_cast<size_t>(steps.obs_dim));
  REQUIRE(policy.action_size() == static_cast<size_t>(steps.act_dim));
  Eigen::MatrixXf single(steps.act_dim, steps.obs.cols()), batch(steps.act_dim, steps.obs.cols());
  for (Eigen::Index j = 0; j < steps.obs.cols(); ++j)
    policy.act({steps.obs.col(j).data(), policy.observation_size()},
               {single.col(j).data(), policy.action_size()});
  check_actions(single, steps.actions, c.discrete);
  policy.act_batch({steps.obs.data(), static_cast<size_t>(steps.obs.size())},
                   {batch.data(), static_cast<size_t>(batch.size())},
                   static_cast<size_t>(steps.obs.cols()));
  check_actions(batch, steps.actions, c.discrete);

  // The C export, compiled and run: the same actions.
  check_actions(run_c_export(model, steps.obs, steps.act_dim, dir), steps.actions, c.discrete);
  check_onnx_file(onnx);
}

// A recurrent policy (RecurrentPPO) over the evaluation's 1000 steps, one step at a time: the
// state starts at zeros, is zeroed where an episode starts and each step's state_out is the next
// step's state_in — what `rlrun eval` does with the policy's LSTM state. Every export acts as
// eval did.
void check_recurrent_case(const Case& c) {
  INFO(c.name);
  TempDir dir(std::string("onnx_") + c.name);
  const auto [model, onnx, steps] = train_and_export(c, dir);
  const Eigen::Index n = steps.obs.cols();

  // The graph evaluator, the state carried by hand.
  const LoadedModel loaded = load_model(model, builtin_registry(), {}, {}, ModelEnv::kSpacesOnly);
  const PolicyGraph graph = build_model_graph(loaded, /*with_value=*/true);
  REQUIRE(graph.state_width() > 0);
  Eigen::MatrixXf actions(steps.act_dim, n), values(graph.width(graph.value()), n);
  Eigen::MatrixXf state = Eigen::MatrixXf::Zero(graph.state_width(), 1);
  for (Eigen::Index j = 0; j < n; ++j) {
    if (steps.starts[j] != 0.0f) state.setZero();
    std::vector<Eigen::MatrixXf> inputs = split_inputs(graph, steps.obs.col(j));
    inputs.push_back(state);
    const auto out = evaluate_graph(graph, inputs);
    actions.col(j) = out.at(graph.action());
    values.col(j) = out.at(graph.value());
    state = out.at(graph.state_output());
  }
  check_actions(actions, steps.actions, c.discrete);

  // ONNX Runtime, one session run per step.
  const nlohmann::json ort = run_onnxruntime(onnx, graph, steps.obs, dir, &steps.starts);
  check_actions(from_json(ort["action"], n), steps.actions, c.discrete);
  const Eigen::MatrixXf ort_values = from_json(ort["value"], n);
  CHECK(((ort_values - values).array().abs() <= 1e-4f * values.array().abs().max(1.0f)).all());

  // rlrun::Policy without the value: the actor's state alone.
  const Policy policy = Policy::load(model);
  REQUIRE(policy.state_size() > 0);
  REQUIRE(policy.state_size() <= static_cast<size_t>(graph.state_width()));
  std::vector<float> policy_state(policy.state_size());
  Eigen::MatrixXf single(steps.act_dim, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    if (steps.starts[j] != 0.0f) std::fill(policy_state.begin(), policy_state.end(), 0.0f);
    policy.act({steps.obs.col(j).data(), policy.observation_size()}, policy_state,
               {single.col(j).data(), policy.action_size()});
  }
  check_actions(single, steps.actions, c.discrete);
  std::vector<float> action(policy.action_size());
  CHECK_THROWS_AS(policy.act({steps.obs.col(0).data(), policy.observation_size()}, action),
                  std::invalid_argument);

  // The C export: policy_act(obs, state, action).
  check_actions(run_c_export(model, steps.obs, steps.act_dim, dir, &steps.starts), steps.actions,
                c.discrete);
  check_onnx_file(onnx);
}

}  // namespace

TEST_CASE("export onnx: Discrete, MultiDiscrete and MultiBinary actions (PPO, A2C, DQN)",
          "[deploy][onnx]") {
  check_case(
      {"ppo_cartpole", 2048,
       "env: {id: CartPole-v1}\n"
       "algo: {id: PPO, n_steps: 256, batch_size: 64, n_epochs: 2, policy: {net_arch: [32, 32]}}\n",
       100, true});
  check_case({"dqn_cartpole", 2000,
              "env: {id: CartPole-v1}\n"
              "algo: {id: DQN, learning_starts: 500, policy: {net_arch: [32, 32]}}\n",
              200, true});
  check_case({"a2c_multidiscrete", 2000,
              "env: {id: IdentityEnvMultiDiscrete-v0}\n"
              "algo: {id: A2C, policy: {net_arch: [16], activation_fn: relu}}\n",
              100, true});
  check_case({"ppo_multibinary", 2048,
              "env: {id: IdentityEnvMultiBinary-v0}\n"
              "algo: {id: PPO, n_steps: 256, batch_size: 64, n_epochs: 2}\n",
              100, true});
}

TEST_CASE("export onnx: MaskablePPO exports its unmasked argmax (MultiBinary as two-way parts)",
          "[deploy][onnx][ppo_mask]") {
  // Envs without masks (use_masking: false), so that eval's actions are the unmasked argmax
  // the graph computes; MultiBinary's head is 2n logits, one two-way categorical per entry.
  check_case({"maskable_multibinary", 1024,
              "env: {id: IdentityEnvMultiBinary-v0}\n"
              "algo: {id: MaskablePPO, n_steps: 256, batch_size: 64, n_epochs: 2,"
              " use_masking: false}\n",
              100, true});
  check_case({"maskable_multidiscrete", 1024,
              "env: {id: IdentityEnvMultiDiscrete-v0}\n"
              "algo: {id: MaskablePPO, n_steps: 256, batch_size: 64, n_epochs: 2,"
              " use_masking: false}\n",
              100, true});
}

TEST_CASE(
    "export onnx: CnnPolicy of PPO, A2C, DQN, SAC and TD3 on uint8 images (NatureCNN as Conv)",
    "[deploy][onnx][cnn]") {
  // BrightSide's Box(0, 255, (36, 36, 1), uint8) frames (tests/python_envs): the exported graph
  // divides by 255, runs three Conv + Relu on the channels-last image (a Transpose to NCHW in
  // ONNX) and the linear layer, on 1000 observations of evaluation episodes.
  const std::string env =
      "env: {id: \"python:rlrun_test_envs.pixels:BrightSide\", python: " + kPython + "}\n";
  const std::string box_env =
      "env: {id: \"python:rlrun_test_envs.pixels:BrightSideBox\", python: " + kPython + "}\n";
  const std::string cnn = "features_extractor_class: NatureCNN, features_dim: 16";
  const std::string ppo = env +
                          "algo: {id: PPO, n_steps: 64, batch_size: 32, n_epochs: 1, policy: {" +
                          cnn + ", net_arch: []}}\n";
  const std::string a2c = env + "algo: {id: A2C, n_steps: 8, policy: {" + cnn +
                          ", net_arch: [], share_features_extractor: false}}\n";
  const std::string dqn = env +
                          "algo: {id: DQN, learning_starts: 50, buffer_size: 500, "
                          "batch_size: 16, policy: {" +
                          cnn + ", net_arch: []}}\n";
  const std::string sac = box_env +
                          "algo: {id: SAC, learning_starts: 50, buffer_size: 500, "
                          "batch_size: 16, policy: {" +
                          cnn + ", net_arch: [32]}}\n";
  const std::string td3 = box_env +
                          "algo: {id: TD3, learning_starts: 50, buffer_size: 500, "
                          "batch_size: 16, policy_delay: 1, policy: {" +
                          cnn + ", net_arch: [32]}}\n";
  check_case({"ppo_cnn", 128, ppo.c_str(), 130, true, true});
  check_case({"a2c_cnn_separate", 64, a2c.c_str(), 130, true, true});
  check_case({"dqn_cnn", 150, dqn.c_str(), 130, true, true});
  check_case({"sac_cnn", 120, sac.c_str(), 130, false, true});
  check_case({"td3_cnn", 120, td3.c_str(), 130, false, true});
}

TEST_CASE("export onnx: Dict, Discrete and MultiBinary observations (one-hot encodings)",
          "[deploy][onnx]") {
  check_case({"ppo_dict", 2048,
              "env: {id: SimpleMultiObsEnv-v0}\n"
              "algo: {id: PPO, n_steps: 256, batch_size: 64, n_epochs: 2}\n",
              600, true});
  check_case({"dqn_onehot_wrapper", 2000,
              "env: {id: GridWorld-v0, wrappers: [{id: OneHotObservation}]}\n"
              "algo: {id: DQN, learning_starts: 500, policy: {net_arch: [32]}}\n",
              300, true});
  check_case({"ppo_dictreach", 2048,
              "env: {id: DictReach-v0}\n"
              "algo: {id: PPO, n_steps: 256, batch_size: 64, n_epochs: 2}\n",
              200, false});
}

TEST_CASE("export onnx: Box actions, normalised observations and action wrappers (A2C, PPO, SAC)",
          "[deploy][onnx]") {
  check_case({"a2c_pendulum_normalize_gsde", 2000,
              "env: {id: Pendulum-v1, normalize: true}\n"
              "algo: {id: A2C, use_sde: true, policy: {log_std_init: -2, ortho_init: false}}\n",
              5, false});
  check_case({"ppo_pendulum_clip_action", 2048,
              "env: {id: Pendulum-v1, wrappers: [{id: ClipAction}]}\n"
              "algo: {id: PPO, n_steps: 256, batch_size: 64, n_epochs: 2,\n"
              "       policy: {net_arch: {pi: [16], vf: [32]}, activation_fn: leaky_relu}}\n",
              5, false});
  check_case(
      {"sac_pendulum_wrappers", 300,
       "env: {id: Pendulum-v1, wrappers: [{id: NormalizeObservation},\n"
       "  {id: RescaleAction, min_action: -0.5, max_action: 0.5}]}\n"
       "algo: {id: SAC, learning_starts: 100, batch_size: 32, policy: {net_arch: [16, 16]}}\n",
       5, false});
  check_case({"sac_gsde", 300,
              "env: {id: MountainCarContinuous-v0}\n"
              "algo: {id: SAC, learning_starts: 100, batch_size: 32, use_sde: true,\n"
              "       policy: {net_arch: [16, 16], clip_mean: 0.5}}\n",
              2, false});
}

TEST_CASE("export onnx: CrossQ (eval-mode BatchRenorm folded into the dense layers)",
          "[deploy][onnx][crossq]") {
  check_case({"crossq_pendulum", 600,
              "env: {id: Pendulum-v1, wrappers: [{id: NormalizeObservation}]}\n"
              "algo: {id: CrossQ, learning_starts: 100, batch_size: 32,\n"
              "       policy: {net_arch: {pi: [16, 16], qf: [32]}, renorm_warmup_steps: 200}}\n",
              5, false});
  check_case({"crossq_gsde", 300,
              "env: {id: MountainCarContinuous-v0}\n"
              "algo: {id: CrossQ, learning_starts: 100, batch_size: 32, use_sde: true,\n"
              "       policy: {net_arch: [16], use_expln: true, log_std_init: -1}}\n",
              2, false});
}

TEST_CASE("export onnx: a GELU policy (Mul, Erf, Add: opset 13 has no Gelu), C's erfcf",
          "[deploy][onnx]") {
  // rl-zoo's PPO CarRacing-v3 policy_kwargs (nn.GELU, gSDE, log_std_init -2, no orthogonal
  // init) on Pendulum, with two GELU layers in the actor.
  check_case({"ppo_pendulum_gelu", 2048,
              "env: {id: Pendulum-v1}\n"
              "algo: {id: PPO, n_steps: 256, batch_size: 64, n_epochs: 2, use_sde: true,\n"
              "       policy: {net_arch: {pi: [32, 32], vf: [32]}, activation_fn: gelu,\n"
              "                log_std_init: -2, ortho_init: false}}\n",
              5, false});
}

TEST_CASE("export onnx: TQC (SAC's squashed actor, the mean of every atom as the value)",
          "[deploy][onnx][tqc]") {
  check_case({"tqc_pendulum", 300,
              "env: {id: Pendulum-v1}\n"
              "algo: {id: TQC, learning_starts: 100, batch_size: 32,\n"
              "       policy: {net_arch: [16, 16], n_quantiles: 5, n_critics: 3}}\n",
              5, false});
}

TEST_CASE("export onnx: TRPO (the actor-critic policy, gSDE's mean as the action)",
          "[deploy][onnx][trpo]") {
  check_case({"trpo_pendulum_sde", 1024,
              "env: {id: Pendulum-v1, n_envs: 2}\n"
              "algo: {id: TRPO, n_steps: 256, use_sde: true, policy: {net_arch: [32, 32]}}\n",
              5, false});
}

TEST_CASE("export onnx: ARS (tanh scaled to the bounds, a linear policy's argmax)",
          "[deploy][onnx][ars]") {
  check_case({"ars_pendulum", 3200,
              "env: {id: Pendulum-v1}\n"
              "algo: {id: ARS, n_delta: 4, zero_policy: false, policy: {net_arch: [16]}}\n",
              5, false, false, false});
  check_case({"ars_cartpole_linear", 2000,
              "env: {id: CartPole-v1}\n"
              "algo: {id: ARS, n_delta: 2, policy: {net_arch: [], with_bias: false,"
              " squash_output: false}}\n",
              100, true, false, false});
}

TEST_CASE("export onnx: QRDQN (argmax of each action's quantile mean, the means as the value)",
          "[deploy][onnx][qrdqn]") {
  check_case({"qrdqn_cartpole", 2000,
              "env: {id: CartPole-v1}\n"
              "algo: {id: QRDQN, learning_starts: 500, policy: {net_arch: [32], n_quantiles: 7}}\n",
              200, true});
}

TEST_CASE("export onnx: RecurrentPPO (the LSTM step with its state as input and output)",
          "[deploy][onnx][ppo_recurrent]") {
  // Two stacked layers with the critic's own LSTM (its state follows the actor's when the
  // value is exported); a continuous policy with the critic on the actor's LSTM; and the
  // Linear critic. Short untrained episodes: many starts among the 1000 steps.
  check_recurrent_case({"recurrent_cartpole_novel", 512,
                        "env: {id: CartPoleNoVel-v1}\n"
                        "algo: {id: RecurrentPPO, n_steps: 128, batch_size: 64, n_epochs: 1,\n"
                        "       policy: {lstm_hidden_size: 8, n_lstm_layers: 2, net_arch: [16]}}\n",
                        120, true});
  check_recurrent_case({"recurrent_pendulum_shared", 512,
                        "env: {id: PendulumNoVel-v1}\n"
                        "algo: {id: RecurrentPPO, n_steps: 128, batch_size: 64, n_epochs: 1,\n"
                        "       policy: {lstm_hidden_size: 8, shared_lstm: true,\n"
                        "                enable_critic_lstm: false, net_arch: [16]}}\n",
                        5, false});
  check_recurrent_case({"recurrent_pendulum_linear_critic", 512,
                        "env: {id: Pendulum-v1}\n"
                        "algo: {id: RecurrentPPO, n_steps: 128, batch_size: 64, n_epochs: 1,\n"
                        "       policy: {lstm_hidden_size: 8, enable_critic_lstm: false}}\n",
                        5, false});
}

TEST_CASE("export onnx: TD3 and DDPG (deterministic tanh actors, Q(s, a) as the value)",
          "[deploy][onnx]") {
  check_case({"td3_elu", 300,
              "env: {id: Pendulum-v1}\n"
              "algo: {id: TD3, learning_starts: 100, batch_size: 32,\n"
              "       policy: {net_arch: [16, 16], activation_fn: elu}}\n",
              5, false});
  check_case(
      {"ddpg_lunar", 300,
       "env: {id: LunarLanderContinuous-v3}\n"
       "algo: {id: DDPG, learning_starts: 100, batch_size: 32, policy: {net_arch: [32, 32]}}\n",
       30, false});
}

TEST_CASE("rlrun::Policy: wrong sizes and bad files are exceptions, act is thread-safe",
          "[deploy][onnx]") {
  TempDir dir("policy_library");
  const std::string config = dir / "exp.yaml";
  std::ofstream(config)
      << "run: {name: m, seed: 1, total_timesteps: 300, out_dir: " << dir.str()
      << "/runs}\nenv: {id: Pendulum-v1}\n"
         "algo: {id: SAC, learning_starts: 100, batch_size: 32, policy: {net_arch: [16]}}\n";
  REQUIRE(run_rlrun("train " + config).exit_code == 0);
  const Policy policy = Policy::load(dir / "runs/m/seed1/model.zip");
  CHECK(policy.env_id() == "Pendulum-v1");
  CHECK(policy.algorithm() == "SAC");
  std::vector<float> obs = {1.0f, 0.0f, 0.5f}, action(1), wrong(2);
  CHECK_THROWS_AS(policy.act({obs.data(), 2}, action), std::invalid_argument);
  CHECK_THROWS_AS(policy.act(obs, wrong), std::invalid_argument);
  CHECK_THROWS_AS(policy.act_batch(obs, action, 2), std::invalid_argument);
  CHECK_THROWS_AS(Policy::load(dir / "missing.zip"), std::runtime_error);
  std::ofstream(dir / "junk.zip") << "not a zip";
  CHECK_THROWS_AS(Policy::load(dir / "junk.zip"), std::runtime_error);

  // Two threads acting at once with one Policy get what one thread gets.
  std::vector<float> many(3 * 500), expected(500), got_a(500), got_b(500);
  for (size_t k = 0; k < many.size(); ++k) many[k] = std::sin(static_cast<float>(k));
  for (size_t j = 0; j < 500; ++j) policy.act({&many[3 * j], 3}, {&expected[j], 1});
  auto worker = [&](std::vector<float>& out) {
    for (int round = 0; round < 20; ++round)
      for (size_t j = 0; j < 500; ++j) policy.act({&many[3 * j], 3}, {&out[j], 1});
  };
  std::thread a(worker, std::ref(got_a)), b(worker, std::ref(got_b));
  a.join();
  b.join();
  CHECK(got_a == expected);
  CHECK(got_b == expected);
}

TEST_CASE("export: refusals are clear errors", "[deploy][onnx]") {
  TempDir dir("onnx_refusals");
  const std::string config = dir / "exp.yaml";
  std::ofstream(config)
      << "run: {name: m, seed: 1, total_timesteps: 512, out_dir: " << dir.str()
      << "/runs}\nenv: {id: CartPole-v1, wrappers: [{id: FrameStack, n_stack: 2}]}\n"
         "algo: {id: PPO, n_steps: 256, batch_size: 64, n_epochs: 1}\n";
  REQUIRE(run_rlrun("train " + config).exit_code == 0);
  const std::string model = dir / "runs/m/seed1/model.zip";
  // A wrapper that keeps frames but passes actions on: the graph reads its observations, and
  // says so.
  const auto stacked = run_rlrun("export --model " + model + " --output " + (dir / "s.onnx"));
  INFO(stacked.output);
  CHECK(stacked.exit_code == 0);
  CHECK_THAT(stacked.output, Catch::Contains("reads the observations of the wrapper FrameStack") &&
                                 Catch::Contains("obs [batch, 8]"));
  // A stateful wrapper without an export (TimeFeature): named, and nothing written.
  const std::string timed = dir / "timed.yaml";
  std::ofstream(timed) << "run: {name: t, seed: 1, total_timesteps: 256, out_dir: " << dir.str()
                       << "/runs}\nenv: {id: Pendulum-v1, wrappers: [{id: TimeFeature}]}\n"
                          "algo: {id: PPO, n_steps: 256, batch_size: 64, n_epochs: 1}\n";
  REQUIRE(run_rlrun("train " + timed).exit_code == 0);
  const auto refused = run_rlrun("export --model " + (dir / "runs/t/seed1/model.zip") +
                                 " --output " + (dir / "p.onnx"));
  CHECK(refused.exit_code == 1);
  CHECK(refused.output.find("TimeFeature") != std::string::npos);
  CHECK_FALSE(std::ifstream(dir / "p.onnx").good());
  // An output in a directory that does not exist.
  const auto missing =
      run_rlrun("export --model " + model + " --output " + (dir / "no/such/p.onnx"));
  CHECK(missing.exit_code == 1);
  CHECK(missing.output.find("does not exist") != std::string::npos);
  // Not a model file.
  std::ofstream(dir / "junk.zip") << "not a zip";
  const auto junk =
      run_rlrun("export --model " + (dir / "junk.zip") + " --output " + (dir / "j.onnx"));
  CHECK(junk.exit_code == 1);
  CHECK_FALSE(std::ifstream(dir / "j.onnx").good());
  // A model of a format version this rlrun does not know: export and the library refuse.
  const std::string meta = R"({"format_version": 99, "rlrun_version": "9.0.0", "algorithm": "PPO",
    "env_id": "CartPole-v1", "observation_space": "", "action_space": "", "num_timesteps": 0})";
  write_zip_atomic(
      dir / "future.zip",
      {{"meta.json", std::vector<uint8_t>(meta.begin(), meta.end())}, {"config.yaml", {}}});
  const auto future = run_rlrun("export --model " + (dir / "future.zip") + " --format c --output " +
                                (dir / "future_c"));
  CHECK(future.exit_code == 1);
  CHECK(future.output.find("format version 99") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir / "future_c/policy.c"));
  try {
    (void)Policy::load(dir / "future.zip");
    FAIL("a model of format version 99 loaded");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()).find("format version 99") != std::string::npos);
  }
}
