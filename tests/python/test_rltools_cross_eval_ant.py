"""scripts/bench/rltools_cross_eval_ant.py, the tool behind docs/benchmarks.md's same-start-state
Ant-v4 returns: its reading of an RLtools PPO actor export (standardize layer, dense layers with
the activations the file names; the forward pass checked against the file's own example), and
both policies run from the same Gymnasium start states on rlrun's Ant-v4 (when this build has
the MuJoCo component)."""

import importlib.util
import os
import unittest

import numpy as np

import rlrun
from rlrun_testing import TempDirMixin, compiled_cpp_lines, train_model

SOURCE_DIR = os.environ.get("RLRUN_SOURCE_DIR",
                            os.path.join(os.path.dirname(__file__), "..", ".."))
spec = importlib.util.spec_from_file_location(
    "rltools_cross_eval_ant",
    os.path.join(SOURCE_DIR, "scripts", "bench", "rltools_cross_eval_ant.py"))
cross_eval = importlib.util.module_from_spec(spec)
spec.loader.exec_module(cross_eval)


# RLtools' Ant evaluation draws, written by C++ with libstdc++ as RLtools makes them
# (random/operations_cpu.h: std::mt19937(seed + 1), a fresh distribution object per draw;
# mujoco/ant/operations_cpu.h: 15 qpos offsets, then 14 qvel offsets, per episode).
ANT_DRAWS_CPP = r"""
#include <cstdio>
#include <cstdlib>
#include <random>
int main(int argc, char** argv) {
  std::mt19937 engine(static_cast<std::mt19937::result_type>(std::atoi(argv[1]) + 1));
  for (int episode = 0; episode < std::atoi(argv[2]); ++episode) {
    for (int i = 0; i < 15; ++i)
      std::printf("%a ", std::uniform_real_distribution<double>(-0.1, 0.1)(engine));
    for (int i = 0; i < 14; ++i)
      std::printf("%a ", static_cast<double>(std::normal_distribution<float>(0.0, 0.1)(engine)));
    std::printf("\n");
  }
}
"""


def have_ant():
    try:
        rlrun.make("Ant-v4").close()
        return True
    except Exception:  # the MuJoCo component's placeholder says how to get it
        return False


def memory(values):
    return ("constexpr float memory[] = {"
            + ", ".join(float(v).hex() + "f" for v in np.asarray(values, np.float32).ravel())
            + "};\n")


def write_ppo_checkpoint(path, mean, precision, layers, log_std, example_in, example_out):
    """A file in the layout of RLtools' actor code export (checkpoint::save_code) of a PPO actor:
    a standardize layer, dense layers (weights, biases; a Configuration line naming the
    activation), the learned log std, then the example input and output namespaces."""
    with open(path, "w") as f:
        f.write("namespace rl_tools::checkpoint::actor {\nnamespace layer_0 {\n")
        f.write(memory(mean) + memory(precision))
        f.write("using CONFIG = ::rl_tools::nn::layers::standardize::Configuration<T, TI>;\n}\n")
        for i, (weights, bias, activation) in enumerate(layers):
            f.write(f"namespace dense_{i} {{\n{memory(weights)}{memory(bias)}")
            f.write(f"using CONFIG = ::rl_tools::nn::layers::dense::Configuration<T, TI, {bias.size},"
                    f" ::rl_tools::nn::activation_functions::ActivationFunction::{activation}, I>;\n}}\n")
        f.write(memory(log_std) + "}\n")
        f.write("namespace rl_tools::checkpoint::example::input {\n" + memory(example_in) + "}\n")
        f.write("namespace rl_tools::checkpoint::example::output {\n" + memory(example_out) + "}\n")


