"""`rlrun export --format sb3` writes model files SB3 opens.

Everywhere: Python's own zipfile and pickle modules read what rlrun wrote (CRCs, the `data`
JSON, every pickle, torch's archive layout), with every global the pickles name replaced by a
stand-in that records it, so nothing is imported and the shapes are checked.

Where the real Stable-Baselines3 2.4.1 and Debian's torch are at hand (SB3_SRC and
GYMNASIUM_SRC name their source trees, as for scripts/data/make_sb3_models.sh; the script
scripts/data/check_sb3_export.sh sets them): SB3's `load` opens each file with warnings turned
into errors, and its `predict` gives rlrun's actions on 1000 observations.
"""

import base64
import io
import json
import os
import pickle
import shutil
import subprocess
import sys
import tempfile
import unittest
import zipfile

import numpy as np

import rlrun

SOURCE = os.environ.get("RLRUN_SOURCE_DIR", "../..")
BINARY = os.environ.get("RLRUN_BINARY", "rlrun")
SB3_DIR = os.path.join(SOURCE, "tests", "data", "sb3")

# SB3's own files (tests/data/sb3), each re-written by rlrun, and the env each acts in.
CASES = [
    ("ppo_cartpole", "CartPole-v1", "PPO"),
    ("a2c_cartpole", "CartPole-v1", "A2C"),
    ("dqn_cartpole", "CartPole-v1", "DQN"),
    ("ppo_pendulum", "Pendulum-v1", "PPO"),
    ("ppo_sde_pendulum", "Pendulum-v1", "PPO"),
    ("sac_pendulum", "Pendulum-v1", "SAC"),
    ("sac_sde_pendulum", "Pendulum-v1", "SAC"),
    ("td3_pendulum", "Pendulum-v1", "TD3"),
    ("ddpg_pendulum", "Pendulum-v1", "DDPG"),
    ("qrdqn_cartpole", "CartPole-v1", "QRDQN"),
    ("tqc_pendulum", "Pendulum-v1", "TQC"),
    ("trpo_pendulum", "Pendulum-v1", "TRPO"),
    ("maskable_ppo_cartpole", "CartPole-v1", "MaskablePPO"),
    ("recurrent_ppo_cartpole", "CartPole-v1", "RecurrentPPO"),
    ("recurrent_ppo_pendulum", "Pendulum-v1", "RecurrentPPO"),
    ("ppo_cnn_gripper_pixels", "GripperLift-v0", "PPO"),
    ("dqn_cnn_cartpole_pixels", "CartPole-v1", "DQN"),
    ("sac_cnn_pendulum_pixels", "Pendulum-v1", "SAC"),
    ("ppo_multi_input_gripper_both", "GripperLift-v0", "PPO"),
]
# rlrun's pixel CartPole / Pendulum: 36x36 gray frames (uint8, channels last).
PIXELS = ("[{id: AddRenderObservation, width: 36, height: 36}, "
          "{id: GrayscaleObservation, keep_dim: true}]")
# The env settings a case's model needs (`--set` for rlrun; SB3's file does not record them).
CASE_SETTINGS = {"ppo_cnn_gripper_pixels": ["env.kwargs.obs_type=pixels", "env.kwargs.image_size=36"],
                 "dqn_cnn_cartpole_pixels": [f"env.wrappers={PIXELS}"],
                 "sac_cnn_pendulum_pixels": [f"env.wrappers={PIXELS}"],
                 "ppo_multi_input_gripper_both": ["env.kwargs.obs_type=both",
                                                  "env.kwargs.image_size=36"]}
CONTRIB = {"QRDQN", "TQC", "TRPO", "MaskablePPO", "RecurrentPPO"}


def observations_path(case):
    """A fixture's observations: observations.npy, or observations.npz for a Dict's keys."""
    path = os.path.join(SB3_DIR, case, "observations.npy")
    return path if os.path.exists(path) else os.path.join(SB3_DIR, case, "observations.npz")


def load_observations(path):
    observations = np.load(path)
    if hasattr(observations, "files"):  # a Dict's keys (.npz)
        return {k: observations[k] for k in observations.files}
    return observations


