"""rlrun.make: rlrun's envs pass a Gymnasium-style env checker (written here, after
gymnasium/utils/env_checker.py and passive_env_checker.py: signatures, spaces, dtypes,
observations in their space, seeding determinism) and produce the same trajectories as the
C++ envs for the same seed (`rlrun eval --policy random --trajectory`)."""

import inspect
import os
import sys
import unittest

import numpy as np

import rlrun
from rlrun_testing import TempDirMixin, read_trajectory, run_rlrun

SPACE_TYPES = ("Box", "Discrete", "MultiDiscrete", "MultiBinary", "Dict")
FAST_ENVS = ["CartPole-v1", "Pendulum-v1", "MountainCar-v0", "MountainCarContinuous-v0",
             "Acrobot-v1", "DictReach-v0"]


def equal(a, b):
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(equal(a[k], b[k]) for k in a)
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and np.array_equal(a, b)


def check_obs(test, obs, space, where):
    kind = type(space).__name__
    if kind == "Dict":
        test.assertIsInstance(obs, dict, where)
        test.assertEqual(list(obs), list(space.spaces), where)
        for k, s in space.spaces.items():
            check_obs(test, obs[k], s, f"{where}[{k!r}]")
        return
    if kind == "Discrete":
        test.assertIsInstance(obs, (int, np.integer), where)
    else:
        test.assertIsInstance(obs, np.ndarray, where)
        test.assertEqual(obs.shape, space.shape, where)
        test.assertEqual(obs.dtype, space.dtype, where)
    test.assertTrue(space.contains(obs), f"{where}: {obs} not in {space}")


def check_space(test, space, where):
    kind = type(space).__name__
    test.assertIn(kind, SPACE_TYPES, where)
    if kind == "Box":
        test.assertEqual(space.dtype, np.float32, where)
        test.assertEqual(space.low.shape, space.shape, where)
        test.assertEqual(space.high.shape, space.shape, where)
        test.assertTrue(np.all(space.low <= space.high), where)
    if kind == "Discrete":
        test.assertGreater(int(space.n), 0, where)
    if kind == "Dict":
        for k, s in space.spaces.items():
            check_space(test, s, f"{where}[{k!r}]")
    if rlrun.HAVE_GYMNASIUM:
        import gymnasium

        test.assertIsInstance(space, gymnasium.spaces.Space, where)


def check_env(test, env, steps=50):
    """A Gymnasium-style env checker: what gymnasium.utils.env_checker.check_env asserts."""
    name = repr(env)
    check_space(test, env.observation_space, name + " observation_space")
    check_space(test, env.action_space, name + " action_space")
    reset = inspect.signature(env.reset).parameters
    test.assertIn("seed", reset)
    test.assertIn("options", reset)
    test.assertEqual(len(inspect.signature(env.step).parameters), 1)
    result = env.reset(seed=123)
    test.assertIsInstance(result, tuple)
    test.assertEqual(len(result), 2)
    obs, info = result
    check_obs(test, obs, env.observation_space, name + " reset obs")
    test.assertIsInstance(info, dict)
    test.assertIsNotNone(env.unwrapped.np_random)  # super().reset(seed=...) ran
    # Same seed, same first observation; seeding the action space, same trajectory.
    obs2, _ = env.reset(seed=123)
    test.assertTrue(equal(obs, obs2), name + ": reset(seed=123) twice differs")
    env.action_space.seed(5)
    actions = [env.action_space.sample() for _ in range(steps)]
    trajectories = []
    for _ in range(2):
        obs, _ = env.reset(seed=123)
        seen = [obs]
        for a in actions:
            result = env.step(a)
            test.assertEqual(len(result), 5)
            obs, reward, terminated, truncated, info = result
            check_obs(test, obs, env.observation_space, name + " step obs")
            test.assertIsInstance(reward, float)
            test.assertIsInstance(terminated, bool)
            test.assertIsInstance(truncated, bool)
            test.assertIsInstance(info, dict)
            for k, v in info.items():
                test.assertIsInstance(k, str)
                if k == "action_mask":  # sb3-contrib's form: one 0/1 int8 entry per action
                    test.assertEqual(np.asarray(v).dtype, np.int8)
                    test.assertTrue(set(np.asarray(v).tolist()) <= {0, 1})
                else:
                    test.assertIsInstance(v, float)
            seen.append(obs)
            if terminated or truncated:
                obs, _ = env.reset()
                seen.append(obs)
        trajectories.append(seen)
    test.assertTrue(all(equal(a, b) for a, b in zip(*trajectories)), name + ": not deterministic")
    other, _ = env.reset(seed=124)
    test.assertEqual(type(other), type(trajectories[0][0]))
    test.assertIn("render_modes", env.metadata)
    test.assertIs(env.unwrapped, env)


