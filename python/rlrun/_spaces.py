"""Spaces for rlrun's envs and models.

rlrun's C++ core describes a space as a dict (python/src/module.cpp ``space_dict``). Here it
becomes a real ``gymnasium.spaces`` object when Gymnasium is importable (SB3's ``_patch_env``
and Gymnasium's env checker want those), else one of the small compatible classes below,
which follow ``gymnasium/spaces/*.py``: ``shape``, ``dtype``, ``low``/``high``, ``n``/
``start``, ``nvec``, ``spaces``, ``sample()``, ``contains()``, ``seed()``.

rlrun itself passes every observation and action as one flat float32 vector (include/rlrun/
space.hpp: a Discrete value is one float, a Dict its keys' values in sorted key order);
``to_flat`` and ``from_flat`` convert between that and the Python values of a space.
"""

from __future__ import annotations

import numpy as np

try:  # Gymnasium is optional: rlrun works without it.
    import gymnasium as _gym
    from gymnasium import spaces as _gym_spaces
except ImportError:  # pragma: no cover - depends on the machine
    _gym = None
    _gym_spaces = None

HAVE_GYMNASIUM = _gym is not None


class Space:
    """Base of the fallback spaces (gymnasium.spaces.Space's interface)."""

    def __init__(self, shape, dtype, seed=None):
        self.shape = None if shape is None else tuple(int(d) for d in shape)
        self.dtype = None if dtype is None else np.dtype(dtype)
        self._np_random = None
        if seed is not None:
            self.seed(seed)

    @property
    def np_random(self) -> np.random.Generator:
        if self._np_random is None:
            self.seed()
        return self._np_random

    def seed(self, seed=None):
        self._np_random = np.random.default_rng(seed)
        return [seed]

    def __contains__(self, x) -> bool:
        return self.contains(x)


class Box(Space):
    def __init__(self, low, high, shape=None, dtype=np.float32, seed=None):
        dtype = np.dtype(dtype)
        if shape is None:
            shape = np.shape(low) if np.ndim(low) else np.shape(high)
        self.low = np.broadcast_to(np.asarray(low, dtype=dtype), shape).copy()
        self.high = np.broadcast_to(np.asarray(high, dtype=dtype), shape).copy()
        super().__init__(shape, dtype, seed)

    def is_bounded(self, manner: str = "both") -> bool:
        below = bool(np.all(np.isfinite(self.low)))
        above = bool(np.all(np.isfinite(self.high)))
        return {"both": below and above, "below": below, "above": above}[manner]

    def sample(self, mask=None):
        # Uniform where bounded, shifted exponential where half-bounded, normal where unbounded
        # (gymnasium/spaces/box.py).
        rng = self.np_random
        low, high = self.low.astype(np.float64), self.high.astype(np.float64)
        out = np.empty(self.shape, dtype=np.float64)
        lo, hi = np.isfinite(low), np.isfinite(high)
        both, only_lo, only_hi, none = lo & hi, lo & ~hi, ~lo & hi, ~lo & ~hi
        out[both] = rng.uniform(low[both], high[both])
        out[only_lo] = low[only_lo] + rng.exponential(size=only_lo.sum())
        out[only_hi] = high[only_hi] - rng.exponential(size=only_hi.sum())
        out[none] = rng.normal(size=none.sum())
        return out.astype(self.dtype)

    def contains(self, x) -> bool:
        if not isinstance(x, np.ndarray):
            try:
                x = np.asarray(x, dtype=self.dtype)
            except (ValueError, TypeError):
                return False
        return bool(
            np.can_cast(x.dtype, self.dtype)
            and x.shape == self.shape
            and np.all(x >= self.low)
            and np.all(x <= self.high)
        )

    def __repr__(self):
        # As gymnasium's Box: scalar bounds when every element shares them.
        def bound(b):
            return str(b.flat[0]) if b.size and np.all(b == b.flat[0]) else str(b)

        return f"Box({bound(self.low)}, {bound(self.high)}, {self.shape}, {self.dtype})"

    def __eq__(self, other):
        return (
            isinstance(other, Box)
            and self.shape == other.shape
            and np.array_equal(self.low, other.low)
            and np.array_equal(self.high, other.high)
        )


