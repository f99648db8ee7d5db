"""SB3's training API (python/rlrun/_algorithms.py): rlrun.PPO(policy, env, **kwargs).learn()
continuing in-process, SB3-style callbacks, save/load, predict, get_env, evaluate_policy and the
policy's tensors; live env objects stepped in this interpreter. With GYMNASIUM_SRC set (the
Gymnasium source tree, as for test_sb3_export.py), SB3's README quick start runs on a real
gymnasium.Env with only its import changed."""

import contextlib
import io
import os
import subprocess
import sys
import textwrap
import unittest

import numpy as np

import rlrun
from rlrun._spaces import Box, Discrete
from rlrun.callbacks import BaseCallback
from rlrun_testing import TempDirMixin


class Corridor:
    """A Gymnasium-style env of this interpreter: walk right along 5 cells (reward 1 at the
    end, -0.1 a step), 50 steps at most. Counts its own calls."""

    def __init__(self):
        self.observation_space = Box(0.0, 1.0, (5,), np.float32)
        self.action_space = Discrete(2)
        self.pos, self.t, self.steps, self.resets, self.seeds = 0, 0, 0, 0, []
        self.actions = []

    def _obs(self):
        obs = np.zeros(5, np.float32)
        obs[self.pos] = 1
        return obs

    def reset(self, seed=None, options=None):
        self.pos, self.t = 0, 0
        self.resets += 1
        self.seeds.append(seed)
        return self._obs(), {}

    def step(self, action):
        self.steps += 1
        self.actions.append(int(action))
        self.t += 1
        self.pos = max(0, min(4, self.pos + (1 if int(action) == 1 else -1)))
        done = self.pos == 4
        return self._obs(), (1.0 if done else -0.1), done, self.t >= 50, {"pos": float(self.pos)}


class Recorder(BaseCallback):
    def __init__(self, stop_after=None):
        super().__init__()
        self.events, self.stop_after, self.rewards = [], stop_after, []

    def _on_training_start(self):
        self.events.append("start")

    def _on_rollout_start(self):
        self.events.append("rollout_start")

    def _on_step(self):
        self.rewards.append(float(self.locals["rewards"][0]))
        return self.stop_after is None or self.n_calls < self.stop_after

    def _on_rollout_end(self):
        self.events.append("rollout_end")

    def _on_training_end(self):
        self.events.append("end")


