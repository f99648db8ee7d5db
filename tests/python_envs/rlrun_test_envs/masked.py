"""An env with invalid actions for MaskablePPO's tests (src/rlrun/env/action_mask.hpp): the
worker reads its mask from an action_masks() method (sb3-contrib's ActionMasker convention)
or from info["action_mask"] (Gymnasium's / PettingZoo's)."""
import numpy as np

from rlrun_test_envs.spaces import Box, Discrete


class LegalPick:
    """Each step two of four actions are legal; the observation is the mask itself, reward 1 for
    the first legal action, 0.5 for the other. An illegal action raises: a run that finishes
    took none. Ten steps an episode.

    mask_in_info: report info["action_mask"] instead of having action_masks().
    empty_at: the step (counted over the env's life) whose mask allows nothing.
    mask_length: report masks of this many entries (4 is right)."""

    metadata = {"render_modes": []}

    def __init__(self, mask_in_info=False, empty_at=-1, mask_length=4):
        self.observation_space = Box(0.0, 1.0, shape=(4,), dtype=np.float32)
        self.action_space = Discrete(4)
        self.mask_in_info = mask_in_info
        self.empty_at = empty_at
        self.mask_length = mask_length
        self.rng = np.random.default_rng()
        self.total_steps = 0
        if not mask_in_info:
            self.action_masks = self._action_masks

    def _draw(self):
        legal = self.rng.choice(4, size=2, replace=False)
        self.mask = np.zeros(4, dtype=bool)
        self.mask[legal] = True
        self.best = int(min(legal))

    def _action_masks(self):
        if self.total_steps == self.empty_at:
            return np.zeros(self.mask_length, dtype=bool)
        return np.resize(self.mask, self.mask_length)

    def _reply(self):
        info = {"action_mask": self._action_masks()} if self.mask_in_info else {}
        return self.mask.astype(np.float32), info

    def reset(self, *, seed=None, options=None):
        if seed is not None:
            self.rng = np.random.default_rng(seed)
        self.t = 0
        self._draw()
        return self._reply()

    def step(self, action):
        action = int(action)
        if not self.mask[action]:
            raise ValueError(f"illegal action {action} under mask {self.mask.tolist()}")
        reward = 1.0 if action == self.best else 0.5
        self.t += 1
        self.total_steps += 1
        self._draw()
        obs, info = self._reply()
        return obs, reward, False, self.t >= 10, info
