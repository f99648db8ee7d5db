"""rlrun.load reads the model files the real Stable-Baselines3 2.4.1 saved (tests/data/sb3/,
made by scripts/data/make_sb3_models.sh) and predicts SB3's actions on SB3's observations."""

import os
import unittest

import numpy as np

import rlrun

SB3_DIR = os.path.join(os.environ.get("RLRUN_SOURCE_DIR", "../.."), "tests", "data", "sb3")


class Sb3ModelFiles(unittest.TestCase):
    def check(self, case, env_id):
        model = rlrun.load(os.path.join(SB3_DIR, case, "model.zip"), env=env_id)
        observations = np.load(os.path.join(SB3_DIR, case, "observations.npy"))
        expected = np.load(os.path.join(SB3_DIR, case, "actions.npy"))
        actions, state = model.predict(observations, deterministic=True)
        self.assertIsNone(state)
        self.assertEqual(actions.dtype, expected.dtype)
        self.assertEqual(actions.shape, expected.shape)
        if expected.dtype == np.int64:
            np.testing.assert_array_equal(actions, expected)
        else:
            np.testing.assert_allclose(actions, expected, atol=1e-5, rtol=0)
        return model

    def test_discrete_and_box_actions(self):
        self.assertEqual(self.check("ppo_cartpole", "CartPole-v1").algorithm, "PPO")
        self.assertEqual(self.check("dqn_cartpole", "CartPole-v1").algorithm, "DQN")
        self.assertEqual(self.check("sac_pendulum", "Pendulum-v1").algorithm, "SAC")
        self.assertEqual(self.check("td3_pendulum", "Pendulum-v1").algorithm, "TD3")

    def test_multi_input_policy(self):
        # A Dict-observation env defined in the fixture script: predict needs only the spaces
        # the file records, so the env need not exist in rlrun.
        model = rlrun.load(os.path.join(SB3_DIR, "ppo_multi_input", "model.zip"), env="DictObsEnv")
        observations = np.load(os.path.join(SB3_DIR, "ppo_multi_input", "observations.npz"))
        expected = np.load(os.path.join(SB3_DIR, "ppo_multi_input", "actions.npy"))
        actions, _ = model.predict({k: observations[k] for k in ("a", "b")}, deterministic=True)
        np.testing.assert_array_equal(actions, expected)

    def test_multi_input_policy_over_an_image_and_a_vector(self):
        # SB3's CombinedExtractor: a NatureCNN (cnn_output_dim 16) for the image key, which the
        # file keeps channels first (VecTransposeImage) and rlrun reads as the env's HWC; the
        # extractor under SB3's three names. GripperLift-v0's obs_type both has these spaces.
        case = "ppo_multi_input_gripper_both"
        model = rlrun.load(os.path.join(SB3_DIR, case, "model.zip"),
                           ["env.kwargs.obs_type=both", "env.kwargs.image_size=36"],
                           env="GripperLift-v0")
        self.assertEqual(model.observation_space["pixels"].shape, (36, 36, 3))
        tensors = model._core.tensors
        self.assertEqual(tensors["features_extractor.extractors.pixels.linear.0.weight"].shape,
                         (16, 64))
        self.assertNotIn("pi_features_extractor.extractors.pixels.cnn.0.weight", tensors)
        observations = np.load(os.path.join(SB3_DIR, case, "observations.npz"))
        expected = np.load(os.path.join(SB3_DIR, case, "actions.npy"))
        actions, _ = model.predict({k: observations[k] for k in ("pixels", "state")},
                                   deterministic=True)
        np.testing.assert_allclose(actions, expected, atol=1e-5, rtol=0)

    def test_off_policy_cnn_policies(self):
        # DQN's and SAC's CnnPolicy: an extractor per network. Their spaces are pixel
        # CartPole's / Pendulum's; predict needs only the spaces the file records.
        for case, env_id in (("dqn_cnn_cartpole_pixels", "CartPole-v1"),
                             ("sac_cnn_pendulum_pixels", "Pendulum-v1")):
            with self.subTest(case=case):
                model = self.check(case, env_id)
                self.assertEqual(model.observation_space.shape, (36, 36, 1))

    def test_vec_normalize_beside_the_model(self):
        # predict() takes the env's raw observations and normalises them with the frozen
        # statistics of vecnormalize.pkl, as rl_zoo3.enjoy plays such a model.
        self.check("ppo_pendulum_vecnormalize", "Pendulum-v1")

    def test_without_env_says_so(self):
        with self.assertRaises(rlrun.RuntimeFailure) as raised:
            rlrun.load(os.path.join(SB3_DIR, "ppo_cartpole", "model.zip"))
        self.assertIn("--env", str(raised.exception))

    def test_code_in_a_pickle_is_refused(self):
        marker = "/tmp/rlrun_pwned"
        if os.path.exists(marker):
            os.remove(marker)
        for case in ("evil_os_system", "evil_torch"):
            with self.assertRaises(rlrun.RuntimeFailure) as raised:
                rlrun.load(os.path.join(SB3_DIR, case, "model.zip"), env="CartPole-v1")
            self.assertIn("posix.system", str(raised.exception))
        self.assertFalse(os.path.exists(marker))


if __name__ == "__main__":
    unittest.main()