def write_td3_checkpoint(path, layers, example_in, example_out):
    """A file in the layout of RLtools' export of its TD3 actor (checkpoint::save_code of a
    Sequential): layer_0 an MLP (input_layer, hidden_layer_i, output_layer namespaces, each a
    dense Configuration line after its weights and biases, then the MLP's own Configuration line
    naming both activations), layer_1 the td3_sampling layer, without parameters."""
    names = (["input_layer"] + [f"hidden_layer_{i}" for i in range(len(layers) - 2)]
             + ["output_layer"])
    activation_type = "::rl_tools::nn::activation_functions::ActivationFunction::"
    with open(path, "w") as f:
        f.write("namespace rl_tools::checkpoint::actor {\nnamespace layer_0 {\n")
        for name, (weights, bias, activation) in zip(names, layers):
            f.write(f"namespace {name} {{\nnamespace weights {{\n{memory(weights)}}}\n"
                    f"namespace biases {{\n{memory(bias)}}}\n}}\n")
            f.write(f"namespace {name} {{\nusing CONFIG = ::rl_tools::nn::layers::dense::"
                    f"Configuration<TYPE_POLICY, unsigned long, {bias.size}, "
                    f"{activation_type}{activation}, I, G>;\n}}\n")
        f.write(f"using CONFIG = ::rl_tools::nn_models::mlp::Configuration<TYPE_POLICY, unsigned "
                f"long, 8, {len(layers)}, 16, {activation_type}RELU, {activation_type}TANH, I>;\n}}\n")
        f.write("namespace layer_1 {\nusing PARAMETERS = struct PARAMETERS{ static constexpr float "
                "STD = 0.1; };\nusing CONFIG = ::rl_tools::nn::layers::td3_sampling::"
                "Configuration<float, unsigned long, PARAMETERS>;\n}\n}\n")
        f.write("namespace rl_tools::checkpoint::example::input {\n" + memory(example_in) + "}\n")
        f.write("namespace rl_tools::checkpoint::example::output {\n" + memory(example_out) + "}\n")

def random_actor(rng, obs_dim=27, hidden=16, actions=8):
    mean = rng.normal(size=obs_dim).astype(np.float32)
    precision = rng.uniform(0.5, 2.0, obs_dim).astype(np.float32)
    precision[3] = 0  # a constant dimension: RLtools leaves it unscaled
    layers = [(rng.normal(size=(hidden, obs_dim)).astype(np.float32) / 5,
               rng.normal(size=hidden).astype(np.float32), "RELU"),
              (rng.normal(size=(hidden, hidden)).astype(np.float32) / 4,
               rng.normal(size=hidden).astype(np.float32), "RELU"),
              (rng.normal(size=(actions, hidden)).astype(np.float32) / 4,
               rng.normal(size=actions).astype(np.float32), "IDENTITY")]
    return mean, precision, layers


def forward(mean, precision, layers, obs):
    x = obs if mean is None else (obs - mean) * np.where(precision != 0, precision, 1)
    for weights, bias, activation in layers:
        x = x @ weights.T + bias
        x = {"RELU": lambda v: np.maximum(v, 0), "TANH": np.tanh}.get(activation, lambda v: v)(x)
    return x


