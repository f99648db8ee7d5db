"""Shared helpers of the Python package's tests (tests/CMakeLists.txt runs them with Debian's
python3 and PYTHONPATH=build/python; RLRUN_BINARY names the rlrun binary of the same build)."""

import csv
import os
import shutil
import subprocess
import tempfile
import unittest

import numpy as np

BINARY = os.environ.get("RLRUN_BINARY", os.path.join(os.path.dirname(__file__), "../../build/rlrun"))


def run_rlrun(*args, check=True, cwd=None):
    """Runs the rlrun binary; returns (exit code, stdout + stderr)."""
    p = subprocess.run([BINARY, *map(str, args)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, cwd=cwd)
    if check and p.returncode != 0:
        raise AssertionError(f"rlrun {' '.join(map(str, args))} exited {p.returncode}:\n{p.stdout}")
    return p.returncode, p.stdout


def read_trajectory(path):
    """`rlrun eval --trajectory` rows as dicts: episode, step, obs (float32), action (float32),
    reward, terminated, truncated."""
    rows = []
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        obs_cols = [i for i, h in enumerate(header) if h.startswith("obs_")]
        act_cols = [i for i, h in enumerate(header) if h.startswith("action_")]
        for cells in reader:
            rows.append({
                "episode": int(cells[0]),
                "step": int(cells[1]),
                # float32 text with 9 significant digits: parses back to the exact float32.
                "obs": np.array([np.float32(cells[i]) for i in obs_cols], dtype=np.float32),
                "action": np.array([np.float32(cells[i]) for i in act_cols], dtype=np.float32),
                "reward": float(cells[-3]),
                "terminated": cells[-2] == "1",
                "truncated": cells[-1] == "1",
            })
    return rows


def train_model(directory, name, yaml_text, timesteps=None):
    """Trains `yaml_text` with the real binary into `directory`; returns model.zip's path."""
    config = os.path.join(directory, name + ".yaml")
    with open(config, "w") as f:
        f.write(yaml_text)
    args = ["train", config, "--out", os.path.join(directory, "runs")]
    if timesteps:
        args += ["--timesteps", timesteps]
    run_rlrun(*args)
    return os.path.join(directory, "runs", name, "seed1", "model.zip")


class TempDirMixin:
    """setUpClass/tearDownClass with a temporary directory `cls.tmp`."""

    @classmethod
    def setUpClass(cls):
        cls._tmp = tempfile.TemporaryDirectory(prefix="rlrun_py_")
        cls.tmp = cls._tmp.name

    @classmethod
    def tearDownClass(cls):
        cls._tmp.cleanup()


def compiled_cpp_lines(directory, name, source, *args):
    """Compiles C++ `source` (-O0: no fused multiply-adds) in `directory`, runs it with `args` and
    returns its output's lines split into fields; skips the test without a C++ compiler."""
    compiler = shutil.which("c++") or shutil.which("g++")
    if compiler is None:
        raise unittest.SkipTest("no C++ compiler to write the reference values")
    binary = os.path.join(directory, name)
    if not os.path.exists(binary):
        with open(binary + ".cpp", "w") as f:
            f.write(source)
        subprocess.run([compiler, "-O0", "-o", binary, binary + ".cpp"], check=True)
    out = subprocess.run([binary, *map(str, args)], check=True, capture_output=True, text=True)
    return [line.split() for line in out.stdout.splitlines()]
