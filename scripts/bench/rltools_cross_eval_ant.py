#!/usr/bin/env python3
"""Score an RLtools Ant-v4 PPO or TD3 policy and an rlrun model on the *same* start states.

RLtools' zoo prints the mean return of 100 episodes whose start states come from its own random
engine; `rlrun eval --seed 1000` scores other ones. This script takes the policy out of both
(RLtools: the `checkpoint.h` its benchmark build writes beside its results, a code export of
the actor, PPO's with its observation standardisation, TD3's an MLP followed by its
exploration-noise layer, which the export's example shows is off when evaluating; rlrun:
`model.zip` through the Python package, whose `predict` applies the model's NormalizeObservation
statistics) and runs both from the same start states, set with `env.unwrapped.set_state`:

  * `--episodes` states of Gymnasium's Ant-v4 distribution (gymnasium/envs/mujoco/ant_v4.py,
    `reset_model`: qpos = init_qpos + U(-0.1, 0.1), qvel = init_qvel + 0.1 N(0, 1)), drawn
    with numpy, and
  * with `--rltools-seed`, RLtools' own 100 evaluation states of that run, redrawn as its
    libstdc++ draws them (libstdcxx_random.py): the episodes behind the return it printed,
    replayed on Gymnasium's rules (RLtools' first step measures the torso's move from the
    model's initial pose, not from the start state: up to 2 apart in that step's reward).

The env is rlrun's Ant-v4 (Gymnasium's rules, TimeLimit 1000); both policies' mean actions are
clipped to the action space [-1, 1] before the env, as SB3 does and as RLtools' env clamps them.
The result is a paired comparison: the per-episode differences' mean and standard error.

Usage (docs/rltools.md, "Ant-v4"):
  PYTHONPATH=build/python /usr/bin/python3 scripts/bench/rltools_cross_eval_ant.py \
      --checkpoint DIR/.../checkpoint.h --model runs/.../model.zip [--episodes 100] \
      [--rltools-seed SEED]
Prints one line per policy and set of states, then `cross_eval` lines for scripts to parse.
"""
import argparse
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from libstdcxx_random import mt19937_stream, normal_float, uniform_double  # noqa: E402 (beside)
from rltools_checkpoint import fast_tanh, read_actor_export  # noqa: E402

ACTIVATIONS = {
    "IDENTITY": lambda x: x,
    "RELU": lambda x: np.maximum(x, 0),
    "TANH": np.tanh,
    "FAST_TANH": fast_tanh,
}


def rltools_policy(path):
    """The deterministic actor of an RLtools checkpoint.h: an optional standardize layer (mean,
    precision; PPO), then dense layers with the activations the file names, in order (PPO's
    Sequential of dense layers or TD3's MLP: input_layer, hidden_layer_i, output_layer); the
    output's first ACTION_DIM columns are the action (PPO: the Gaussian's mean, its learned log
    std after the dense layers unused; TD3: the tanh output, the td3_sampling layer after it has
    no parameters). The file's own example input and output check the forward pass."""
    export = read_actor_export(path)
    arrays, standardize = export.arrays, export.standardize is not None
    if standardize:
        obs_mean, obs_precision = (a.astype(np.float64) for a in export.standardize)
    activations = re.findall(r"dense::Configuration<.*?ActivationFunction::(\w+)", export.text)
    if not activations or len(arrays) < 2 * len(activations):
        raise SystemExit(f"{path}: found {len(activations)} dense layers and {len(arrays)} arrays")
    unknown = set(activations) - set(ACTIVATIONS)
    if unknown:
        raise SystemExit(f"{path}: activation {sorted(unknown)} not known to this script")
    example_in, example_out = export.example_in, export.example_out
    inputs = obs_mean.size if standardize else None
    layers = []
    for i, name in enumerate(activations):
        weights, bias = arrays[2 * i], arrays[2 * i + 1]
        fan_in = weights.size // bias.size
        if inputs is not None and fan_in != inputs:
            raise SystemExit(f"{path}: layer {i} takes {fan_in} inputs, the previous gives {inputs}")
        layers.append((weights.reshape(bias.size, fan_in).astype(np.float64), bias.astype(np.float64),
                       ACTIVATIONS[name]))
        inputs = bias.size
    obs_dim = layers[0][0].shape[1]

    def mean_action(obs):
        x = obs.astype(np.float64)
        if standardize:
            x = (x - obs_mean) * np.where(obs_precision != 0, obs_precision, 1)
        for weights, bias, activation in layers:
            x = activation(x @ weights.T + bias)
        return x

    batch = example_in.reshape(-1, obs_dim)
    expected = example_out.reshape(batch.shape[0], -1)
    got = mean_action(batch)
    error = np.abs(got[:, :expected.shape[1]] - expected).max()
    if error > 1e-3 * max(1.0, np.abs(expected).max()):
        raise SystemExit(f"{path}: forward pass differs from the file's example by {error}")
    return lambda obs: np.clip(mean_action(obs[None])[0], -1.0, 1.0)