class MakeCheck(unittest.TestCase):
    def test_fast_envs_pass_the_checker(self):
        for env_id in FAST_ENVS:
            with self.subTest(env=env_id):
                env = rlrun.make(env_id)
                check_env(self, env)
                env.close()
                env.close()  # closing twice is allowed (Gymnasium's checker asks for it)

    def test_gripper_passes_the_checker(self):
        env = rlrun.make("GripperLift-v0")
        check_env(self, env, steps=10)
        env.close()

    def test_every_registered_env_is_listed(self):
        ids = rlrun.list_envs()
        for env_id in FAST_ENVS + ["TrafficSignal-v0", "GripperLift-v0"]:
            self.assertIn(env_id, ids)

    def test_spaces_and_dtypes(self):
        env = rlrun.make("CartPole-v1")
        self.assertEqual(type(env.action_space).__name__, "Discrete")
        self.assertEqual(env.action_space.n, 2)
        self.assertEqual(env.observation_space.shape, (4,))
        self.assertEqual(env.observation_space.dtype, np.float32)
        obs, _ = env.reset(seed=1)
        for action in (1, np.int64(0), np.array(1), np.array([0])):
            obs, *_ = env.step(action)
        self.assertEqual(obs.dtype, np.float32)
        with self.assertRaisesRegex(ValueError, "not in Discrete"):
            env.step(2)
        pendulum = rlrun.make("Pendulum-v1")
        np.testing.assert_array_equal(pendulum.action_space.low, [-2.0])
        pendulum.reset(seed=0)
        pendulum.step(np.array([0.5], dtype=np.float32))
        pendulum.step([1.0])

    def test_time_limit_as_gymnasium_make(self):
        env = rlrun.make("Pendulum-v1")
        self.assertEqual(env.max_episode_steps, 200)
        env.reset(seed=0)
        flags = [env.step([0.0])[3] for _ in range(200)]
        self.assertEqual(flags, [False] * 199 + [True])
        short = rlrun.make("Pendulum-v1", max_episode_steps=5)
        short.reset(seed=0)
        self.assertEqual([short.step([0.0])[3] for _ in range(5)], [False] * 4 + [True])
        self.assertEqual(short.spec.id, "Pendulum-v1")
        self.assertEqual(short.spec.max_episode_steps, 5)
        again = short.spec.make()
        self.assertEqual(again.observation_space, short.observation_space)

    def test_kwargs_parsed_strictly(self):
        with self.assertRaises(rlrun.ConfigError) as caught:
            rlrun.make("CartPole-v2")
        self.assertIn("CartPole-v1", str(caught.exception))  # the closest registered id
        self.assertIsInstance(caught.exception, ValueError)
        with self.assertRaisesRegex(rlrun.ConfigError, "rlrun.make\\('Pendulum-v1'\\) kwargs:.*"):
            rlrun.make("Pendulum-v1", gravty=9.81)
        with self.assertRaises(ValueError):
            rlrun.make("Pendulum-v1", g="heavy")

    def test_load_plugin_errors(self):
        with self.assertRaisesRegex(rlrun.UsageError, "plugin 'nope/x.so' not found"):
            rlrun.load_plugin("nope/x.so")

    def test_render_rgb_array(self):
        env = rlrun.make("CartPole-v1", render_mode="rgb_array")
        self.assertIn("rgb_array", env.metadata["render_modes"])
        self.assertGreater(env.metadata["render_fps"], 0)
        env.reset(seed=0)
        frame = env.render()
        self.assertEqual(frame.dtype, np.uint8)
        self.assertEqual(frame.ndim, 3)
        self.assertEqual(frame.shape[2], 3)
        self.assertGreater(frame.shape[0], 100)
        self.assertGreater(len(np.unique(frame.reshape(-1, 3), axis=0)), 2)  # something drawn

    def test_gymnasium_classes_when_importable(self):
        env = rlrun.make("CartPole-v1")
        if not rlrun.HAVE_GYMNASIUM:
            self.assertTrue(hasattr(env.action_space, "sample"))
            self.skipTest("gymnasium is not importable: the fallback spaces were checked")
        import gymnasium

        self.assertIsInstance(env, gymnasium.Env)
        self.assertIsInstance(env.observation_space, gymnasium.spaces.Box)
        from gymnasium.utils.env_checker import check_env as gymnasium_check_env

        gymnasium_check_env(env, skip_render_check=False)


