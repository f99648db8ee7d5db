"""model.predict returns exactly the actions `rlrun eval` takes on the same observations, for
all six algorithms (with a NormalizeObservation model, Box actions rescaled from the policy's
[-1, 1], and Dict observations), and follows SB3's batching rules."""

import os
import unittest

import numpy as np

import rlrun
from rlrun_testing import TempDirMixin, read_trajectory, run_rlrun, train_model

# name -> (experiment, timesteps). Tiny networks and budgets: the models only have to exist.
MODELS = {
    "ppo_norm": ("env: {id: CartPole-v1, n_envs: 2, wrappers: [{id: NormalizeObservation}]}\n"
                 "algo: {id: PPO, n_steps: 64, batch_size: 64, n_epochs: 1,"
                 " policy: {net_arch: [16]}}\n", 256),
    # env.normalize (SB3's VecNormalize as rl-zoo's `normalize: true`): obs and reward halves.
    "ppo_vecnorm": ("env: {id: Acrobot-v1, n_envs: 4, normalize: true}\n"
                    "algo: {id: PPO, n_steps: 32, batch_size: 64, n_epochs: 1,"
                    " policy: {net_arch: [16]}}\n", 256),
    "a2c": ("env: {id: Acrobot-v1}\n"
            "algo: {id: A2C, n_steps: 8, policy: {net_arch: [16]}}\n", 160),
    "dqn": ("env: {id: MountainCar-v0}\n"
            "algo: {id: DQN, learning_starts: 50, batch_size: 16, buffer_size: 1000,"
            " policy: {net_arch: [16]}}\n", 200),
    "qrdqn": ("env: {id: Acrobot-v1}\n"
              "algo: {id: QRDQN, learning_starts: 50, batch_size: 16, buffer_size: 1000,"
              " policy: {net_arch: [16], n_quantiles: 5}}\n", 200),
    "trpo": ("env: {id: CartPole-v1, n_envs: 2}\n"
             "algo: {id: TRPO, n_steps: 64, batch_size: 32, n_critic_updates: 2,"
             " policy: {net_arch: [16]}}\n", 256),
    "ars": ("env: {id: Pendulum-v1, normalize: {norm_obs: true, norm_reward: false}}\n"
            "algo: {id: ARS, n_delta: 2, zero_policy: false, policy: {net_arch: [8]}}\n", 2000),
    "ppo_lstm": ("env: {id: PendulumNoVel-v1, n_envs: 2, normalize: true}\n"
                 "algo: {id: RecurrentPPO, n_steps: 32, batch_size: 16, n_epochs: 1,"
                 " policy: {lstm_hidden_size: 8, n_lstm_layers: 2, net_arch: [16]}}\n", 128),
    "sac": ("env: {id: Pendulum-v1, wrappers: [{id: NormalizeObservation},"
            " {id: RescaleAction, min_action: -0.5, max_action: 0.5}]}\n"
            "algo: {id: SAC, learning_starts: 50, batch_size: 16, policy: {net_arch: [16]}}\n", 150),
    "crossq": ("env: {id: Pendulum-v1}\n"
               "algo: {id: CrossQ, learning_starts: 50, batch_size: 16,"
               " policy: {net_arch: [16], renorm_warmup_steps: 60}}\n", 150),
    "td3": ("env: {id: MountainCarContinuous-v0}\n"
            "algo: {id: TD3, learning_starts: 50, batch_size: 16, policy: {net_arch: [16]}}\n", 150),
    "ddpg": ("env: {id: Pendulum-v1}\n"
             "algo: {id: DDPG, learning_starts: 50, batch_size: 16, policy: {net_arch: [16]}}\n", 150),
    "dqn_onehot": ("env: {id: GridWorld-v0, wrappers: [{id: OneHotObservation}]}\n"
                   "algo: {id: DQN, learning_starts: 50, batch_size: 16, buffer_size: 1000,"
                   " policy: {net_arch: [16]}}\n", 200),
    "ppo_dict": ("env: {id: DictReach-v0, n_envs: 2}\n"
                 "algo: {id: PPO, n_steps: 32, batch_size: 64, n_epochs: 1,"
                 " policy: {net_arch: [16]}}\n", 128),
    # rl-zoo's policy_kwargs forms: separate pi/vf (pi/qf) sizes, torch activation classes,
    # ortho_init False.
    "ppo_arch": ("env: {id: Pendulum-v1, n_envs: 2}\n"
                 "algo: {id: PPO, n_steps: 32, batch_size: 64, n_epochs: 1,"
                 " policy: {net_arch: {pi: [32], vf: [64, 64]}, activation_fn: nn.ELU,"
                 " ortho_init: false}}\n", 128),
    "sac_arch": ("env: {id: Pendulum-v1}\n"
                 "algo: {id: SAC, learning_starts: 50, batch_size: 16,"
                 " policy: {net_arch: {pi: [64], qf: [400, 300]},"
                 " activation_fn: nn.LeakyReLU}}\n", 100),
}


