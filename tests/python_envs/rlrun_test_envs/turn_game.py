"""Tic-tac-toe as a turn-based AECEnv written without PettingZoo, laid out as PettingZoo's
classic modules are (tictactoe_v3: ``raw_env`` the class, ``env`` the function that builds it),
with PettingZoo classic's conventions: players ``player_1`` and ``player_2``, observation
{"observation": 3x3x2 planes (own marks, the other's), "action_mask": int8[9]}, +1 / -1 at a
win, 0 at a draw; an illegal move raises. For `pettingzoo:rlrun_test_envs.turn_game:env`."""
import numpy as np

from rlrun_test_envs.spaces import Box, Dict, Discrete

LINES = [(0, 1, 2), (3, 4, 5), (6, 7, 8), (0, 3, 6), (1, 4, 7), (2, 5, 8), (0, 4, 8), (2, 4, 6)]


class TurnTicTacToe:
    metadata = {"name": "tictactoe_v3", "is_parallelizable": False, "render_modes": ["rgb_array"]}

    def __init__(self, render_mode=None):
        self.render_mode = render_mode
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

    def render(self):
        """A 33 x 31 frame (odd on purpose: rlrun's video needs even sizes and pads): white
        board, player_1's squares red, player_2's blue; squares numbered down the columns."""
        if self.render_mode != "rgb_array":
            return None
        frame = np.full((31, 33, 3), 255, dtype=np.uint8)
        for square, mark in enumerate(self.board):
            if mark:
                row, col = square % 3, square // 3
                frame[row * 10 + 1:row * 10 + 10, col * 11 + 1:col * 11 + 11] = \
                    (220, 40, 40) if mark == 1 else (40, 40, 220)
        return frame

    def close(self):
        pass


raw_env = TurnTicTacToe  # PettingZoo's modules name their class so; rlrun reads its metadata


def env(**kwargs):
    return TurnTicTacToe(**kwargs)
