#!/usr/bin/env python3
"""Env steps/s from Python (issue 17): rlrun.make_vec("CartPole-v1", 64) stepping all 64 envs
in C++ per call, against CartPole stepped in pure Python — a port of Gymnasium's
classic_control/cartpole.py physics written here (what an SB3 user's DummyVecEnv steps), and
Gymnasium's own CartPole when gymnasium is importable. Random actions drawn up front. Prints a
Markdown table (scripts/bench.sh adds it to docs/benchmarks.md).

    PYTHONPATH=build/python /usr/bin/python3 scripts/bench/python_env.py [--steps N]
"""

import argparse
import os
import random
import sys
import time

import numpy as np

import rlrun

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests",
                                "python_envs"))
from rlrun_test_envs.cartpole import CartPolePort  # noqa: E402


class PyCartPole:
    """The tests' pure-Python port of Gymnasium's CartPole-v1 physics
    (tests/python_envs/rlrun_test_envs/cartpole.py), with its TimeLimit of 500 steps and
    auto-reset, as a Python env loop steps it."""

    def __init__(self, seed):
        self.env = CartPolePort()
        self.reset(seed)

    def reset(self, seed=None):
        self.steps = 0
        return self.env.reset(seed=seed)[0]

    def step(self, action):
        obs, reward, terminated, _, info = self.env.step(action)
        self.steps += 1
        truncated = self.steps >= 500
        if terminated or truncated:
            obs = self.reset()
        return obs, reward, terminated, truncated, info


def rate(step_once, calls, envs_per_call):
    step_once()  # warm-up
    start = time.perf_counter()
    for _ in range(calls):
        step_once()
    return calls * envs_per_call / (time.perf_counter() - start)


def best_of(n, f):
    return max(f() for _ in range(n))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--steps", type=int, default=640_000, help="env steps per measurement")
    parser.add_argument("--n", type=int, default=64, help="envs in the vector env")
    args = parser.parse_args()
    n = args.n
    calls = args.steps // n
    rows = []

    envs = rlrun.make_vec("CartPole-v1", n)
    envs.reset(seed=0)
    actions = np.random.default_rng(0).integers(0, 2, size=(calls + 1, n))
    it = iter(range(10**12))
    r = best_of(3, lambda: rate(lambda: envs.step(actions[next(it) % len(actions)]), calls, n))
    rows.append((f"rlrun.make_vec(\"CartPole-v1\", {n}).step (one C++ call for {n} envs)", r))

    env = rlrun.make("CartPole-v1")
    env.reset(seed=0)
    single = random.Random(0)

    def single_step():
        _, _, te, tr, _ = env.step(single.randrange(2))
        if te or tr:
            env.reset()

    r = best_of(3, lambda: rate(single_step, args.steps // 16, 1))
    rows.append(("rlrun.make(\"CartPole-v1\").step, one env", r))

    py_envs = [PyCartPole(i) for i in range(n)]
    py_rng = random.Random(0)

    def py_step():
        obs = [e.step(py_rng.randrange(2))[0] for e in py_envs]
        return np.stack(obs)

    r = best_of(3, lambda: rate(py_step, calls // 8, n))
    rows.append((f"pure-Python CartPole (Gymnasium's physics), {n} envs in a Python loop", r))

    if rlrun.HAVE_GYMNASIUM:
        import gymnasium

        g = gymnasium.vector.SyncVectorEnv([lambda: gymnasium.make("CartPole-v1") for _ in range(n)])
        g.reset(seed=0)
        g_rng = np.random.default_rng(0)
        r = best_of(3, lambda: rate(lambda: g.step(g_rng.integers(0, 2, size=n)), calls // 8, n))
        rows.append((f"gymnasium {gymnasium.__version__} SyncVectorEnv of {n} CartPole-v1", r))

    base = rows[2][1]
    print("| env loop (random actions) | env steps/s | vs pure Python |")
    print("|---|---|---|")
    for name, r in rows:
        print(f"| {name} | {r:,.0f} | {r / base:.1f}x |")


if __name__ == "__main__":
    main()
