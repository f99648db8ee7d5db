"""MaskablePPO from Python (docs/maskable_ppo.md): model.predict(obs, action_masks=...) as
sb3-contrib's, the deterministic masked actions equal to what `rlrun eval` takes with the
env's masks, bad masks refused; rlrun.make's envs give info["action_mask"] and action_masks()."""

import os
import unittest

import numpy as np

import rlrun
from rlrun_testing import TempDirMixin, read_trajectory, run_rlrun, train_model

MASKABLE = ("run: {name: maskable, seed: 1, total_timesteps: 512}\n"
            "env: {id: GridWorld-v0, n_envs: 2}\n"
            "algo: {id: MaskablePPO, n_steps: 64, batch_size: 64, n_epochs: 2,"
            " policy: {net_arch: [16]}}\n")
UNMASKED = ("run: {name: unmasked, seed: 1, total_timesteps: 128}\n"
            "env: {id: GridWorld-v0}\n"
            "algo: {id: PPO, n_steps: 64, batch_size: 64, n_epochs: 1, policy: {net_arch: [16]}}\n")


def grid_mask(row, col, size=5):
    """GridWorld-v0's mask: up, right, down, left when they stay on the grid."""
    return np.array([row > 0, col < size - 1, row < size - 1, col > 0])


class MaskedPredict(TempDirMixin, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.maskable = train_model(cls.tmp, "maskable", MASKABLE)
        cls.unmasked = train_model(cls.tmp, "unmasked", UNMASKED)
        cls.steps_csv = os.path.join(cls.tmp, "steps.csv")
        run_rlrun("eval", "--model", cls.maskable, "--episodes", 2, "--seed", 3,
                  "--trajectory", cls.steps_csv)

    def test_masked_actions_are_never_chosen(self):
        model = rlrun.load(self.maskable)
        self.assertEqual(model.algorithm, "MaskablePPO")
        obs = np.zeros((300, 2), dtype=np.int64)  # the corner (0, 0): right and down only
        masks = np.tile(grid_mask(0, 0), (300, 1))
        actions, _ = model.predict(obs, action_masks=masks)
        self.assertTrue(set(actions.tolist()) <= {1, 2})
        # One observation, one mask; a mask with a single legal move decides the action.
        action, _ = model.predict(np.array([2, 2]), action_masks=[False, False, False, True],
                                  deterministic=True)
        self.assertEqual(int(action), 3)

    def test_deterministic_masked_predict_matches_eval(self):
        model = rlrun.load(self.maskable)
        rows = read_trajectory(self.steps_csv)
        self.assertGreater(len(rows), 0)
        for row in rows:
            row_, col = (int(v) for v in row["obs"])
            action, _ = model.predict(row["obs"].astype(np.int64), deterministic=True,
                                      action_masks=grid_mask(row_, col))
            self.assertEqual(int(action), int(row["action"][0]), f"step {row['step']}")
            self.assertTrue(grid_mask(row_, col)[int(action)])

    def test_bad_masks_are_refused(self):
        model = rlrun.load(self.maskable)
        with self.assertRaisesRegex(ValueError, "allows no action"):
            model.predict(np.array([0, 0]), action_masks=np.zeros(4, dtype=bool))
        with self.assertRaisesRegex(ValueError, "takes 4 per observation"):
            model.predict(np.array([0, 0]), action_masks=np.ones(3, dtype=bool))
        with self.assertRaisesRegex(ValueError, "not 0 or 1"):
            model.predict(np.array([0, 0]), action_masks=np.array([0.5, 1, 1, 1]))
        with self.assertRaisesRegex(ValueError, "takes no action masks"):
            rlrun.load(self.unmasked).predict(np.array([0, 0]), action_masks=np.ones(4))

    def test_made_env_reports_its_mask(self):
        env = rlrun.make("GridWorld-v0")
        _, info = env.reset(seed=1)
        np.testing.assert_array_equal(info["action_mask"], [0, 1, 1, 0])
        self.assertFalse(any(key.startswith("action_mask.") for key in info))
        np.testing.assert_array_equal(env.action_masks(), grid_mask(0, 0))
        _, _, _, _, info = env.step(2)  # down to (1, 0)
        np.testing.assert_array_equal(env.action_masks(), grid_mask(1, 0))
        np.testing.assert_array_equal(info["action_mask"], grid_mask(1, 0).astype(np.int8))


if __name__ == "__main__":
    unittest.main()


class VectorMasks(unittest.TestCase):
    def test_make_vec_gives_each_envs_current_mask_across_auto_resets(self):
        env = rlrun.make_vec("GridWorld-v0", 3)
        obs, infos = env.reset(seed=5)
        self.assertEqual(infos["action_mask"].shape, (3, 4))
        self.assertEqual(infos["action_mask"].dtype, np.int8)
        self.assertNotIn("action_mask.0", infos)
        rng = np.random.default_rng(0)
        resets = 0
        for _ in range(400):
            masks = env.action_masks()
            for i in range(3):
                np.testing.assert_array_equal(masks[i], grid_mask(*obs[i]))
            # A legal move for every env, from its mask.
            actions = np.array([rng.choice(np.flatnonzero(m)) for m in masks])
            obs, _, terminated, truncated, infos = env.step(actions)
            done = terminated | truncated
            resets += int(done.sum())
            # After an auto-reset the mask is the new first state's, the ending one's is in
            # final_info.
            np.testing.assert_array_equal(infos["action_mask"].astype(bool), env.action_masks())
            if done.any():
                self.assertIn("action_mask", infos["final_info"])
        self.assertGreater(resets, 0)
        env.close()