def load_class(algorithm):
    return ("sb3_contrib." if algorithm in CONTRIB else "stable_baselines3.") + algorithm


def stand_in(module, name):
    """A class standing for `module.name`: calling it, NEWOBJ and BUILD record their
    arguments."""

    class StandIn:
        qualname = module + "." + name

        def __new__(cls, *args):
            obj = object.__new__(cls)
            obj.args = args
            obj.state = None
            return obj

        def __init__(self, *args):
            pass

        def __setstate__(self, state):
            self.state = state

    return StandIn


class RecordingUnpickler(pickle.Unpickler):
    """Python's unpickler with every global a stand-in (collections.OrderedDict excepted) and
    torch's storages as ('storage', type, key, location, numel) tuples."""

    def find_class(self, module, name):
        if (module, name) == ("collections", "OrderedDict"):
            import collections

            return collections.OrderedDict
        return stand_in(module, name)

    def persistent_load(self, pid):
        return tuple(pid)


def unpickle(data):
    return RecordingUnpickler(io.BytesIO(data)).load()


def run(*args):
    result = subprocess.run([BINARY, *args], capture_output=True, text=True)
    if result.returncode != 0:
        raise AssertionError(f"rlrun {' '.join(args)}: {result.stdout}{result.stderr}")
    return result.stdout


class Sb3Export(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="rlrun_sb3_export_")
        cls.written = {}
        for case, env_id, _ in CASES:
            path = os.path.join(cls.dir, case + ".zip")
            settings = [a for v in CASE_SETTINGS.get(case, []) for a in ("--set", v)]
            run("export", "--model", os.path.join(SB3_DIR, case, "model.zip"), "--env", env_id,
                *settings, "--format", "sb3", "--output", path)
            cls.written[case] = path

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def test_python_reads_the_zip_the_json_and_every_pickle(self):
        for case, _, algorithm in CASES:
            with self.subTest(case=case), zipfile.ZipFile(self.written[case]) as archive:
                self.assertIsNone(archive.testzip())  # every CRC holds
                self.assertEqual(archive.read("_stable_baselines3_version"), b"2.4.1")
                data = json.loads(archive.read("data"))
                policy_class = unpickle(
                    base64.b64decode(data["policy_class"][":serialized:"]))
                # TRPO keeps SB3's ActorCriticPolicy; the other contrib ones have their own.
                own_policy = algorithm in CONTRIB and algorithm != "TRPO"
                self.assertTrue(policy_class.qualname.startswith(
                    "sb3_contrib." if own_policy else "stable_baselines3."))
                space = unpickle(
                    base64.b64decode(data["observation_space"][":serialized:"]))
                if space.qualname == "gymnasium.spaces.dict.Dict":  # a MultiInputPolicy's
                    space = space.state["spaces"]["pixels"]
                self.assertEqual(space.qualname, "gymnasium.spaces.box.Box")
                self.assertEqual(set(space.state),
                                 {"dtype", "_shape", "low", "high", "bounded_below",
                                  "bounded_above", "_np_random"})
                kwargs = unpickle(
                    base64.b64decode(data["policy_kwargs"][":serialized:"]))
                self.assertIn("net_arch", kwargs)
                self.assertTrue(kwargs["activation_fn"].qualname.startswith("torch.nn.modules."))
                expected_pth = {"policy.pth", "pytorch_variables.pth"}
                if algorithm in ("PPO", "A2C", "DQN", "QRDQN", "TRPO", "MaskablePPO",
                                 "RecurrentPPO"):
                    expected_pth.add("policy.optimizer.pth")
                else:
                    expected_pth |= {"actor.optimizer.pth", "critic.optimizer.pth"}
                names = {n for n in archive.namelist() if n.endswith(".pth")}
                self.assertTrue(expected_pth <= names, names)
                for name in names:
                    self.check_torch_file(archive.read(name), name)

    def check_torch_file(self, data, name):
        with zipfile.ZipFile(io.BytesIO(data)) as torch_zip:
            self.assertIsNone(torch_zip.testzip())
            first = torch_zip.infolist()[0]
            self.assertEqual(first.filename, "archive/data.pkl")
            self.assertEqual(torch_zip.read("archive/version"), b"3\n")
            obj = unpickle(torch_zip.read("archive/data.pkl"))
            if name.endswith("optimizer.pth"):
                self.assertEqual(obj["state"], {})
                group = obj["param_groups"][0]
                self.assertGreater(len(group["params"]), 0)
                self.assertIn("lr", group)
                return
            for key, tensor in obj.items():
                storage, offset, size, stride, requires_grad, hooks = tensor.args
                self.assertEqual(storage[0], "storage")
                self.assertEqual(storage[1].qualname, "torch.FloatStorage")
                self.assertEqual(offset, 0)
                numel = int(np.prod(size)) if size else 1
                self.assertEqual(storage[4], numel)
                raw = torch_zip.read("archive/data/" + storage[2])
                self.assertEqual(len(raw), 4 * numel, key)
                # torch maps records into memory when asked: each starts at a multiple of 64.
                info = torch_zip.getinfo("archive/data/" + storage[2])
                self.assertEqual(self.data_offset(data, info) % 64, 0)

    @staticmethod
    def data_offset(archive_bytes, info):
        header = info.header_offset
        name_len = int.from_bytes(archive_bytes[header + 26:header + 28], "little")
        extra_len = int.from_bytes(archive_bytes[header + 28:header + 30], "little")
        return header + 30 + name_len + extra_len

    def test_rlrun_reads_the_written_files_and_acts_as_sb3(self):
        for case, env_id, algorithm in CASES:
            if any(v.startswith("env.wrappers=") for v in CASE_SETTINGS.get(case, [])):
                # rlrun.load's predict takes the env's own observations (the state the wrappers
                # render): these files' predictions on images are checked in C++
                # (tests/runtime/test_sb3_model_writer.cpp, test_sb3_model_file.cpp).
                continue
            with self.subTest(case=case):
                model = rlrun.load(self.written[case], CASE_SETTINGS.get(case), env=env_id)
                self.assertEqual(model.algorithm, algorithm)
                observations = load_observations(observations_path(case))
                expected = np.load(os.path.join(SB3_DIR, case, "actions.npy"))
                actions, _ = model.predict(observations, deterministic=True)
                np.testing.assert_allclose(actions, expected, atol=1e-5, rtol=0)