class Discrete(Space):
    def __init__(self, n, seed=None, start=0):
        self.n = np.int64(n)
        self.start = np.int64(start)
        super().__init__((), np.int64, seed)

    def sample(self, mask=None):
        return np.int64(self.start + self.np_random.integers(self.n))

    def contains(self, x) -> bool:
        if isinstance(x, (int, np.integer)):
            v = int(x)
        elif isinstance(x, np.ndarray) and np.issubdtype(x.dtype, np.integer) and x.shape == ():
            v = int(x)
        else:
            return False
        return int(self.start) <= v < int(self.start + self.n)

    def __repr__(self):
        return f"Discrete({self.n})" if self.start == 0 else f"Discrete({self.n}, start={self.start})"

    def __eq__(self, other):
        return isinstance(other, Discrete) and self.n == other.n and self.start == other.start


class MultiDiscrete(Space):
    def __init__(self, nvec, dtype=np.int64, seed=None):
        self.nvec = np.asarray(nvec, dtype=dtype)
        self.start = np.zeros_like(self.nvec)
        super().__init__(self.nvec.shape, dtype, seed)

    def sample(self, mask=None):
        return (self.np_random.random(self.nvec.shape) * self.nvec).astype(self.dtype)

    def contains(self, x) -> bool:
        x = np.asarray(x)
        return bool(
            x.shape == self.shape
            and np.issubdtype(x.dtype, np.integer)
            and np.all(x >= 0)
            and np.all(x < self.nvec)
        )

    def __repr__(self):
        return f"MultiDiscrete({self.nvec})"

    def __eq__(self, other):
        return isinstance(other, MultiDiscrete) and np.array_equal(self.nvec, other.nvec)


class MultiBinary(Space):
    def __init__(self, n, seed=None):
        self.n = n
        super().__init__((int(n),), np.int8, seed)

    def sample(self, mask=None):
        return self.np_random.integers(0, 2, size=self.shape, dtype=self.dtype)

    def contains(self, x) -> bool:
        x = np.asarray(x)
        return bool(x.shape == self.shape and np.all((x == 0) | (x == 1)))

    def __repr__(self):
        return f"MultiBinary({self.n})"

    def __eq__(self, other):
        return isinstance(other, MultiBinary) and self.n == other.n


class Dict(Space):
    def __init__(self, spaces, seed=None):
        self.spaces = dict(sorted(dict(spaces).items()))
        super().__init__(None, None, seed)

    def seed(self, seed=None):
        super().seed(seed)
        base = np.random.default_rng(seed)
        for space in self.spaces.values():
            space.seed(int(base.integers(2**32)))
        return [seed]

    def sample(self, mask=None):
        return {k: s.sample() for k, s in self.spaces.items()}

    def contains(self, x) -> bool:
        return (
            isinstance(x, dict)
            and x.keys() == self.spaces.keys()
            and all(s.contains(x[k]) for k, s in self.spaces.items())
        )

    def __getitem__(self, key):
        return self.spaces[key]

    def keys(self):
        return self.spaces.keys()

    def items(self):
        return self.spaces.items()

    def __repr__(self):
        return "Dict(" + ", ".join(f"{k!r}: {s}" for k, s in self.spaces.items()) + ")"

    def __eq__(self, other):
        return isinstance(other, Dict) and self.spaces == other.spaces


def from_description(d: dict):
    """A gymnasium.spaces object (or the fallback's) from the core's dict."""
    ns = _gym_spaces if HAVE_GYMNASIUM else None
    kind = d["kind"]
    if kind == "Box":
        cls = ns.Box if ns else Box
        # float32, or uint8 for images (SB3's is_image_space asks for uint8).
        dtype = np.dtype(d.get("dtype", "float32"))
        return cls(low=np.asarray(d["low"]).astype(dtype), high=np.asarray(d["high"]).astype(dtype),
                   shape=tuple(d["shape"]), dtype=dtype)
    if kind == "Discrete":
        cls = ns.Discrete if ns else Discrete
        return cls(int(d["n"]), start=int(d["start"]))
    if kind == "MultiDiscrete":
        cls = ns.MultiDiscrete if ns else MultiDiscrete
        return cls(np.asarray(d["nvec"], dtype=np.int64))
    if kind == "MultiBinary":
        cls = ns.MultiBinary if ns else MultiBinary
        return cls(int(d["n"]))
    if kind == "Dict":
        cls = ns.Dict if ns else Dict
        return cls({k: from_description(s) for k, s in zip(d["keys"], d["spaces"])})
    raise ValueError(f"unknown space kind {kind!r}")


