"""SB3's VecNormalize.reset / step_wait (stable_baselines3/common/vec_env/vec_normalize.py,
common/running_mean_std.py) in numpy, over recorded raw transitions, for
tests/wrappers/test_vec_normalize.cpp. Written from SB3's formulas (no SB3 import: it needs
torch). Reads the raw batch from argv[1]; prints the normalised batch.

Input lines:  gamma n dim / "reset" obs... / "step" obs... | rewards... | dones... | final...
Output lines: "reset" obs... / "step" obs... | rewards... | final (of done envs)...
Floats are printed with repr (shortest round-trip)."""
import sys

import numpy as np


class RunningMeanStd:  # SB3 common/running_mean_std.py
    def __init__(self, shape=()):
        self.mean = np.zeros(shape, np.float64)
        self.var = np.ones(shape, np.float64)
        self.count = 1e-4

    def update(self, arr):
        batch_mean = np.mean(arr, axis=0)
        batch_var = np.var(arr, axis=0)
        batch_count = arr.shape[0]
        delta = batch_mean - self.mean
        tot_count = self.count + batch_count
        new_mean = self.mean + delta * batch_count / tot_count
        m_a = self.var * self.count
        m_b = batch_var * batch_count
        m_2 = m_a + m_b + np.square(delta) * self.count * batch_count / tot_count
        self.mean, self.var, self.count = new_mean, m_2 / tot_count, tot_count


def main():
    lines = open(sys.argv[1]).read().split("\n")
    gamma, n, dim = lines[0].split()
    gamma, n, dim = float(gamma), int(n), int(dim)
    obs_rms, ret_rms = RunningMeanStd((dim,)), RunningMeanStd(())
    returns = np.zeros(n)
    eps, clip = 1e-8, 10.0

    def norm_obs(o):
        return np.clip((o - obs_rms.mean) / np.sqrt(obs_rms.var + eps), -clip, clip).astype(np.float32)

    def fmt(values):
        return " ".join(repr(float(v)) for v in values)

    out = []
    for line in lines[1:]:
        if not line:
            continue
        kind, rest = line.split(" ", 1)
        parts = rest.split("|")
        obs = np.array(parts[0].split(), np.float32).reshape(n, dim)
        obs_rms.update(obs)
        if kind == "reset":
            returns = np.zeros(n)
            out.append("reset " + fmt(norm_obs(obs).ravel()))
            continue
        rewards = np.array(parts[1].split(), np.float64)
        dones = np.array(parts[2].split(), np.int64).astype(bool)
        final = np.array(parts[3].split(), np.float32).reshape(n, dim)
        normalized = norm_obs(obs)
        returns = returns * gamma + rewards
        ret_rms.update(returns)
        scaled = np.clip(rewards / np.sqrt(ret_rms.var + eps), -clip, clip)
        finals = norm_obs(final[dones]).ravel()
        returns[dones] = 0
        out.append("step " + fmt(normalized.ravel()) + "|" + fmt(scaled) + "|" + fmt(finals))
    print("\n".join(out))


main()
