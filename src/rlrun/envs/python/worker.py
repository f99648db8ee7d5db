# rlrun's Python env worker: one Gymnasium env in its own interpreter process, stepped by
# rlrun over a Unix socket (src/rlrun/envs/python/python_worker.cpp starts it as
# `PYTHON -c <this file> FD`). SB3's SubprocVecEnv does the same with pickled commands
# (stable_baselines3/common/vec_env/subproc_vec_env.py); here every message after the
# handshake is a fixed binary layout, so a step costs rlrun no Python objects at all and the
# worker only one recv and one send. The layouts are described in python_protocol.hpp; keep
# the two in step.
#
# The env follows Gymnasium's API (gymnasium/core.py): reset(seed=..., options=None) ->
# (obs, info); step(action) -> (obs, reward, terminated, truncated, info); observation_space /
# action_space are gymnasium.spaces objects or anything with the same attributes. What rlrun
# cannot learn from (an observation of another shape or dtype than its space, NaN, a Discrete
# value outside its range, the old gym API) is an error naming the env and the step; what
# Gymnasium's own checker only warns about is a warning, printed once.
import faulthandler
import json
import os
import signal
import socket
import struct
import sys
import traceback

PROTOCOL_VERSION = 1
KIND_NAMES = ("Dict", "MultiDiscrete", "MultiBinary", "Discrete", "Box")
UNSUPPORTED = ("Tuple", "Text", "Graph", "Sequence", "OneOf")
MAX_INFO_KEYS = 256 + 4096  # python_protocol.hpp: numeric keys and an action mask's entries


class EnvError(Exception):
    """A problem of the env (not of this worker): reported without this file's frames."""


def fail(message):
    raise EnvError(message)


def class_names(obj):
    return [c.__name__ for c in type(obj).__mro__]


def space_kind(space, where):
    names = class_names(space)
    for name in UNSUPPORTED:
        if name in names:
            fail(f"{where} is a {name} space; rlrun takes Box, Discrete, MultiDiscrete, "
                 "MultiBinary and a Dict of those (as SB3's policies do)")
    for name in KIND_NAMES:
        if name in names:
            return name
    # Not a gymnasium class: recognise it by its attributes, as the issue's "any object with
    # the same attributes" asks.
    spaces = getattr(space, "spaces", None)
    if hasattr(spaces, "items"):
        return "Dict"
    if hasattr(space, "nvec"):
        return "MultiDiscrete"
    if hasattr(space, "low") and hasattr(space, "high"):
        return "Box"
    if hasattr(space, "n"):
        return "Discrete" if tuple(getattr(space, "shape", ()) or ()) == () else "MultiBinary"
    fail(f"{where} ({type(space).__name__}) is not a space rlrun knows: it has none of the "
         "attributes of gymnasium's Box (low, high), Discrete (n), MultiDiscrete (nvec), "
         "MultiBinary (n, shape) or Dict (spaces)")


def bound(value):
    f = float(value)
    if f == float("inf"):
        return "inf"
    if f == float("-inf"):
        return "-inf"
    return f


