"""SB3's callbacks for rlrun's Python training API (stable_baselines3/common/callbacks.py).

``model.learn(total_timesteps, callback=...)`` takes a BaseCallback, a list of them (a
CallbackList), or a function ``f(locals, globals) -> bool`` (SB3's ConvertCallback). Subclass
BaseCallback as in SB3 and override ``_on_step`` (return False to stop training),
``_on_training_start``, ``_on_rollout_start``, ``_on_rollout_end`` or ``_on_training_end``.
A callback written for SB3 (its own BaseCallback subclass) works too: rlrun's model has the
attributes SB3's BaseCallback reads (num_timesteps, get_env(), logger).

``self.locals`` holds, after each env step, SB3's common keys of collect_rollouts: ``new_obs``
(the batch of observations the policy sees next, shaped by the observation space), ``rewards``
(float32), ``dones`` (bool), ``infos`` (one dict per env: the env's numeric info, with
``TimeLimit.truncated`` at every step and ``terminal_observation`` where an episode ended),
``actions``
(the actions the envs were stepped with: SB3's ``clipped_actions`` for a Box, indices for
Discrete), ``n_envs``, ``num_timesteps`` and ``total_timesteps``. ``_on_rollout_end`` comes
where SB3 calls it: after a rollout, before the update that learns from it. Where rlrun
differs from SB3: the step runs in C++, so ``locals`` has no ``values`` or ``log_probs``
(tensors SB3's rollout loop holds in torch).
"""

from __future__ import annotations

import numpy as np

from . import _spaces


class BaseCallback:
    """SB3's BaseCallback: ``model``, ``n_calls``, ``num_timesteps``, ``locals``, ``globals``,
    ``training_env``, ``logger``, ``parent`` as there."""

    def __init__(self, verbose: int = 0):
        self.verbose = verbose
        self.model = None
        self.n_calls = 0
        self.num_timesteps = 0
        self.locals: dict = {}
        self.globals: dict = {}
        self.parent = None

    @property
    def training_env(self):
        return self.model.get_env() if self.model is not None else None

    @property
    def logger(self):
        return self.model.logger if self.model is not None else None

    def init_callback(self, model) -> None:
        self.model = model
        self._init_callback()

    def _init_callback(self) -> None:
        pass

    def on_training_start(self, locals_: dict, globals_: dict) -> None:
        self.locals = locals_
        self.globals = globals_
        self.num_timesteps = self.model.num_timesteps
        self._on_training_start()

    def _on_training_start(self) -> None:
        pass

    def on_rollout_start(self) -> None:
        self._on_rollout_start()

    def _on_rollout_start(self) -> None:
        pass

    def _on_step(self) -> bool:
        return True

    def on_step(self) -> bool:
        self.n_calls += 1
        self.num_timesteps = self.model.num_timesteps
        return self._on_step()

    def on_training_end(self) -> None:
        self._on_training_end()

    def _on_training_end(self) -> None:
        pass

    def on_rollout_end(self) -> None:
        self._on_rollout_end()

    def _on_rollout_end(self) -> None:
        pass

    def update_locals(self, locals_: dict) -> None:
        self.locals.update(locals_)
        self.update_child_locals(locals_)

    def update_child_locals(self, locals_: dict) -> None:
        pass


class CallbackList(BaseCallback):
    """Runs every callback at every event; training stops when any on_step returns False (all
    of them still run, as SB3's CallbackList)."""

    def __init__(self, callbacks: list):
        super().__init__()
        self.callbacks = list(callbacks)

    def _init_callback(self) -> None:
        for callback in self.callbacks:
            callback.init_callback(self.model)
            callback.parent = self.parent

    def _on_training_start(self) -> None:
        for callback in self.callbacks:
            callback.on_training_start(self.locals, self.globals)

    def _on_rollout_start(self) -> None:
        for callback in self.callbacks:
            callback.on_rollout_start()

    def _on_step(self) -> bool:
        continue_training = True
        for callback in self.callbacks:
            continue_training = callback.on_step() and continue_training
        return continue_training

    def _on_rollout_end(self) -> None:
        for callback in self.callbacks:
            callback.on_rollout_end()

    def _on_training_end(self) -> None:
        for callback in self.callbacks:
            callback.on_training_end()

    def update_child_locals(self, locals_: dict) -> None:
        for callback in self.callbacks:
            callback.update_locals(locals_)


class ConvertCallback(BaseCallback):
    """A function ``f(locals, globals) -> bool`` as a callback (None counts as True)."""

    def __init__(self, callback, verbose: int = 0):
        super().__init__(verbose)
        self.callback = callback

    def _on_step(self) -> bool:
        if self.callback is not None:
            return self.callback(self.locals, self.globals) is not False
        return True