class GoalEnvs(unittest.TestCase):
    """Goal-conditioned envs have GoalEnv.compute_reward for single goals and batches (SB3's
    HerReplayBuffer calls it with (n, goal_dim) arrays), equal to the step reward."""

    def test_compute_reward_matches_the_step_reward(self):
        env = rlrun.make("BitFlippingEnv-v0", n_bits=4)
        obs, _ = env.reset(seed=3)
        achieved, desired = [], []
        for t in range(4):
            obs, reward, terminated, truncated, info = env.step(t)
            self.assertEqual(env.compute_reward(obs["achieved_goal"], obs["desired_goal"], info), reward)
            achieved.append(obs["achieved_goal"])
            desired.append(obs["desired_goal"])
            if terminated or truncated:
                break
        batch = env.compute_reward(np.stack(achieved), np.stack(desired), None)
        self.assertEqual(batch.shape, (len(achieved),))
        self.assertEqual(env.compute_reward(np.ones(4), np.ones(4), None), 0.0)
        with self.assertRaises(ValueError):
            env.compute_reward(np.ones(4), np.ones(3), None)
        with self.assertRaises(AttributeError):
            rlrun.make("CartPole-v1").compute_reward(np.zeros(1), np.zeros(1), None)


# Every env rlrun.make builds without a simulator or named code (TrafficSignal-v0 and
# TrafficNetwork-v0 need SUMO; python:/gymnasium: name a module).
def makeable_envs():
    return [i for i in rlrun.list_envs() if not i.startswith("Traffic") and not i.endswith(":")]


GOAL_KEYS = {"observation", "achieved_goal", "desired_goal"}


class Sb3CheckEnv(unittest.TestCase):
    """SB3's check_env (stable_baselines3/common/env_checker.py) takes any env with a
    ``compute_reward`` attribute for a GoalEnv (``_is_goal_env``: hasattr on env.unwrapped) and
    then requires a Dict observation with observation/achieved_goal/desired_goal and rewards
    equal to compute_reward's. Issue 41: every rlrun.make env had compute_reward, so SB3's
    check_env failed on all but the goal envs."""

    def test_compute_reward_only_on_goal_envs(self):
        # The check SB3's check_env makes, mirrored (it runs without SB3 and Gymnasium).
        goal_envs = []
        for env_id in makeable_envs():
            with self.subTest(env=env_id):
                env = rlrun.make(env_id)
                space = env.observation_space
                goal_obs = type(space).__name__ == "Dict" and GOAL_KEYS <= set(space.spaces)
                self.assertEqual(hasattr(env.unwrapped, "compute_reward"), goal_obs)
                if goal_obs:
                    goal_envs.append(env_id)
                env.close()
        self.assertEqual(sorted(goal_envs), ["BitFlippingEnv-v0", "GripperPickAndPlace-v0",
                                             "GripperPush-v0", "GripperReach-v0"])

    def test_goal_env_rewards_are_compute_reward(self):
        # SB3's _check_goal_env_compute_reward: the step reward equals compute_reward of the
        # step's goals, and a batch of goals gives a batch of rewards.
        for env_id in ("BitFlippingEnv-v0", "GripperReach-v0"):
            with self.subTest(env=env_id):
                env = rlrun.make(env_id)
                env.reset(seed=1)
                env.action_space.seed(1)
                obs, reward, _, _, info = env.step(env.action_space.sample())
                self.assertEqual(env.compute_reward(obs["achieved_goal"], obs["desired_goal"], info), reward)
                batch = env.compute_reward(np.stack([obs["achieved_goal"]] * 2),
                                           np.stack([obs["desired_goal"]] * 2), [info] * 2)
                self.assertEqual(batch.shape, (2,))
                self.assertEqual(float(batch[0]), reward)

    def test_stable_baselines3_check_env(self):
        try:
            from stable_baselines3.common.env_checker import check_env as sb3_check_env
        except ImportError:
            self.skipTest("stable_baselines3 is not importable")
        import warnings

        for env_id in makeable_envs():
            with self.subTest(env=env_id):
                env = rlrun.make(env_id)
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")  # SB3's advice (e.g. normalise Box actions)
                    sb3_check_env(env)
                env.close()


