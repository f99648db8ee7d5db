"""scripts/bench/rltools_cross_eval.py, the tool behind docs/rltools.md's same-start-state returns:
its std::mt19937 and libstdc++ float draws against a C++ program compiled here, its Pendulum
against Gymnasium's recorded episodes, its reading of RLtools' checkpoint.h (the forward pass
checked against the file's own example), and rlrun models scored in batches."""

import importlib.util
import os
import unittest

import numpy as np

from rlrun_testing import TempDirMixin, compiled_cpp_lines, train_model

SOURCE_DIR = os.environ.get("RLRUN_SOURCE_DIR",
                            os.path.join(os.path.dirname(__file__), "..", ".."))
spec = importlib.util.spec_from_file_location(
    "rltools_cross_eval", os.path.join(SOURCE_DIR, "scripts", "bench", "rltools_cross_eval.py"))
cross_eval = importlib.util.module_from_spec(spec)
spec.loader.exec_module(cross_eval)

# RLtools' evaluation start states, written by C++ the way RLtools draws them
# (random/operations_cpu.h: std::mt19937(seed + 1); pendulum/operations_generic.h: theta, then
# theta_dot, each std::uniform_real_distribution<float>).
STATES_CPP = r"""
#include <cstdio>
#include <cstdlib>
#include <random>
int main(int argc, char** argv) {
  std::mt19937 engine(static_cast<std::mt19937::result_type>(std::atoi(argv[1]) + 1));
  const float pi = 3.14159265358979323846f;
  for (int i = 0; i < 100; ++i) {
    float theta = std::uniform_real_distribution<float>(-pi, pi)(engine);
    float theta_dot = std::uniform_real_distribution<float>(-1.0f, 1.0f)(engine);
    std::printf("%a %a\n", theta, theta_dot);
  }
}
"""


def write_checkpoint(path, arrays, example_in, example_out):
    """A file in the layout of RLtools' actor code export (checkpoint::save_code): the actor's
    parameter arrays in order, then the example input and output namespaces."""
    def memory(values):
        return ("constexpr float memory[] = {"
                + ", ".join(float(v).hex() + "f"
                            for v in np.asarray(values, dtype=np.float32).ravel()) + "};\n")
    with open(path, "w") as f:
        f.write("namespace rl_tools::checkpoint::actor {\n")
        for i, a in enumerate(arrays):
            f.write(f"namespace p{i} {{ {memory(a)} }}\n")
        f.write("}\nnamespace rl_tools::checkpoint::example::input {\n" + memory(example_in) + "}\n")
        f.write("namespace rl_tools::checkpoint::example::output {\n" + memory(example_out) + "}\n")


class RltoolsCrossEval(TempDirMixin, unittest.TestCase):
    def test_mt19937_is_the_standard_engine(self):
        # [rand.predef]: the 10000th output of a default-constructed std::mt19937 is 4123659995.
        stream = cross_eval.mt19937_stream(5489)
        for _ in range(9999):
            next(stream)
        self.assertEqual(next(stream), 4123659995)

    def test_rltools_start_states_equal_libstdcxx_draws(self):
        for seed in (1, 7, 123):
            expected = np.array([[float.fromhex(v) for v in line] for line in
                                 compiled_cpp_lines(self.tmp, "states", STATES_CPP, seed)])
            np.testing.assert_array_equal(cross_eval.rltools_start_states(seed), expected,
                                          err_msg=f"seed {seed}")

    def test_pendulum_replays_gymnasium_episodes(self):
        reference = os.environ.get("RLRUN_GYM_REFERENCE") or os.path.join(
            SOURCE_DIR, "..", "shared", "reference", "gymnasium")
        steps_csv = os.path.join(reference, "Pendulum-v1.csv")
        if not os.path.exists(steps_csv):
            self.skipTest(f"no Gymnasium reference at {reference} (RLRUN_GYM_REFERENCE)")
        init = np.genfromtxt(os.path.join(reference, "Pendulum-v1.init.csv"), delimiter=",",
                             names=True)
        rows = np.genfromtxt(steps_csv, delimiter=",", names=True)
        episodes = init["episode"].astype(int)
        actions = {e: rows["a0"][(rows["episode"] == e) & (rows["step"] > 0)] for e in episodes}
        rewards = np.array([rows["reward"][(rows["episode"] == e) & (rows["step"] > 0)].sum()
                            for e in episodes])
        self.assertTrue(all(len(a) == 200 for a in actions.values()))
        step = [0]

        def recorded(obs):
            a = np.array([actions[e][step[0]] for e in episodes])
            step[0] += 1
            return a
        returns = cross_eval.episode_returns(recorded, np.stack([init["s0"], init["s1"]], 1))
        np.testing.assert_allclose(returns, rewards, rtol=1e-6)

    def test_reads_an_rltools_td3_actor_and_checks_its_example(self):
        rng = np.random.default_rng(0)
        w0, b0 = rng.normal(size=(8, 3)), rng.normal(size=8)
        w1, b1 = rng.normal(size=(8, 8)), rng.normal(size=8)
        w2, b2 = rng.normal(size=(1, 8)), rng.normal(size=1)
        arrays = [a.astype(np.float32) for a in (w0, b0, w1, b1, w2, b2)]
        obs = rng.normal(size=(13, 3)).astype(np.float32)
        h = np.maximum(np.maximum(obs @ arrays[0].T + arrays[1], 0) @ arrays[2].T + arrays[3], 0)
        raw = np.tanh(h @ arrays[4].T + arrays[5])[:, 0]
        path = os.path.join(self.tmp, "checkpoint.h")
        write_checkpoint(path, arrays, obs, raw)
        policy = cross_eval.rltools_policy(path)
        np.testing.assert_allclose(policy(obs), 2.0 * raw, rtol=1e-5, atol=1e-6)
        write_checkpoint(path, arrays, obs, raw + 0.01)
        with self.assertRaisesRegex(SystemExit, "differs from the file's example"):
            cross_eval.rltools_policy(path)
        with open(path, "w") as f:
            f.write("// not a checkpoint\n")
        with self.assertRaisesRegex(SystemExit, "not an RLtools checkpoint.h"):
            cross_eval.rltools_policy(path)

    def test_scores_an_rlrun_model_on_many_start_states(self):
        # More episodes than Pendulum's 200-step limit in one predict batch.
        path = train_model(self.tmp, "sac", "run: {name: sac, seed: 1, total_timesteps: 120}\n"
                           "env: {id: Pendulum-v1}\n"
                           "algo: {id: SAC, learning_starts: 50, batch_size: 16,"
                           " policy: {net_arch: [16]}}\n")
        policy = cross_eval.rlrun_policy(path)
        states = cross_eval.gymnasium_start_states(1, 300)
        returns = cross_eval.episode_returns(policy, states)
        self.assertEqual(returns.shape, (300,))
        self.assertTrue(np.all(returns <= 0) and np.all(returns > -200 * 16.3))


if __name__ == "__main__":
    unittest.main()