SB3_CHECK = r"""
import json, sys, warnings
import numpy as np
warnings.simplefilter("error")  # SB3 opens the file without a single warning
import importlib
cases = json.loads(sys.argv[1])
out = {}
for path, load_class, obs_path in cases:
    module, name = load_class.rsplit(".", 1)
    model = getattr(importlib.import_module(module), name).load(path, device="cpu")
    observations = np.load(obs_path)
    if hasattr(observations, "files"):  # a Dict's keys (.npz)
        observations = {k: observations[k] for k in observations.files}
    actions, _ = model.predict(observations, deterministic=True)
    out[path] = actions.tolist()
print(json.dumps(out))
"""


def contrib_source():
    """SB3_CONTRIB_SRC: sb3-contrib 2.4.0's source tree, for its algorithms' cases."""
    contrib = os.environ.get("SB3_CONTRIB_SRC")
    return contrib if contrib and os.path.isdir(os.path.join(contrib, "sb3_contrib")) else None


def sb3_sources():
    sb3, gym = os.environ.get("SB3_SRC"), os.environ.get("GYMNASIUM_SRC")
    if not (sb3 and gym and os.path.isdir(os.path.join(sb3, "stable_baselines3"))
            and os.path.isdir(os.path.join(gym, "gymnasium"))):
        return None
    probe = subprocess.run([sys.executable, "-c", "import torch, cloudpickle"],
                           capture_output=True)
    return (sb3, gym) if probe.returncode == 0 else None


