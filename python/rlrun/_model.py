"""rlrun.load: a trained model file for prediction from Python.

``predict`` has SB3's signature and batching rules (stable_baselines3/common/policies.py
``BasePolicy.predict``, common/utils.py ``is_vectorized_observation``): one observation gives
one action without the batch axis (a 0-d int64 array for Discrete), a batch of n gives n
actions; Dict observations are dicts of arrays. Unlike SB3, where a VecNormalize wrapper is
the caller's business, the observation is the env's own and the model applies everything
``rlrun eval`` applies between the env and the policy — the normalisation statistics stored
in the model, one-hot encoding, action rescaling and clipping — so the action can be passed
straight to ``rlrun.make(model.env_id).step`` (runtime/io/model_policy.hpp).
"""

from __future__ import annotations

import os

import numpy as np

from . import _core
from . import _spaces


def _is_vectorized(observation, space) -> bool:
    kind = type(space).__name__
    if kind == "Box":
        if observation.shape == space.shape:
            return False
        if observation.shape[1:] == space.shape:
            return True
        raise ValueError(
            f"Error: Unexpected observation shape {observation.shape} for Box environment, "
            f"please use {space.shape} or (n_env, {', '.join(map(str, space.shape))}) for the "
            "observation shape."
        )
    if kind == "Discrete":
        if observation.shape == ():
            return False
        if len(observation.shape) == 1:
            return True
        raise ValueError(
            f"Error: Unexpected observation shape {observation.shape} for Discrete environment, "
            "please use () or (n_env,) for the observation shape."
        )
    if kind == "MultiDiscrete":
        n = len(space.nvec)
        if observation.shape == (n,):
            return False
        if len(observation.shape) == 2 and observation.shape[1] == n:
            return True
        raise ValueError(
            f"Error: Unexpected observation shape {observation.shape} for MultiDiscrete "
            f"environment, please use ({n},) or (n_env, {n}) for the observation shape."
        )
    if kind == "MultiBinary":
        if observation.shape == space.shape:
            return False
        if len(observation.shape) == len(space.shape) + 1 and observation.shape[1:] == space.shape:
            return True
        raise ValueError(
            f"Error: Unexpected observation shape {observation.shape} for MultiBinary "
            f"environment, please use {space.shape} or (n_env, {space.n}) for the observation shape."
        )
    raise ValueError(f"Error: Cannot determine if the observation is vectorized with the space type {space}.")


def _is_vectorized_dict(observation: dict, space) -> bool:
    subspaces = space.spaces
    missing = [k for k in subspaces if k not in observation]
    if missing:
        raise ValueError(f"Error: the observation lacks the key(s) {missing} of {space}")
    if all(np.shape(observation[k]) == s.shape for k, s in subspaces.items()):
        return False
    if all(np.shape(observation[k])[1:] == s.shape for k, s in subspaces.items()):
        return True
    problems = []
    for key, s in subspaces.items():
        try:
            _is_vectorized(np.asarray(observation[key]), s)
        except ValueError as e:
            problems.append(f"key '{key}' observation: {e}")
    raise ValueError(
        "There seems to be a mix of vectorized and non-vectorized observations. "
        "Unexpected observation shape for Dict environment: " + "; ".join(problems)
    )