class TrainingApi(TempDirMixin, unittest.TestCase):
    def test_live_env_object_is_stepped_here_and_learns(self):
        env = Corridor()
        model = rlrun.PPO("MlpPolicy", env, n_steps=128, batch_size=64, learning_rate=3e-3,
                          seed=2, out_dir=os.path.join(self.tmp, "live"))
        self.assertEqual(model.num_timesteps, 0)
        recorder = Recorder()
        model.learn(3000, callback=recorder)
        # Every env step of training was this object's step, in this interpreter.
        self.assertEqual(env.steps, model.num_timesteps)
        self.assertEqual(model.num_timesteps, 3072)  # 24 rollouts of 128
        self.assertEqual(recorder.n_calls, 3072)
        self.assertEqual(recorder.events[:2], ["start", "rollout_start"])
        self.assertEqual(recorder.events.count("rollout_end"), 24)
        self.assertEqual(recorder.events[-1], "end")
        self.assertEqual(recorder.locals["new_obs"].shape, (1, 5))
        self.assertEqual(recorder.locals["infos"][0]["pos"], env.pos)
        self.assertIn(1.0, recorder.rewards)
        self.assertEqual(env.seeds[0], 2)  # SB3: env i is seeded seed + i at the first reset
        mean, std = rlrun.evaluate_policy(model, env, n_eval_episodes=4)
        self.assertAlmostEqual(mean, 0.7, places=5)  # the shortest way: 3 x -0.1, then +1
        self.assertEqual(std, 0.0)

    def test_locals_actions_rollout_end_and_log_interval(self):
        # locals["actions"] are the actions the env was stepped with; _on_rollout_end once per
        # rollout; log_interval as SB3's (A2C's default 100 iterations a progress.csv row).
        env = Corridor()

        class Actions(BaseCallback):
            def __init__(self):
                super().__init__()
                self.actions, self.rollout_ends = [], []

            def _on_step(self):
                self.actions.append(self.locals["actions"].copy())
                # SB3's DummyVecEnv sets it at every step.
                assert self.locals["infos"][0]["TimeLimit.truncated"] in (True, False)
                return True

            def _on_rollout_end(self):
                self.rollout_ends.append(self.num_timesteps)

        model = rlrun.A2C("MlpPolicy", env, n_steps=5, seed=4, out_dir=os.path.join(self.tmp, "a"))
        seen = Actions()
        model.learn(1000, callback=seen)
        self.assertEqual(seen.actions[0].shape, (1,))
        self.assertEqual(seen.actions[0].dtype, np.int64)
        self.assertEqual([int(a[0]) for a in seen.actions], env.actions)
        self.assertEqual(seen.rollout_ends, list(range(5, 1001, 5)))
        def rows():
            with open(os.path.join(model.run_dir, "progress.csv")) as f:
                return f.read().splitlines()

        self.assertEqual(len(rows()), 1 + 2)  # a header, iterations 100 and 200
        model.learn(500, log_interval=20)
        self.assertEqual(len(rows()), 1 + 2 + 5)

        box = rlrun.SAC("MlpPolicy", "Pendulum-v1", learning_starts=50, seed=1,
                        out_dir=os.path.join(self.tmp, "b"))
        actions = []
        box.learn(60, callback=lambda l, g: actions.append(l["actions"].copy()) or True)
        self.assertEqual(actions[0].shape, (1, 1))
        self.assertTrue(all(-2.0 <= a[0, 0] <= 2.0 for a in actions))  # the env's own bounds

    def test_vectorized_env_objects_and_progress_bar(self):
        # A DummyVecEnv of live envs (SB3's make_vec_env gives one): its envs are the n_envs.
        envs = [Corridor(), Corridor(), Corridor()]
        vec = rlrun.DummyVecEnv(envs)
        model = rlrun.PPO("MlpPolicy", vec, n_steps=32, batch_size=48, seed=7,
                          out_dir=os.path.join(self.tmp, "vec"))
        self.assertIs(model.get_env(), vec)
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            model.learn(192, progress_bar=True)
        self.assertEqual(model.num_timesteps, 192)
        self.assertEqual([e.steps for e in envs], [64, 64, 64])
        self.assertEqual(sorted(e.seeds[0] for e in envs), [7, 8, 9])
        self.assertIn("192/192", err.getvalue())  # tqdm's bar, or rlrun's line without it

        # SB3's make_vec_env gives its envs render_mode="rgb_array"; one whose render() fails
        # (Gymnasium's CartPole without pygame) still trains: it is taken as not rendering.
        class NoPygame(Corridor):
            render_mode = "rgb_array"

            def render(self):
                raise ImportError("pygame is not installed")

        broken = rlrun.PPO("MlpPolicy", rlrun.DummyVecEnv([NoPygame(), NoPygame()]), n_steps=16,
                           batch_size=32, out_dir=os.path.join(self.tmp, "norender"))
        with contextlib.redirect_stderr(io.StringIO()):
            broken.learn(64)
        self.assertEqual(broken.num_timesteps, 64)

        class Elsewhere:  # like SB3's SubprocVecEnv: its envs are in other processes
            num_envs = 2
            observation_space = envs[0].observation_space
            action_space = envs[0].action_space

        with self.assertRaisesRegex(TypeError, "n_envs=N"):
            rlrun.PPO("MlpPolicy", Elsewhere())

        class Normalized(Elsewhere):  # like VecNormalize: a wrapper of a VecEnv
            venv = vec

        with self.assertRaisesRegex(TypeError, "normalize=True"):
            rlrun.PPO("MlpPolicy", Normalized())

    def test_learn_continues_stops_and_raises(self):
        model = rlrun.PPO("MlpPolicy", "CartPole-v1", n_steps=64, batch_size=64, seed=1,
                          out_dir=os.path.join(self.tmp, "cont"))
        first = model.policy.state_dict()
        model.learn(640)
        self.assertEqual(model.num_timesteps, 640)
        trained = model.policy.state_dict()
        self.assertFalse(np.array_equal(first["action_net.weight"], trained["action_net.weight"]))
        model.learn(128)
        self.assertEqual(model.num_timesteps, 768)  # counting on from the first learn()
        stopper = Recorder(stop_after=10)
        model.learn(1000, callback=stopper)
        self.assertEqual(model.num_timesteps, 778)  # stopped at its 10th step
        self.assertEqual(stopper.n_calls, 10)

        def boom(locals_, globals_):
            raise ZeroDivisionError("from the callback")

        with self.assertRaises(ZeroDivisionError):
            model.learn(1000, callback=boom)
        model.learn(64, callback=[Recorder(), lambda l, g: True])
        self.assertGreater(model.num_timesteps, 778)

    def test_save_load_predict_and_vec_env(self):
        model = rlrun.DQN("MlpPolicy", "CartPole-v1", learning_starts=100, buffer_size=1000,
                          policy_kwargs=dict(net_arch=[32]), seed=3,
                          out_dir=os.path.join(self.tmp, "dqn"))
        model.learn(300)
        shapes = {k: v.shape for k, v in model.policy.state_dict().items()}
        self.assertEqual(shapes["q_net.q_net.0.weight"], (32, 4))  # SB3's names
        self.assertEqual(shapes["q_net_target.q_net.2.weight"], (2, 32))
        self.assertNotIn("exploration_rate", shapes)  # the algorithm's, not the policy's
        path = os.path.join(self.tmp, "dqn_cartpole")
        model.save(path)  # ".zip" added, as SB3 does
        loaded = rlrun.DQN.load(path + ".zip", out_dir=os.path.join(self.tmp, "dqn2"))
        obs = np.random.default_rng(0).normal(size=(100, 4)).astype(np.float32)
        np.testing.assert_array_equal(loaded.predict(obs, deterministic=True)[0],
                                      model.predict(obs, deterministic=True)[0])
        with self.assertRaises(ValueError):
            rlrun.PPO.load(path + ".zip")
        vec_env = model.get_env()
        observations = vec_env.reset()
        self.assertEqual(observations.shape, (1, 4))
        for _ in range(600):
            action, _ = model.predict(observations, deterministic=True)
            observations, rewards, dones, infos = vec_env.step(action)
            if dones[0]:
                self.assertIn("terminal_observation", infos[0])
                break
        self.assertEqual(rewards.dtype, np.float32)
        loaded.learn(200)  # training goes on from the file's weights
        self.assertGreaterEqual(loaded.num_timesteps, 200)

    def test_off_policy_keywords_and_refusals(self):
        model = rlrun.SAC("MlpPolicy", "Pendulum-v1", learning_starts=50, buffer_size=500,
                          batch_size=32, train_freq=(1, "step"), seed=4,
                          policy_kwargs={"net_arch": [16, 16]}, out_dir=os.path.join(self.tmp, "sac"))
        model.learn(100)
        action, _ = model.predict(np.zeros(3, np.float32))
        self.assertEqual(action.shape, (1,))
        with self.assertRaises(TypeError):  # a schedule as a Python function
            rlrun.PPO("MlpPolicy", "CartPole-v1", learning_rate=lambda p: 3e-4 * p)
        with self.assertRaises(ValueError):  # a keyword PPO does not have, named
            rlrun.PPO("MlpPolicy", "CartPole-v1", n_stpes=64)
        with self.assertRaises(TypeError):
            rlrun.PPO("MyCustomPolicy", "CartPole-v1")

    def test_every_algorithm(self):
        small = {"policy_kwargs": {"net_arch": [16]}}
        cases = [
            ("PPO", "MlpPolicy", "CartPole-v1", {"n_steps": 64}),
            ("A2C", "MlpPolicy", "CartPole-v1", {}),
            ("DQN", "MlpPolicy", "CartPole-v1", {"learning_starts": 50}),
            ("QRDQN", "MlpPolicy", "CartPole-v1", {"learning_starts": 50}),
            ("SAC", "MlpPolicy", "Pendulum-v1", {"learning_starts": 50}),
            ("TD3", "MlpPolicy", "Pendulum-v1", {"learning_starts": 50}),
            ("DDPG", "MlpPolicy", "Pendulum-v1", {"learning_starts": 50}),
            ("TQC", "MlpPolicy", "Pendulum-v1", {"learning_starts": 50}),
            ("CrossQ", "MlpPolicy", "Pendulum-v1", {"learning_starts": 50}),
            ("TRPO", "MlpPolicy", "Pendulum-v1", {"n_steps": 64}),
            ("ARS", "MlpPolicy", "Pendulum-v1", {"n_delta": 2}),
            ("MaskablePPO", "MlpPolicy", "TicTacToe-v0", {"n_steps": 64}),
            ("RecurrentPPO", "MlpLstmPolicy", "CartPoleNoVel-v1", {"n_steps": 64}),
        ]
        for name, policy, env_id, kwargs in cases:
            with self.subTest(name):
                model = getattr(rlrun, name)(policy, env_id, seed=1, **small, **kwargs,
                                             out_dir=os.path.join(self.tmp, "all", name))
                model.learn(200)
                self.assertGreaterEqual(model.num_timesteps, 200)
                self.assertEqual(model._model.algorithm, name)
                observations = model.get_env().reset()
                action, _ = model.predict(observations)
                self.assertEqual(len(action), 1)

    def test_ctrl_c_stops_learn_which_raises_and_the_model_goes_on(self):
        script = textwrap.dedent(f"""
            import sys
            sys.path.insert(0, {os.path.dirname(os.path.abspath(__file__))!r})
            import rlrun
            from test_sb3_api import Corridor
            model = rlrun.PPO("MlpPolicy", Corridor(), n_steps=128, verbose=0,
                              out_dir={os.path.join(self.tmp, "ctrl_c")!r})
            print("ready", flush=True)
            try:
                model.learn(100_000_000)
            except KeyboardInterrupt:
                print("interrupted", model.num_timesteps, flush=True)
            before = model.num_timesteps
            model.learn(128)
            print("continued", model.num_timesteps - before, flush=True)
        """)
        proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True)
        self.assertEqual(proc.stdout.readline().strip(), "ready")
        import signal
        import time
        time.sleep(1.0)
        proc.send_signal(signal.SIGINT)
        output = proc.communicate(timeout=120)[0]
        self.assertEqual(proc.returncode, 0, output)
        self.assertIn("interrupted", output)
        self.assertIn("continued 128", output)

    def test_verbose_zero_prints_nothing(self):
        script = textwrap.dedent(f"""
            import rlrun
            rlrun.PPO("MlpPolicy", "CartPole-v1", n_steps=64, verbose=0,
                      out_dir={os.path.join(self.tmp, "quiet")!r}).learn(256)
        """)
        quiet = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                               check=True)
        self.assertEqual(quiet.stdout, "")
        loud = subprocess.run([sys.executable, "-c", script.replace("verbose=0", "verbose=1")],
                              capture_output=True, text=True, check=True)
        self.assertIn("trained 256 steps", loud.stdout)


