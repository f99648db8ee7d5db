"""SB3 2.4.1's SAC with the zoo's HalfCheetah-v4 settings, driving rlrun's own HalfCheetah-v4
through the rlrun Python package (Debian has no MuJoCo Python bindings; the physics is the same
on both sides). Half of scripts/bench/sb3_mujoco.sh; needs SB3 + torch importable.
    python scripts/bench/sb3_mujoco.py STEPS SEED"""

import sys
import time

import rlrun
import torch
from stable_baselines3 import SAC

torch.set_num_threads(1)

steps, seed = int(sys.argv[1]), int(sys.argv[2])
start = time.time()
env = rlrun.make("HalfCheetah-v4")
# rl-baselines3-zoo hyperparams/sac.yml, HalfCheetah-v4 (&mujoco-defaults): learning_starts
# 10000, SB3's defaults otherwise.
model = SAC("MlpPolicy", env, learning_starts=10000, seed=seed, verbose=0)
model.learn(total_timesteps=steps)
print(f"sb3 {steps} steps {time.time() - start:.2f} s")
