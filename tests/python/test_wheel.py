"""The wheel (python/build_wheel.py) installs into a virtualenv with one command and no
network — `VENV/bin/pip install --no-index rlrun-*.whl` (docs/python.md) — and works there."""

import glob
import os
import subprocess
import sys
import unittest
import zipfile

import rlrun
from rlrun_testing import TempDirMixin

SOURCE = os.environ.get("RLRUN_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "../.."))


class WheelInVirtualenv(TempDirMixin, unittest.TestCase):
    def test_pip_install_no_index(self):
        package = os.path.dirname(rlrun.__file__)
        dist = os.path.join(self.tmp, "dist")
        subprocess.run([sys.executable, os.path.join(SOURCE, "python", "build_wheel.py"),
                        "--package", package, "--version", rlrun.__version__, "--out", dist],
                       check=True, stdout=subprocess.PIPE)
        wheels = glob.glob(os.path.join(dist, f"rlrun-{rlrun.__version__}-cp*-cp*-linux_*.whl"))
        self.assertEqual(len(wheels), 1, os.listdir(dist))
        with zipfile.ZipFile(wheels[0]) as whl:
            names = whl.namelist()
            self.assertIn("rlrun/__init__.py", names)
            self.assertTrue(any(n.startswith("rlrun/_core.") and n.endswith(".so") for n in names))
            # The shipped data travels in the wheel: the extension finds it beside itself.
            for data in ("configs/cartpole_ppo.yaml", "scenarios/grasp/lift.yaml",
                         "sumo_data/single_intersection/single.sumocfg"):
                self.assertIn("rlrun/share/rlrun/" + data, names)
            # TrafficNetwork-v0's SUMO worker and the libsumo module it loads, executable.
            for helper in ("rlrun/rlrun-sumo-worker", "rlrun/librlrun_libsumo.so"):
                self.assertIn(helper, names)
                self.assertTrue((whl.getinfo(helper).external_attr >> 16) & 0o100)
            record = whl.read(f"rlrun-{rlrun.__version__}.dist-info/RECORD").decode()
            self.assertIn("rlrun/__init__.py,sha256=", record)

        venv = os.path.join(self.tmp, "venv")
        # --system-site-packages: the venv sees Debian's numpy (and gymnasium, if installed).
        subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", venv], check=True)
        env = {k: v for k, v in os.environ.items()
               if k not in ("PYTHONPATH", "PYTHONHOME", "RLRUN_DATA_DIR")}
        install = subprocess.run([os.path.join(venv, "bin", "pip"), "install", "--no-index", wheels[0]],
                                 stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
        self.assertEqual(install.returncode, 0, install.stdout)
        script = (
            "import os, rlrun\n"
            "assert os.path.realpath(rlrun.__file__).startswith(os.path.realpath(os.environ['VENV'])), rlrun.__file__\n"
            "env = rlrun.make('CartPole-v1')\n"
            "obs, _ = env.reset(seed=0)\n"
            "obs, r, te, tr, _ = env.step(1)\n"
            "print('ok', obs.shape, r)\n"
            "grasp = rlrun.make('GripperLift-v0')  # reads rlrun/share/rlrun/scenarios/grasp/lift.yaml\n"
            "print('grasp', grasp.reset(seed=0)[0].shape)\n"
            "# 16 traffic lights over libsumo, two SUMOs in the package's own worker processes\n"
            "net = rlrun.make_vec('TrafficNetwork-v0', 2, num_seconds=30)\n"
            "print('network', net.reset(seed=0)[0].shape)\n"
        )
        run = subprocess.run([os.path.join(venv, "bin", "python"), "-c", script], cwd=self.tmp,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                             env=dict(env, VENV=venv))
        self.assertEqual(run.returncode, 0, run.stdout)
        self.assertIn("ok (4,) 1.0", run.stdout)
        self.assertIn("grasp (26,)", run.stdout)
        self.assertIn("network (32, 29)", run.stdout)


if __name__ == "__main__":
    unittest.main()
