"""rlrun.parallel_env / rlrun.env: rlrun's multi-agent envs through PettingZoo's two APIs.

PettingZoo (pettingzoo/utils/env.py) has a Parallel API (every agent acts at once: dicts keyed
by agent name) and an AEC API (agents act in turn: ``agent_iter()``, ``last()``, ``step(a)``).
rlrun's multi-agent envs are parallel ones (include/rlrun/env.hpp): TrafficNetwork-v0's
traffic lights all act every ``delta_time`` seconds, as sumo-rl's ``parallel_env`` does.

    env = rlrun.parallel_env("TrafficNetwork-v0", num_seconds=600)
    obs, infos = env.reset(seed=1)
    while env.agents:
        obs, rewards, terminations, truncations, infos = env.step(
            {agent: env.action_space(agent).sample() for agent in env.agents})

The agents are named as the env names them (the traffic light ids; ``agent_<i>`` otherwise).
Each agent's info holds the env's numeric info (the same for every agent) and, when the env
masks actions, that agent's ``action_mask`` (int8, PettingZoo classic's convention). All agents
end together, so after the last step ``env.agents`` is empty.

``rlrun.env(...)`` is the same env under the AEC API, with the semantics of PettingZoo's own
parallel-to-AEC conversion (pettingzoo/utils/conversions.py, written here again so the env is
an AECEnv itself, as PettingZoo's api_test asks): the agents' actions are collected in turn,
the env steps when the last live agent has acted, and ``last()`` gives each agent the rewards
accumulated since it last acted. When PettingZoo is importable the classes derive from
``pettingzoo.ParallelEnv`` and ``pettingzoo.AECEnv``; without it they offer the same methods.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from . import _core
from . import _spaces
from ._env import kwargs_text

try:  # PettingZoo's base classes when it is there (isinstance checks, api_test); else plain.
    import pettingzoo as _pettingzoo

    _ParallelBase = _pettingzoo.ParallelEnv
    _AECBase = _pettingzoo.AECEnv
    HAVE_PETTINGZOO = True
except ImportError:  # pragma: no cover - depends on the machine
    _ParallelBase = object
    _AECBase = object
    HAVE_PETTINGZOO = False


class _Agents:
    """What both APIs give of the agents: the spaces per agent (the same object on every call,
    as PettingZoo's tests check) and the counts."""

    def observation_space(self, agent: str):
        return self.observation_spaces[agent]

    def action_space(self, agent: str):
        return self.action_spaces[agent]

    @property
    def num_agents(self) -> int:
        return len(self.agents)

    @property
    def max_num_agents(self) -> int:
        return len(self.possible_agents)

    @property
    def unwrapped(self):
        return self


class _Turns(_Agents):
    """What an AEC env gives of its turns (AECEnv.last and agent_iter): the selected agent's
    observation and the rewards it accumulated since it last acted."""

    def _begin(self, agents, zero) -> None:
        """The per-agent tables at an episode's start (no agents: before the first reset);
        `zero` is the rewards' type of zero (PettingZoo's classic games count in ints)."""
        self.agents = list(agents)
        self.rewards = dict.fromkeys(self.agents, zero)
        self._cumulative_rewards = dict.fromkeys(self.agents, zero)
        self.terminations = dict.fromkeys(self.agents, False)
        self.truncations = dict.fromkeys(self.agents, False)

    def _drop(self, agent: str) -> None:
        """A done agent leaves every table (its dead step, AECEnv._was_dead_step)."""
        for table in (self.terminations, self.truncations, self.rewards, self._cumulative_rewards,
                      self.infos):
            del table[agent]
        self.agents.remove(agent)

    def last(self, observe: bool = True):
        agent = self.agent_selection
        if agent is None:
            raise RuntimeError("last(): call reset() first")
        return (self.observe(agent) if observe else None, self._cumulative_rewards[agent],
                self.terminations[agent], self.truncations[agent], self.infos[agent])

    def agent_iter(self, max_iter: int = 2**63):
        """The agent to act, until no agents are left (or max_iter turns)."""
        while self.agents and max_iter > 0:
            max_iter -= 1
            yield self.agent_selection


class RlrunParallelEnv(_Agents, _ParallelBase):
    """One of rlrun's envs under PettingZoo's Parallel API. Build it with
    ``rlrun.parallel_env(id, **kwargs)``."""

    def __init__(self, id: str, render_mode: str | None = None,
                 max_episode_steps: int | None = None, **kwargs):
        self._core = _core.MultiAgentEnv(id, kwargs_text(kwargs),
                                         -1 if max_episode_steps is None else int(max_episode_steps))
        self.possible_agents = list(self._core.agent_names)
        self._index = {a: i for i, a in enumerate(self.possible_agents)}  # row of each agent
        self.agents: list[str] = []
        # One space object per agent, the same object on every call (api_test checks `is`; an
        # agent's action space is seeded on its own).
        self.observation_spaces = {a: _spaces.from_description(self._core.observation_space)
                                   for a in self.possible_agents}
        self.action_spaces = {a: _spaces.from_description(self._core.action_space)
                              for a in self.possible_agents}
        space = next(iter(self.observation_spaces.values()))
        self._box_obs = type(space).__name__ == "Box"
        self._uint8_obs = self._box_obs and np.dtype(space.dtype) == np.uint8
        self._obs_space = space
        self._act_space = next(iter(self.action_spaces.values()))
        self._act_kind = type(self._act_space).__name__
        can_render = self._core.can_render
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"{id}: render_mode {render_mode!r} is not supported (use 'rgb_array' or None)")
        if render_mode == "rgb_array" and not can_render:
            raise ValueError(f"{id} cannot render")
        self.render_mode = render_mode
        self.metadata = {
            "name": id,
            "render_modes": ["rgb_array"] if can_render else [],
            "render_fps": self._core.render_fps,
            "is_parallelizable": True,
        }
        self._actions = np.zeros((len(self.possible_agents),
                                  _spaces.flat_dim(self._act_space)), dtype=np.float32)
        self._last_obs = None

    # -- PettingZoo's ParallelEnv ------------------------------------------------------------
    def reset(self, seed: int | None = None, options: dict | None = None):
        if seed is not None and (not isinstance(seed, (int, np.integer)) or seed < 0):
            raise ValueError(f"seed must be a non-negative int, got {seed!r}")
        obs, info, masks = self._core.reset(None if seed is None else int(seed))
        self.agents = list(self.possible_agents)
        self._last_obs = obs
        return self._per_agent(obs), self._infos(info, masks)

    def step(self, actions: dict):
        if not self.agents:
            raise RuntimeError(f"{self.metadata['name']}: the episode is over (no agents): call reset()")
        missing = [a for a in self.agents if a not in actions]
        if missing:
            raise ValueError(f"step: no action for agent(s) {missing} (every live agent acts each step)")
        unknown = [a for a in actions if a not in self.observation_spaces]
        if unknown:
            raise ValueError(f"step: unknown agent(s) {unknown}; the agents are {self.possible_agents}")
        live = set(self.agents)
        for i, agent in enumerate(self.possible_agents):
            # An agent that is done (none are before the episode ends: they end together) acts 0.
            self._actions[i] = self._flat_action(actions[agent]) if agent in live else 0.0
        obs, rewards, terminated, truncated, info, masks = self._core.step(self._actions)
        self._last_obs = obs
        agents = self.agents
        index = self._index
        out = (
            self._per_agent(obs, agents),
            {a: float(rewards[index[a]]) for a in agents},
            {a: bool(terminated[index[a]]) for a in agents},
            {a: bool(truncated[index[a]]) for a in agents},
            self._infos(info, masks, agents),
        )
        self.agents = [a for a in agents if not (terminated[index[a]] or truncated[index[a]])]
        return out

    def state(self) -> np.ndarray:
        """The global state: every agent's observation, flat, agent after agent."""
        if self._last_obs is None:
            raise RuntimeError("state(): call reset() first")
        return np.asarray(self._last_obs, dtype=np.float32).reshape(-1).copy()

    @property
    def state_space(self):
        """The Box that state() values lie in (the agents' Boxes side by side)."""
        k, d = len(self.possible_agents), _spaces.flat_dim(self._obs_space)
        if self._box_obs:
            low = np.tile(np.asarray(self._obs_space.low, np.float32).reshape(-1), k)
            high = np.tile(np.asarray(self._obs_space.high, np.float32).reshape(-1), k)
        else:
            low, high = np.full(k * d, -np.inf, np.float32), np.full(k * d, np.inf, np.float32)
        return _spaces.from_description({"kind": "Box", "low": low, "high": high,
                                         "shape": (k * d,), "dtype": "float32"})

    def render(self):
        """An (H, W, 3) uint8 frame of the whole env (render_mode "rgb_array")."""
        return self._core.render()

    def close(self):
        if not self._core.closed:
            self._core.close()

    def __str__(self):
        return self.metadata["name"]

    def __repr__(self):
        return f"<RlrunParallelEnv<{self.metadata['name']}>>"

    # -- shaping values ---------------------------------------------------------------------
    def _agent_obs(self, row):
        if self._uint8_obs:
            return row.astype(np.uint8)
        return row.copy() if self._box_obs else _spaces.from_flat(self._obs_space, row)

    def _per_agent(self, obs, agents=None) -> dict:
        index = self._index
        return {a: self._agent_obs(obs[index[a]]) for a in (agents or self.possible_agents)}

    def _infos(self, info: dict, masks, agents=None) -> dict:
        out = {}
        for i, agent in enumerate(self.possible_agents):
            if agents is not None and agent not in agents:
                continue
            d = dict(info)
            if masks is not None:
                d["action_mask"] = masks[i].copy()
            out[agent] = d
        return out

    def _flat_action(self, action) -> np.ndarray:
        if self._act_kind == "Dict":
            return _spaces.to_flat(self._act_space, action)
        return np.asarray(action, dtype=np.float32).reshape(-1)