class RltoolsCrossEvalAnt(TempDirMixin, unittest.TestCase):
    def test_reads_an_rltools_ppo_actor_and_checks_its_example(self):
        rng = np.random.default_rng(0)
        mean, precision, layers = random_actor(rng)
        obs = rng.normal(size=(13, 27)).astype(np.float32)
        out = forward(mean, precision, layers, obs)
        path = os.path.join(self.tmp, "checkpoint.h")
        write_ppo_checkpoint(path, mean, precision, layers, np.full(8, -0.7), obs, out)
        policy = cross_eval.rltools_policy(path)
        for row in range(13):
            np.testing.assert_allclose(policy(obs[row]), np.clip(out[row], -1, 1),
                                       rtol=1e-5, atol=1e-5)
        write_ppo_checkpoint(path, mean, precision, layers, np.full(8, -0.7), obs, out + 0.1)
        with self.assertRaisesRegex(SystemExit, "differs from the file's example"):
            cross_eval.rltools_policy(path)
        layers[1] = (layers[1][0], layers[1][1], "SOFTPLUS")
        write_ppo_checkpoint(path, mean, precision, layers, np.full(8, -0.7), obs, out)
        with self.assertRaisesRegex(SystemExit, "not known to this script"):
            cross_eval.rltools_policy(path)

    def test_reads_an_rltools_td3_actor(self):
        # TD3's export: no standardize layer, an MLP ending in tanh, the exploration-noise layer
        # after it (off in the example, as when RLtools evaluates).
        rng = np.random.default_rng(1)
        _, _, layers = random_actor(rng)
        layers[2] = (layers[2][0] * 4, layers[2][1], "TANH")  # outputs reaching saturation
        obs = rng.normal(size=(13, 27)).astype(np.float32)
        out = forward(None, None, layers, obs)
        self.assertGreater(np.abs(out).max(), 0.9)
        path = os.path.join(self.tmp, "checkpoint.h")
        write_td3_checkpoint(path, layers, obs, out)
        policy = cross_eval.rltools_policy(path)
        for row in range(13):
            np.testing.assert_allclose(policy(obs[row]), out[row], rtol=1e-5, atol=1e-5)
        # An example with exploration noise in it is not the deterministic actor: refused.
        write_td3_checkpoint(path, layers, obs, np.clip(out + 0.1 * rng.normal(size=out.shape), -1, 1))
        with self.assertRaisesRegex(SystemExit, "differs from the file's example"):
            cross_eval.rltools_policy(path)

    def test_rltools_start_states_equal_libstdcxx_draws(self):
        # Ant's qpos0 (torso at 0.75, upright) and zero velocities, as RLtools' init_q, init_q_dot.
        init_qpos = np.array([0, 0, 0.75, 1, 0, 0, 0] + [0] * 8, dtype=np.float64)
        init_qvel = np.zeros(14)
        for seed in (1, 4, 77):
            draws = np.array([[float.fromhex(v) for v in line] for line in
                              compiled_cpp_lines(self.tmp, "draws", ANT_DRAWS_CPP, seed, 100)])
            self.assertEqual(draws.shape, (100, 29))
            states = cross_eval.rltools_start_states(init_qpos, init_qvel, seed)
            self.assertEqual(len(states), 100)
            np.testing.assert_array_equal(np.array([q for q, _ in states]),
                                          init_qpos + draws[:, :15], err_msg=f"seed {seed}")
            np.testing.assert_array_equal(np.array([v for _, v in states]),
                                          init_qvel + draws[:, 15:], err_msg=f"seed {seed}")

    @unittest.skipUnless(have_ant(), "this build has no MuJoCo envs (RLRUN_WITH_MUJOCO)")
    def test_runs_both_policies_from_the_same_start_states(self):
        env = rlrun.make("Ant-v4", max_episode_steps=50)
        states = cross_eval.start_states(env, 3, seed=5)
        u = env.unwrapped
        for qpos, qvel in states:
            self.assertTrue(np.all(np.abs(qpos - u.init_qpos) <= 0.1))
        # The start state is the one set (MuJoCo's mj_forward normalises the torso quaternion,
        # as in Gymnasium): the first observation is qpos[2:] and qvel.
        env.reset(seed=0)
        u.set_state(*states[0])
        np.testing.assert_array_equal(u.data.qvel, states[0][1])
        np.testing.assert_allclose(u.data.qpos[:3], states[0][0][:3])
        np.testing.assert_allclose(u._get_obs(), np.concatenate([u.data.qpos[2:], u.data.qvel]),
                                   rtol=1e-6, atol=1e-6)
        path = train_model(self.tmp, "ant", "run: {name: ant, seed: 1, total_timesteps: 64}\n"
                           "env: {id: Ant-v4, normalize: {norm_obs: true, norm_reward: false}}\n"
                           "algo: {id: PPO, n_steps: 32, batch_size: 32, n_epochs: 1,"
                           " policy: {net_arch: [8]}}\n")
        model_policy = cross_eval.rlrun_policy(path)
        first = [cross_eval.episode_return(env, model_policy, *state)[0] for state in states]
        again = [cross_eval.episode_return(env, model_policy, *state)[0] for state in states]
        self.assertEqual(first, again)
        self.assertTrue(all(np.isfinite(first)))
        # Different start states give different returns for the same policy.
        self.assertEqual(len(set(first)), 3)


if __name__ == "__main__":
    unittest.main()