class PredictMatchesEval(TempDirMixin, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.models, cls.trajectories = {}, {}
        for name, (body, steps) in MODELS.items():
            text = f"run: {{name: {name}, seed: 1, total_timesteps: {steps}}}\n" + body
            path = train_model(cls.tmp, name, text)
            steps_csv = os.path.join(cls.tmp, name + "_steps.csv")
            run_rlrun("eval", "--model", path, "--episodes", 1, "--seed", 11,
                      "--trajectory", steps_csv)
            cls.models[name] = path
            cls.trajectories[name] = read_trajectory(steps_csv)

    def check_exact(self, name, algorithm):
        model = rlrun.load(self.models[name])
        self.assertEqual(model.algorithm, algorithm)
        self.assertGreater(model.num_timesteps, 0)
        rows = self.trajectories[name]
        self.assertGreater(len(rows), 0)
        dim = rlrun._spaces.flat_dim
        for row in rows:
            obs = rlrun._spaces.from_flat(model.observation_space, row["obs"])
            action, state = model.predict(obs, deterministic=True)
            self.assertIsNone(state)
            np.testing.assert_array_equal(
                np.asarray(action, dtype=np.float32).reshape(-1), row["action"],
                err_msg=f"{name} step {row['step']}")
            self.assertEqual(np.asarray(action).size, dim(model.action_space))
        return model, rows

    def test_ppo_with_normalize_observation(self):
        model, rows = self.check_exact("ppo_norm", "PPO")
        # The model normalises: raw CartPole observations go in (not the normalised ones).
        self.assertEqual(model.observation_space.shape, (4,))
        action, _ = model.predict(rows[0]["obs"], deterministic=True)
        self.assertEqual(action.shape, ())
        self.assertEqual(action.dtype, np.int64)

    def test_ppo_with_env_normalize(self):
        # The model file's statistics normalise raw observations in predict(), as in eval.
        model, rows = self.check_exact("ppo_vecnorm", "PPO")
        self.assertIn("normalize", model.config)
        self.assertEqual(model.observation_space.shape, (6,))

    def test_a2c(self):
        self.check_exact("a2c", "A2C")

    def test_dqn(self):
        self.check_exact("dqn", "DQN")

    def test_qrdqn(self):
        self.check_exact("qrdqn", "QRDQN")

    def test_trpo(self):
        self.check_exact("trpo", "TRPO")

    def test_ars(self):
        self.check_exact("ars", "ARS")

    def test_crossq(self):
        self.check_exact("crossq", "CrossQ")

    def test_recurrent_ppo_carries_sb3_contribs_state(self):
        model = rlrun.load(self.models["ppo_lstm"])
        self.assertEqual(model.algorithm, "RecurrentPPO")
        rows = self.trajectories["ppo_lstm"]
        self.assertEqual(len(rows), 200)
        # PendulumNoVel-v1: the trajectory holds the observations the env id gives (as
        # rlrun.make's), the angular velocity masked to 0.
        self.assertTrue(all(row["obs"][2] == 0.0 for row in rows))
        self.assertTrue(any(row["obs"][0] != 0.0 for row in rows))
        state, stateless_differs = None, False
        for row in rows:
            # sb3-contrib's loop: the state predict returned, episode_start at the first step.
            action, state = model.predict(row["obs"], state=state,
                                          episode_start=np.array([row["step"] == 0]),
                                          deterministic=True)
            self.assertEqual([s.shape for s in state], [(2, 1, 8), (2, 1, 8)])
            np.testing.assert_array_equal(np.asarray(action, dtype=np.float32).reshape(-1),
                                          row["action"], err_msg=f"step {row['step']}")
            fresh, _ = model.predict(row["obs"], deterministic=True)
            stateless_differs |= bool(np.any(fresh != action))
        self.assertTrue(stateless_differs)  # the state matters
        with self.assertRaises(ValueError):
            model.predict(rows[0]["obs"], state=(np.zeros((1, 1, 8)), np.zeros((1, 1, 8))))

    def test_multidiscrete_observations_one_hot_encoded(self):
        # GridWorld's MultiDiscrete positions go in; the model's OneHotObservation encodes them.
        model, rows = self.check_exact("dqn_onehot", "DQN")
        self.assertEqual(type(model.observation_space).__name__, "MultiDiscrete")
        self.assertEqual(model.policy_observation_space.shape, (10,))
        obs = rlrun._spaces.from_flat(model.observation_space, rows[0]["obs"])
        self.assertEqual(obs.dtype, np.int64)
        batch, _ = model.predict(np.stack([obs, obs]), deterministic=True)
        self.assertEqual(batch.shape, (2,))

    def test_sac_box_actions_rescaled(self):
        # SAC acts in [-0.5, 0.5] (RescaleAction over Pendulum's [-2, 2]); predict returns
        # Pendulum's actions, as eval steps it.
        model, rows = self.check_exact("sac", "SAC")
        policy_space = rlrun._spaces.from_description(model._core.policy_action_space)
        np.testing.assert_array_equal(policy_space.high, [0.5])
        np.testing.assert_array_equal(model.action_space.high, [2.0])
        samples = np.array([model.predict(rows[0]["obs"])[0][0] for _ in range(200)])
        self.assertTrue(np.all(np.abs(samples) <= 2.0))
        self.assertTrue(np.any(np.abs(samples) > 0.5))  # beyond the policy's own bounds
        action, _ = model.predict(rows[0]["obs"], deterministic=True)
        self.assertEqual(action.shape, (1,))
        self.assertEqual(action.dtype, np.float32)

    def test_network_options(self):
        self.check_exact("ppo_arch", "PPO")
        self.check_exact("sac_arch", "SAC")

    def test_td3(self):
        self.check_exact("td3", "TD3")

    def test_ddpg(self):
        self.check_exact("ddpg", "DDPG")

    def test_dict_observations(self):
        model, rows = self.check_exact("ppo_dict", "PPO")
        self.assertEqual(type(model.observation_space).__name__, "Dict")
        obs = rlrun._spaces.from_flat(model.observation_space, rows[0]["obs"])
        self.assertIsInstance(obs, dict)
        # A batch of dicts: each key's array gets a leading axis.
        batch = {k: np.stack([v, v, v]) for k, v in obs.items()}
        actions, _ = model.predict(batch, deterministic=True)
        single, _ = model.predict(obs, deterministic=True)
        self.assertEqual(actions.shape[0], 3)
        for a in actions:
            np.testing.assert_array_equal(a, single)

    def test_batching_rules(self):
        model = rlrun.load(self.models["sac"])
        rows = self.trajectories["sac"][:5]
        batch = np.stack([r["obs"] for r in rows])
        actions, _ = model.predict(batch, deterministic=True)
        self.assertEqual(actions.shape, (5, 1))
        for a, r in zip(actions, rows):
            single, _ = model.predict(r["obs"], deterministic=True)
            np.testing.assert_allclose(a, single, rtol=1e-5, atol=1e-6)
        # A batch longer than an episode (Pendulum's TimeLimit is 200) gives the same actions
        # as one observation at a time.
        wide = np.random.default_rng(0).uniform(-1, 1, (450, 3)).astype(np.float32)
        actions, _ = model.predict(wide, deterministic=True)
        self.assertEqual(actions.shape, (450, 1))
        for a, o in zip(actions[::50], wide[::50]):
            np.testing.assert_array_equal(a, model.predict(o, deterministic=True)[0])
        with self.assertRaisesRegex(ValueError, "Unexpected observation shape"):
            model.predict(np.zeros(4, dtype=np.float32))
        with self.assertRaisesRegex(ValueError, "mixing Gym API"):
            model.predict((rows[0]["obs"], {}))
        # Stochastic actions stay in the action space.
        for _ in range(5):
            a, _ = model.predict(rows[0]["obs"], deterministic=False)
            self.assertTrue(model.action_space.contains(a))
        discrete = rlrun.load(self.models["dqn"])
        obs = np.stack([r["obs"] for r in self.trajectories["dqn"][:3]])
        actions, _ = discrete.predict(obs, deterministic=True)
        self.assertEqual(actions.shape, (3,))
        self.assertEqual(actions.dtype, np.int64)

    def test_model_attributes(self):
        model = rlrun.load(self.models["ppo_norm"])
        self.assertEqual(model.env_id, "CartPole-v1")
        self.assertEqual(type(model.action_space).__name__, "Discrete")
        self.assertEqual(model.action_space.n, 2)
        self.assertIn("NormalizeObservation", model.config)
        self.assertIn("PPO", repr(model))


class UntrustedModelFiles(TempDirMixin, unittest.TestCase):
    def test_a_zip_bomb_is_refused_before_reading(self):
        # A tiny model whose weight member inflates to 64 MiB of zeros: refused by the byte
        # budget its configuration justifies (runtime/io/model_budget.hpp), as eval refuses it.
        import zipfile

        source = train_model(self.tmp, "tiny", "run: {name: tiny, seed: 1, total_timesteps: 64}\n"
                             "env: {id: CartPole-v1}\n"
                             "algo: {id: PPO, n_steps: 64, batch_size: 64, n_epochs: 1}\n")
        bomb = os.path.join(self.tmp, "bomb.zip")
        with zipfile.ZipFile(source) as src, zipfile.ZipFile(bomb, "w", zipfile.ZIP_DEFLATED) as out:
            for name in src.namelist():
                data = src.read(name)
                if name == "action_net.weight.npy":
                    data = data[:128] + bytes(64 << 20)
                out.writestr(name, data)
        self.assertLess(os.path.getsize(bomb), 1 << 20)
        with self.assertRaises(rlrun.RuntimeFailure) as caught:
            rlrun.load(bomb)
        self.assertIn(bomb + ": its tensors declare ", str(caught.exception))
        code, output = run_rlrun("eval", "--model", bomb, check=False)
        self.assertEqual(code, 1)
        self.assertIn(str(caught.exception), output)

    def test_nan_weights_are_refused_naming_the_tensor(self):
        # A model whose weights hold a NaN (training diverged, or a tampered file) would predict
        # NaN actions: rlrun.load refuses it as eval does (runtime/io/model_file.hpp).
        import io
        import zipfile

        source = train_model(self.tmp, "tiny_nan", "run: {name: tiny_nan, seed: 1, total_timesteps: 64}\n"
                             "env: {id: CartPole-v1}\n"
                             "algo: {id: PPO, n_steps: 64, batch_size: 64, n_epochs: 1}\n")
        damaged = os.path.join(self.tmp, "nan.zip")
        with zipfile.ZipFile(source) as src, zipfile.ZipFile(damaged, "w") as out:
            for name in src.namelist():
                data = src.read(name)
                if name == "action_net.weight.npy":
                    weight = np.load(io.BytesIO(data))
                    weight[0, 0] = np.nan
                    buffer = io.BytesIO()
                    np.save(buffer, weight)
                    data = buffer.getvalue()
                out.writestr(name, data)
        with self.assertRaises(rlrun.RuntimeFailure) as caught:
            rlrun.load(damaged)
        self.assertIn(damaged + ": parameter action_net.weight has 1 non-finite value (first: nan)",
                      str(caught.exception))

    def test_errors_are_exceptions_with_the_cli_message(self):
        missing = os.path.join(self.tmp, "missing.zip")
        with self.assertRaises(rlrun.RuntimeFailure) as caught:
            rlrun.load(missing)
        code, output = run_rlrun("eval", "--model", missing, check=False)
        self.assertEqual(code, 1)
        self.assertIn(str(caught.exception), output)
        self.assertIsInstance(caught.exception, RuntimeError)

        not_a_zip = os.path.join(self.tmp, "model.zip")
        with open(not_a_zip, "wb") as f:
            f.write(b"PK\x03\x04 certainly not a zip file")
        with self.assertRaises(rlrun.RuntimeFailure) as caught:
            rlrun.load(not_a_zip)
        code, output = run_rlrun("eval", "--model", not_a_zip, check=False)
        self.assertEqual(code, 1)
        self.assertIn(str(caught.exception), output)


def stderr_of(call):
    """call()'s result and what it wrote to file descriptor 2 (C++'s stderr included)."""
    import tempfile

    with tempfile.TemporaryFile() as captured:
        saved = os.dup(2)
        os.dup2(captured.fileno(), 2)
        try:
            result = call()
        finally:
            os.dup2(saved, 2)
            os.close(saved)
        captured.seek(0)
        return result, captured.read().decode()


class TrustedModel(TempDirMixin, unittest.TestCase):
    """rlrun.load of a model of one's own Python env: it builds no env (the file records the
    env's spaces), so nothing the file names runs and it loads without trust; trust=True and an
    override are still taken (they matter for files older than the recorded spaces)."""

    ENV_ID = "python:rlrun_test_envs.cartpole:CartPolePort"

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        source = os.environ.get("RLRUN_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "../.."))
        cls.saved_path = os.environ.get("PYTHONPATH")
        envs = os.path.join(source, "tests", "python_envs")
        os.environ["PYTHONPATH"] = envs + (os.pathsep + cls.saved_path if cls.saved_path else "")
        cls.model = train_model(cls.tmp, "port", "run: {name: port, seed: 1, total_timesteps: 64}\n"
                                f'env: {{id: "{cls.ENV_ID}"}}\n'
                                "algo: {id: PPO, n_steps: 64, batch_size: 64, n_epochs: 1}\n")

    @classmethod
    def tearDownClass(cls):
        if cls.saved_path is None:
            os.environ.pop("PYTHONPATH", None)
        else:
            os.environ["PYTHONPATH"] = cls.saved_path
        super().tearDownClass()

    def test_loads_without_trust_and_starts_no_interpreter(self):
        saved = os.environ.get("PATH", "")
        os.environ["PATH"] = "/nonexistent"
        try:
            model, said = stderr_of(lambda: rlrun.load(self.model))
        finally:
            os.environ["PATH"] = saved
        self.assertNotIn("trusting", said)
        action, _ = model.predict(np.zeros(4, dtype=np.float32), deterministic=True)
        self.assertIn(int(action), (0, 1))
        self.assertEqual(model.env_id, self.ENV_ID)

    def test_trust_true_has_nothing_to_announce(self):
        model, said = stderr_of(lambda: rlrun.load(self.model, trust=True))
        self.assertNotIn("trusting", said)
        self.assertEqual(model.env_id, self.ENV_ID)

    def test_an_override_still_vouches_for_one_value(self):
        model, said = stderr_of(lambda: rlrun.load(self.model, overrides=["env.id=" + self.ENV_ID]))
        self.assertEqual(model.env_id, self.ENV_ID)
        self.assertNotIn("trusting", said)

if __name__ == "__main__":
    unittest.main()