class SameTrajectoriesAsTheCppEnvs(TempDirMixin, unittest.TestCase):
    def replay(self, env_id, episodes=2, seed=9, **kwargs):
        path = os.path.join(self.tmp, env_id + ".csv")
        run_rlrun("eval", "--policy", "random", "--env", env_id, "--episodes", episodes,
                  "--seed", seed, "--trajectory", path)
        rows = read_trajectory(path)
        env = rlrun.make(env_id, **kwargs)
        episode = -1
        flat = rlrun._spaces.to_flat
        for row in rows:
            if row["episode"] != episode:
                obs, _ = env.reset(seed=seed if episode < 0 else None)
                episode = row["episode"]
            np.testing.assert_array_equal(flat(env.observation_space, obs, "obs"), row["obs"],
                                          err_msg=f"{env_id} episode {episode} step {row['step']}")
            action = rlrun._spaces.from_flat(env.action_space, row["action"])
            obs, reward, terminated, truncated, _ = env.step(action)
            self.assertEqual(reward, row["reward"])
            self.assertEqual(terminated, row["terminated"])
        self.assertTrue(terminated or truncated)
        return rows

    def test_classic_control(self):
        for env_id in ["CartPole-v1", "Pendulum-v1", "Acrobot-v1", "MountainCarContinuous-v0"]:
            with self.subTest(env=env_id):
                self.replay(env_id)

    def test_dict_observations(self):
        self.replay("DictReach-v0")

    def test_traffic_signal_on_sumo(self):
        # Ten simulated minutes of the SUMO task (SUMO seeded from the reset seed).
        config = os.path.join(self.tmp, "traffic.yaml")
        with open(config, "w") as f:
            f.write("env: {id: TrafficSignal-v0, kwargs: {num_seconds: 600}}\nalgo: {id: DQN}\n")
        path = os.path.join(self.tmp, "traffic.csv")
        run_rlrun("eval", "--policy", "random", "--config", config, "--episodes", 1, "--seed", 3,
                  "--trajectory", path)
        rows = read_trajectory(path)
        self.assertEqual(len(rows), 120)  # 600 s in steps of delta_time 5 s
        env = rlrun.make("TrafficSignal-v0", num_seconds=600)
        check_env(self, env, steps=5)
        obs, _ = env.reset(seed=3)
        for row in rows:
            np.testing.assert_array_equal(obs, row["obs"], err_msg=f"step {row['step']}")
            obs, reward, terminated, truncated, info = env.step(int(row["action"][0]))
            self.assertEqual(reward, row["reward"])
        self.assertTrue(terminated or truncated)
        self.assertIn("total_queue_length", info)  # the env's metrics, as numbers
        env.close()


if __name__ == "__main__":
    unittest.main()


class PythonEnvsThroughRlrun(unittest.TestCase):
    """rlrun.make of a python: id: the env runs in a worker process of this very interpreter
    (import rlrun sets RLRUN_PYTHON to sys.executable), behind rlrun's Gymnasium API."""

    @classmethod
    def setUpClass(cls):
        here = os.path.dirname(os.path.abspath(__file__))
        sys.path.insert(0, os.path.join(here, "..", "python_envs"))
        os.environ["PYTHONPATH"] = os.path.join(here, "..", "python_envs") + os.pathsep + \
            os.environ.get("PYTHONPATH", "")

    def test_python_env_passes_the_checker_and_matches_the_class(self):
        from rlrun_test_envs.cartpole import CartPolePort
        env = rlrun.make("python:rlrun_test_envs.cartpole:CartPolePort")
        check_env(self, env)
        # The same seed and actions give what the class itself gives, step for step.
        direct = CartPolePort()
        obs, _ = env.reset(seed=5)
        expected, _ = direct.reset(seed=5)
        np.testing.assert_array_equal(obs, expected)
        for t in range(30):
            obs, reward, terminated, truncated, _ = env.step(t % 2)
            expected, r2, te2, _, _ = direct.step(t % 2)
            np.testing.assert_array_equal(obs, expected)
            self.assertEqual((reward, terminated), (r2, te2))
            if terminated:
                break
        env.close()
        self.assertEqual(os.environ["RLRUN_PYTHON"], sys.executable)
