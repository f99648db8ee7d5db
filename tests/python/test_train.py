"""rlrun.train: trains in-process like `rlrun train`, returns the run directory; config errors
are ConfigErrors (ValueErrors) with the CLI's file:line:col message and did-you-mean."""

import os
import signal
import subprocess
import sys
import time
import unittest

import rlrun
from rlrun_testing import TempDirMixin, run_rlrun

CONFIG = {
    "run": {"name": "tiny", "seed": 1, "total_timesteps": 256},
    "env": {"id": "CartPole-v1", "n_envs": 2},
    "algo": {"id": "PPO", "n_steps": 64, "batch_size": 64, "n_epochs": 1,
             "policy": {"net_arch": [16]}},
}


class Train(TempDirMixin, unittest.TestCase):
    def test_dict_config_returns_the_run_directory(self):
        out = os.path.join(self.tmp, "runs")
        run_dir = rlrun.train(CONFIG, out=out, seed=3)
        self.assertEqual(os.path.realpath(run_dir), os.path.realpath(os.path.join(out, "tiny", "seed3")))
        for name in ("model.zip", "config.yaml", "progress.csv", "finished"):
            self.assertTrue(os.path.exists(os.path.join(run_dir, name)), name)
        model = rlrun.load(os.path.join(run_dir, "model.zip"))
        self.assertEqual(model.algorithm, "PPO")
        self.assertGreaterEqual(model.num_timesteps, 256)
        # Overrides as a dict of config paths, like --set.
        run_dir = rlrun.train(CONFIG, {"algo.learning_rate": 1e-3, "run.name": "lr"}, out=out)
        with open(os.path.join(run_dir, "config.yaml")) as f:
            self.assertIn("learning_rate: 0.001", f.read())

    def test_tensorboard_log_as_in_sb3(self):
        # SB3: PPO(..., tensorboard_log="tb").learn(..., tb_log_name="PPO") -> tb/PPO_1/.
        tb = os.path.join(self.tmp, "tb")
        rlrun.train(CONFIG, out=os.path.join(self.tmp, "runs"), tensorboard_log=tb, tb_log_name="PPO")
        rlrun.train(CONFIG, out=os.path.join(self.tmp, "runs"), tensorboard_log=tb, tb_log_name="PPO")
        self.assertEqual(sorted(os.listdir(tb)), ["PPO_1", "PPO_2"])
        files = os.listdir(os.path.join(tb, "PPO_2"))
        self.assertEqual(len(files), 1)
        self.assertTrue(files[0].startswith("events.out.tfevents."))

    def test_file_config_and_bad_keys(self):
        path = os.path.join(self.tmp, "typo.yaml")
        with open(path, "w") as f:
            f.write("env:\n  id: CartPole-v1\nalgo:\n  id: PPO\n  n_stpes: 32\n")
        with self.assertRaises(rlrun.ConfigError) as caught:
            rlrun.train(path, out=os.path.join(self.tmp, "runs"))
        message = str(caught.exception)
        self.assertIsInstance(caught.exception, ValueError)
        self.assertIn(path + ":5:3", message)
        self.assertIn("did you mean 'n_steps'", message)
        code, output = run_rlrun("train", path, check=False)
        self.assertEqual(code, 2)
        self.assertIn(message.splitlines()[0], output)
        bad = dict(CONFIG, algo=dict(CONFIG["algo"], clip_rnage=0.1))
        with self.assertRaisesRegex(rlrun.ConfigError, r"rlrun.train\(dict\):\d+:\d+: .*did you mean 'clip_range'"):
            rlrun.train(bad, out=os.path.join(self.tmp, "runs"))
        with self.assertRaisesRegex(rlrun.ConfigError, "did you mean 'learning_rate'"):
            rlrun.train(CONFIG, {"algo.learnig_rate": 0.1}, out=os.path.join(self.tmp, "runs"))
        with self.assertRaisesRegex(TypeError, "unknown override 'lr'"):
            rlrun.train(CONFIG, lr=0.1)


    def test_training_releases_the_gil(self):
        # Another Python thread keeps running while rlrun trains.
        import threading

        counter, stop = [0], threading.Event()

        def count():
            while not stop.is_set():
                counter[0] += 1

        thread = threading.Thread(target=count)
        thread.start()
        start, t0 = counter[0], time.perf_counter()
        time.sleep(0.1)
        free_rate = (counter[0] - start) / (time.perf_counter() - t0)  # the thread alone
        start, t0 = counter[0], time.perf_counter()
        rlrun.train(CONFIG, out=os.path.join(self.tmp, "gil"), timesteps=50000,
                    **{"run.console_interval": 10**9})
        during, seconds = counter[0] - start, time.perf_counter() - t0
        stop.set()
        thread.join()
        # Holding the GIL, the thread would count only in the Python around the C++ call.
        self.assertGreater(during, 0.25 * free_rate * seconds)

    def test_ctrl_c_stops_training_cleanly(self):
        # A long training in a child interpreter; SIGINT stops it at the next safe point with
        # a checkpoint, rlrun.train raises KeyboardInterrupt, Python's handler is back.
        script = f"""
import os, signal, sys, time, rlrun
config = {CONFIG!r}
config["run"]["total_timesteps"] = 10**9
config["checkpoint"] = {{"freq": 10**8}}
try:
    rlrun.train(config, out={os.path.join(self.tmp, "ctrl_c")!r})
except KeyboardInterrupt as e:
    print("interrupted:", e)
try:  # Python's own SIGINT handling is back: a second Ctrl-C is a KeyboardInterrupt again
    os.kill(os.getpid(), signal.SIGINT)
    time.sleep(5)
except KeyboardInterrupt:
    print("handler restored: True")
    sys.exit(0)
sys.exit(3)
"""
        child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                                 stderr=subprocess.STDOUT, text=True)
        progress = os.path.join(self.tmp, "ctrl_c", "tiny", "seed1", "progress.csv")
        deadline = time.time() + 60
        while not os.path.exists(progress) and time.time() < deadline:
            time.sleep(0.05)
        time.sleep(0.3)
        child.send_signal(signal.SIGINT)
        output, _ = child.communicate(timeout=60)
        self.assertEqual(child.returncode, 0, output)
        self.assertIn("interrupted: training interrupted at step", output)
        self.assertIn("handler restored: True", output)
        checkpoints = os.path.join(self.tmp, "ctrl_c", "tiny", "seed1", "checkpoints")
        self.assertTrue(os.listdir(checkpoints), output)


if __name__ == "__main__":
    unittest.main()
