"""rlrun.make_vec: Gymnasium 1.x VectorEnv shapes, seeding (env i with seed + i) and same-step
auto-reset (final_obs), checked against single rlrun.make envs stepped alongside."""

import unittest

import numpy as np

import rlrun


class MakeVec(unittest.TestCase):
    def test_shapes_and_spaces(self):
        envs = rlrun.make_vec("CartPole-v1", 4)
        self.assertEqual(envs.num_envs, 4)
        self.assertEqual(envs.single_observation_space.shape, (4,))
        self.assertEqual(envs.observation_space.shape, (4, 4))
        self.assertEqual(type(envs.single_action_space).__name__, "Discrete")
        self.assertEqual(envs.action_space.shape, (4,))
        obs, infos = envs.reset(seed=0)
        self.assertEqual(obs.shape, (4, 4))
        self.assertEqual(obs.dtype, np.float32)
        self.assertIsInstance(infos, dict)
        obs, rewards, terminations, truncations, infos = envs.step(np.array([0, 1, 0, 1]))
        self.assertEqual(obs.shape, (4, 4))
        self.assertEqual(rewards.shape, (4,))
        self.assertEqual(terminations.dtype, np.bool_)
        self.assertEqual(truncations.dtype, np.bool_)
        self.assertTrue(envs.observation_space.contains(obs))
        self.assertIn(str(envs.metadata["autoreset_mode"]).split(".")[-1], ("SAME_STEP", "SameStep"))
        pendulum = rlrun.make_vec("Pendulum-v1", 3)
        self.assertEqual(pendulum.action_space.shape, (3, 1))
        pendulum.reset(seed=1)
        obs, *_ = pendulum.step(np.zeros((3, 1), dtype=np.float32))
        self.assertEqual(obs.shape, (3, 3))
        with self.assertRaises(ValueError):
            pendulum.step(np.zeros((2, 1), dtype=np.float32))
        dict_envs = rlrun.make_vec("DictReach-v0", 2)
        obs, _ = dict_envs.reset(seed=0)
        self.assertIsInstance(obs, dict)
        for key, space in dict_envs.single_observation_space.spaces.items():
            self.assertEqual(obs[key].shape, (2,) + space.shape)

    def test_seeding_and_same_step_autoreset_match_single_envs(self):
        n, seed = 3, 42
        envs = rlrun.make_vec("CartPole-v1", n)
        singles = [rlrun.make("CartPole-v1") for _ in range(n)]
        obs, _ = envs.reset(seed=seed)
        for i, env in enumerate(singles):
            first, _ = env.reset(seed=seed + i)
            np.testing.assert_array_equal(obs[i], first)
        rng = np.random.default_rng(0)
        ended = 0
        for _ in range(300):
            actions = rng.integers(0, 2, size=n)
            obs, rewards, terms, truncs, infos = envs.step(actions)
            for i, env in enumerate(singles):
                o, r, te, tr, _ = env.step(int(actions[i]))
                self.assertEqual(rewards[i], r)
                self.assertEqual(terms[i], te)
                self.assertEqual(truncs[i], tr)
                if te or tr:
                    ended += 1
                    self.assertTrue(infos["_final_obs"][i])
                    np.testing.assert_array_equal(infos["final_obs"][i], o)
                    o, _ = env.reset()  # same-step auto-reset: obs is the next episode's first
                elif "_final_obs" in infos:
                    self.assertFalse(infos["_final_obs"][i])
                np.testing.assert_array_equal(obs[i], o)
                if "final_obs" in infos:  # Gymnasium's layout: one array over all envs
                    self.assertEqual(infos["final_obs"].shape, (n, 4))
                    self.assertEqual(infos["final_obs"].dtype, np.float32)
        self.assertGreater(ended, 3)

    def test_info_arrays_with_masks(self):
        envs = rlrun.make_vec("DictReach-v0", 2, max_episode_steps=2)
        envs.reset(seed=0)
        seen_final = False
        for _ in range(4):
            _, _, terms, truncs, infos = envs.step(envs.action_space.sample())
            for key, value in infos.items():
                if key.startswith("_") or key in ("final_obs", "final_info"):
                    continue
                self.assertEqual(value.shape, (2,))
                self.assertEqual(infos["_" + key].dtype, np.bool_)
            if "final_obs" in infos:
                seen_final = True
                done = terms | truncs
                np.testing.assert_array_equal(infos["_final_obs"], done)
                for key, space in envs.single_observation_space.spaces.items():
                    self.assertEqual(infos["final_obs"][key].shape, (2,) + space.shape)
                    np.testing.assert_array_equal(infos["final_obs"]["_" + key], done)
                self.assertIsInstance(infos["final_info"], dict)
        self.assertTrue(seen_final)

    def test_time_limit_truncates_and_kwargs(self):
        envs = rlrun.make_vec("Pendulum-v1", 2, max_episode_steps=3)
        envs.reset(seed=0)
        flags = [envs.step(np.zeros((2, 1), dtype=np.float32))[3] for _ in range(3)]
        self.assertEqual([f.tolist() for f in flags], [[False, False], [False, False], [True, True]])
        with self.assertRaises(rlrun.ConfigError):
            rlrun.make_vec("Pendulum-v1", 2, no_such_parameter=1)
        with self.assertRaises(ValueError):
            rlrun.make_vec("Pendulum-v1", 0)

    def test_gymnasium_vector_env_when_importable(self):
        if not rlrun.HAVE_GYMNASIUM:
            self.skipTest("gymnasium is not importable")
        import gymnasium

        envs = rlrun.make_vec("CartPole-v1", 2)
        self.assertIsInstance(envs, gymnasium.vector.VectorEnv)
        self.assertIsInstance(envs.single_observation_space, gymnasium.spaces.Box)
        self.assertIsInstance(envs.action_space, gymnasium.spaces.MultiDiscrete)
        envs.close()


if __name__ == "__main__":
    unittest.main()
