"""Minimal stand-ins for gymnasium.spaces with the same attribute names (shape, dtype, low,
high, n, start, nvec, spaces), as a Python user without gymnasium might write them."""
import numpy as np


class Box:
    def __init__(self, low, high, shape=None, dtype=np.float32):
        self.dtype = np.dtype(dtype)
        shape = tuple(shape) if shape is not None else np.shape(low)
        self.shape = shape
        self.low = np.broadcast_to(np.asarray(low, dtype=self.dtype), shape).copy()
        self.high = np.broadcast_to(np.asarray(high, dtype=self.dtype), shape).copy()


class Discrete:
    def __init__(self, n, start=0):
        self.n = int(n)
        self.start = int(start)
        self.shape = ()
        self.dtype = np.dtype(np.int64)


class MultiDiscrete:
    def __init__(self, nvec):
        self.nvec = np.asarray(nvec, dtype=np.int64)
        self.shape = self.nvec.shape
        self.dtype = np.dtype(np.int64)


class MultiBinary:
    def __init__(self, n):
        self.n = n
        self.shape = (n,)
        self.dtype = np.dtype(np.int8)


class Dict:
    def __init__(self, spaces):
        self.spaces = dict(sorted(spaces.items()))


class Interval:
    """Not named like any gymnasium space: recognised by its low/high attributes."""

    def __init__(self, low, high, size):
        self.low = np.full(size, low, dtype=np.float32)
        self.high = np.full(size, high, dtype=np.float32)
        self.shape = (size,)
        self.dtype = np.dtype(np.float32)


class Tuple:
    def __init__(self, spaces):
        self.spaces = tuple(spaces)
