"""rlrun.make: rlrun's registered envs as Gymnasium-API envs (gymnasium/core.py semantics).

The env is stepped in C++ (rlrun._core.Env); this class only shapes values: observations as
numpy arrays shaped like the space (float32 Box, np.int64 Discrete, dict for Dict), info as a
dict of the env's numeric values, render() as an (H, W, 3) uint8 frame. When Gymnasium is
importable the class is a ``gymnasium.Env`` subclass (SB3's ``_patch_env`` accepts nothing
else), with real ``gymnasium.spaces``.
"""

from __future__ import annotations

import json
import types
from typing import Any

import numpy as np

from . import _core
from . import _spaces

_Namespace = types.SimpleNamespace

class _GymnasiumLike:
    """Without gymnasium: what gymnasium.Env and gymnasium.vector.VectorEnv both give the
    classes rlrun builds on them (unwrapped, a lazily made np_random, a context manager)."""

    _np_random = None

    @property
    def unwrapped(self):
        return self

    @property
    def np_random(self) -> np.random.Generator:
        if self._np_random is None:
            self._np_random = np.random.default_rng()
        return self._np_random

    def __enter__(self):
        return self

    def __exit__(self, *args):
        self.close()
        return False


if _spaces.HAVE_GYMNASIUM:
    import gymnasium as _gym

    _EnvBase = _gym.Env
else:

    class _EnvBase(_GymnasiumLike):  # the parts of gymnasium.Env that rlrun's env relies on
        metadata: dict[str, Any] = {"render_modes": []}
        render_mode = None
        spec = None
        _np_random_seed = None

        def reset(self, *, seed=None, options=None):
            if seed is not None:
                self._np_random = np.random.default_rng(seed)
                self._np_random_seed = seed


def kwargs_text(kwargs: dict) -> str:
    """An env's kwargs as the YAML mapping its Config parses (JSON is YAML)."""
    try:
        return json.dumps(kwargs, indent=1, sort_keys=True, default=_json_default)
    except TypeError as e:
        raise TypeError(f"env kwargs must be plain values (numbers, strings, lists, dicts): {e}") from None


def _json_default(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"{value!r} ({type(value).__name__})")


def split_make_kwargs(kwargs: dict):
    """gymnasium.make's own keywords (max_episode_steps, render_mode) apart from the env's."""
    kwargs = dict(kwargs)
    limit = kwargs.pop("max_episode_steps", None)
    render_mode = kwargs.pop("render_mode", None)
    for key in ("disable_env_checker", "autoreset", "apply_api_compatibility"):
        kwargs.pop(key, None)
    if limit is not None and (not isinstance(limit, (int, np.integer)) or limit < 0):
        raise ValueError(f"max_episode_steps must be a non-negative int, got {limit!r}")
    return kwargs, (-1 if limit is None else int(limit)), render_mode


def registered_limit(env_id: str) -> int:
    for id_, _, limit in _core.list_envs():
        if id_ == env_id:
            return limit
    return 0


class _PhysicsData:
    """``env.unwrapped.data``: the qpos and qvel of a MuJoCo task, read when asked."""

    def __init__(self, core):
        self._core = core

    @property
    def qpos(self) -> np.ndarray:
        return self._core.qpos

    @property
    def qvel(self) -> np.ndarray:
        return self._core.qvel

    @property
    def qacc_warmstart(self) -> np.ndarray:
        return self._core.qacc_warmstart


