"""rlrun from Python (docs/python.md): trained models, rlrun's envs, and training.

    model = rlrun.load("runs/cartpole_ppo/seed1/model.zip")
    action, _ = model.predict(obs, deterministic=True)

    env = rlrun.make("CartPole-v1")              # a gymnasium.Env when Gymnasium is installed
    envs = rlrun.make_vec("CartPole-v1", 64)     # stepped together in C++
    run_dir = rlrun.train("configs/cartpole_ppo.yaml", seed=3)
    model = rlrun.PPO("MlpPolicy", "CartPole-v1").learn(10_000)   # SB3's API (_algorithms.py)
    lights = rlrun.parallel_env("TrafficNetwork-v0")  # PettingZoo's Parallel API (rlrun.env: AEC)
"""

import os as _os
import sys as _sys

# Python envs (env.id: python:...) that rlrun builds from here run in this interpreter (and so
# this virtualenv) unless a config names another in env.python (src/rlrun/envs/python/).
if _sys.executable:
    _os.environ.setdefault("RLRUN_PYTHON", _sys.executable)

from ._core import ConfigError, Interrupted, RuntimeFailure, UsageError
from ._core import __version__
from . import callbacks
from ._algorithms import (A2C, ARS, DDPG, DQN, PPO, QRDQN, SAC, TD3, TQC, TRPO, BaseAlgorithm,
                          CrossQ, MaskablePPO, RecurrentPPO)
from ._env import RlrunEnv, make
from ._model import Model, load
from ._pettingzoo import RlrunAECEnv, RlrunParallelEnv, env, parallel_env
from ._spaces import HAVE_GYMNASIUM
from ._train import train
from ._vec_env import DummyVecEnv
from ._vector import RlrunVectorEnv, make_vec
from .evaluation import evaluate_policy


def load_plugin(path) -> str:
    """Loads an env plugin library built against include/rlrun/ (as ``rlrun --plugin``): its
    envs become available to make, make_vec, train and load. Returns the resolved path."""
    import os

    from ._core import load_plugin as _load

    return _load(os.fspath(path))


def list_envs():
    """The registered env ids, as ``rlrun list`` shows them."""
    from ._core import list_envs as _list

    return [env_id for env_id, _, _ in _list()]


__all__ = [
    "A2C",
    "ARS",
    "BaseAlgorithm",
    "CrossQ",
    "DDPG",
    "DQN",
    "DummyVecEnv",
    "MaskablePPO",
    "PPO",
    "QRDQN",
    "RecurrentPPO",
    "SAC",
    "TD3",
    "TQC",
    "TRPO",
    "callbacks",
    "evaluate_policy",
    "ConfigError",
    "HAVE_GYMNASIUM",
    "Interrupted",
    "Model",
    "RlrunAECEnv",
    "RlrunEnv",
    "RlrunParallelEnv",
    "RlrunVectorEnv",
    "RuntimeFailure",
    "UsageError",
    "__version__",
    "list_envs",
    "load",
    "load_plugin",
    "make",
    "make_vec",
    "env",
    "parallel_env",
    "train",
]
