"""PettingZoo-API envs written without PettingZoo (its API by duck typing, as
pettingzoo/utils/env.py defines it), for `env.id: pettingzoo:rlrun_test_envs.multi_agent:...`.

* ``parallel_env``: "Homing", a ParallelEnv. Each agent walks a line of cells towards its own
  home (Discrete(3): left, stay, right), sees (position, home) / size, gets -0.1 a step and +1
  on arrival, and then leaves the env (terminated), while the others go on; the episode is
  truncated after ``max_cycles``. An agent that learns walks home in |home - start| steps.

The turn-based game is in turn_game.py (a module laid out as PettingZoo's: raw_env and env).
"""
import numpy as np

from rlrun_test_envs.spaces import Box, Discrete


class Homing:
    metadata = {"name": "homing_v0", "render_modes": []}

    def __init__(self, n_agents=3, size=7, max_cycles=25, leave_early=True):
        self.possible_agents = [f"walker_{i}" for i in range(n_agents)]
        self.size, self.max_cycles, self.leave_early = size, max_cycles, leave_early
        self._obs_spaces = {a: Box(0.0, 1.0, shape=(2,), dtype=np.float32) for a in self.possible_agents}
        self._act_spaces = {a: Discrete(3) for a in self.possible_agents}
        self.agents = []
        self.rng = np.random.default_rng()

    def observation_space(self, agent):
        return self._obs_spaces[agent]

    def action_space(self, agent):
        return self._act_spaces[agent]

    def _obs(self, agent):
        return np.array([self.pos[agent], self.home[agent]], dtype=np.float32) / (self.size - 1)

    def reset(self, seed=None, options=None):
        if seed is not None:
            self.rng = np.random.default_rng(seed)
        self.agents = list(self.possible_agents)
        self.cycle = 0
        self.pos, self.home = {}, {}
        for a in self.agents:
            start, home = self.rng.choice(self.size, size=2, replace=False)
            self.pos[a], self.home[a] = int(start), int(home)
        return {a: self._obs(a) for a in self.agents}, {a: {"distance": abs(self.pos[a] - self.home[a])} for a in self.agents}

    def step(self, actions):
        self.cycle += 1
        obs, rewards, terminations, truncations, infos = {}, {}, {}, {}, {}
        for a in self.agents:
            move = int(actions[a]) - 1
            self.pos[a] = min(self.size - 1, max(0, self.pos[a] + move))
            arrived = self.pos[a] == self.home[a]
            rewards[a] = 1.0 if arrived else -0.1
            terminations[a] = bool(arrived and self.leave_early)
            truncations[a] = self.cycle >= self.max_cycles
            obs[a] = self._obs(a)
            infos[a] = {"distance": abs(self.pos[a] - self.home[a])}
        self.agents = [a for a in self.agents if not (terminations[a] or truncations[a])]
        return obs, rewards, terminations, truncations, infos

    def close(self):
        pass


def parallel_env(**kwargs):
    return Homing(**kwargs)


def uneven_env(**kwargs):
    """A parallel env whose agents' spaces differ (refused: rlrun's agents share a policy)."""
    env = Homing(**kwargs)
    env._act_spaces[env.possible_agents[-1]] = Discrete(5)
    return env


class _Misbehaving(Homing):
    """Homing whose step() breaks PettingZoo's contract in one way (`fault`), from the second
    step on, for the worker's refusals."""

    def __init__(self, fault, **kwargs):
        super().__init__(**kwargs)
        self.fault = fault

    def step(self, actions):
        obs, rewards, terminations, truncations, infos = super().step(actions)
        if self.cycle >= 2:
            if self.fault == "missing":
                obs.pop(next(iter(obs)))
            elif self.fault == "unknown":
                rewards["ghost"] = 0.0
            elif self.fault == "agents":
                self.agents = self.agents + ["ghost"]
        return obs, rewards, terminations, truncations, infos


def duplicate_agents_env(**kwargs):
    """possible_agents names one agent twice (refused)."""
    env = Homing(**kwargs)
    env.possible_agents = env.possible_agents + env.possible_agents[:1]
    return env


def missing_agent_env(**kwargs):
    """step() leaves a live agent out of the observations (refused)."""
    return _Misbehaving("missing", leave_early=False, **kwargs)


def unknown_agent_env(**kwargs):
    """step() returns a reward for an agent that is not one of possible_agents (refused)."""
    return _Misbehaving("unknown", leave_early=False, **kwargs)


def unknown_live_agent_env(**kwargs):
    """env.agents grows an agent that is not one of possible_agents (refused)."""
    return _Misbehaving("agents", leave_early=False, **kwargs)


class Sides(Homing):
    """Two walkers start in the middle of the line; walker_0's home is the left end, walker_1's
    the right end, and an observation is the position alone. One shared policy cannot tell the
    walkers apart, so at most one of them walks home; with env.agent_indicator both can."""

    def __init__(self, size=7, max_cycles=12):
        super().__init__(n_agents=2, size=size, max_cycles=max_cycles, leave_early=True)
        self._obs_spaces = {a: Box(0.0, 1.0, shape=(1,), dtype=np.float32) for a in self.possible_agents}

    def _obs(self, agent):
        return np.array([self.pos[agent]], dtype=np.float32) / (self.size - 1)

    def reset(self, seed=None, options=None):
        super().reset(seed=seed, options=options)
        for i, a in enumerate(self.possible_agents):
            self.pos[a], self.home[a] = self.size // 2, 0 if i == 0 else self.size - 1
        return {a: self._obs(a) for a in self.agents}, {a: {} for a in self.agents}


def sides_env(**kwargs):
    return Sides(**kwargs)
