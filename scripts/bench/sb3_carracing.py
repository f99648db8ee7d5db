"""SB3 2.4.1's PPO with the zoo's CarRacing-v3 settings (rl-baselines3-zoo hyperparams/ppo.yml,
CarRacing entry, as configs/zoo/carracing_ppo.yaml imports it), driving rlrun's own
CarRacing-v3 through the rlrun Python package (Debian has no Box2D Python bindings; the car and
track are the same on both sides). Half of scripts/bench/sb3_carracing.sh; needs SB3, torch and
Gymnasium importable, and cv2 for Gymnasium's ResizeObservation (python3-opencv).
    python scripts/bench/sb3_carracing.py STEPS SEED [TORCH_THREADS]
TORCH_THREADS defaults to 1, SB3's fastest here (2: 63.0 s against 50.8 s for 8192 steps)."""

import sys
import time

import gymnasium as gym
import rlrun
import torch
from stable_baselines3 import PPO
from stable_baselines3.common.env_util import make_vec_env
from stable_baselines3.common.vec_env import VecFrameStack, VecNormalize

torch.set_num_threads(int(sys.argv[3]) if len(sys.argv) > 3 else 1)


class FrameSkip(gym.Wrapper):
    """rl_zoo3.wrappers.FrameSkip: the action repeated `skip` times, rewards summed."""

    def __init__(self, env, skip=2):
        super().__init__(env)
        self._skip = skip

    def step(self, action):
        total = 0.0
        for _ in range(self._skip):
            obs, reward, terminated, truncated, info = self.env.step(action)
            total += float(reward)
            if terminated or truncated:
                break
        return obs, total, terminated, truncated, info


def wrapped(env):
    # env_wrapper of the zoo's entry: FrameSkip 2, ResizeObservation 64, GrayScaleObservation
    # keep_dim (Gymnasium's names since 1.0).
    env = FrameSkip(env, skip=2)
    env = gym.wrappers.ResizeObservation(env, (64, 64))
    return gym.wrappers.GrayscaleObservation(env, keep_dim=True)


steps, seed = int(sys.argv[1]), int(sys.argv[2])
start = time.time()
vec_env = make_vec_env(lambda: rlrun.make("CarRacing-v3"), n_envs=8, seed=seed,
                       wrapper_class=wrapped)
# rl_zoo3's ExperimentManager.create_envs: normalize, then frame_stack.
vec_env = VecFrameStack(VecNormalize(vec_env, norm_obs=False, norm_reward=True), n_stack=2)
model = PPO("CnnPolicy", vec_env, batch_size=128, n_steps=512, gamma=0.99, gae_lambda=0.95,
            n_epochs=10, ent_coef=0.0, sde_sample_freq=4, max_grad_norm=0.5, vf_coef=0.5,
            learning_rate=lambda progress: 1e-4 * progress, use_sde=True, clip_range=0.2,
            policy_kwargs=dict(log_std_init=-2, ortho_init=False, activation_fn=torch.nn.GELU,
                               net_arch=dict(pi=[256], vf=[256])),
            seed=seed, verbose=0)
model.learn(total_timesteps=steps)
print(f"sb3 {steps} steps {time.time() - start:.2f} s")