class Codec:
    """One space: its description for rlrun, and how its samples become flat float32."""

    def __init__(self, space, where, np):
        self.np = np
        self.where = where
        self.kind = space_kind(space, where)
        self.shape = tuple(int(d) for d in (getattr(space, "shape", None) or ()))
        self.children = []
        if self.kind == "Box":
            self.dtype = np.dtype(getattr(space, "dtype", np.float32))
            low = np.broadcast_to(np.asarray(space.low, dtype=np.float64), self.shape)
            high = np.broadcast_to(np.asarray(space.high, dtype=np.float64), self.shape)
            self.size = int(np.prod(self.shape, dtype=np.int64)) if self.shape else 1
            if not self.shape:
                self.shape = ()
            self.describe = {"kind": "Box", "shape": list(self.shape) or [1],
                             "low": [bound(v) for v in low.reshape(-1)],
                             "high": [bound(v) for v in high.reshape(-1)],
                             "dtype": self.dtype.name}
        elif self.kind == "Discrete":
            self.n = int(space.n)
            self.start = int(getattr(space, "start", 0))
            self.size = 1
            self.describe = {"kind": "Discrete", "n": self.n, "start": self.start}
        elif self.kind == "MultiDiscrete":
            nvec = np.asarray(space.nvec, dtype=np.int64)
            start = np.asarray(getattr(space, "start", 0), dtype=np.int64)
            if np.any(start != 0):
                fail(f"{where} is a MultiDiscrete with start={start.tolist()}; rlrun's "
                     "MultiDiscrete starts at 0 (as SB3's)")
            self.shape = tuple(nvec.shape)
            self.nvec = nvec.reshape(-1)
            self.size = int(self.nvec.size)
            self.describe = {"kind": "MultiDiscrete", "nvec": self.nvec.tolist()}
        elif self.kind == "MultiBinary":
            if not self.shape:
                self.shape = (int(space.n),)
            self.size = int(np.prod(self.shape, dtype=np.int64))
            self.describe = {"kind": "MultiBinary", "n": self.size}
        else:
            entries = sorted(space.spaces.items(), key=lambda kv: str(kv[0]))
            self.keys = []
            offset = 0
            desc = {}
            for key, sub in entries:
                if not isinstance(key, str):
                    fail(f"{where} has the key {key!r}; rlrun's Dict keys are strings")
                child = Codec(sub, f"{where}['{key}']", np)
                if child.kind == "Dict":
                    fail(f"{where}['{key}'] is a Dict inside a Dict; rlrun takes one level of "
                         "keys (as SB3's MultiInputPolicy)")
                self.keys.append(key)
                self.children.append((key, child, offset))
                offset += child.size
                desc[key] = child.describe
            self.size = offset
            self.describe = {"kind": "Dict", "spaces": desc}

    # ----- observations: env value -> flat float32 ------------------------------------------
    def write(self, value, out, what):
        np = self.np
        if self.kind == "Dict":
            if not hasattr(value, "keys"):
                fail(f"{what} is a {type(value).__name__}; {self.where} is a Dict, so it must "
                     "be a dict of its keys")
            for key, child, offset in self.children:
                if key not in value:
                    fail(f"{what} has no key '{key}' (keys: {sorted(map(str, value.keys()))})")
                child.write(value[key], out[offset:offset + child.size], f"{what}['{key}']")
            return
        if self.kind == "Discrete":
            if isinstance(value, np.ndarray) and value.shape in ((), (1,)):
                value = value.reshape(-1)[0]
            if not isinstance(value, (int, np.integer)) or isinstance(value, bool):
                fail(f"{what} is {value!r} ({type(value).__name__}); {self.where} is "
                     f"Discrete({self.n}), so it must be an int")
            if not self.start <= int(value) < self.start + self.n:
                fail(f"{what} is {int(value)}, outside {self.where} = Discrete({self.n}"
                     + (f", start={self.start}" if self.start else "") + ")")
            out[0] = int(value)
            return
        array = value if isinstance(value, np.ndarray) else np.asarray(value)
        if array.shape != self.shape:
            fail(f"{what} has shape {array.shape}, but {self.where} has shape {self.shape}")
        if self.kind == "Box":
            if array.dtype != self.dtype and not np.can_cast(array.dtype, self.dtype):
                fail(f"{what} has dtype {array.dtype}, but {self.where} is a Box of "
                     f"{self.dtype.name} (gymnasium's Box.contains refuses it; return "
                     f"obs.astype(np.{self.dtype.name}))")
            np.copyto(out, array.reshape(-1), casting="unsafe")
            if array.dtype.kind == "f" and not np.isfinite(out).all():
                bad = int(np.flatnonzero(~np.isfinite(out))[0])
                fail(f"{what} holds {out[bad]} at flat index {bad}: observations must be finite")
            return
        if array.dtype.kind not in "biu":
            fail(f"{what} has dtype {array.dtype}; {self.where} is a {self.kind}, so it must "
                 "hold integers")
        flat = array.reshape(-1)
        high = self.nvec if self.kind == "MultiDiscrete" else 2
        if np.any(flat < 0) or np.any(flat >= high):
            fail(f"{what} is {array.tolist()}, outside {self.where}")
        np.copyto(out, flat, casting="unsafe")

    # ----- actions: flat float32 -> what the env's step() takes ------------------------------
    def action(self, flat):
        np = self.np
        if self.kind == "Box":
            return flat.reshape(self.shape).astype(self.dtype)  # a copy the env may keep
        if self.kind == "Discrete":
            return np.int64(flat[0])  # what SB3 passes (an element of its int64 action array)
        if self.kind == "MultiDiscrete":
            return flat.astype(np.int64).reshape(self.shape)
        if self.kind == "MultiBinary":
            return flat.astype(np.int8).reshape(self.shape)
        fail(f"{self.where} is a Dict; rlrun's algorithms take Box, Discrete, MultiDiscrete or "
             "MultiBinary actions (as SB3's)")


