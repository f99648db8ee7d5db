#!/usr/bin/env python3
"""Records reference trajectories from the real Gymnasium classic-control envs.

tests/envs/test_gym_reference.cpp replays them through rlrun's ports and checks every
observation, reward and flag (tests/data/gymnasium/README.md describes the files). The data
in the repo was made by this script with Gymnasium 1.0.0 and numpy 1.24 (Debian 12's); it runs
outside CI, wherever that Gymnasium can be imported:

    python3 scripts/data/make_gymnasium_reference.py tests/data/gymnasium

Each env gets a few episodes, alternating a controller that keeps the episode going (so time
limits are reached: CartPole balanced for 500 steps, Pendulum swung for 200) or ends it by
success (MountainCar and Acrobot pumped to the goal) with uniformly random actions. Continuous
actions are drawn up to 25 % beyond the action space on purpose: the env must clip them exactly
as Gymnasium does.
"""
import csv
import math
import os
import sys

import gymnasium as gym
import numpy as np

# id -> episodes recorded
ENVS = {
    "CartPole-v1": 8,
    "Pendulum-v1": 4,
    "MountainCar-v0": 4,
    "MountainCarContinuous-v0": 3,
    "Acrobot-v1": 4,
}
SEED = 20241001  # any fixed number: the files are what this script printed for it


def internal_state(env):
    """The state the env steps from, as float64 (what the test sets before replaying)."""
    return [float(v) for v in np.asarray(env.unwrapped.state, dtype=np.float64).ravel()]


def controller(env_id, obs, rng):
    """A policy that keeps an episode going or ends it by success (see the module doc)."""
    if env_id == "CartPole-v1":  # push toward where the pole falls
        return int(obs[2] + 0.5 * obs[3] > 0)
    if env_id == "Pendulum-v1":  # energy pumping, torque beyond the limit on purpose
        return np.array([2.5 * math.copysign(1.0, obs[2])], dtype=np.float32)
    if env_id == "MountainCar-v0":  # accelerate with the velocity
        return 2 if obs[1] >= 0 else 0
    if env_id == "MountainCarContinuous-v0":
        return np.array([1.3 if obs[1] >= 0 else -1.3], dtype=np.float32)
    if env_id == "Acrobot-v1":  # torque with the second joint's velocity
        return 2 if obs[5] >= 0 else 0
    raise KeyError(env_id)


def random_action(space, rng):
    if isinstance(space, gym.spaces.Discrete):
        return int(rng.integers(space.n))
    span = space.high - space.low
    return rng.uniform(space.low - 0.25 * span, space.high + 0.25 * span).astype(np.float32)


def action_values(action):
    return [float(v) for v in np.atleast_1d(np.asarray(action, dtype=np.float64))]


def record(env_id, episodes, out_dir, rng):
    env = gym.make(env_id)
    rows, inits = [], []
    for episode in range(episodes):
        obs, _ = env.reset(seed=int(rng.integers(2**31)))
        inits.append([episode] + internal_state(env))
        rows.append([episode, 0, "", "", "", ""] + [float(v) for v in obs])
        use_controller = episode % 2 == 0
        step, done = 0, False
        while not done:
            action = controller(env_id, obs, rng) if use_controller else random_action(env.action_space, rng)
            obs, reward, terminated, truncated, _ = env.step(action)
            step += 1
            done = terminated or truncated
            rows.append([episode, step] + action_values(action) + [float(reward), int(terminated), int(truncated)]
                        + [float(v) for v in obs])
    env.close()
    n_obs = len(rows[0]) - 6
    n_act = len(action_values(env.action_space.sample()))
    header = ["episode", "step"] + [f"a{i}" for i in range(n_act)] + ["reward", "terminated", "truncated"]
    header += [f"o{i}" for i in range(n_obs)]
    write(os.path.join(out_dir, env_id + ".csv"), header, rows)
    write(os.path.join(out_dir, env_id + ".init.csv"),
          ["episode"] + [f"s{i}" for i in range(len(inits[0]) - 1)], inits)


def write(path, header, rows):
    # repr of a Python float is the shortest string that reads back as the same double.
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        for row in rows:
            w.writerow([repr(v) if isinstance(v, float) else v for v in row])


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else "tests/data/gymnasium"
    os.makedirs(out_dir, exist_ok=True)
    rng = np.random.default_rng(SEED)
    for env_id, episodes in ENVS.items():
        record(env_id, episodes, out_dir, rng)
        print(f"{env_id}: {episodes} episodes -> {out_dir}")
    print(f"gymnasium {gym.__version__}, numpy {np.__version__}")


if __name__ == "__main__":
    main()
