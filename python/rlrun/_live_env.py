"""Live env objects for training (src/rlrun/envs/python/python_live_env.hpp).

``rlrun.PPO("MlpPolicy", env)`` with a gymnasium.Env object (or anything with reset, step,
observation_space and action_space) numbers the object here and trains on the env id
``python-object:<number>``. When rlrun builds that env, it calls ``connect(number)``: a socket
pair, one end served by a thread running worker.py's loop over the object itself (so its checks,
info and error messages are those of any Python env), the other end returned to rlrun. The env
is stepped in this interpreter, one step at a time (SB3's DummyVecEnv of one env): one
connection per object at a time.
"""

from __future__ import annotations

import itertools
import socket
import threading
import types

from . import _core

_lock = threading.Condition()
_objects: dict[int, object] = {}
_serving: set[int] = set()
_numbers = itertools.count(1)
_worker_module = None


def register(env) -> int:
    """Numbers `env` for rlrun; the id to train on is f"python-object:{number}"."""
    with _lock:
        number = next(_numbers)
        _objects[number] = env
    return number


def release(number: int) -> None:
    with _lock:
        _objects.pop(number, None)


def _worker():
    """worker.py (compiled into rlrun) as a module of this interpreter, built once."""
    global _worker_module
    if _worker_module is None:
        module = types.ModuleType("rlrun._env_worker")
        # "<string>" as in a worker process: its frames are left out of env tracebacks.
        exec(compile(_core.worker_script(), "<string>", "exec"), module.__dict__)
        _worker_module = module
    return _worker_module


def connect(number: int) -> int:
    """A connected socket's fd whose other end serves object `number` from a thread."""
    with _lock:
        if number not in _objects:
            raise RuntimeError(f"no live env object numbered {number} in this interpreter")
        # rlrun may build the env, close it and build it again (a config's check, then the
        # training): the closed one's thread is then still returning.
        _lock.wait_for(lambda: number not in _serving, timeout=5.0)
        if number in _serving:
            raise RuntimeError(
                "this env object is already being stepped by rlrun: a live env object serves one "
                "env copy at a time (n_envs 1). For more copies, or an evaluation env beside the "
                "training one, pass an env id (e.g. 'CartPole-v1', 'gymnasium:MyEnv-v0') instead")
        _serving.add(number)
        env = _objects[number]
    worker = _worker()
    ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_STREAM)

    def serve():
        try:
            worker.serve_live_env(ours.detach(), env)
        finally:
            with _lock:
                _serving.discard(number)
                _lock.notify_all()

    threading.Thread(target=serve, name=f"rlrun-live-env-{number}", daemon=True).start()
    return theirs.detach()