def load_target(target, kwargs):
    """python:module:Attr -> Attr(**kwargs); gymnasium:ID -> gymnasium.make(ID, **kwargs);
    pettingzoo:module:function -> function(**kwargs) (pettingzoo_agents.py takes it on)."""
    family, _, rest = target.partition(":")
    if family == "gymnasium":
        try:
            import gymnasium
        except ImportError as e:
            fail(f"gymnasium is not importable by {sys.executable} (Python "
                 f"{sys.version.split()[0]}): {e}. Install it into that interpreter "
                 "(pip install gymnasium) or set env.python to one that has it")
        render = {}
        if "render_mode" not in kwargs and "rgb_array" in gymnasium_render_modes(gymnasium, rest):
            render = {"render_mode": "rgb_array"}
        return gymnasium.make(rest, **render, **kwargs)
    module_name, _, attr = rest.partition(":")
    import importlib
    try:
        module = importlib.import_module(module_name)
    except Exception as e:
        raise EnvError(f"cannot import module '{module_name}' with {sys.executable} (Python "
                       f"{sys.version.split()[0]}, working directory {os.getcwd()}): "
                       f"{type(e).__name__}: {e}. Is it on that interpreter's sys.path "
                       "(PYTHONPATH, an installed package)? env.python picks another "
                       "interpreter") from e
    factory = module
    for part in attr.split("."):
        if not hasattr(factory, part):
            names = [n for n in dir(module) if not n.startswith("_")]
            fail(f"module '{module_name}' ({getattr(module, '__file__', '?')}) has no "
                 f"'{attr}'; it defines: {', '.join(names[:30])}")
        factory = getattr(factory, part)
    if not callable(factory):
        fail(f"{module_name}:{attr} is a {type(factory).__name__}, not a class or function "
             "that builds an env")
    # PettingZoo's env modules build with functions (env, parallel_env) that have no metadata:
    # their class, raw_env, says which render modes there are.
    described = factory if hasattr(factory, "metadata") else getattr(module, "raw_env", factory)
    if "render_mode" not in kwargs and wants_render_mode(factory, described):
        kwargs = dict(kwargs, render_mode="rgb_array")
    return factory(**kwargs)


def gymnasium_render_modes(gymnasium, env_id):
    # gymnasium.make checks render_mode against the env class's metadata; look first.
    try:
        from gymnasium.envs.registration import load_env_creator
        creator = gymnasium.spec(env_id).entry_point
        if isinstance(creator, str):
            creator = load_env_creator(creator)
        return list(getattr(creator, "metadata", {}).get("render_modes", []) or [])
    except Exception:
        return []


def wants_render_mode(factory, described=None):
    modes = getattr(described if described is not None else factory, "metadata", {}) or {}
    if "rgb_array" not in (modes.get("render_modes", []) if hasattr(modes, "get") else []):
        return False
    import inspect
    try:
        params = inspect.signature(factory).parameters.values()
    except (TypeError, ValueError):
        return False
    return any(p.name == "render_mode" or p.kind == p.VAR_KEYWORD for p in params)


