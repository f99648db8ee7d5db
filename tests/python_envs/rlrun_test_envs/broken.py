"""Envs that go wrong, one way each, for the bridge's error tests."""
import ctypes
import os
import signal

import numpy as np

from rlrun_test_envs.spaces import Box, Discrete, Tuple


class _Base:
    fail_at = 5

    def __init__(self, fail_at=5):
        self.fail_at = fail_at
        self.observation_space = Box(-1.0, 1.0, shape=(3,), dtype=np.float32)
        self.action_space = Discrete(2)

    def reset(self, *, seed=None, options=None):
        self.t = 0
        return np.zeros(3, dtype=np.float32), {}

    def step(self, action):
        self.t += 1
        if self.t == self.fail_at:
            return self.go_wrong()
        return np.zeros(3, dtype=np.float32), 0.0, False, False, {}


class RaisesInStep(_Base):
    def go_wrong(self):
        return self.compute_reward()

    def compute_reward(self):
        raise ValueError("the reward table has no entry for state 42")


class CrashesInStep(_Base):
    def go_wrong(self):
        ctypes.string_at(0)  # reads address 0: the interpreter dies with SIGSEGV


class KilledInStep(_Base):
    def go_wrong(self):
        os.kill(os.getpid(), signal.SIGKILL)


class WrongShape(_Base):
    def go_wrong(self):
        return np.zeros(4, dtype=np.float32), 0.0, False, False, {}


class WrongDtype(_Base):
    def go_wrong(self):
        return np.zeros(3, dtype=np.float64), 0.0, False, False, {}


class NanObservation(_Base):
    def go_wrong(self):
        return np.array([0.0, np.nan, 0.0], dtype=np.float32), 0.0, False, False, {}


class OldGymApi(_Base):
    def go_wrong(self):
        return np.zeros(3, dtype=np.float32), 0.0, False, {}


class TupleSpace(_Base):
    def __init__(self):
        super().__init__()
        self.observation_space = Tuple([Discrete(2), Discrete(3)])


class NotAnEnv:
    """Has no step(), reset() or spaces."""

    def __init__(self, **kwargs):
        self.kwargs = kwargs


class FailsInInit:
    def __init__(self, size=3):
        raise RuntimeError(f"cannot open the simulator config for size {size}")


class HangsInStep(_Base):
    def go_wrong(self):
        import sys
        import time
        print("HangsInStep: hanging in step()", file=sys.stderr, flush=True)  # tests wait for it
        while True:
            time.sleep(1)


class HangsInInit:
    """__init__ never returns (it waits for a server that never answers, or deadlocks)."""

    def __init__(self, **kwargs):
        import time
        while True:
            time.sleep(1)


class HugeDiscrete(_Base):
    """Discrete(2**62) actions: no policy can have an output per value."""

    def __init__(self):
        super().__init__()
        self.action_space = Discrete(2 ** 62)
