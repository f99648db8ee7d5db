"""rlrun.make_vec: n of rlrun's envs stepped together in C++ (EnvPool's idea), with Gymnasium
1.x's VectorEnv API (gymnasium/vector/vector_env.py).

Auto-reset happens in the same step (Gymnasium 1.1's ``AutoresetMode.SAME_STEP``, SB3's
VecEnv habit): when env i's episode ends, ``obs[i]`` is already the next episode's first
observation and ``infos["final_obs"][i]`` the observation that ended it
(``infos["_final_obs"]`` the mask). Numeric info values come as arrays with ``_key`` masks,
as Gymnasium's ``VectorEnv._add_info`` builds them; ``infos["final_info"]`` holds the ending
step's info values (arrays and masks again). Per step: one C++ call and a handful of numpy
arrays, no per-env Python objects.
"""

from __future__ import annotations

import numpy as np

from . import _core
from . import _spaces
from ._env import _GymnasiumLike, kwargs_text, registered_limit, split_make_kwargs

if _spaces.HAVE_GYMNASIUM:
    import gymnasium as _gym

    _VectorBase = _gym.vector.VectorEnv
    try:  # Gymnasium >= 1.1
        from gymnasium.vector import AutoresetMode as _AutoresetMode

        _SAME_STEP = _AutoresetMode.SAME_STEP
    except ImportError:
        _SAME_STEP = "SameStep"
else:

    class _VectorBase(_GymnasiumLike):  # the parts of gymnasium's VectorEnv rlrun relies on
        metadata: dict = {}
        spec = None
        render_mode = None
        closed = False

    _SAME_STEP = "SameStep"


class RlrunVectorEnv(_VectorBase):
    """n copies of one of rlrun's envs. Build it with ``rlrun.make_vec(id, n, **kwargs)``."""

    def __init__(self, id: str, num_envs: int, max_episode_steps: int | None = None, **kwargs):
        self.closed = True  # until built: VectorEnv.__del__ closes envs that are not closed
        self._core = _core.VecEnv(id, int(num_envs), kwargs_text(kwargs),
                                  -1 if max_episode_steps is None else int(max_episode_steps))
        self.num_envs = self._core.num_envs
        self.single_observation_space = _spaces.from_description(self._core.observation_space)
        self.single_action_space = _spaces.from_description(self._core.action_space)
        self.observation_space = _spaces.batch_space(self.single_observation_space, self.num_envs)
        self.action_space = _spaces.batch_space(self.single_action_space, self.num_envs)
        self.metadata = {"autoreset_mode": _SAME_STEP, "render_modes": []}
        self.render_mode = None
        self.closed = False
        self._keys = list(self._core.info_keys)
        limit = registered_limit(id) if max_episode_steps is None else int(max_episode_steps)
        self.max_episode_steps = limit or None

    @property
    def id(self) -> str:
        return self._core.id

    def _infos(self, values: np.ndarray) -> dict:
        infos = {}
        if values.size:
            present = ~np.isnan(values)
            for j, key in enumerate(self._keys):
                mask = present[:, j]
                if mask.any():
                    infos[key] = np.where(mask, values[:, j], 0.0)
                    infos["_" + key] = mask
        self._gather_action_masks(infos)
        return infos

    def _gather_action_masks(self, infos: dict) -> None:
        # An env's mask travels as info keys action_mask.0, action_mask.1, ...
        # (src/rlrun/env/action_mask.hpp); here they become one (num_envs, n) int8 array
        # infos["action_mask"] with its "_action_mask" row mask, as rlrun.make's info["action_mask"]
        # per env. After a same-step auto-reset the row is the new episode's first state's mask
        # (the ending step's is in infos["final_info"]).
        n = 0
        while f"action_mask.{n}" in infos:
            n += 1
        if n == 0:
            return
        columns = [infos.pop(f"action_mask.{i}") for i in range(n)]
        rows = infos.pop("_action_mask.0")
        for i in range(1, n):
            infos.pop(f"_action_mask.{i}")
        infos["action_mask"] = np.stack(columns, axis=1).astype(np.int8)
        infos["_action_mask"] = rows

    def action_masks(self):
        """sb3-contrib's ``env_method("action_masks")`` for every env at once: a (num_envs, n)
        bool array of each env's legal actions in its current state (after an auto-reset, the
        new episode's), or None when the env reports no masks."""
        mask = getattr(self, "_action_mask", None)
        return None if mask is None else mask.astype(bool)

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        """Resets every env; with a seed, env i is seeded seed + i (Gymnasium's rule)."""
        if seed is not None:
            if not isinstance(seed, (int, np.integer)) or seed < 0:
                raise ValueError(f"seed must be a non-negative int, got {seed!r}")
            self._np_random = np.random.default_rng(seed)
        obs, values = self._core.reset(None if seed is None else int(seed))
        infos = self._infos(values)
        self._action_mask = infos.get("action_mask")
        return _spaces.batch_from_flat(self.single_observation_space, obs), infos

    def step(self, actions):
        flat = _spaces.batch_to_flat(self.single_action_space, actions, self.num_envs)
        obs, rewards, terminated, truncated, final_obs, values, step_values = self._core.step(flat)
        infos = self._infos(values)
        self._action_mask = infos.get("action_mask")
        if final_obs is not None:
            # As Gymnasium's SAME_STEP SyncVectorEnv fills them through VectorEnv._add_info:
            # arrays over all envs (zeros where no episode ended) with `_` masks, a Dict's keys
            # each with its mask.
            done = terminated | truncated
            rows = np.where(done[:, None], final_obs, np.float32(0))
            finals = _spaces.batch_from_flat(self.single_observation_space, rows)
            if isinstance(finals, dict):
                finals = {**finals, **{"_" + k: done for k in list(finals)}}
            infos["final_obs"], infos["_final_obs"] = finals, done
            infos["final_info"] = self._infos(np.where(done[:, None], step_values, np.nan))
            infos["_final_info"] = done
        return (_spaces.batch_from_flat(self.single_observation_space, obs), rewards, terminated,
                truncated, infos)

    def close(self, **kwargs):
        """Ends the envs (SUMO processes, Bullet worlds); closing twice is fine."""
        if not self.closed:
            self._core = _ClosedCore(self._core.id)
        self.closed = True

    def __repr__(self):
        return f"RlrunVectorEnv({self._core.id}, num_envs={self.num_envs})"


class _ClosedCore:
    def __init__(self, env_id):
        self.id = env_id

    def __getattr__(self, name):
        raise ValueError(f"rlrun.make_vec('{self.id}'): the vector env is closed")


def make_vec(id: str, num_envs: int = 1, **kwargs) -> RlrunVectorEnv:
    """``num_envs`` copies of rlrun's env ``id`` stepped together in C++, as a Gymnasium 1.x
    VectorEnv (same-step auto-reset). ``kwargs`` as for ``rlrun.make``."""
    env_kwargs, limit, render_mode = split_make_kwargs(kwargs)
    if render_mode is not None:
        raise ValueError("make_vec does not render; use rlrun.make(id, render_mode='rgb_array')")
    return RlrunVectorEnv(id, num_envs, max_episode_steps=None if limit < 0 else limit, **env_kwargs)
