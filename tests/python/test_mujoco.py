"""The MuJoCo tasks from Python: Gymnasium's MujocoEnv state access (set_state, data.qpos /
data.qvel, init_qpos, dt, frame_skip, state_vector) on env.unwrapped, and `rlrun eval
--trajectory` rows that replay exactly through it (set_state(qpos, qvel, qacc_warmstart), then
step(action)).
Skipped when this build has no MuJoCo component."""

import csv
import os
import unittest

import numpy as np

import rlrun
from rlrun_testing import TempDirMixin, run_rlrun


def have_mujoco():
    try:
        rlrun.make("HalfCheetah-v4").close()
        return True
    except Exception:  # the component's placeholder entry says how to get it
        return False


@unittest.skipUnless(have_mujoco(), "this build has no MuJoCo envs (RLRUN_WITH_MUJOCO)")
class MujocoStateTest(TempDirMixin, unittest.TestCase):
    def test_state_access(self):
        env = rlrun.make("HalfCheetah-v4")
        env.reset(seed=3)
        u = env.unwrapped
        self.assertEqual(u.data.qpos.shape, (9,))
        self.assertEqual(u.data.qvel.dtype, np.float64)
        self.assertEqual(u.frame_skip, 5)
        self.assertAlmostEqual(u.dt, 0.05)
        np.testing.assert_array_equal(u.state_vector(), np.concatenate([u.data.qpos, u.data.qvel]))
        qpos, qvel = u.init_qpos.copy(), u.init_qvel.copy()
        qpos[2], qvel[0] = 0.25, 1.5
        u.set_state(qpos, qvel)
        np.testing.assert_array_equal(u.data.qpos, qpos)
        np.testing.assert_array_equal(u.data.qvel, qvel)
        obs = u._get_obs()
        self.assertEqual(obs.dtype, np.float32)
        np.testing.assert_array_equal(obs, np.concatenate([qpos[1:], qvel]).astype(np.float32))
        with self.assertRaises(ValueError):
            u.set_state(qpos[:4], qvel)
        # Envs without a simulator state have none of the attributes (hasattr is False).
        self.assertFalse(hasattr(rlrun.make("CartPole-v1").unwrapped, "set_state"))

    def test_trajectory_rows_replay(self):
        path = os.path.join(self.tmp, "cheetah.csv")
        run_rlrun("eval", "--env", "HalfCheetah-v4", "--policy", "random", "--episodes", "1",
                  "--seed", "4", "--trajectory", path)
        with open(path, newline="") as f:
            reader = csv.reader(f)
            header = next(reader)
            rows = [cells for cells, _ in zip(reader, range(60))]
        cols = lambda prefix: [i for i, h in enumerate(header) if h.startswith(prefix)]
        obs_c, qpos_c, qvel_c, act_c = cols("obs_"), cols("qpos_"), cols("qvel_"), cols("action_")
        warm_c = cols("qacc_warmstart_")
        self.assertEqual((len(obs_c), len(qpos_c), len(qvel_c), len(warm_c), len(act_c)),
                         (17, 9, 9, 9, 6))
        env = rlrun.make("HalfCheetah-v4")
        env.reset(seed=0)
        for row, following in zip(rows, rows[1:]):
            env.unwrapped.set_state(np.array([float(row[i]) for i in qpos_c]),
                                    np.array([float(row[i]) for i in qvel_c]),
                                    np.array([float(row[i]) for i in warm_c]))
            np.testing.assert_array_equal(
                env.unwrapped._get_obs(), np.array([np.float32(row[i]) for i in obs_c]))
            action = np.array([np.float32(row[i]) for i in act_c], dtype=np.float32)
            obs, reward, terminated, truncated, _ = env.step(action)
            self.assertEqual(reward, float(row[-3]))  # Python's repr: the exact double
            np.testing.assert_array_equal(obs, np.array([np.float32(following[i]) for i in obs_c]))


if __name__ == "__main__":
    unittest.main()