class Channel:
    def __init__(self, fd):
        self.sock = socket.socket(fileno=fd)
        os.set_inheritable(fd, False)  # the env's own subprocesses must not hold rlrun's socket

    def recv_exact(self, view):
        got = 0
        while got < len(view):
            n = self.sock.recv_into(view[got:])
            if n == 0:
                raise EOFError
            got += n

    def recv_json(self):
        header = bytearray(4)
        self.recv_exact(memoryview(header))
        body = bytearray(struct.unpack("<I", header)[0])
        self.recv_exact(memoryview(body))
        return json.loads(body.decode("utf-8"))

    def send(self, data):
        self.sock.sendall(data)

    def send_parts(self, *parts):
        total = sum(len(p) for p in parts)
        sent = self.sock.sendmsg(parts)
        if sent < total:  # a short write (a large observation): send the rest plainly
            self.sock.sendall(b"".join(bytes(p) for p in parts)[sent:])

    def send_json(self, obj):
        body = json.dumps(obj).encode("utf-8")
        self.send(struct.pack("<I", len(body)) + body)

    def send_error(self, text):
        body = text.encode("utf-8", "replace")[-(1 << 20):]
        self.send(b"E" + struct.pack("<I", len(body)) + body)


class Worker:
    def __init__(self, channel, np, spec, live_env=None):
        """live_env: an env object of this interpreter to serve (serve_live_env) instead of
        building one from spec's target; its owner closes it, not the close request."""
        self.np = np
        self.channel = channel
        self.target = spec["target"]
        self.live = live_env is not None
        self.env = live_env if self.live else load_target(self.target, spec.get("kwargs") or {})
        # A PettingZoo env: its agents (pettingzoo_agents.py); None for a Gymnasium env.
        self.agents = None
        if self.target.startswith("pettingzoo:"):
            self.agents = pettingzoo_agents(self.env, np, spec.get("turn_based"),
                                            spec.get("agent_indicator", "none"))
            self.obs_codec, self.act_codec = self.agents.obs_codec, self.agents.act_codec
        else:
            for attr in ("reset", "step", "observation_space", "action_space"):
                if not hasattr(self.env, attr):
                    fail(f"{self.target} built a {type(self.env).__module__}."
                         f"{type(self.env).__qualname__}, which is not a Gymnasium env: it has "
                         f"no '{attr}' (a gymnasium.Env has reset, step, observation_space and "
                         "action_space; a PettingZoo env is built with pettingzoo:module:function)")
            self.obs_codec = Codec(self.env.observation_space, "observation_space", np)
            self.act_codec = Codec(self.env.action_space, "action_space", np)
        if self.act_codec.kind == "Dict":
            self.act_codec.action(None)
        self.act_dim = self.act_codec.size
        self.obs_dim = self.obs_codec.size
        k = self.num_agents = len(self.agents.names) if self.agents else 1
        # Requests are fixed-size frames: op byte + max(seed, every agent's action) payload.
        self.request = bytearray(1 + max(9, 4 * self.act_dim * k))
        self.request_view = memoryview(self.request)
        self.action_view = np.frombuffer(self.request, dtype=np.float32,
                                         count=self.act_dim * k, offset=1)
        # Reply: 'K', u32 length, f64 reward[k], u8 terminated[k], u8 truncated[k], obs floats
        # (agent-major), info.
        self.fixed = 1 + 4 + 10 * k + 4 * self.obs_dim * k
        self.reply = bytearray(self.fixed)
        self.obs_view = np.frombuffer(self.reply, dtype=np.float32, count=self.obs_dim * k,
                                      offset=5 + 10 * k)
        self.info_keys = {}
        # sb3-contrib's ActionMasker / get_action_masks: env.action_masks(), through wrappers.
        self.mask_method = None
        getter = getattr(self.env, "get_wrapper_attr", None) if not self.agents else None
        try:
            method = getter("action_masks") if getter else getattr(self.env, "action_masks")
            self.mask_method = method if callable(method) and not self.agents else None
        except AttributeError:
            pass
        self.warned = set()
        self.step_count = 0
        metadata = getattr(self.env, "metadata", None) or {}
        self.render_mode = getattr(self.env, "render_mode", None)
        spec_obj = getattr(self.env, "spec", None)
        self.handshake = {
            "ok": True, "protocol": PROTOCOL_VERSION,
            "observation_space": self.obs_codec.describe, "action_space": self.act_codec.describe,
            "obs_dim": self.obs_dim, "act_dim": self.act_dim, "num_agents": k,
            "agents": [str(a) for a in self.agents.names] if self.agents else [],
            "render_mode": self.render_mode if isinstance(self.render_mode, str) else None,
            "render_fps": float(metadata.get("render_fps") or 30) if hasattr(metadata, "get") else 30.0,
            "max_episode_steps": getattr(spec_obj, "max_episode_steps", None),
            "class": f"{type(self.env).__module__}.{type(self.env).__qualname__}",
            "python": sys.executable, "python_version": sys.version.split()[0],
            "numpy_version": np.__version__,
        }

    def warn_once(self, key, message):
        if key not in self.warned:
            self.warned.add(key)
            print(f"rlrun: warning: {self.target}: {message}", file=sys.stderr, flush=True)

    def flag(self, value, name):
        np = self.np
        if isinstance(value, (bool, np.bool_)):
            return bool(value)
        if isinstance(value, (int, np.integer)) and int(value) in (0, 1):
            self.warn_once(name, f"step() returned {name} as {type(value).__name__}; "
                           "Gymnasium expects a bool")
            return bool(value)
        fail(f"step() returned {name} = {value!r} ({type(value).__name__}); it must be a bool")

    def action_mask_items(self, info):
        """The env's action mask as info items action_mask.0, action_mask.1, ...
        (src/rlrun/env/action_mask.hpp): sb3-contrib's action_masks() method (found through
        wrappers as get_action_masks does), else Gymnasium's info["action_mask"]."""
        np = self.np
        mask = None
        if self.mask_method is not None:
            mask = self.mask_method()
        elif info is not None and "action_mask" in info:
            mask = info["action_mask"]
        if mask is None:
            return []
        try:
            mask = np.asarray(mask, dtype=np.float64).reshape(-1)
        except (TypeError, ValueError):
            fail(f"the action mask is a {type(mask).__name__}; it must be an array of 0/1 or bools")
        return [(f"action_mask.{i}", value) for i, value in enumerate(mask.tolist())]

    def finish(self, obs, info, reward, terminated, truncated, what):
        self.obs_codec.write(obs, self.obs_view, what)
        self.send_reply([reward], [terminated], [truncated], info, self.action_mask_items(info))

    def finish_agents(self, rows, info, what):
        """Every agent's (observation or None, mask or None, reward, terminated, truncated)."""
        np = self.np
        views = self.obs_view.reshape(self.num_agents, self.obs_dim)
        masks = []
        for i, (obs, mask, _, _, _) in enumerate(rows):
            if obs is None:
                views[i].fill(0.0)  # an agent that has left (black death)
            else:
                self.obs_codec.write(obs, views[i], f"{what} of agent '{self.agents.names[i]}'")
            masks.append(None if mask is None else np.asarray(mask, dtype=np.float64).reshape(-1))
        items = []
        size = max((len(m) for m in masks if m is not None), default=0)
        if size:  # agents without a mask (gone) may take any action
            for i, m in enumerate(masks):
                values = m if m is not None else np.ones(size)
                if len(values) != size:
                    fail(f"agent '{self.agents.names[i]}'s action mask has {len(values)} "
                         f"entries, the others' {size}")
                items += [(f"action_mask.{i * size + j}", v) for j, v in enumerate(values.tolist())]
        rewards = []
        for i, (_, _, reward, _, _) in enumerate(rows):
            rewards.append(self.reward_value(reward, f"the reward of agent '{self.agents.names[i]}'"))
        self.send_reply(rewards, [r[3] for r in rows], [r[4] for r in rows], info, items)

    def reward_value(self, reward, what):
        np = self.np
        if isinstance(reward, np.ndarray) and reward.shape in ((), (1,)) and reward.dtype.kind in "iuf":
            reward = reward.reshape(-1)[0].item()
        if not isinstance(reward, (int, float, np.integer, np.floating)) or isinstance(
                reward, (bool, np.bool_)):
            fail(f"{what} is {reward!r} ({type(reward).__name__}); it must be a number")
        reward = float(reward)
        if reward != reward or reward in (float("inf"), float("-inf")):
            fail(f"{what} is {reward}; rewards must be finite")
        return reward

    def send_reply(self, rewards, terminated, truncated, info, mask_items):
        np = self.np
        tail = bytearray()
        new_keys = []
        values = []
        if info is not None and not hasattr(info, "items"):
            fail(f"the info is a {type(info).__name__}; it must be a dict")
        items = list(info.items()) if info else []
        for key, value in items + mask_items:
            if isinstance(value, (bool, int, float, np.bool_, np.integer, np.floating)) or (
                    isinstance(value, np.ndarray) and value.shape == () and
                    value.dtype.kind in "biuf"):
                index = self.info_keys.get(key)
                if index is None:
                    if not isinstance(key, str) or len(self.info_keys) >= MAX_INFO_KEYS:
                        continue
                    index = self.info_keys[key] = len(self.info_keys)
                    name = key.encode("utf-8")[:255]
                    new_keys.append(struct.pack("<H", len(name)) + name)
                values.append(struct.pack("<Hd", index, float(value)))
        tail += struct.pack("<H", len(new_keys))
        for k in new_keys:
            tail += k
        tail += struct.pack("<H", len(values))
        for v in values:
            tail += v
        # The fixed part holds the observation view, so it is never resized; the info goes
        # after it in the same sendmsg.
        k = self.num_agents
        struct.pack_into(f"<cI{k}d{k}B{k}B", self.reply, 0, b"K", self.fixed - 5 + len(tail),
                         *rewards, *map(bool, terminated), *map(bool, truncated))
        self.channel.send_parts(self.reply, tail)

    def reset(self, has_seed, seed):
        if self.agents:
            rows, info = self.agents.reset(has_seed, seed)
            self.step_count = 0
            self.finish_agents(rows, info, "the observation of reset()")
            return
        result = self.env.reset(seed=seed) if has_seed else self.env.reset()
        if not isinstance(result, tuple) or len(result) != 2:
            fail("reset() returned " + (f"{len(result)} values" if isinstance(result, tuple)
                 else f"a {type(result).__name__}") +
                 "; Gymnasium's reset returns (obs, info) (the old gym API returned obs alone)")
        self.step_count = 0
        self.finish(result[0], result[1], 0.0, False, False, "the observation of reset()")

    def step(self):
        if self.agents:
            rows, info = self.agents.step(
                self.action_view.reshape(self.num_agents, self.act_dim))
            self.step_count += 1
            self.finish_agents(rows, info, "the observation of step()")
            return
        action = self.act_codec.action(self.action_view)
        result = self.env.step(action)
        if not isinstance(result, tuple) or len(result) != 5:
            count = len(result) if isinstance(result, tuple) else None
            fail(f"step() returned {count if count is not None else type(result).__name__}"
                 " values; Gymnasium's step returns (obs, reward, terminated, truncated, info)" +
                 (" (4 values is the old gym API with done)" if count == 4 else ""))
        obs, reward, terminated, truncated, info = result
        np = self.np
        if not isinstance(reward, (int, float, np.integer, np.floating)) or isinstance(
                reward, (bool, np.bool_)):
            if isinstance(reward, np.ndarray) and reward.shape == () and reward.dtype.kind in "iuf":
                reward = reward.item()
            else:
                fail(f"step() returned reward {reward!r} ({type(reward).__name__}); it must "
                     "be a number")
        reward = float(reward)
        if reward != reward or reward in (float("inf"), float("-inf")):
            fail(f"step() returned reward {reward}; rewards must be finite")
        self.step_count += 1
        self.finish(obs, info, reward, self.flag(terminated, "terminated"),
                    self.flag(truncated, "truncated"), "the observation of step()")

    def render(self):
        np = self.np
        frame = self.env.render() if self.render_mode == "rgb_array" else None
        if frame is None:
            self.channel.send(b"K" + struct.pack("<III", 8, 0, 0))
            return
        frame = np.asarray(frame)
        if frame.ndim != 3 or frame.shape[2] not in (3, 4) or frame.dtype != np.uint8:
            fail(f"render() returned an array of shape {frame.shape} and dtype {frame.dtype}; "
                 "an rgb_array frame is (height, width, 3) uint8")
        height, width = int(frame.shape[0]), int(frame.shape[1])
        if not (0 < width <= 4096 and 0 < height <= 4096):
            fail(f"render() returned a {width}x{height} frame; at most 4096 pixels a side")
        pixels = np.ascontiguousarray(frame[:, :, :3]).tobytes()
        self.channel.send(b"K" + struct.pack("<III", 8 + len(pixels), height, width) + pixels)

    def serve(self):
        request, view = self.request, self.request_view
        while True:
            self.channel.recv_exact(view)
            op = request[0]
            try:
                if op == 0x53:  # 'S'
                    self.step()
                elif op == 0x52:  # 'R'
                    has_seed, seed = struct.unpack_from("<BQ", request, 1)
                    self.reset(has_seed, seed)
                elif op == 0x46:  # 'F'
                    self.render()
                elif op == 0x43:  # 'C'
                    close = None if self.live else getattr(self.env, "close", None)
                    if close:
                        close()
                    return
                else:
                    raise RuntimeError(f"unknown request {op}")
            except EnvError as e:
                self.channel.send_error(str(e))
            except Exception:
                self.channel.send_error(env_traceback())


