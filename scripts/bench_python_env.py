#!/usr/bin/env python3
"""Env steps/s from Python (issue 17): rlrun.make_vec("CartPole-v1", 64) stepping all 64 envs
in C++ per call, against CartPole stepped in pure Python — a port of Gymnasium's
classic_control/cartpole.py physics written here (what an SB3 user's DummyVecEnv steps), and
Gymnasium's own CartPole when gymnasium is importable. Random actions drawn up front. Prints a
Markdown table (scripts/bench.sh adds it to docs/benchmarks.md).

    PYTHONPATH=build/python /usr/bin/python3 scripts/bench_python_env.py [--steps N]
"""

import argparse
import math
import random
import time

import numpy as np

import rlrun


class PyCartPole:
    """Gymnasium's CartPole-v1 (classic_control/cartpole.py) in plain Python, with its
    TimeLimit of 500 steps and auto-reset, as a Python env loop steps it."""

    gravity, masscart, masspole, length, force_mag, tau = 9.8, 1.0, 0.1, 0.5, 10.0, 0.02
    total_mass = masspole + masscart
    polemass_length = masspole * length
    theta_threshold = 12 * 2 * math.pi / 360
    x_threshold = 2.4

    def __init__(self, seed):
        self.rng = np.random.default_rng(seed)
        self.reset()

    def reset(self):
        self.state = self.rng.uniform(-0.05, 0.05, size=4).tolist()
        self.steps = 0
        return np.array(self.state, dtype=np.float32)

    def step(self, action):
        x, x_dot, theta, theta_dot = self.state
        force = self.force_mag if action == 1 else -self.force_mag
        costheta, sintheta = math.cos(theta), math.sin(theta)
        temp = (force + self.polemass_length * theta_dot**2 * sintheta) / self.total_mass
        thetaacc = (self.gravity * sintheta - costheta * temp) / (
            self.length * (4.0 / 3.0 - self.masspole * costheta**2 / self.total_mass))
        xacc = temp - self.polemass_length * thetaacc * costheta / self.total_mass
        x, x_dot = x + self.tau * x_dot, x_dot + self.tau * xacc
        theta, theta_dot = theta + self.tau * theta_dot, theta_dot + self.tau * thetaacc
        self.state = [x, x_dot, theta, theta_dot]
        self.steps += 1
        terminated = (x < -self.x_threshold or x > self.x_threshold
                      or theta < -self.theta_threshold or theta > self.theta_threshold)
        truncated = self.steps >= 500
        obs = np.array(self.state, dtype=np.float32)
        if terminated or truncated:
            obs = self.reset()
        return obs, 1.0, terminated, truncated, {}


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