class EveryNTimesteps(BaseCallback):
    """Calls ``callback.on_step()`` every ``n_steps`` timesteps (SB3's EveryNTimesteps)."""

    def __init__(self, n_steps: int, callback: BaseCallback):
        super().__init__()
        self.n_steps = n_steps
        self.last_time_trigger = 0
        self.callback = callback

    def _init_callback(self) -> None:
        self.callback.init_callback(self.model)
        self.callback.parent = self

    def _on_training_start(self) -> None:
        self.callback.on_training_start(self.locals, self.globals)

    def _on_step(self) -> bool:
        if (self.num_timesteps - self.last_time_trigger) >= self.n_steps:
            self.last_time_trigger = self.num_timesteps
            return self.callback.on_step()
        return True

    def _on_training_end(self) -> None:
        self.callback.on_training_end()

    def update_child_locals(self, locals_: dict) -> None:
        self.callback.update_locals(locals_)


class StopTrainingOnMaxEpisodes(BaseCallback):
    """Stops once ``max_episodes`` episodes per env have ended (SB3's: counted over all envs,
    max_episodes * n_envs in total)."""

    def __init__(self, max_episodes: int, verbose: int = 0):
        super().__init__(verbose)
        self.max_episodes = max_episodes
        self._total_max_episodes = max_episodes
        self.n_episodes = 0

    def _init_callback(self) -> None:
        self._total_max_episodes = self.max_episodes * self.training_env.num_envs

    def _on_step(self) -> bool:
        self.n_episodes += int(np.sum(self.locals["dones"]).item())
        continue_training = self.n_episodes < self._total_max_episodes
        if self.verbose >= 1 and not continue_training:
            print(f"Stopping training with a total of {self.num_timesteps} steps because the "
                  f"{self.max_episodes} episodes per env were reached")
        return continue_training


class ProgressBarCallback(BaseCallback):
    """SB3's ``learn(progress_bar=True)``: a bar of env steps over this ``learn()`` call, with
    tqdm when it is installed (SB3 uses tqdm.rich), else a line of text on stderr redrawn at
    most ten times a second."""

    def __init__(self):
        super().__init__()
        self._bar = None
        self._start = 0
        self._total = 0
        self._shown = 0.0

    def _on_training_start(self) -> None:
        self._start = self.model.num_timesteps
        self._total = int(self.locals.get("total_timesteps", 0))
        try:
            from tqdm import tqdm
            self._bar = tqdm(total=self._total, unit="steps")
        except ImportError:
            self._bar = None

    def _on_step(self) -> bool:
        done = self.num_timesteps - self._start
        if self._bar is not None:
            self._bar.update(done - self._bar.n)
            return True
        import sys
        import time
        now = time.monotonic()
        if now - self._shown >= 0.1 or done >= self._total:
            self._shown = now
            fraction = min(done / self._total, 1.0) if self._total > 0 else 1.0
            bar = "#" * int(fraction * 30)
            sys.stderr.write(f"\r{fraction:6.1%} [{bar:<30}] {done}/{self._total} steps")
            sys.stderr.flush()
        return True

    def _on_training_end(self) -> None:
        if self._bar is not None:
            self._bar.close()
        else:
            import sys
            sys.stderr.write("\n")
            sys.stderr.flush()


def as_callback(callback):
    """SB3's BaseAlgorithm._init_callback: None, a list, a function or a callback object."""
    if callback is None:
        return None
    if isinstance(callback, (list, tuple)):
        return CallbackList([as_callback(c) for c in callback])
    if hasattr(callback, "on_step") and hasattr(callback, "init_callback"):
        return callback
    if callable(callback):
        return ConvertCallback(callback)
    raise TypeError(f"callback must be a BaseCallback, a list of them or a function, got {callback!r}")


class _Dispatcher:
    """What rlrun's C++ training calls (python/src/py_training_session.cpp): shapes its flat
    arrays as SB3's locals and forwards each event to the callback."""

    def __init__(self, callback, model, total_timesteps: int):
        self.callback = callback
        self.model = model
        self.total_timesteps = total_timesteps
        self.space = model.observation_space
        self.action_space = model.action_space

    def _shape(self, flat):
        return _spaces.batch_from_flat(self.space, np.asarray(flat, dtype=np.float32))

    def __call__(self, event, num_timesteps, new_obs, rewards, dones, infos, actions=None):
        self.model.num_timesteps = int(num_timesteps)
        if event == "rollout_start":
            self.callback.on_rollout_start()
            return True
        if event == "rollout_end":
            self.callback.on_rollout_end()
            return True
        for info in infos:
            last = info.get("terminal_observation")
            if last is not None:
                info["terminal_observation"] = _spaces.from_flat(self.space, last)
        self.callback.update_locals({
            "new_obs": self._shape(new_obs),
            "actions": _spaces.batch_from_flat(self.action_space,
                                               np.asarray(actions, dtype=np.float32)),
            "rewards": rewards,
            "dones": dones,
            "infos": infos,
            "n_envs": len(dones),
            "num_timesteps": int(num_timesteps),
            "total_timesteps": self.total_timesteps,
        })
        return bool(self.callback.on_step())
