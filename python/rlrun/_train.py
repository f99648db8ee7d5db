"""rlrun.train: ``rlrun train`` in-process (runtime/run/trainer.hpp, the same code as the CLI).

Overrides map to ``rlrun train --set`` assignments by one rule:

* a key with a dot is a config path: ``{"algo.learning_rate": 3e-4}`` -> ``--set
  algo.learning_rate=0.0003``;
* the CLI's shorthand options keep their meaning: ``seed`` -> ``run.seed``, ``timesteps`` (or
  ``total_timesteps``) -> ``run.total_timesteps``, ``out`` (or ``out_dir``) -> ``run.out_dir``,
  ``name`` -> ``run.name``, ``init_from`` -> ``run.init_from``, and SB3's ``tensorboard_log``
  / ``tb_log_name`` -> ``run.tensorboard_log`` / ``run.tb_log_name``;
* any other key is a TypeError.

Values are written as YAML, as a value typed after ``--set key=`` would be: numbers and
strings as they are (``"lin_0.001"`` stays a schedule), True/False/None as true/false/null,
lists and dicts in flow style.
"""

from __future__ import annotations

import json
import os

from . import _core

_SHORTHANDS = {
    "seed": "run.seed",
    "timesteps": "run.total_timesteps",
    "total_timesteps": "run.total_timesteps",
    "out": "run.out_dir",
    "out_dir": "run.out_dir",
    "name": "run.name",
    "init_from": "run.init_from",
    "tensorboard_log": "run.tensorboard_log",
    "tb_log_name": "run.tb_log_name",
}


def _yaml_value(value) -> str:
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float, str)):
        return str(value) if not isinstance(value, float) else repr(value)
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if hasattr(value, "item"):  # numpy scalars
        return _yaml_value(value.item())
    return json.dumps(value)


def override_assignments(overrides) -> list[str]:
    """The ``--set`` assignments a dict (or list of "key=value" strings) of overrides means."""
    if overrides is None:
        return []
    if isinstance(overrides, (list, tuple)):
        out = []
        for item in overrides:
            if not isinstance(item, str) or "=" not in item:
                raise TypeError(f"an override in a list is a 'key=value' string, got {item!r}")
            out.append(item)
        return out
    out = []
    for key, value in dict(overrides).items():
        if "." in key:
            path = key
        elif key in _SHORTHANDS:
            path = _SHORTHANDS[key]
        else:
            raise TypeError(
                f"rlrun.train: unknown override {key!r}: use a config path with a dot "
                f"(e.g. 'algo.learning_rate') or one of {sorted(_SHORTHANDS)}"
            )
        out.append(f"{path}={_yaml_value(value)}")
    return out


def train(config, overrides=None, /, **kwargs) -> str:
    """Trains an experiment and returns its run directory (``runs/<name>/seed<N>``).

    ``config`` is an experiment file's path or the experiment as a dict (the file's content);
    ``overrides`` (a dict or a list of "key=value" strings) and keyword arguments change it as
    ``--set`` does (see the module's rule), e.g. ``train("configs/cartpole_ppo.yaml", seed=3,
    timesteps=20000)`` or ``train(cfg, {"algo.learning_rate": 3e-4})``.

    A bad file or value raises rlrun.ConfigError (a ValueError) with the CLI's message
    (file:line:col, the key path, the closest valid name); a failure while training raises
    rlrun.RuntimeFailure (a RuntimeError). The GIL is released while training, which uses the
    CPUs this process may use (as ``rlrun --threads auto``; the result is the same with any
    number). Ctrl-C stops
    the training as on the command line, at its next safe point with a checkpoint, and then
    raises KeyboardInterrupt (resume with ``rlrun train --resume RUN_DIR``); where no safe point
    comes (a Python env's worker that hangs) it raises rlrun.Interrupted, a KeyboardInterrupt.
    """
    assignments = override_assignments(overrides) + override_assignments(kwargs)
    if isinstance(config, dict):
        text = json.dumps(config, indent=2)
        outcome = _core.train_text(text, "rlrun.train(dict)", "train", assignments)
    elif isinstance(config, (str, os.PathLike)):
        outcome = _core.train_file(os.fspath(config), assignments)
    else:
        raise TypeError(f"rlrun.train takes an experiment file's path or a dict, got {type(config).__name__}")
    if outcome["interrupted"]:
        raise KeyboardInterrupt(
            f"training interrupted at step {outcome['timesteps']}; checkpoint "
            f"{outcome['checkpoint_path']}; resume with: rlrun train --resume {outcome['run_dir']}"
        )
    return outcome["run_dir"]
