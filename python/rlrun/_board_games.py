"""rlrun.env("TicTacToe-v0") / rlrun.env("ConnectFour-v0"): both seats of rlrun's board games
under PettingZoo's AEC API, as PettingZoo classic's ``tictactoe_v3.env()`` and
``connect_four_v3.env()`` are (pettingzoo/classic/tictactoe/tictactoe.py,
connect_four/connect_four.py, with the wrappers their ``env()`` puts around them).

    env = rlrun.env("TicTacToe-v0")
    env.reset(seed=1)
    for agent in env.agent_iter():
        observation, reward, termination, truncation, info = env.last()
        if termination or truncation:
            action = None
        else:
            mask = observation["action_mask"]
            action = env.action_space(agent).sample(mask)
        env.step(action)

The agents are PettingZoo's names (tic-tac-toe ``player_1`` and ``player_2``, connect four
``player_0`` and ``player_1``); the first moves first. Each agent observes
``{"observation": int8 planes (rows, cols, 2), "action_mask": int8}``: plane 0 its own pieces,
plane 1 the other player's, and the mask of legal moves when it is that agent's turn (all 0
otherwise; PettingZoo's games keep the board's open moves in the mask of the agent selected
after the end too). The winner's reward is +1 and the loser's -1, both 0 for a draw; every agent is then
terminated. An illegal move ends the game as PettingZoo's ``TerminateIllegalWrapper
(illegal_reward=-1)`` does: the mover gets -1, the other 0, every agent terminated and
truncated. The rules are rlrun's own C++ (src/rlrun/envs/board_games/), the same the single-
agent envs of these ids play (``rlrun.make("TicTacToe-v0")``: an opponent inside the env).
"""

from __future__ import annotations

import numpy as np

from . import _core
from . import _spaces
from ._pettingzoo import _AECBase, _Turns

# PettingZoo's agent names per game (tictactoe.py: player_1, player_2; connect_four.py:
# player_0, player_1).
_AGENT_NAMES = {
    "TicTacToe-v0": ("player_1", "player_2"),
    "ConnectFour-v0": ("player_0", "player_1"),
}
_ILLEGAL_REWARD = -1.0  # TerminateIllegalWrapper(illegal_reward=-1) in both games' env()


def is_board_game(id: str) -> bool:
    return id in _core.board_game_ids()


