"""Small tasks in Python for the bridge's tests."""
import numpy as np

from rlrun_test_envs.spaces import Box, Dict, Discrete, Interval, MultiBinary


class Reach1D:
    """Move a point to a target on a line: obs (position, target), action a velocity in
    [-1, 1] (x 0.2 per step), reward -|position - target|; 20 steps. A random policy gets
    about -14 per episode, a good one about -3. Its action space is an Interval, which is not a
    gymnasium class name: rlrun reads it by its attributes."""

    metadata = {"render_modes": []}

    def __init__(self, episode_steps=20):
        self.observation_space = Box(-2.0, 2.0, shape=(2,), dtype=np.float32)
        self.action_space = Interval(-1.0, 1.0, 1)
        self.episode_steps = episode_steps
        self.rng = np.random.default_rng()

    def reset(self, *, seed=None, options=None):
        if seed is not None:
            self.rng = np.random.default_rng(seed)
        self.pos = float(self.rng.uniform(-1, 1))
        self.target = float(self.rng.uniform(-1, 1))
        self.t = 0
        return self._obs(), {}

    def _obs(self):
        return np.array([self.pos, self.target], dtype=np.float32)

    def step(self, action):
        a = float(np.clip(action[0], -1, 1))
        self.pos = float(np.clip(self.pos + 0.2 * a, -2, 2))
        self.t += 1
        distance = abs(self.pos - self.target)
        info = {"distance": distance, "is_success": distance < 0.1}
        return self._obs(), -distance, False, self.t >= self.episode_steps, info


class DictGoal:
    """Dict observations: {'goal': Discrete(4), 'position': Box(2), 'walls': MultiBinary(4)}.
    Reach the quadrant `goal` names; Discrete(4) actions move up/down/left/right by 0.25.
    Ends (terminated) with is_success=1 in the goal quadrant."""

    def __init__(self):
        self.observation_space = Dict({
            "goal": Discrete(4),
            "position": Box(-1.0, 1.0, shape=(2,), dtype=np.float32),
            "walls": MultiBinary(4),
        })
        self.action_space = Discrete(4)
        self.rng = np.random.default_rng()

    def reset(self, *, seed=None, options=None):
        if seed is not None:
            self.rng = np.random.default_rng(seed)
        self.goal = int(self.rng.integers(4))
        self.position = np.zeros(2, dtype=np.float32)
        return self._obs(), {"is_success": False}

    def _quadrant(self):
        return int(self.position[0] > 0) + 2 * int(self.position[1] > 0)

    def _obs(self):
        walls = np.array([self.position[1] >= 1, self.position[1] <= -1,
                          self.position[0] <= -1, self.position[0] >= 1], dtype=np.int8)
        return {"goal": self.goal, "position": self.position.copy(), "walls": walls}

    def step(self, action):
        move = [(0, 0.25), (0, -0.25), (-0.25, 0), (0.25, 0)][int(action)]
        self.position = np.clip(self.position + np.array(move, dtype=np.float32), -1, 1)
        success = self._quadrant() == self.goal and bool(np.all(np.abs(self.position) >= 0.25))
        return self._obs(), 1.0 if success else -0.1, success, False, {"is_success": success}
