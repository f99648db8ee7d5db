#!/usr/bin/env python3
"""Score an RLtools Pendulum-v1 policy and an rlrun model on the *same* start states.

RLtools' zoo prints the mean return of 100 episodes whose start states come from its own
random engine (seeded with the run's seed); `rlrun eval --seed 1000` scores other start states.
A Pendulum episode's return depends mostly on where it starts (std ~85 over start states), so
two 100-episode means differ by ~10 points even for equally good policies. This script takes
the policy out of both (RLtools: the `checkpoint.h` its benchmark build writes beside its
results; rlrun: `model.zip` through the Python package) and evaluates them on

  * RLtools' own 100 evaluation start states for the seed (`--rltools-seed`): the episodes
    behind the return RLtools printed, which the script recomputes as a check, and
  * `--episodes` start states drawn from Gymnasium's distribution (theta ~ U(-pi, pi),
    theta_dot ~ U(-1, 1)), the same for both policies: a paired comparison.

Pendulum's dynamics and cost are Gymnasium's (gymnasium/envs/classic_control/pendulum.py),
vectorised over episodes. RLtools' reward (include/rl_tools/rl/environments/pendulum/
operations_generic.h) charges the torque before clamping; `--rltools-reward` does the same,
only to recompute RLtools' printed PPO return (its policy's mean can leave [-1, 1]).

Usage (docs/rltools.md; scripts/bench/rltools.sh calls it):
  PYTHONPATH=build/python /usr/bin/python3 scripts/bench/rltools_cross_eval.py \
      --checkpoint DIR/.../checkpoint.h --model runs/.../model.zip --rltools-seed 1
Prints one line per policy and start-state set, then `cross_eval` lines for scripts to parse.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from libstdcxx_random import mt19937_stream, uniform_float  # noqa: E402 (beside this script)
from rltools_checkpoint import fast_tanh, read_actor_export  # noqa: E402


# --- RLtools' evaluation start states ---------------------------------------------------------
# zoo.cpp seeds an std::mt19937 with seed + 1 (include/rl_tools/random/operations_cpu.h, `init`)
# and draws, per episode, theta then theta_dot with std::uniform_real_distribution<float>
# (rl/environments/pendulum/operations_generic.h, `sample_initial_state`); libstdcxx_random.py
# has the engine and the draws.

def rltools_start_states(seed, episodes=100):
    stream = mt19937_stream(seed + 1)
    pi = np.float32(np.pi)
    states = []
    for _ in range(episodes):
        theta = uniform_float(next(stream), -pi, pi)
        theta_dot = uniform_float(next(stream), -1.0, 1.0)
        states.append((theta, theta_dot))
    return np.array(states, dtype=np.float64)


def gymnasium_start_states(seed, episodes):
    rng = np.random.default_rng(seed)
    return np.stack([rng.uniform(-np.pi, np.pi, episodes), rng.uniform(-1.0, 1.0, episodes)], 1)


# --- the two policies, as functions from observations (n, 3) to torques (n,) in [-2, 2] ------

def rltools_policy(path):
    """The deterministic actor in an RLtools checkpoint.h (its code export of the actor).

    SAC: ReLU MLP with 2 outputs (mean, log std), deterministic action tanh(mean). TD3: ReLU MLP
    with a tanh output. PPO: a standardize layer (mean, precision), FAST_TANH MLP, identity
    output. Actions are in [-1, 1] units; the env multiplies by max_torque 2. The file's own
    example input and output (13 observations) check the forward pass."""
    export = read_actor_export(path)
    arrays, standardize = export.arrays, export.standardize is not None
    if standardize:
        obs_mean, obs_precision = export.standardize
    if len(arrays) < 6:
        raise SystemExit(f"{path}: expected three dense layers, found {len(arrays)} arrays")
    w0, b0, w1, b1, w2, b2 = arrays[:6]
    w0 = w0.reshape(b0.size, 3)
    w1 = w1.reshape(b1.size, b0.size)
    w2 = w2.reshape(b2.size, b1.size)

    def raw_action(obs):
        if standardize:
            x = (obs - obs_mean) * np.where(obs_precision != 0, obs_precision, 1)
            h = fast_tanh(fast_tanh(x @ w0.T + b0) @ w1.T + b1)
            return (h @ w2.T + b2)[:, 0]
        h = np.maximum(np.maximum(obs @ w0.T + b0, 0) @ w1.T + b1, 0)
        return np.tanh((h @ w2.T + b2)[:, 0])

    example_in, example_out = export.example_in.reshape(-1, 3), export.example_out
    error = np.abs(raw_action(example_in) - example_out).max()
    if error > 1e-4:
        raise SystemExit(f"{path}: forward pass differs from the file's example by {error}")
    return lambda obs: 2.0 * raw_action(obs).astype(np.float64)


def rlrun_policy(path):
    import rlrun  # PYTHONPATH=build/python (docs/python.md)
    model = rlrun.load(path)
    if model.env_id != "Pendulum-v1":
        raise SystemExit(f"{path}: a model of {model.env_id}, not Pendulum-v1")
    return lambda obs: model.predict(obs, deterministic=True)[0][:, 0].astype(np.float64)


# --- Gymnasium's Pendulum-v1, one column per episode --------------------------------------------

def episode_returns(policy, start_states, charge_unclamped=False):
    g, m, l, dt, max_speed, max_torque = 10.0, 1.0, 1.0, 0.05, 8.0, 2.0
    theta, theta_dot = start_states[:, 0].copy(), start_states[:, 1].copy()
    returns = np.zeros(len(start_states))
    for _ in range(200):  # TimeLimit 200 (Gymnasium's registration; RLtools' EPISODE_STEP_LIMIT)
        obs = np.stack([np.cos(theta), np.sin(theta), theta_dot], 1).astype(np.float32)
        action = policy(obs)
        u = np.clip(action, -max_torque, max_torque)
        charged = action if charge_unclamped else u
        angle = ((theta + np.pi) % (2 * np.pi)) - np.pi
        returns -= angle ** 2 + 0.1 * theta_dot ** 2 + 0.001 * charged ** 2
        theta_dot = np.clip(theta_dot + (3 * g / (2 * l) * np.sin(theta) + 3.0 / (m * l ** 2) * u) * dt,
                            -max_speed, max_speed)
        theta = theta + theta_dot * dt
    return returns


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--checkpoint", required=True, help="RLtools' checkpoint.h")
    parser.add_argument("--model", required=True, help="rlrun's model.zip")
    parser.add_argument("--rltools-seed", type=int, required=True,
                        help="the seed RLtools trained and evaluated with (-s)")
    parser.add_argument("--episodes", type=int, default=10000,
                        help="common start states from Gymnasium's distribution (default 10000)")
    parser.add_argument("--states-seed", type=int, default=12345)
    parser.add_argument("--rltools-reward", action="store_true",
                        help="charge the unclamped torque, as RLtools' reward does")
    args = parser.parse_args()

    policies = {"rltools": rltools_policy(args.checkpoint), "rlrun": rlrun_policy(args.model)}
    state_sets = {
        "rltools_states": rltools_start_states(args.rltools_seed),
        "common_states": gymnasium_start_states(args.states_seed, args.episodes),
    }
    for set_name, states in state_sets.items():
        returns = {name: episode_returns(policy, states, args.rltools_reward)
                   for name, policy in policies.items()}
        difference = returns["rltools"] - returns["rlrun"]
        n = len(states)
        print(f"{set_name} ({n} episodes): RLtools {returns['rltools'].mean():.2f}, "
              f"rlrun {returns['rlrun'].mean():.2f}, paired difference "
              f"{difference.mean():+.2f} +/- {difference.std() / np.sqrt(n):.2f} (standard error)")
        print(f"cross_eval {set_name} {n} {returns['rltools'].mean():.2f} "
              f"{returns['rlrun'].mean():.2f} {difference.mean():.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
