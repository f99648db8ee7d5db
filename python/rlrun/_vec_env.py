"""SB3's VecEnv API over Gymnasium-style envs (stable_baselines3/common/vec_env/
dummy_vec_env.py): what ``model.get_env()`` returns and ``evaluate_policy`` steps.

``reset()`` returns the batch of observations only; ``step(actions)`` returns ``(obs, rewards,
dones, infos)`` with rewards float32, dones = terminated or truncated, and an env that finished
reset at once, its last observation in ``infos[i]["terminal_observation"]`` and
``infos[i]["TimeLimit.truncated"]`` at every step (true when it was truncated), as SB3's.
"""

from __future__ import annotations

import numpy as np


def _stack(values):
    if isinstance(values[0], dict):
        return {k: np.stack([v[k] for v in values]) for k in values[0]}
    return np.stack([np.asarray(v) for v in values])


class DummyVecEnv:
    def __init__(self, envs):
        self.envs = list(envs)
        self.num_envs = len(self.envs)
        self.observation_space = self.envs[0].observation_space
        self.action_space = self.envs[0].action_space
        self.render_mode = getattr(self.envs[0], "render_mode", None)
        self._seeds = [None] * self.num_envs
        self._options = [{} for _ in range(self.num_envs)]
        self.reset_infos = [{} for _ in range(self.num_envs)]

    def seed(self, seed=None):
        """The next reset seeds env i with seed + i (SB3's VecEnv.seed)."""
        if seed is None:
            return [None] * self.num_envs
        self._seeds = [seed + i for i in range(self.num_envs)]
        return list(self._seeds)

    def set_options(self, options=None):
        self._options = [dict(options or {}) for _ in range(self.num_envs)]

    def reset(self):
        observations = []
        for i, env in enumerate(self.envs):
            kwargs = {"seed": self._seeds[i]} if self._seeds[i] is not None else {}
            if self._options[i]:
                kwargs["options"] = self._options[i]
            obs, self.reset_infos[i] = env.reset(**kwargs)
            observations.append(obs)
        self._seeds = [None] * self.num_envs
        return _stack(observations)

    def step(self, actions):
        observations, rewards, dones, infos = [], [], [], []
        for i, env in enumerate(self.envs):
            action = actions[i] if self.num_envs > 1 or np.ndim(actions) > 0 else actions
            obs, reward, terminated, truncated, info = env.step(action)
            info = dict(info)
            done = bool(terminated or truncated)
            info["TimeLimit.truncated"] = bool(truncated and not terminated)
            if done:
                info["terminal_observation"] = obs
                obs, self.reset_infos[i] = env.reset()
            observations.append(obs)
            rewards.append(reward)
            dones.append(done)
            infos.append(info)
        return _stack(observations), np.asarray(rewards, dtype=np.float32), np.asarray(dones), infos

    def render(self, mode=None):
        return self.envs[0].render()

    def close(self):
        for env in self.envs:
            close = getattr(env, "close", None)
            if close:
                close()

    def get_attr(self, name, indices=None):
        return [getattr(self.envs[i], name) for i in self._indices(indices)]

    def env_method(self, name, *args, indices=None, **kwargs):
        return [getattr(self.envs[i], name)(*args, **kwargs) for i in self._indices(indices)]

    def _indices(self, indices):
        if indices is None:
            return range(self.num_envs)
        return [indices] if isinstance(indices, int) else indices