class RlrunBoardGameEnv(_Turns, _AECBase):
    """Both seats of TicTacToe-v0 or ConnectFour-v0 under PettingZoo's AEC API. Build it with
    ``rlrun.env(id)``."""

    def __init__(self, id: str, render_mode: str | None = None, **kwargs):
        if kwargs:
            raise ValueError(
                f"rlrun.env({id!r}) plays both seats and takes only render_mode; "
                f"{sorted(kwargs)} are kwargs of the single-agent env with an opponent inside "
                f"(rlrun.make({id!r}, ...))")
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"{id}: render_mode {render_mode!r} is not supported "
                             "(use 'rgb_array' or None)")
        self._game = _core.BoardGame(id)
        self.render_mode = render_mode
        self.metadata = {"name": id, "render_modes": ["rgb_array"],
                         "render_fps": self._game.render_fps, "is_parallelizable": False}
        self.possible_agents = list(_AGENT_NAMES[id])
        n, shape = self._game.num_actions, tuple(self._game.observation_shape)
        box = lambda s: {"kind": "Box", "low": np.zeros(s, np.int8), "high": np.ones(s, np.int8),
                         "shape": s, "dtype": "int8"}
        # One space object per agent, the same on every call (api_test checks `is`).
        self.observation_spaces = {
            a: _spaces.from_description({"kind": "Dict", "keys": ["action_mask", "observation"],
                                         "spaces": [box((n,)), box(shape)]})
            for a in self.possible_agents}
        self.action_spaces = {a: _spaces.from_description({"kind": "Discrete", "n": n, "start": 0})
                              for a in self.possible_agents}
        self._begin([], 0)
        self.infos: dict[str, dict] = {}
        self.agent_selection = None
        self._skip_agent_selection = None

    # -- PettingZoo's AECEnv -----------------------------------------------------------------
    def reset(self, seed: int | None = None, options: dict | None = None) -> None:
        # The games have no randomness: the seed is accepted, as PettingZoo's are.
        self._game.reset()
        self._begin(self.possible_agents, 0)
        self.infos = {a: {} for a in self.agents}
        self.agent_selection = self.possible_agents[0]
        self._skip_agent_selection = None

    def observe(self, agent: str):
        seat = self.possible_agents.index(agent)
        if agent == self.agent_selection:
            # PettingZoo's mask: the board's open moves, also for the agent selected after the
            # game's end (tictactoe.py _get_mask, connect_four.py observe).
            mask = self._game.legal_mask(after_end=True)
        else:
            mask = np.zeros(self._game.num_actions, dtype=np.int8)
        return {"observation": self._game.planes(seat), "action_mask": mask}

    def step(self, action) -> None:
        agent = self.agent_selection
        if agent is None:
            raise RuntimeError("step(): call reset() first")
        if self.terminations[agent] or self.truncations[agent]:
            self._was_dead_step(action)
            return
        space = self.action_spaces[agent]
        if action is None or not space.contains(action):
            raise ValueError(f"{agent}: action {action!r} is not in {space}")
        if not self._game.legal_mask()[int(action)]:
            self._illegal_move(agent)
            return
        self._game.play(int(action))
        mover = self.possible_agents.index(agent)
        other = self.possible_agents[1 - mover]
        outcome = self._game.outcome
        if outcome != 0:
            if outcome in (1, 2):  # 1: the first player won, 2: the second
                winner = self.possible_agents[outcome - 1]
                loser = self.possible_agents[2 - outcome]
                self.rewards[winner] += 1
                self.rewards[loser] -= 1
            self.terminations = dict.fromkeys(self.agents, True)
        self.agent_selection = other
        self._accumulate_rewards()

    def render(self):
        """An (H, W, 3) uint8 picture of the board (render_mode "rgb_array")."""
        if self.render_mode is None:
            return None
        return self._game.render()

    def close(self) -> None:
        pass

    def __str__(self):
        return self.metadata["name"]

    def __repr__(self):
        return f"<RlrunBoardGameEnv<{self.metadata['name']}>>"

    # -- PettingZoo's bookkeeping (pettingzoo/utils/env.py), written here again ----------------
    def _accumulate_rewards(self) -> None:
        for agent, reward in self.rewards.items():
            self._cumulative_rewards[agent] += reward

    def _illegal_move(self, agent: str) -> None:
        # TerminateIllegalWrapper.step: the mover's cumulative reward restarts at the penalty.
        self._cumulative_rewards[agent] = 0
        self.terminations = dict.fromkeys(self.agents, True)
        self.truncations = dict.fromkeys(self.agents, True)
        self.rewards = dict.fromkeys(self.agents, 0)
        self.rewards[agent] = _ILLEGAL_REWARD
        self._accumulate_rewards()
        self._skip_agent_selection = self.agent_selection
        self.agent_selection = self.agents[0]  # every agent is dead: the first steps first

    def _was_dead_step(self, action) -> None:
        if action is not None:
            raise ValueError("when an agent is dead, the only valid action is None")
        self._drop(self.agent_selection)
        dead = [a for a in self.agents if self.terminations[a] or self.truncations[a]]
        if dead:
            if self._skip_agent_selection is None:
                self._skip_agent_selection = self.agent_selection
            self.agent_selection = dead[0]
        else:
            if self._skip_agent_selection is not None:
                self.agent_selection = self._skip_agent_selection
            self._skip_agent_selection = None
        self.rewards = dict.fromkeys(self.rewards, 0)