def _kind(space) -> str:
    return type(space).__name__


def flat_dim(space) -> int:
    kind = _kind(space)
    if kind == "Discrete":
        return 1
    if kind == "Dict":
        return sum(flat_dim(s) for s in space.spaces.values())
    return int(np.prod(space.shape, dtype=np.int64))


def _dtype(space):
    # The numpy type of a space's values as Gymnasium returns them.
    kind = _kind(space)
    if kind == "Box":
        return np.uint8 if np.dtype(space.dtype) == np.uint8 else np.float32
    if kind == "MultiBinary":
        return np.int8
    return np.int64


def from_flat(space, row: np.ndarray):
    """One flat float32 vector -> the space's value (Discrete: np.int64; Dict: a dict)."""
    kind = _kind(space)
    if kind == "Box":
        return row.reshape(space.shape).astype(_dtype(space), copy=False)
    if kind == "Discrete":
        return np.int64(row[0])
    if kind == "Dict":
        out, at = {}, 0
        for key, sub in space.spaces.items():
            d = flat_dim(sub)
            out[key] = from_flat(sub, row[at : at + d])
            at += d
        return out
    return row.reshape(space.shape).astype(_dtype(space))


def batch_from_flat(space, rows: np.ndarray):
    """(n, flat) float32 -> a batch of the space's values ((n, *shape) arrays; Dict: dict)."""
    kind = _kind(space)
    n = rows.shape[0]
    if kind == "Box":
        return rows.reshape((n,) + tuple(space.shape)).astype(_dtype(space), copy=False)
    if kind == "Discrete":
        return rows[:, 0].astype(np.int64)
    if kind == "Dict":
        out, at = {}, 0
        for key, sub in space.spaces.items():
            d = flat_dim(sub)
            out[key] = batch_from_flat(sub, rows[:, at : at + d])
            at += d
        return out
    return rows.reshape((n,) + tuple(space.shape)).astype(_dtype(space))


def to_flat(space, value, what: str = "action") -> np.ndarray:
    """The space's value (numpy array, Python int/float/list, dict for Dict) -> flat float32."""
    kind = _kind(space)
    if kind == "Dict":
        if not isinstance(value, dict):
            raise ValueError(f"{what} must be a dict with keys {list(space.spaces)}")
        return np.concatenate([to_flat(s, value[k], what) for k, s in space.spaces.items()])
    flat = np.asarray(value, dtype=np.float32).reshape(-1)
    if flat.size != flat_dim(space):
        raise ValueError(
            f"{what} has {flat.size} values, {space} takes {flat_dim(space)}"
        )
    return flat


def batch_to_flat(space, values, n: int, what: str = "actions") -> np.ndarray:
    """A batch of n values -> (n, flat) float32, C order."""
    if _kind(space) == "Dict":
        if not isinstance(values, dict):
            raise ValueError(f"{what} must be a dict of arrays with keys {list(space.spaces)}")
        return np.concatenate(
            [batch_to_flat(s, values[k], n, what) for k, s in space.spaces.items()], axis=1
        )
    arr = np.ascontiguousarray(values, dtype=np.float32)
    d = flat_dim(space)
    if arr.size != n * d:
        raise ValueError(f"{what}: expected {n} x {d} values for {space}, got shape {arr.shape}")
    return arr.reshape(n, d)


def batch_space(space, n: int):
    """Gymnasium's vector.utils.batch_space where available, else the same rule here."""
    if HAVE_GYMNASIUM:
        from gymnasium.vector.utils import batch_space as gym_batch_space

        return gym_batch_space(space, n)
    kind = _kind(space)
    if kind == "Box":
        reps = (n,) + (1,) * len(space.shape)
        return Box(np.tile(space.low, reps), np.tile(space.high, reps), dtype=space.dtype)
    if kind == "Discrete":
        return MultiDiscrete(np.full((n,), space.n, dtype=np.int64))
    if kind == "MultiDiscrete":
        return MultiDiscrete(np.tile(space.nvec, (n,) + (1,) * space.nvec.ndim))
    if kind == "MultiBinary":
        return Box(0, 1, shape=(n,) + space.shape, dtype=np.int8)
    return Dict({k: batch_space(s, n) for k, s in space.spaces.items()})
