"""Live env objects for training (src/rlrun/envs/python/python_live_env.hpp).

``rlrun.PPO("MlpPolicy", env)`` with a gymnasium.Env object (or anything with reset, step,
observation_space and action_space) numbers the object here and trains on the env id
``python-object:<number>``. When rlrun builds that env, it calls ``connect(number)``: a socket
pair, one end served by a thread running worker.py's loop over the object itself (so its checks,
info and error messages are those of any Python env), the other end returned to rlrun. The env
is stepped in this interpreter, one step at a time (SB3's DummyVecEnv). A vectorized env's
members are numbered together (n_envs copies of one id): each connection takes the first member
not being served; one connection per member at a time.
"""

from __future__ import annotations

import itertools
import socket
import threading
import types

from . import _core

_lock = threading.Condition()
_objects: dict[int, list] = {}
_serving: set[tuple[int, int]] = set()  # (number, member) being served
_numbers = itertools.count(1)
_worker_module = None


def register(envs) -> int:
    """Numbers an env object, or a list of them (a vectorized env's members, as many as the
    run's n_envs), for rlrun; the id to train on is f"python-object:{number}"."""
    with _lock:
        number = next(_numbers)
        _objects[number] = list(envs) if isinstance(envs, list) else [envs]
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
        members = _objects[number]

        def free():
            return [m for m in range(len(members)) if (number, m) not in _serving]

        # rlrun may build the env, close it and build it again (a config's check, then the
        # training): the closed one's thread is then still returning.
        _lock.wait_for(lambda: bool(free()), timeout=5.0)
        if not free():
            raise RuntimeError(
                f"this env object is already being stepped by rlrun: a live env object serves one "
                f"env copy at a time (here {len(members)}: n_envs {len(members)}). For more "
                "copies, or an evaluation env beside the training one, pass an env id (e.g. "
                "'CartPole-v1', 'gymnasium:MyEnv-v0') instead")
        member = free()[0]
        _serving.add((number, member))
        env = members[member]
    worker = _worker()
    ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_STREAM)

    def serve():
        try:
            worker.serve_live_env(ours.detach(), env)
        finally:
            with _lock:
                _serving.discard((number, member))
                _lock.notify_all()

    threading.Thread(target=serve, name=f"rlrun-live-env-{number}", daemon=True).start()
    return theirs.detach()
