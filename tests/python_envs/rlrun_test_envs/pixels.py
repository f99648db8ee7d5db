"""An image-observation task for the CNN path from Python: Box(0, 255, (36, 36, 1), np.uint8),
SB3's idea of an image (is_image_space asks for uint8). A bright square sits on the left or the
right half; action 0 says left, 1 says right; reward 1 when right, 0 otherwise; 8 steps."""
import numpy as np

from .spaces import Box, Discrete


class BrightSide:
    def __init__(self):
        self.observation_space = Box(0, 255, shape=(36, 36, 1), dtype=np.uint8)
        self.action_space = Discrete(2)
        self.rng = np.random.default_rng()

    def reset(self, *, seed=None, options=None):
        if seed is not None:
            self.rng = np.random.default_rng(seed)
        self.steps = 0
        return self._draw(), {}

    def _draw(self):
        self.side = int(self.rng.integers(2))
        image = np.full((36, 36, 1), 20, dtype=np.uint8)
        left = 4 if self.side == 0 else 22
        image[10:20, left:left + 10, 0] = 230
        return image

    def step(self, action):
        reward = 1.0 if int(action) == self.side else 0.0
        self.steps += 1
        return self._draw(), reward, False, self.steps >= 8, {}


class FloatBrightSide(BrightSide):
    """The same pictures in a float32 Box of 0-255: not an image to SB3 (is_image_space asks
    for uint8), so CnnPolicy refuses it."""

    def __init__(self):
        super().__init__()
        self.observation_space = Box(0, 255, shape=(36, 36, 1), dtype=np.float32)

    def _draw(self):
        return super()._draw().astype(np.float32)


class BrightSideBox(BrightSide):
    """The same pictures with a continuous answer: Box(-1, 1, (1,)), -1 for left and +1 for
    right; the reward is minus the distance to the right answer (for SAC / TD3 CnnPolicy)."""

    def __init__(self):
        super().__init__()
        self.action_space = Box(-1.0, 1.0, shape=(1,), dtype=np.float32)

    def step(self, action):
        target = 1.0 if self.side == 1 else -1.0
        reward = -abs(float(np.asarray(action).reshape(-1)[0]) - target)
        self.steps += 1
        return self._draw(), reward, False, self.steps >= 8, {}