def gymnasium_importable():
    src = os.environ.get("GYMNASIUM_SRC")
    if src and src not in sys.path:
        sys.path.insert(0, src)
    try:
        import gymnasium  # noqa: F401
        return True
    except ImportError:
        return False


@unittest.skipUnless(gymnasium_importable(), "Gymnasium: set GYMNASIUM_SRC to its source tree")
class Sb3QuickStart(unittest.TestCase):
    def test_readme_quick_start_with_the_import_changed(self):
        # stable-baselines3's README, `from stable_baselines3 import PPO` -> `from rlrun import
        # PPO`, without render_mode="human" (no display here).
        import gymnasium as gym

        from rlrun import PPO

        env = gym.make("CartPole-v1")
        model = PPO("MlpPolicy", env, verbose=1)
        with contextlib.redirect_stdout(io.StringIO()):
            model.learn(total_timesteps=10_000)
        vec_env = model.get_env()
        obs = vec_env.reset()
        total = 0.0
        for _ in range(1000):
            action, _states = model.predict(obs, deterministic=True)
            obs, reward, done, info = vec_env.step(action)
            total += float(reward[0])
        env.close()
        self.assertEqual(model.num_timesteps, 10240)
        self.assertGreater(total, 900)  # a balanced pole: 1 a step


if __name__ == "__main__":
    unittest.main()
