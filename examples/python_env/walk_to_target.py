"""A complete Gymnasium env in Python, trained by rlrun (docs/python.md, "Python envs in rlrun
training"):

    cd examples/python_env && rlrun train walk_to_target_ppo.yaml

A walker on a line starts at a random spot and must reach a random target: actions 0 / 1 / 2
step left / stay / right by 0.1; the reward is -0.01 a step and +1 on arrival (terminated);
observations are (position, target) in [-1, 1]; 100 steps at most (TimeLimit, set in the
experiment file). `is_success` in the info reaches rlrun's monitor.csv and success_rate.
"""
import numpy as np

try:
    import gymnasium as gym
except ImportError:  # rlrun reads only the spaces' attributes: numpy stand-ins work too
    gym = None


def _spaces():
    if gym is not None:
        return (gym.spaces.Box(-1.0, 1.0, shape=(2,), dtype=np.float32), gym.spaces.Discrete(3))

    class Box:
        low, high, shape, dtype = np.full(2, -1.0, np.float32), np.full(2, 1.0, np.float32), (2,), np.float32

    class Discrete:
        n, start, shape, dtype = 3, 0, (), np.int64

    return Box(), Discrete()


class WalkToTarget(gym.Env if gym is not None else object):
    metadata = {"render_modes": ["rgb_array"], "render_fps": 10}

    def __init__(self, step_size=0.1, render_mode=None):
        self.observation_space, self.action_space = _spaces()
        self.step_size = step_size
        self.render_mode = render_mode
        self.rng = np.random.default_rng()

    def reset(self, *, seed=None, options=None):
        if seed is not None:
            self.rng = np.random.default_rng(seed)  # what gymnasium.Env.reset(seed=...) does
        self.position, self.target = self.rng.uniform(-1, 1, size=2)
        return self._obs(), {}

    def step(self, action):
        self.position = float(np.clip(self.position + (int(action) - 1) * self.step_size, -1, 1))
        arrived = abs(self.position - self.target) < self.step_size / 2
        reward = 1.0 if arrived else -0.01
        return self._obs(), reward, arrived, False, {"is_success": arrived}

    def _obs(self):
        return np.array([self.position, self.target], dtype=np.float32)

    def render(self):
        """A 40 x 200 strip: the target in green, the walker in blue."""
        frame = np.full((40, 200, 3), 255, dtype=np.uint8)
        for x, colour in ((self.target, (40, 160, 40)), (self.position, (40, 40, 200))):
            col = int((x + 1) / 2 * 199)
            frame[10:30, max(0, col - 3):col + 4] = colour
        return frame
