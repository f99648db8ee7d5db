"""PettingZoo-API envs written without PettingZoo (its API by duck typing, as
pettingzoo/utils/env.py defines it), for `env.id: pettingzoo:rlrun_test_envs.multi_agent:...`.

* ``parallel_env``: "Homing", a ParallelEnv. Each agent walks a line of cells towards its own
  home (Discrete(3): left, stay, right), sees (position, home) / size, gets -0.1 a step and +1
  on arrival, and then leaves the env (terminated), while the others go on; the episode is
  truncated after ``max_cycles``. An agent that learns walks home in |home - start| steps.
* ``turn_env``: tic-tac-toe as a turn-based AECEnv with PettingZoo classic's conventions
  (tictactoe_v3): players ``player_1`` and ``player_2``, observation {"observation": 3x3x2
  planes (own marks, the other's), "action_mask": int8[9]}, +1 / -1 at a win, 0 at a draw.
"""
import numpy as np

from rlrun_test_envs.spaces import Box, Dict, Discrete


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


LINES = [(0, 1, 2), (3, 4, 5), (6, 7, 8), (0, 3, 6), (1, 4, 7), (2, 5, 8), (0, 4, 8), (2, 4, 6)]


class TurnTicTacToe:
    metadata = {"name": "tictactoe_v3", "is_parallelizable": False, "render_modes": []}

    def __init__(self):
        self.possible_agents = ["player_1", "player_2"]
        space = Dict({"observation": Box(0, 1, shape=(3, 3, 2), dtype=np.int8),
                      "action_mask": Box(0, 1, shape=(9,), dtype=np.int8)})
        self._obs_spaces = {a: space for a in self.possible_agents}
        self._act_spaces = {a: Discrete(9) for a in self.possible_agents}
        self.agents = []

    def observation_space(self, agent):
        return self._obs_spaces[agent]

    def action_space(self, agent):
        return self._act_spaces[agent]

    def agent_iter(self, max_iter=2**63):
        while self.agents and max_iter > 0:
            max_iter -= 1
            yield self.agent_selection

    def reset(self, seed=None, options=None):
        self.board = np.zeros(9, dtype=np.int8)  # 0 empty, 1 player_1, 2 player_2
        self.agents = list(self.possible_agents)
        self.agent_selection = "player_1"
        self.rewards = dict.fromkeys(self.agents, 0)
        self._cumulative_rewards = dict.fromkeys(self.agents, 0)
        self.terminations = dict.fromkeys(self.agents, False)
        self.truncations = dict.fromkeys(self.agents, False)
        self.infos = {a: {} for a in self.agents}

    def observe(self, agent):
        me = 1 + self.possible_agents.index(agent)
        other = 3 - me
        planes = np.stack([(self.board == me), (self.board == other)], axis=-1).astype(np.int8)
        mask = (self.board == 0).astype(np.int8)
        return {"observation": planes.reshape(3, 3, 2), "action_mask": mask}

    def step(self, action):
        agent = self.agent_selection
        if self.terminations[agent] or self.truncations[agent]:
            assert action is None
            self.agents.remove(agent)
            if self.agents:
                self.agent_selection = self.agents[0]
            return
        action = int(action)
        if self.board[action] != 0:
            raise ValueError(f"illegal move {action}")
        me = 1 + self.possible_agents.index(agent)
        self.board[action] = me
        other = self.possible_agents[2 - me]
        self.rewards = dict.fromkeys(self.agents, 0)
        self._cumulative_rewards[agent] = 0
        won = any(all(self.board[i] == me for i in line) for line in LINES)
        if won:
            self.rewards[agent], self.rewards[other] = 1, -1
        if won or not (self.board == 0).any():
            self.terminations = dict.fromkeys(self.agents, True)
        for a, r in self.rewards.items():
            self._cumulative_rewards[a] += r
        self.agent_selection = other

    def close(self):
        pass


def turn_env():
    return TurnTicTacToe()
