"""env.render() of a MuJoCo task returns frames as Gymnasium's MujocoRenderer does in rgb_array
mode: (480, 480, 3) uint8, top row first, drawn by MuJoCo's renderer on an offscreen OpenGL
context (OSMesa), in a process without a display. Skipped when rlrun was built without MuJoCo."""

import os
import unittest

import numpy as np

import rlrun


class MujocoRender(unittest.TestCase):
    def setUp(self):
        if "HalfCheetah-v4" not in rlrun.list_envs():
            self.skipTest("rlrun was built without the MuJoCo envs")
        os.environ.pop("DISPLAY", None)

    def test_half_cheetah_rgb_array(self):
        env = rlrun.make("HalfCheetah-v4", render_mode="rgb_array")
        self.assertEqual(env.metadata["render_fps"], 20)  # round(1 / dt), dt = 0.05
        env.reset(seed=0)
        frame = env.render()
        self.assertEqual(frame.shape, (480, 480, 3))
        self.assertEqual(frame.dtype, np.uint8)
        # MuJoCo's grey sky at the top (the frame is not upside down), the tan cheetah below it.
        top = frame[:40].reshape(-1, 3).astype(int)
        self.assertLess(np.abs(top[:, 0] - top[:, 2]).max(), 8)
        r, g, b = (frame[240:].astype(int)[..., i] for i in range(3))
        self.assertGreater(np.count_nonzero((r > b + 30) & (r > g + 10)), 3000)
        self.assertTrue(np.array_equal(env.render(), frame))  # the same state, the same frame
        for _ in range(5):
            env.step(np.full(6, 0.8, dtype=np.float32))
        self.assertFalse(np.array_equal(env.render(), frame))
        env.close()


if __name__ == "__main__":
    unittest.main()