def env_traceback():
    # The traceback without this worker's own frames: it starts in the env's code.
    exc_type, exc, tb = sys.exc_info()
    while tb is not None and tb.tb_frame.f_code.co_filename == "<string>":
        tb = tb.tb_next
    return "".join(traceback.format_exception(exc_type, exc, tb)).rstrip()


def serve_live_env(fd, env):
    """Serves `env`, an object of this interpreter, to rlrun over the connected socket `fd`
    (python_live_env.hpp): the `rlrun` package runs this in a thread while rlrun trains. Returns
    when rlrun closes the env or the socket; an exception in the env goes to rlrun as in a
    worker process."""
    import numpy as np
    channel = Channel(fd)
    try:
        spec = channel.recv_json()
        try:
            worker = Worker(channel, np, spec, live_env=env)
        except EnvError as e:
            channel.send_json({"ok": False, "error": str(e)})
            return
        except Exception:
            channel.send_json({"ok": False, "error": env_traceback()})
            return
        channel.send_json(worker.handshake)
        worker.serve()
    except (EOFError, BrokenPipeError, ConnectionResetError, OSError):
        pass  # rlrun closed the socket: it is done with this env
    finally:
        channel.sock.close()


def main():
    faulthandler.enable()  # a crash inside the env prints its Python stack before rlrun reports it
    # Ctrl-C reaches the whole process group; rlrun handles it (checkpoint, then closes this
    # worker's socket). rlrun ignored SIGINT before exec; keep it so.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    channel = Channel(int(sys.argv[1]))
    spec = channel.recv_json()
    try:
        import numpy as np
    except ImportError as e:
        channel.send_json({"ok": False, "error": f"numpy is not importable by {sys.executable}: "
                           f"{e}. Install numpy into that interpreter"})
        return
    try:
        worker = Worker(channel, np, spec)
    except EnvError as e:
        channel.send_json({"ok": False, "error": str(e)})
        return
    except BaseException:
        channel.send_json({"ok": False, "error": env_traceback()})
        return
    channel.send_json(worker.handshake)
    try:
        worker.serve()
    except (EOFError, BrokenPipeError, ConnectionResetError):
        pass  # rlrun closed the socket: it is done with this env
    # The env is closed: skip the interpreter's teardown (tens of ms with numpy loaded), which
    # rlrun would wait for once per env.
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(0)


if __name__ == "__main__":  # `python -c <this file> FD`; the rlrun package imports it instead
    main()