class RlrunEnv(_EnvBase):
    """One of rlrun's envs. Build it with ``rlrun.make(id, **kwargs)``."""

    def __init__(self, id: str, render_mode: str | None = None, max_episode_steps: int | None = None,
                 **kwargs):
        self._core = _core.Env(id, kwargs_text(kwargs),
                               -1 if max_episode_steps is None else int(max_episode_steps))
        self.observation_space = _spaces.from_description(self._core.observation_space)
        self.action_space = _spaces.from_description(self._core.action_space)
        self._box_obs = type(self.observation_space).__name__ == "Box"
        # Images (Box of uint8, e.g. CarRacing-v3's) come back as uint8 arrays, as Gymnasium's.
        self._uint8_obs = self._box_obs and np.dtype(self.observation_space.dtype) == np.uint8
        self._dict_action = type(self.action_space).__name__ == "Dict"
        can_render = self._core.can_render
        self.metadata = {
            "render_modes": ["rgb_array"] if can_render else [],
            "render_fps": self._core.render_fps,
        }
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"{id}: render_mode {render_mode!r} is not supported (use 'rgb_array' or None)")
        if render_mode == "rgb_array" and not can_render:
            raise ValueError(f"{id} cannot render")
        self.render_mode = render_mode
        limit = registered_limit(id) if max_episode_steps is None else int(max_episode_steps)
        self.max_episode_steps = limit or None
        self.spec = _make_spec(id, limit, kwargs)
        self._kwargs = dict(kwargs)

    @property
    def id(self) -> str:
        return self._core.id

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        # gymnasium.Env.reset seeds self.np_random (Gymnasium's checker asserts it).
        super().reset(seed=seed)
        if seed is not None and (not isinstance(seed, (int, np.integer)) or seed < 0):
            raise ValueError(f"seed must be a non-negative int, got {seed!r}")
        if options:
            self._apply_reset_options(options)
        obs, info = self._core.reset(None if seed is None else int(seed))
        return self._observation(obs), self._gather_action_mask(info)

    def _gather_action_mask(self, info: dict) -> dict:
        # An env's action mask travels as info keys action_mask.0, action_mask.1, ...
        # (src/rlrun/env/action_mask.hpp); Python sees Gymnasium's info["action_mask"] (int8,
        # PettingZoo's convention) and sb3-contrib's action_masks() method.
        if "action_mask.0" not in info:
            self._action_mask = None
            return info
        entries = []
        while f"action_mask.{len(entries)}" in info:
            entries.append(info.pop(f"action_mask.{len(entries)}"))
        self._action_mask = np.asarray(entries, dtype=np.int8)
        info["action_mask"] = self._action_mask.copy()
        return info

    def action_masks(self):
        """sb3-contrib's action_masks(): the legal actions of the current state (bool), as the
        env reported them with its last reset() or step(); None when it reports none."""
        mask = getattr(self, "_action_mask", None)
        return None if mask is None else mask.astype(bool)

    def _observation(self, obs):
        if self._uint8_obs:
            return obs.astype(np.uint8)
        return obs if self._box_obs else _spaces.from_flat(self.observation_space, obs)

    def _apply_reset_options(self, options: dict):
        # CarRacing-v3's: options["randomize"] (Gymnasium's, with domain_randomize) and
        # options["track"] (rlrun's: the track to build, as env.unwrapped.track gives it).
        # Other envs take no options, as Gymnasium's own ignore theirs.
        if not self._core.has_race_track:
            return
        if "track" in options:
            self._core.set_next_track(options["track"])
        if "randomize" in options:
            self._core.set_next_randomize(bool(options["randomize"]))

    def step(self, action):
        if self._dict_action:
            action = _spaces.to_flat(self.action_space, action)
        obs, reward, terminated, truncated, info = self._core.step(action)
        return self._observation(obs), reward, terminated, truncated, self._gather_action_mask(info)

    @property
    def compute_reward(self):
        """GoalEnv.compute_reward(achieved_goal, desired_goal, info) (Gymnasium-Robotics'
        contract), on goal-conditioned envs only (BitFlippingEnv-v0, GripperReach-v0,
        GripperPush-v0, GripperPickAndPlace-v0: Dict observations with ``achieved_goal`` and
        ``desired_goal``). Other envs have no such attribute: SB3 takes any env that has one for
        a GoalEnv (``env_checker._is_goal_env``: ``hasattr(env.unwrapped, "compute_reward")``)
        and checks it as one."""
        if not self._core.is_goal_env:
            raise AttributeError(f"{self.id} is not a goal-conditioned env: it has no compute_reward")
        return self._compute_goal_reward

    def _compute_goal_reward(self, achieved_goal, desired_goal, info=None):
        # Goals of shape (goal_dim,) or (n, goal_dim), rewards of shape () or (n,); ``info`` is
        # not read. SB3's HerReplayBuffer calls it through ``env_method``.
        return self._core.compute_reward(np.asarray(achieved_goal), np.asarray(desired_goal))

    # Gymnasium's MujocoEnv state access (gymnasium/envs/mujoco/mujoco_env.py), on the MuJoCo
    # tasks only (other envs have none of these attributes): set_state(qpos, qvel), data.qpos and
    # data.qvel, init_qpos / init_qvel, dt, frame_skip, state_vector(). Arrays are float64
    # copies: change the state with set_state, as Gymnasium's own tasks do (docs/mujoco.md).
    def _physics(self):
        if not self._core.has_physics_state:
            raise AttributeError(f"{self.id} has no simulator state (qpos, qvel)")
        return self._core

    @property
    def set_state(self):
        """set_state(qpos, qvel, qacc_warmstart=None): MujocoEnv.set_state (then mj_forward);
        qacc_warmstart, when given, also sets the solver's warm start, which an exact replay of a
        recorded step needs (Gymnasium: data.qacc_warmstart[:] = ...)."""
        core = self._physics()
        return lambda qpos, qvel, qacc_warmstart=None: core.set_state(qpos, qvel, qacc_warmstart)

    @property
    def data(self):
        """The simulator state as MjData names it: ``data.qpos``, ``data.qvel`` (copies)."""
        return _PhysicsData(self._physics())

    @property
    def init_qpos(self) -> np.ndarray:
        return self._physics().init_qpos

    @property
    def init_qvel(self) -> np.ndarray:
        return self._physics().init_qvel

    @property
    def dt(self) -> float:
        return self._physics().dt

    @property
    def frame_skip(self) -> int:
        return self._physics().frame_skip

    def state_vector(self) -> np.ndarray:
        """np.concatenate([qpos, qvel]), as MujocoEnv.state_vector."""
        core = self._physics()
        return np.concatenate([core.qpos, core.qvel])

    def _get_obs(self) -> np.ndarray:
        """The observation of the current state (the task's _get_obs), float32."""
        return self._physics().observation()

    # Gymnasium's CarRacing attributes (gymnasium/envs/box2d/car_racing.py), on CarRacing-v3
    # only: track (the (alpha, beta, x, y) points of the centre line), car (hull and wheels as
    # Box2D and car_dynamics.py name them: car.hull.position, car.wheels[0].omega, ...; a
    # snapshot), reward, tile_visited_count and t; plus set_track(track), rlrun's way to build a
    # given track at the next reset (also reset(options={"track": track})): a seed need not
    # give Gymnasium's track, a track set here does (docs/car_racing.md).
    def _race_track(self):
        if not self._core.has_race_track:
            raise AttributeError(f"{self.id} has no race track")
        return self._core

    @property
    def track(self) -> list:
        return self._race_track().race_track()

    def set_track(self, track):
        """Builds ``track`` (a sequence of (alpha, beta, x, y)) at the next reset."""
        self._race_track().set_next_track(track)

    @property
    def car(self):
        state = self._race_track().race_car()
        wheels = []
        for w in state["wheels"]:
            wheel = _Namespace(**{k: v for k, v in w.items() if k != "joint_angle"})
            wheel.joint = _Namespace(angle=w["joint_angle"])
            wheels.append(wheel)
        return _Namespace(hull=_Namespace(**state["hull"]), wheels=wheels)

    @property
    def reward(self) -> float:
        return self._race_track().race_reward()

    @property
    def tile_visited_count(self) -> int:
        return self._race_track().race_tiles_visited()

    @property
    def t(self) -> float:
        return self._race_track().race_time()

    def render(self):
        """An (H, W, 3) uint8 RGB frame of the current state (render_mode "rgb_array")."""
        return self._core.render()

    def close(self):
        if not self._core.closed:
            self._core.close()

    def __repr__(self):
        return f"<RlrunEnv<{self._core.id}>>"


