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

        # Another Debian 12 machine lacks the -dev packages' libraries: what the extension
        # loads must come from the wheel (rlrun/.libs) or the base system every Debian 12 has.
        # The dynamic loader's own log (LD_DEBUG=libs) of this process after numpy's import
        # names every library it initialises.
        probe = ("import os, sys, numpy\n"
                 "os.write(2, f'RLRUN-IMPORT {os.getpid()}\\n'.encode())\n"
                 "import rlrun\n"
                 "rlrun.make('CartPole-v1').reset(seed=0)\n")
        run = subprocess.run([os.path.join(venv, "bin", "python"), "-c", probe], cwd=self.tmp,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             env=dict(env, LD_DEBUG="libs"))
        self.assertEqual(run.returncode, 0, run.stderr[-3000:])
        marker = next(line for line in run.stderr.splitlines() if line.startswith("RLRUN-IMPORT"))
        pid = marker.split()[1]
        after = run.stderr[run.stderr.index(marker):]
        loaded = [line.split("calling init:")[1].strip() for line in after.splitlines()
                  if line.strip().startswith(pid + ":") and "calling init:" in line]
        package = os.path.realpath(os.path.dirname(subprocess.run(
            [os.path.join(venv, "bin", "python"), "-c", "import rlrun; print(rlrun.__file__)"],
            stdout=subprocess.PIPE, text=True, env=env, check=True).stdout.strip()))
        self.assertTrue(any(p.endswith("libyaml-cpp.so.0.7") for p in loaded), loaded)
        # Debian 12's base system, and what its python3.11 itself depends on (the stdlib's
        # extension modules load these: _ssl, _ctypes, pyexpat, _bz2, _lzma, ...).
        base = ("libc.so", "libm.so", "libgcc_s.so", "libstdc++.so", "libz.so", "ld-linux",
                "libcrypto.so", "libssl.so", "libffi.so", "libexpat.so", "libbz2.so",
                "liblzma.so", "libmpdec.so", "libuuid.so", "libsqlite3.so", "libtinfo.so",
                "libncursesw.so", "libreadline.so")
        for path in loaded:
            real = os.path.realpath(path)
            if real.startswith(package) or "/python3" in real:  # the wheel; Python's own modules
                continue
            self.assertTrue(os.path.basename(path).startswith(base),
                            f"{path} was loaded from outside the wheel: {loaded}")


if __name__ == "__main__":
    unittest.main()
