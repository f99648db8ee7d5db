"""SB3's training API on rlrun: ``rlrun.PPO("MlpPolicy", env, **kwargs).learn(n)`` and the
same for A2C, DQN, SAC, TD3, DDPG and sb3-contrib's TQC, QRDQN, TRPO, ARS, CrossQ,
MaskablePPO and RecurrentPPO (docs/python.md, "Training as in SB3").

The constructor takes SB3's keywords. They are written as an rl-zoo entry (the zoo files are
SB3's keywords too) and translated as ``rlrun train --zoo`` translates one, so every keyword
means what it means there (docs/zoo.md) and a keyword rlrun lacks is refused with its name;
SB3's objects become the zoo's text (``policy_kwargs=dict(activation_fn=torch.nn.ReLU)`` ->
``nn.ReLU``, ``action_noise=NormalActionNoise(0, 0.1)`` -> ``noise_type: normal``). ``seed``,
``tensorboard_log`` and ``verbose`` are the run's; ``device`` is accepted (rlrun runs on the
CPU). rlrun-only keywords: ``n_envs`` (copies of an env named by id) and the other zoo keys
(``normalize``, ``frame_stack``, ...), and ``run_dir``'s parent ``out_dir`` (default: a
temporary directory removed at exit).

The env is an id (rlrun's own env, else ``gymnasium:<id>``), ``rlrun.make(...)``'s env, a
live object with Gymnasium's API — stepped where it lives, in this interpreter
(python/rlrun/_live_env.py) — or a vectorized env whose envs live here (SB3's DummyVecEnv as
``make_vec_env`` makes it, Gymnasium's SyncVectorEnv): its envs are stepped one after the other.
A VecEnv wrapper (VecNormalize, VecFrameStack) is refused with the keyword that does the same.

Training lives in the model between calls, as in SB3: ``learn()`` continues with the same
envs, optimizer moments and replay buffer; ``num_timesteps`` keeps counting (SB3's default
``reset_num_timesteps=True`` starts its count again, rlrun always continues, so schedules and
logs run on). ``progress_bar=True`` shows tqdm's bar (a text line without tqdm);
``log_interval`` has SB3's meaning and default. ``save(path)`` writes rlrun's model file (``rlrun eval --model`` reads it;
``rlrun export --format sb3`` makes SB3's); ``load(path)`` reads rlrun's or SB3's.
"""

from __future__ import annotations

import atexit
import json
import os
import shutil
import tempfile

import numpy as np

from . import _core, _live_env
from ._model import load as _load_model
from ._vec_env import DummyVecEnv
from .callbacks import CallbackList, ProgressBarCallback, _Dispatcher, as_callback

_POLICIES = ("MlpPolicy", "MultiInputPolicy", "CnnPolicy", "MlpLstmPolicy", "CnnLstmPolicy",
             "MultiInputLstmPolicy")  # the last three: sb3-contrib's RecurrentPPO
# SB3's keywords that are not the algorithm's (rl-zoo's entry has none of them).
_RUN_KEYWORDS = ("seed", "verbose", "device", "tensorboard_log", "_init_setup_model")