def _make_spec(env_id: str, limit: int, kwargs: dict):
    """Gymnasium's EnvSpec (gymnasium/envs/registration.py) when Gymnasium is there: its
    entry point is rlrun.make, so ``env.spec.make()`` builds the same env again."""
    if not _spaces.HAVE_GYMNASIUM:
        # The same fields, and make(), without Gymnasium.
        return types.SimpleNamespace(
            id=env_id, entry_point="rlrun:make", max_episode_steps=limit or None,
            kwargs={"id": env_id, **kwargs},
            make=lambda **more: make(**{"id": env_id, **kwargs, **more}))
    from gymnasium.envs.registration import EnvSpec

    return EnvSpec(
        id=env_id,
        entry_point="rlrun:make",
        max_episode_steps=limit or None,
        kwargs={"id": env_id, **kwargs},
    )


def make(id: str, **kwargs) -> RlrunEnv:
    """rlrun's env `id` (any id ``rlrun list`` shows) as a Gymnasium env.

    ``kwargs`` are the env's own parameters (``env.kwargs`` in an experiment file, checked
    strictly: an unknown or mistyped one raises rlrun.ConfigError), plus gymnasium.make's
    ``max_episode_steps`` (overrides the registered time limit; 0 = none) and
    ``render_mode`` (None or "rgb_array").
    """
    env_kwargs, limit, render_mode = split_make_kwargs(kwargs)
    return RlrunEnv(id, render_mode=render_mode,
                    max_episode_steps=None if limit < 0 else limit, **env_kwargs)