def rlrun_policy(path):
    import rlrun  # PYTHONPATH=build/python (docs/python.md)
    model = rlrun.load(path)
    if model.env_id != "Ant-v4":
        raise SystemExit(f"{path}: a model of {model.env_id}, not Ant-v4")
    return lambda obs: np.asarray(model.predict(obs, deterministic=True)[0], dtype=np.float64)


def start_states(env, episodes, seed):
    """Gymnasium's Ant-v4 reset distribution (ant_v4.py `reset_model`, reset_noise_scale 0.1)."""
    rng = np.random.default_rng(seed)
    u = env.unwrapped
    nq, nv = len(u.init_qpos), len(u.init_qvel)
    return [(u.init_qpos + rng.uniform(-0.1, 0.1, nq), u.init_qvel + 0.1 * rng.standard_normal(nv))
            for _ in range(episodes)]


def rltools_start_states(init_qpos, init_qvel, seed, episodes=100):
    """The start states of RLtools' final evaluation for a run's seed (zoo.cpp: a std::mt19937
    seeded with seed + 1, rl/utils/evaluation: the 100 episodes' states drawn in order before
    any step; rl/environments/mujoco/ant/operations_cpu.h, `sample_initial_state`: each qpos
    entry init + uniform_real_distribution<double>(-0.1, 0.1), then each qvel entry init +
    normal_distribution<float>(0, 0.1)). RLtools' init_q and init_q_dot are the model's qpos0
    and zero velocities, as Gymnasium's init_qpos and init_qvel."""
    stream = mt19937_stream(seed + 1)
    states = []
    for _ in range(episodes):
        qpos = [q + uniform_double(stream, -0.1, 0.1) for q in init_qpos]
        qvel = [v + float(normal_float(stream, 0.0, 0.1)) for v in init_qvel]
        states.append((np.array(qpos), np.array(qvel)))
    return states


def episode_return(env, policy, qpos, qvel):
    """The return of one episode from (qpos, qvel), and whether it ended unhealthy (a fall)."""
    env.reset(seed=0)
    env.unwrapped.set_state(qpos, qvel)
    obs = env.unwrapped._get_obs()
    total = 0.0
    while True:
        obs, reward, terminated, truncated, _ = env.step(policy(obs).astype(np.float32))
        total += reward
        if terminated or truncated:
            return total, terminated


def score(env, policies, states, label):
    """Both policies from every state: one line each, the paired difference, a `cross_eval`
    line (label, episodes, RLtools' mean, rlrun's mean, the mean difference) for scripts."""
    episodes = {name: [episode_return(env, policy, *state) for state in states]
                for name, policy in policies.items()}
    returns = {name: np.array([r for r, _ in runs]) for name, runs in episodes.items()}
    difference = returns["rltools"] - returns["rlrun"]
    n = len(states)
    for name, values in returns.items():
        falls = sum(fell for _, fell in episodes[name])
        print(f"{label} {name}: mean {values.mean():.1f}, median {np.median(values):.1f}, min "
              f"{values.min():.1f}, {falls} of {n} episodes ended unhealthy before step 1000")
    print(f"{label} ({n} episodes): RLtools {returns['rltools'].mean():.1f}, rlrun "
          f"{returns['rlrun'].mean():.1f}, paired difference {difference.mean():+.1f} +/- "
          f"{difference.std() / np.sqrt(n):.1f} (standard error)")
    print(f"cross_eval {label} {n} {returns['rltools'].mean():.2f} "
          f"{returns['rlrun'].mean():.2f} {difference.mean():.2f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--checkpoint", required=True, help="RLtools' checkpoint.h")
    parser.add_argument("--model", required=True, help="rlrun's model.zip")
    parser.add_argument("--episodes", type=int, default=100)
    parser.add_argument("--states-seed", type=int, default=12345)
    parser.add_argument("--rltools-seed", type=int,
                        help="also RLtools' own 100 evaluation states of the run with this seed")
    args = parser.parse_args()

    import rlrun
    env = rlrun.make("Ant-v4")
    policies = {"rltools": rltools_policy(args.checkpoint), "rlrun": rlrun_policy(args.model)}
    if args.rltools_seed is not None:
        u = env.unwrapped
        score(env, policies, rltools_start_states(u.init_qpos, u.init_qvel, args.rltools_seed),
              "rltools_states")
    score(env, policies, start_states(env, args.episodes, args.states_seed), "common_states")
    return 0


if __name__ == "__main__":
    sys.exit(main())