@unittest.skipUnless(sb3_sources(), "SB3_SRC/GYMNASIUM_SRC and torch: scripts/data/check_sb3_export.sh")
class Sb3LoadsExport(unittest.TestCase):
    def test_sb3_loads_and_predicts_as_rlrun(self):
        sb3, gym = sb3_sources()
        work = tempfile.mkdtemp(prefix="rlrun_sb3_load_")
        try:
            stub = os.path.join(work, "stub")
            os.makedirs(stub)
            with open(os.path.join(stub, "farama_notifications.py"), "w") as f:
                f.write("notifications = {}\n")
            cases = self.exported_cases(work)
            paths = [sb3, gym, stub] + ([contrib_source()] if contrib_source() else [])
            env = dict(os.environ, PYTHONPATH=os.pathsep.join(paths))
            result = subprocess.run([sys.executable, "-c", SB3_CHECK, json.dumps(
                [[path, load_class(algo), obs] for path, algo, obs, _, _ in cases])],
                capture_output=True, text=True, env=env)
            self.assertEqual(result.returncode, 0, result.stderr)
            sb3_actions = json.loads(result.stdout)
            for path, algo, obs, model_path, env_id in cases:
                with self.subTest(model=path):
                    model = rlrun.load(model_path, env=env_id) if env_id else rlrun.load(model_path)
                    mine, _ = model.predict(load_observations(obs), deterministic=True)
                    theirs = np.asarray(sb3_actions[path]).reshape(mine.shape)
                    print(f"{os.path.basename(path)}: max |SB3 - rlrun| = "
                          f"{np.max(np.abs(theirs - mine)):.2g}", file=sys.stderr)
                    np.testing.assert_allclose(theirs, mine, atol=1e-5, rtol=0)
        finally:
            shutil.rmtree(work, ignore_errors=True)

    def exported_cases(self, work):
        """SB3's own files re-written, and models rlrun trains here (every algorithm,
        non-default networks and activations), each exported."""
        cases = []
        for case, env_id, algorithm in CASES:
            if algorithm in CONTRIB and not contrib_source():
                continue
            path = os.path.join(work, case + ".zip")
            settings = [a for v in CASE_SETTINGS.get(case, []) for a in ("--set", v)]
            run("export", "--model", os.path.join(SB3_DIR, case, "model.zip"), "--env", env_id,
                *settings, "--format", "sb3", "--output", path)
            cases.append((path, algorithm, observations_path(case),
                          os.path.join(SB3_DIR, case, "model.zip"), env_id))
        trained = {
            "PPO": ("CartPole-v1", "{id: PPO, n_steps: 128, batch_size: 64, "
                    "policy: {net_arch: {pi: [16], vf: [8]}, activation_fn: relu}}"),
            "A2C": ("Pendulum-v1", "{id: A2C, n_steps: 8, policy: {net_arch: [32]}}"),
            "DQN": ("CartPole-v1", "{id: DQN, learning_starts: 64, policy: {net_arch: [16]}}"),
            "SAC": ("Pendulum-v1", "{id: SAC, learning_starts: 64, ent_coef: 0.05, "
                    "policy: {net_arch: [16, 16], activation_fn: tanh}}"),
            "TD3": ("Pendulum-v1", "{id: TD3, learning_starts: 64, policy: {net_arch: [16]}}"),
            "DDPG": ("Pendulum-v1", "{id: DDPG, learning_starts: 64, policy: {net_arch: [16]}}"),
        }
        if contrib_source():
            trained["QRDQN"] = ("CartPole-v1", "{id: QRDQN, learning_starts: 64, "
                                "policy: {net_arch: [16], n_quantiles: 7}}")
            trained["TQC"] = ("Pendulum-v1", "{id: TQC, learning_starts: 64, "
                              "policy: {net_arch: [16], n_quantiles: 6, n_critics: 3}}")
            trained["TRPO"] = ("Pendulum-v1", "{id: TRPO, n_steps: 128, batch_size: 64, "
                               "policy: {net_arch: [16]}}")
            trained["RecurrentPPO"] = ("Pendulum-v1", "{id: RecurrentPPO, n_steps: 64, "
                                       "batch_size: 32, policy: {lstm_hidden_size: 8, "
                                       "n_lstm_layers: 2, net_arch: [8]}}")
        rng = np.random.default_rng(0)
        trained = {(a, a.lower()): (env_id, algo) for a, (env_id, algo) in trained.items()}
        # CnnPolicy (NatureCNN, features_dim 16) of each algorithm on envs that see images:
        # CarRacing-v3 with discrete actions (96x96x3), GripperLift-v0's 36x36 camera. The
        # off-policy ones have an extractor per network (SAC's also shared), PPO's separate.
        cnn = "features_extractor_class: NatureCNN, features_dim: 16"
        off = "learning_starts: 64, buffer_size: 500, batch_size: 16"
        car = "CarRacing-v3, kwargs: {continuous: false}"
        gripper = "GripperLift-v0, kwargs: {obs_type: pixels, image_size: 36}"
        trained[("DQN", "dqn_cnn")] = (car, f"{{id: DQN, {off}, policy: {{{cnn}}}}}")
        trained[("SAC", "sac_cnn")] = (gripper, f"{{id: SAC, {off}, policy: {{{cnn}, "
                                       "net_arch: [16]}}")
        trained[("SAC", "sac_cnn_shared")] = (
            gripper, f"{{id: SAC, {off}, policy: {{{cnn}, net_arch: [16], "
            "share_features_extractor: true}}")
        trained[("TD3", "td3_cnn")] = (gripper, f"{{id: TD3, {off}, policy: {{{cnn}, "
                                       "net_arch: [16]}}")
        trained[("PPO", "ppo_cnn_separate")] = (
            gripper, f"{{id: PPO, n_steps: 128, batch_size: 64, policy: {{{cnn}, "
            "net_arch: [], share_features_extractor: false}}")
        if contrib_source():
            trained[("QRDQN", "qrdqn_cnn")] = (
                car, f"{{id: QRDQN, {off}, policy: {{{cnn}, n_quantiles: 5}}}}")
            trained[("TQC", "tqc_cnn")] = (
                gripper, f"{{id: TQC, {off}, policy: {{{cnn}, net_arch: [16], "
                "n_quantiles: 5, n_critics: 2}}")
        # MultiInputPolicy over an image and a vector (CombinedExtractor, cnn_output_dim 16).
        both = "GripperLift-v0, kwargs: {obs_type: both, image_size: 36}"
        combined = "features_extractor_class: CombinedExtractor, cnn_output_dim: 16"
        trained[("PPO", "ppo_multi_input_cnn")] = (
            both, f"{{id: PPO, n_steps: 128, batch_size: 64, policy: {{{combined}}}}}")
        trained[("SAC", "sac_multi_input_cnn")] = (
            both, f"{{id: SAC, {off}, policy: {{{combined}, net_arch: [16]}}}}")
        for (algorithm, name), (env_id, algo) in trained.items():
            pixels = env_id in (car, gripper)
            config = os.path.join(work, name + ".yaml")
            with open(config, "w") as f:
                f.write(f"run: {{name: {name}, seed: 2, total_timesteps: 256, out_dir: {work}}}\n"
                        f"env: {{id: {env_id}}}\nalgo: {algo}\n")
            run("train", config)
            model = os.path.join(work, name, "seed2", "model.zip")
            path = os.path.join(work, name + "_sb3.zip")
            run("export", "--model", model, "--format", "sb3", "--output", path)
            obs = os.path.join(work, name + "_obs.npy")
            if env_id == both:
                obs = os.path.join(work, name + "_obs.npz")
                np.savez(obs, pixels=rng.integers(0, 256, size=(200, 36, 36, 3), dtype=np.uint8),
                         state=rng.normal(size=(200, 26)).astype(np.float32))
            elif pixels:
                shape = (96, 96, 3) if env_id == car else (36, 36, 3)
                np.save(obs, rng.integers(0, 256, size=(200,) + shape, dtype=np.uint8))
            else:
                dim = 4 if env_id == "CartPole-v1" else 3
                np.save(obs, rng.uniform(-1, 1, size=(1000, dim)).astype(np.float32))
            cases.append((path, algorithm, obs, model, None))
        return cases


if __name__ == "__main__":
    unittest.main()