class Model:
    """A model file loaded for prediction. Build it with ``rlrun.load(path)``."""

    def __init__(self, path: str | os.PathLike, overrides=None, trust: bool = False):
        self.path = os.fspath(path)
        self._core = _core.Model(self.path, list(overrides or []), bool(trust))
        self.observation_space = _spaces.from_description(self._core.observation_space)
        self.action_space = _spaces.from_description(self._core.action_space)
        self._obs_dim = _spaces.flat_dim(self.observation_space)
        kind = type(self.action_space).__name__
        # SB3's action dtypes: int64 from Categorical/MultiCategorical, float32 otherwise
        # (a Bernoulli's MultiBinary actions too).
        self._action_dtype = np.int64 if kind in ("Discrete", "MultiDiscrete") else np.float32

    @property
    def algorithm(self) -> str:
        """"PPO", "A2C", "DQN", "SAC", "TD3", "DDPG", "TQC", "QRDQN", "CrossQ" or "MaskablePPO"."""
        return self._core.algorithm

    @property
    def env_id(self) -> str:
        return self._core.env_id

    @property
    def num_timesteps(self) -> int:
        return self._core.num_timesteps

    @property
    def rlrun_version(self) -> str:
        return self._core.rlrun_version

    @property
    def config(self) -> str:
        """The model's resolved experiment (YAML text)."""
        return self._core.config_yaml

    @property
    def policy_observation_space(self):
        """What the policy sees on top of the model's wrappers (e.g. one-hot, stacked)."""
        return _spaces.from_description(self._core.policy_observation_space)

    def predict(self, observation, state=None, episode_start=None, deterministic: bool = False,
                action_masks=None):
        """SB3's ``predict``: returns ``(action, state)``. A RecurrentPPO model takes and returns
        sb3-contrib's LSTM state, a pair ``(h, c)`` of arrays (n_lstm_layers, n_envs,
        lstm_hidden_size); ``state=None`` starts from zeros and ``episode_start`` (one flag per
        observation; None: all False) zeroes an observation's state first, as sb3-contrib's
        ``RecurrentPPO.predict``. Other models are not recurrent: ``state`` comes back unchanged.
        ``action_masks`` (MaskablePPO models, as
        sb3-contrib's ``predict``): one mask per observation, True/1 for a legal action (n for
        Discrete(n), sum(nvec) for MultiDiscrete, 2n for MultiBinary(n)); masked actions are
        never chosen. None acts without masks."""
        if isinstance(observation, tuple) and len(observation) == 2 and isinstance(observation[1], dict):
            raise ValueError(
                "You have passed a tuple to the predict() function instead of a Numpy array or a "
                "Dict. You are probably mixing Gym API with SB3 VecEnv API: `obs, info = "
                "env.reset()` (Gym) vs `obs = vec_env.reset()` (SB3 VecEnv)."
            )
        space = self.observation_space
        if type(space).__name__ == "Dict":
            if not isinstance(observation, dict):
                raise ValueError(f"Error: the model takes Dict observations {space}, got {type(observation).__name__}")
            vectorized = _is_vectorized_dict(observation, space)
            if vectorized:
                n = len(np.asarray(observation[next(iter(space.spaces))]))
                flat = _spaces.batch_to_flat(space, observation, n, "observation")
            else:
                flat = _spaces.to_flat(space, observation, "observation").reshape(1, -1)
        else:
            obs = np.asarray(observation)
            vectorized = _is_vectorized(obs, space)
            flat = np.ascontiguousarray(obs, dtype=np.float32).reshape(-1, self._obs_dim)
        masks = None
        if action_masks is not None:
            size = self._core.action_mask_size
            if size == 0:
                raise ValueError(f"predict: action_masks given, but {self.algorithm} takes no "
                                 "action masks (MaskablePPO does)")
            masks = np.asarray(action_masks, dtype=np.float32)
            if masks.size != size * flat.shape[0]:
                raise ValueError(f"predict: action_masks has {masks.size} entries; the model takes "
                                 f"{size} per observation ({flat.shape[0]} observations)")
            masks = np.ascontiguousarray(masks.reshape(flat.shape[0], size))
        flat_state, starts = self._recurrent_input(state, episode_start, flat.shape[0])
        flat_actions, next_state = self._core.predict(flat, bool(deterministic), masks, flat_state,
                                                      starts)
        if next_state is not None:
            state = self._recurrent_output(next_state)
        actions = flat_actions.reshape((-1, *self.action_space.shape))
        if self._action_dtype is not np.float32:
            actions = actions.astype(self._action_dtype)
        if not vectorized:
            actions = actions.squeeze(axis=0)
        return actions, state

    def _recurrent_input(self, state, episode_start, n):
        """sb3-contrib's (h, c) state as the core's (n, state size) rows: each observation's h
        of every layer, then its c."""
        size = self._core.recurrent_state_size
        if size == 0:
            return None, None
        layers = self._core.recurrent_layers
        hidden = size // (2 * layers)
        if state is None:
            flat_state = np.zeros((n, size), dtype=np.float32)
        else:
            if not (isinstance(state, tuple) and len(state) == 2):
                raise ValueError("predict: a RecurrentPPO state is the pair (h, c) that predict "
                                 "returned")
            parts = []
            for part in state:
                part = np.asarray(part, dtype=np.float32)
                if part.shape != (layers, n, hidden):
                    raise ValueError(f"predict: expected state arrays of shape ({layers}, {n}, "
                                     f"{hidden}), got {part.shape}")
                parts.append(part.transpose(1, 0, 2).reshape(n, layers * hidden))
            flat_state = np.ascontiguousarray(np.concatenate(parts, axis=1))
        if episode_start is None:
            starts = np.zeros(n, dtype=np.float32)
        else:
            starts = np.asarray(episode_start, dtype=np.float32).reshape(-1)
            if starts.size != n:
                raise ValueError(f"predict: episode_start has {starts.size} entries for {n} "
                                 "observations")
        return flat_state, np.ascontiguousarray(starts)

    def _recurrent_output(self, flat_state):
        layers = self._core.recurrent_layers
        n, size = flat_state.shape
        hidden = size // (2 * layers)
        h = flat_state[:, :layers * hidden].reshape(n, layers, hidden).transpose(1, 0, 2)
        c = flat_state[:, layers * hidden:].reshape(n, layers, hidden).transpose(1, 0, 2)
        return np.ascontiguousarray(h), np.ascontiguousarray(c)

    def __repr__(self):
        return f"<rlrun.Model {self.algorithm} on {self.env_id}, {self.num_timesteps} steps: {self.path}>"


def load(
    path: str | os.PathLike, overrides=None, trust: bool = False, env: str | None = None
) -> Model:
    """Loads a model file written by ``rlrun train`` (model.zip, best_model.zip, a checkpoint),
    or one Stable-Baselines3 saved (``model.save(...)``; docs/sb3_models.md), which does not
    record its env: name it with ``env="CartPole-v1"`` (as ``rlrun eval --env``).

    Model files are untrusted input (docs/security.md): the file is read in two phases within
    a budget its own configuration justifies, and can name no program or plugin. Problems
    raise rlrun.RuntimeFailure with ``rlrun eval``'s message. ``overrides`` are ``--set``
    assignments ("key=value") over the model's config, as ``rlrun eval --set``.
    ``trust=True`` is ``rlrun eval --trust``: for your own models, accept what the file names
    (a ``python:``/``gymnasium:`` env's code, its interpreter, a SUMO binary or scenario,
    plugin libraries) instead of vouching for each with ``overrides``; each such value is
    printed on stderr before it is used.
    """
    overrides = list(overrides or [])
    if env is not None:  # before the caller's own, as rlrun eval puts --env before --set
        overrides.insert(0, "env.id=" + str(env))
    return Model(path, overrides, trust)