class RlrunAECEnv(_Turns, _AECBase):
    """One of rlrun's envs under PettingZoo's AEC API. Build it with ``rlrun.env(id, **kwargs)``."""

    def __init__(self, id: str, **kwargs):
        self._parallel = RlrunParallelEnv(id, **kwargs)
        self.possible_agents = list(self._parallel.possible_agents)
        self.metadata = dict(self._parallel.metadata)
        self.render_mode = self._parallel.render_mode
        self.observation_spaces = self._parallel.observation_spaces
        self.action_spaces = self._parallel.action_spaces
        self._begin([], 0.0)
        self.infos: dict[str, dict] = {}
        self.agent_selection = None
        self._observations: dict[str, Any] = {}
        self._actions: dict[str, Any] = {}
        self._cycle: list[str] = []

    @property
    def state_space(self):
        return self._parallel.state_space

    def reset(self, seed: int | None = None, options: dict | None = None) -> None:
        self._observations, self.infos = self._parallel.reset(seed=seed, options=options)
        self._begin(self._parallel.agents, 0.0)
        self._start_cycle()

    def _start_cycle(self) -> None:
        # The agents act in the order of `agents`, one cycle per step of the parallel env.
        self._cycle = list(self.agents)
        self._actions = {}
        self.agent_selection = self._cycle[0] if self._cycle else None

    def observe(self, agent: str):
        return self._observations[agent]

    def step(self, action) -> None:
        agent = self.agent_selection
        if agent is None:
            raise RuntimeError("step(): call reset() first")
        if self.terminations[agent] or self.truncations[agent]:
            self._remove_done_agent(agent, action)
            return
        # The acting agent collects its rewards anew from here (AEC: last() gives the rewards
        # since the agent last acted).
        self._cumulative_rewards[agent] = 0.0
        self._actions[agent] = action
        position = self._cycle.index(agent)
        if position + 1 < len(self._cycle):
            if position == 0:  # the rewards of the previous parallel step are spent
                self.rewards = dict.fromkeys(self.agents, 0.0)
            self.agent_selection = self._cycle[position + 1]
            return
        obs, rewards, terminations, truncations, infos = self._parallel.step(self._actions)
        self._observations = obs
        self.rewards = rewards
        for a, r in rewards.items():
            self._cumulative_rewards[a] += r
        self.terminations = terminations
        self.truncations = truncations
        self.infos = infos
        done = [a for a in self.agents if terminations[a] or truncations[a]]
        self._start_cycle()
        if done:  # the done agents step (with None) first, to leave, as PettingZoo's envs do
            self.agent_selection = done[0]

    def _remove_done_agent(self, agent: str, action) -> None:
        if action is not None:
            raise ValueError(f"{agent} is done: the only valid action is None")
        self._drop(agent)
        self._cycle.remove(agent)
        self.rewards = dict.fromkeys(self.agents, 0.0)
        done = [a for a in self.agents if self.terminations[a] or self.truncations[a]]
        if done:
            self.agent_selection = done[0]
        elif self.agents:
            self._start_cycle()
        # With no agents left agent_selection stays on the last one, as PettingZoo's envs leave it.

    def state(self) -> np.ndarray:
        return self._parallel.state()

    def render(self):
        return self._parallel.render()

    def close(self):
        self._parallel.close()

    def __str__(self):
        return self.metadata["name"]

    def __repr__(self):
        return f"<RlrunAECEnv<{self.metadata['name']}>>"