def _literal(value):
    """SB3's Python objects as the zoo's text: torch classes as nn.X / th.optim.X."""
    if isinstance(value, type):
        module = value.__module__ or ""
        if module.startswith("torch.nn"):
            return f"nn.{value.__name__}"
        if module.startswith("torch.optim"):
            return f"th.optim.{value.__name__}"
        return value.__name__
    if isinstance(value, dict):
        return {str(k): _literal(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_literal(v) for v in value]
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    return value


def _noise_keys(noise) -> dict:
    """SB3's action noise object as the zoo's noise_type / noise_std."""
    kind = type(noise).__name__
    sigma = np.asarray(getattr(noise, "_sigma", getattr(noise, "sigma", 0.0)), dtype=float)
    if sigma.size and not np.allclose(sigma, sigma.flat[0]):
        raise ValueError(f"{kind}: rlrun's action noise has one sigma for every action dimension")
    std = float(sigma.flat[0]) if sigma.size else 0.0
    if kind == "NormalActionNoise":
        return {"noise_type": "normal", "noise_std": std}
    if kind == "OrnsteinUhlenbeckActionNoise":
        return {"noise_type": "ornstein-uhlenbeck", "noise_std": std}
    raise TypeError(f"action_noise: rlrun has NormalActionNoise and OrnsteinUhlenbeckActionNoise, "
                    f"not {kind}")


def _zoo_entry(policy: str, kwargs: dict, n_envs: int) -> dict:
    entry = {"policy": policy, "n_envs": n_envs, "n_timesteps": 1}
    for key, value in kwargs.items():
        if key == "action_noise":
            if value is not None:
                entry.update(_noise_keys(value))
            continue
        if callable(value) and not isinstance(value, type):
            raise TypeError(
                f"{key}: a Python function cannot reach rlrun's training; write a schedule as "
                f"the zoo does, e.g. {key}='lin_0.001' (linear from 0.001 to 0)")
        entry[key] = _literal(value)
    return entry


def _vec_env_members(env) -> list:
    """The Gymnasium envs a model trains on: the env itself, or the envs of a vectorized env
    that holds them in this interpreter (SB3's DummyVecEnv, as make_vec_env returns it, rlrun's
    own, Gymnasium's SyncVectorEnv), stepped one after the other as DummyVecEnv does."""
    if not hasattr(env, "num_envs") or hasattr(env, "unwrapped") and not hasattr(env, "envs"):
        return [env]
    kind = type(env).__name__
    if hasattr(env, "venv"):
        raise TypeError(
            f"env: {kind} wraps a VecEnv; rlrun applies the same as keywords (VecNormalize: "
            "normalize=True or normalize=dict(...); VecFrameStack: frame_stack=N) to the "
            "unwrapped env or env id")
    members = getattr(env, "envs", None)
    if not isinstance(members, (list, tuple)) or not members:
        raise TypeError(
            f"env: {kind} does not hold its envs here as a list `envs` (SB3's SubprocVecEnv "
            "steps them in worker processes, rlrun.make_vec in C++); pass the env id with "
            "n_envs=N (rlrun steps the copies on its own threads), or a DummyVecEnv")
    return list(members)


def _registered(env_id: str) -> bool:
    return any(e == env_id for e, _, _ in _core.list_envs())


# Tensors of rlrun's model that SB3 keeps on the algorithm, not in its policy's state_dict.
_ALGORITHM_ATTRIBUTES = ("log_ent_coef", "ent_coef_tensor", "exploration_rate")


def _sb3_name(algorithm: str, name: str) -> str:
    """rlrun's tensor name as SB3's policy names it: the same, but for DQN's and QR-DQN's
    network, which SB3's QNetwork / QuantileNetwork nest under their own name
    (q_net.0.weight -> q_net.q_net.0.weight; stable_baselines3/dqn/policies.py)."""
    net = {"DQN": "q_net", "QRDQN": "quantile_net"}.get(algorithm)
    if net:
        for owner in (net, net + "_target"):
            if name.startswith(owner + ".") and not name.startswith(owner + ".features_extractor."):
                return f"{owner}.{net}.{name[len(owner) + 1:]}"
    return name


class _Policy:
    """``model.policy``: the policy's tensors as numpy arrays under SB3's names (its
    ``policy.state_dict()``), read-only copies of the last saved weights (after each learn())."""

    def __init__(self, model):
        self._model = model

    def state_dict(self):
        algorithm = self._model.algorithm
        return {_sb3_name(algorithm, k): v for k, v in self._model._core.tensors.items()
                if k not in _ALGORITHM_ATTRIBUTES}

    def named_parameters(self):
        return list(self.state_dict().items())

    def parameters(self):
        return list(self.state_dict().values())

    def predict(self, observation, state=None, episode_start=None, deterministic=False):
        return self._model.predict(observation, state, episode_start, deterministic)


class _Logger:
    """What SB3 callbacks call on ``self.logger``: values recorded here are printed by
    ``dump()`` (rlrun's own log goes to progress.csv)."""

    def __init__(self):
        self.name_to_value = {}

    def record(self, key, value, exclude=None):
        self.name_to_value[key] = value

    def record_mean(self, key, value, exclude=None):
        self.name_to_value[key] = value

    def dump(self, step=0):
        if self.name_to_value:
            print(" | ".join(f"{k}: {v}" for k, v in self.name_to_value.items()), f"(step {step})")
        self.name_to_value = {}


class BaseAlgorithm:
    """One of SB3's algorithms on rlrun (the subclasses below name which)."""

    algorithm = ""  # rlrun's algorithm id
    _default_log_interval = 1  # SB3's learn(log_interval=...) default for the algorithm

    def __init__(self, policy, env, *args, **kwargs):
        if args:
            raise TypeError(f"{type(self).__name__}(policy, env, ...): pass the hyperparameters "
                            "as keywords (learning_rate=..., n_steps=...)")
        if not isinstance(policy, str) or policy not in _POLICIES:
            raise TypeError(f"policy: rlrun has {', '.join(_POLICIES)} (with policy_kwargs), "
                            f"not {policy!r}")
        self.policy_class = policy
        run = {k: kwargs.pop(k) for k in _RUN_KEYWORDS if k in kwargs}
        out_dir = kwargs.pop("out_dir", None)
        self.seed = run.get("seed")
        self.verbose = run.get("verbose", 0)
        self.tensorboard_log = run.get("tensorboard_log")
        self.logger = _Logger()
        self._env = None
        self._attach_env(env, kwargs.pop("n_envs", None))
        overrides = self._run_overrides(out_dir)
        entry = _zoo_entry(policy, kwargs, self._n_envs)
        path = os.path.join(self._scratch, "hyperparams.yml")
        with open(path, "w") as f:
            json.dump({self._env_id: entry}, f, indent=2)  # JSON is YAML
        self._session = _core.TrainingSession(path, self._env_id, self.algorithm, overrides)
        self._learn(0, None)  # SB3 builds the policy in the constructor: predict works now

    # -- the env ---------------------------------------------------------------------------
    def _attach_env(self, env, n_envs):
        self._live = None
        self._n_envs = 1 if n_envs is None else int(n_envs)
        if isinstance(env, str):
            self._env_id = env if _registered(env) or ":" in env else "gymnasium:" + env
            return
        if env is None:
            raise TypeError("env: pass an env id or a Gymnasium env")
        envs = _vec_env_members(env)
        if n_envs not in (None, len(envs)):
            raise ValueError(f"n_envs={n_envs}: the env object holds {len(envs)} env(s); pass an "
                             "env id for copies made by rlrun")
        self._n_envs = len(envs)
        self._env = env
        self._live = _live_env.register(envs)
        self._env_id = f"python-object:{self._live}"

    def _run_overrides(self, out_dir):
        if out_dir is None:
            out_dir = tempfile.mkdtemp(prefix="rlrun-model-")
            atexit.register(shutil.rmtree, out_dir, True)
        self._scratch = tempfile.mkdtemp(prefix="rlrun-hyperparams-")
        atexit.register(shutil.rmtree, self._scratch, True)
        # SB3's model evaluates nothing by itself (rl-zoo's entries get an EvalCallback).
        overrides = [f"run.out_dir={out_dir}", f"run.name={type(self).__name__.lower()}",
                     "eval.freq=0"]
        if self.seed is not None:
            overrides.append(f"run.seed={int(self.seed)}")
        if self.tensorboard_log:
            overrides.append(f"run.tensorboard_log={os.fspath(self.tensorboard_log)}")
        overrides.append(f"run.verbose={min(int(self.verbose or 0), 2)}")
        return overrides

    def get_env(self):
        """SB3's ``model.get_env()``: the env as an SB3 VecEnv (python/rlrun/_vec_env.py). For
        an env given by id, new copies of it (rlrun's, or gymnasium.make's)."""
        if self._env is None:
            from . import make
            if self._env_id.startswith("gymnasium:"):
                import gymnasium
                self._env = gymnasium.make(self._env_id[len("gymnasium:"):])
            else:
                self._env = make(self._env_id)
        if not hasattr(self._env, "num_envs"):  # a VecEnv given to the model stays as it is
            self._env = DummyVecEnv([self._env])
            if self.seed is not None:
                self._env.seed(self.seed)
        return self._env

    @property
    def env(self):
        return self.get_env()

    # -- training --------------------------------------------------------------------------
    def learn(self, total_timesteps: int, callback=None, log_interval=None,
              tb_log_name: str = "", reset_num_timesteps: bool = True,
              progress_bar: bool = False):
        """Trains ``total_timesteps`` more env steps (over all envs) and returns the model.
        ``log_interval``: a progress.csv row (and, with verbose=1, a console table) every N
        iterations (on-policy) or N episodes (off-policy); default SB3's for the algorithm."""
        if self._session is None:
            raise RuntimeError("this model was loaded without an env to train on: "
                               f"{type(self).__name__}.load(path, env=...) to train it")
        callback = as_callback(callback)
        if progress_bar:
            callback = CallbackList(([callback] if callback is not None else []) +
                                    [ProgressBarCallback()])
        if callback is not None:
            callback.init_callback(self)
            callback.on_training_start(locals(), globals())
        if log_interval is None:
            log_interval = self._default_log_interval
        self._learn(int(total_timesteps), callback, int(log_interval))
        if callback is not None:
            callback.on_training_end()
        return self

    def _learn(self, total_timesteps, callback, log_interval=None):
        target = self._session.num_timesteps + total_timesteps
        dispatch = _Dispatcher(callback, self, target) if callback is not None else None
        outcome = self._session.learn(target, dispatch, log_interval)
        self.run_dir = outcome["run_dir"]
        self._model_path = outcome["model_path"]
        self._model = _load_model(self._model_path, trust=True)
        self.num_timesteps = self._model.num_timesteps
        if outcome["interrupted"]:
            raise KeyboardInterrupt(f"training interrupted at step {outcome['timesteps']}")

    # -- using the model -------------------------------------------------------------------
    @property
    def observation_space(self):
        return self._model.observation_space

    @property
    def action_space(self):
        return self._model.action_space

    @property
    def policy(self):
        return _Policy(self._model)

    def predict(self, observation, state=None, episode_start=None, deterministic: bool = False,
                **kwargs):
        return self._model.predict(observation, state, episode_start, deterministic, **kwargs)

    def save(self, path):
        """rlrun's model file at ``path`` (".zip" added when it has no suffix, as in SB3)."""
        path = os.fspath(path)
        if not os.path.splitext(path)[1]:
            path += ".zip"
        shutil.copyfile(self._model_path, path)

    @classmethod
    def load(cls, path, env=None, device="auto", custom_objects=None, print_system_info=False,
             force_reset=True, **kwargs):
        """Reads rlrun's model file or SB3's (name SB3's env with ``env``: an id or a Gymnasium
        env with a spec). ``learn()`` then continues from its weights on ``env`` (or the env
        the file names)."""
        self = cls.__new__(cls)
        self.policy_class = None
        self.seed = kwargs.pop("seed", None)
        self.verbose = kwargs.pop("verbose", 0)
        self.tensorboard_log = kwargs.pop("tensorboard_log", None)
        self.logger = _Logger()
        self._env = None
        env_id = None
        if isinstance(env, str):
            env_id = env
        elif env is not None:
            spec = getattr(env, "spec", None)
            env_id = getattr(spec, "id", None)
        model = _load_model(path, trust=True, env=env_id)
        if cls.algorithm and model.algorithm != cls.algorithm:
            raise ValueError(f"{path} holds a {model.algorithm} model, not {cls.algorithm}")
        self._model, self._model_path = model, os.fspath(path)
        self.num_timesteps = model.num_timesteps
        self._session = None
        if env is None and (model.env_id.startswith("python-object:") or not model.env_id):
            return self
        self._attach_env(env if env is not None else model.env_id, kwargs.pop("n_envs", None))
        overrides = self._run_overrides(kwargs.pop("out_dir", None))
        overrides += [f"env.id={self._env_id}", f"env.n_envs={self._n_envs}",
                      f"run.init_from={os.path.abspath(self._model_path)}"]
        self._session = _core.TrainingSession.from_experiment(model.config, path, overrides)
        self._learn(0, None)
        return self

    def __repr__(self):
        return f"<rlrun.{type(self).__name__} on {self._env_id}, {self.num_timesteps} steps>"


def _algorithm_class(name: str, doc: str, log_interval: int = 1):
    return type(name, (BaseAlgorithm,), {"algorithm": name, "__doc__": doc,
                                         "__module__": "rlrun",
                                         "_default_log_interval": log_interval})


PPO = _algorithm_class("PPO", "SB3's PPO on rlrun (stable_baselines3/ppo/ppo.py).")
A2C = _algorithm_class("A2C", "SB3's A2C on rlrun (stable_baselines3/a2c/a2c.py).", 100)
DQN = _algorithm_class("DQN", "SB3's DQN on rlrun (stable_baselines3/dqn/dqn.py).", 4)
SAC = _algorithm_class("SAC", "SB3's SAC on rlrun (stable_baselines3/sac/sac.py).", 4)
TD3 = _algorithm_class("TD3", "SB3's TD3 on rlrun (stable_baselines3/td3/td3.py).", 4)
DDPG = _algorithm_class("DDPG", "SB3's DDPG on rlrun (stable_baselines3/ddpg/ddpg.py).", 4)
TQC = _algorithm_class("TQC", "sb3-contrib's TQC on rlrun.", 4)
QRDQN = _algorithm_class("QRDQN", "sb3-contrib's QR-DQN on rlrun.", 4)
TRPO = _algorithm_class("TRPO", "sb3-contrib's TRPO on rlrun.")
ARS = _algorithm_class("ARS", "sb3-contrib's ARS on rlrun.")
CrossQ = _algorithm_class("CrossQ", "sb3-contrib's CrossQ on rlrun.", 4)
MaskablePPO = _algorithm_class("MaskablePPO", "sb3-contrib's MaskablePPO on rlrun.")
RecurrentPPO = _algorithm_class("RecurrentPPO", "sb3-contrib's RecurrentPPO on rlrun.")