def parallel_env(id: str, **kwargs) -> RlrunParallelEnv:
    """rlrun's env `id` under PettingZoo's Parallel API (a ``pettingzoo.ParallelEnv`` when
    PettingZoo is installed). ``kwargs`` are the env's own (checked strictly, as rlrun.make's),
    plus ``render_mode`` (None or "rgb_array") and ``max_episode_steps``."""
    from ._board_games import is_board_game

    if is_board_game(id):
        raise ValueError(f"{id} is turn-based: its two seats are an AEC env, rlrun.env({id!r}) "
                         "(PettingZoo's classic games are not parallelizable either)")
    return RlrunParallelEnv(id, **kwargs)


def env(id: str, **kwargs):
    """rlrun's env `id` under PettingZoo's AEC API (a ``pettingzoo.AECEnv`` when PettingZoo is
    installed); the same kwargs as parallel_env. The board games (TicTacToe-v0, ConnectFour-v0)
    are both of their seats, as PettingZoo's tictactoe_v3 and connect_four_v3
    (python/rlrun/_board_games.py); ``kwargs`` then is ``render_mode`` alone."""
    from ._board_games import RlrunBoardGameEnv, is_board_game

    if is_board_game(id):
        return RlrunBoardGameEnv(id, **kwargs)
    return RlrunAECEnv(id, **kwargs)
