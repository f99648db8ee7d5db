#!/usr/bin/env python3
"""Makes small real Stable-Baselines3 model files and reference predictions for rlrun's tests.

Each case under OUT (tests/data/sb3/<case>/) gets:

* model.zip: written by SB3's own model.save() after a short training run, so the weights are no
  longer the initial ones (a loader that silently ignored policy.pth would still be caught);
* observations.npy (observations.npz for the Dict-observation case): 1000 observations met by
  stepping the env with seeded random actions, resetting on termination or truncation, so they
  cover states the policy really sees and not only reset states;
* actions.npy: model.predict(observations, deterministic=True)[0], in SB3's own dtype;
* network outputs for the same observations, so a port can be checked with a tolerance and not
  only through argmax (a few observations sit within 1e-3 of a tie between two actions, and
  the short DQN run picks the same action everywhere): action_log_probs.npy (PPO/A2C with a
  Discrete action: the Categorical's log-probabilities, float32 (1000, n)), values.npy (PPO/A2C:
  the critic's value, float32 (1000, 1)), q_values.npy (DQN: q_net's output, float32 (1000, n));
* returns.json: one deterministic episode per seed 0..4 on a fresh gymnasium.make(env_id),
  stepped by hand (no SB3 VecEnv, so no auto-reset or observation wrapping in between);
* info.json: how the model was made and with which versions.

It also writes two deliberately malicious model files for rlrun's loader security tests
(evil_os_system, evil_torch); they are made by patching bytes and are NEVER loaded here.

Needs SB3 2.4.1 and Gymnasium 1.0.0 importable and Debian 12's torch (1.13.1); see
make_sb3_models.sh, which sets that up. Usage:

    PYTHONPATH=SB3_SRC:GYMNASIUM_SRC /usr/bin/python3 scripts/data/make_sb3_models.py tests/data/sb3 [CASE...]

(CASE: remake only those cases, e.g. ppo_cartpole; evil_* are always remade from ppo_cartpole.)
"""
import base64
import io
import json
import os
import pickle
import platform
import sys
import zipfile

import gymnasium as gym
import numpy as np
import torch

import stable_baselines3
from stable_baselines3 import A2C, DDPG, DQN, PPO, SAC, TD3
from stable_baselines3.common.vec_env import DummyVecEnv, VecFrameStack, VecNormalize

try:  # sb3-contrib's cases are made when it is importable (make_sb3_models.sh: SB3_CONTRIB_SRC)
    import sb3_contrib
    from sb3_contrib import QRDQN, TQC, TRPO, MaskablePPO, RecurrentPPO
    from sb3_contrib.common.wrappers import ActionMasker
except ImportError:
    sb3_contrib = None

N_OBS = 1000
RETURN_SEEDS = [0, 1, 2, 3, 4]
# Seed for the random-action walk that gathers observations; any fixed number, distinct from the
# training seed (0) so the observations are not the very states the model was trained on.
OBS_SEED = 12345
# The command the malicious pickles would run if a loader ever executed them; the security tests
# check that this file does not appear.
EVIL_COMMAND = "touch /tmp/rlrun_pwned"


class DictObsEnv(gym.Env):
    """A tiny env with a Dict observation, for SB3's MultiInputPolicy.

    Observation Dict(a=Box(-1,1,(3,)), b=Box(0,1,(2,))), action Discrete(2). Reward 1 when the
    action matches the sign of a[0] (so training has something to learn), episodes are 20 steps.
    """

    metadata = {"render_modes": []}

    def __init__(self):
        super().__init__()
        self.observation_space = gym.spaces.Dict(
            {
                "a": gym.spaces.Box(-1.0, 1.0, (3,), dtype=np.float32),
                "b": gym.spaces.Box(0.0, 1.0, (2,), dtype=np.float32),
            }
        )
        self.action_space = gym.spaces.Discrete(2)
        self._t = 0
        self._obs = None

    def _sample(self):
        return {
            "a": self.np_random.uniform(-1.0, 1.0, 3).astype(np.float32),
            "b": self.np_random.uniform(0.0, 1.0, 2).astype(np.float32),
        }

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        self._t = 0
        self._obs = self._sample()
        return self._obs, {}

    def step(self, action):
        reward = 1.0 if int(action) == int(self._obs["a"][0] > 0) else 0.0
        self._t += 1
        self._obs = self._sample()
        return self._obs, reward, False, self._t >= 20, {}


def make_env(env_id):
    if env_id == "DictObsEnv":
        # Wrapped in a TimeLimit like gymnasium.make would do, though the env truncates itself.
        return gym.wrappers.TimeLimit(DictObsEnv(), max_episode_steps=20)
    return gym.make(env_id)


# case -> (algorithm class, policy, env id, constructor kwargs, training steps).
# Nets are small where the brief allows it so every model.zip stays far below 200 KB.
CASES = {
    "ppo_cartpole": (PPO, "MlpPolicy", "CartPole-v1", dict(n_steps=256, batch_size=64), 512),
    "a2c_cartpole": (A2C, "MlpPolicy", "CartPole-v1", dict(policy_kwargs=dict(net_arch=[32, 32])), 500),
    "dqn_cartpole": (
        DQN,
        "MlpPolicy",
        "CartPole-v1",
        dict(policy_kwargs=dict(net_arch=[32, 32]), learning_starts=100, buffer_size=1000),
        600,
    ),
    "ppo_pendulum": (
        PPO,
        "MlpPolicy",
        "Pendulum-v1",
        dict(
            policy_kwargs=dict(net_arch=dict(pi=[32, 32], vf=[16]), activation_fn=torch.nn.ReLU),
            n_steps=256,
            batch_size=64,
        ),
        512,
    ),
    "sac_pendulum": (
        SAC,
        "MlpPolicy",
        "Pendulum-v1",
        dict(policy_kwargs=dict(net_arch=[32, 32]), learning_starts=100, buffer_size=1000),
        300,
    ),
    "td3_pendulum": (
        TD3,
        "MlpPolicy",
        "Pendulum-v1",
        dict(policy_kwargs=dict(net_arch=[32, 32]), learning_starts=100, buffer_size=1000),
        300,
    ),
    "ddpg_pendulum": (
        DDPG,
        "MlpPolicy",
        "Pendulum-v1",
        dict(policy_kwargs=dict(net_arch=[32, 32]), learning_starts=100, buffer_size=1000),
        300,
    ),
    "ppo_multi_input": (
        PPO,
        "MultiInputPolicy",
        "DictObsEnv",
        dict(policy_kwargs=dict(net_arch=[16]), n_steps=256, batch_size=64),
        512,
    ),
    # gSDE, as many of rl-zoo's continuous-control entries train (use_sde=True): the policy has
    # a log_std matrix per latent feature and action, and SAC's mean a Hardtanh (clip_mean).
    "ppo_sde_pendulum": (
        PPO,
        "MlpPolicy",
        "Pendulum-v1",
        dict(use_sde=True, sde_sample_freq=4, policy_kwargs=dict(net_arch=[32], log_std_init=-1.0),
             n_steps=256, batch_size=64),
        512,
    ),
    "sac_sde_pendulum": (
        SAC,
        "MlpPolicy",
        "Pendulum-v1",
        dict(use_sde=True, policy_kwargs=dict(net_arch=[32, 32], log_std_init=-2),
             learning_starts=100, buffer_size=1000),
        300,
    ),
}
if sb3_contrib is not None:
    CASES["qrdqn_cartpole"] = (
        QRDQN,
        "MlpPolicy",
        "CartPole-v1",
        dict(policy_kwargs=dict(net_arch=[32, 32], n_quantiles=10), learning_starts=100,
             buffer_size=1000, target_update_interval=100),
        600,
    )
    # MaskablePPO trains behind sb3-contrib's ActionMasker (every action allowed here);
    # predict without masks is the argmax over all actions.
    CASES["maskable_ppo_cartpole"] = (
        MaskablePPO,
        "MlpPolicy",
        "CartPole-v1",
        dict(policy_kwargs=dict(net_arch=[32]), n_steps=256, batch_size=64),
        512,
    )
    # RecurrentPPO: actions.npy is predict() on the 1000 observations as 1000 envs from a zero
    # LSTM state; returns.json carries the state along each episode.
    CASES["recurrent_ppo_cartpole"] = (
        RecurrentPPO,
        "MlpLstmPolicy",
        "CartPole-v1",
        dict(policy_kwargs=dict(lstm_hidden_size=16, net_arch=[16]), n_steps=128, batch_size=64),
        256,
    )
    CASES["recurrent_ppo_pendulum"] = (
        RecurrentPPO,
        "MlpLstmPolicy",
        "Pendulum-v1",
        dict(policy_kwargs=dict(lstm_hidden_size=16, n_lstm_layers=2, shared_lstm=True,
                                enable_critic_lstm=False, net_arch=[16]),
             n_steps=128, batch_size=64),
        256,
    )
    CASES["trpo_pendulum"] = (
        TRPO,
        "MlpPolicy",
        "Pendulum-v1",
        dict(policy_kwargs=dict(net_arch=[32]), n_steps=256, batch_size=64),
        512,
    )
    CASES["tqc_pendulum"] = (
        TQC,
        "MlpPolicy",
        "Pendulum-v1",
        dict(policy_kwargs=dict(net_arch=[32, 32], n_quantiles=5, n_critics=2),
             learning_starts=100, buffer_size=1000),
        300,
    )


def gather_observations(env_id):
    """N_OBS observations from a seeded random-action walk, resetting when an episode ends."""
    env = make_env(env_id)
    env.action_space.seed(OBS_SEED)
    obs, _ = env.reset(seed=OBS_SEED)
    collected = []
    while len(collected) < N_OBS:
        collected.append(obs)
        obs, _, terminated, truncated, _ = env.step(env.action_space.sample())
        if terminated or truncated:
            obs, _ = env.reset()
    env.close()
    if isinstance(collected[0], dict):
        return {k: np.stack([o[k] for o in collected]).astype(np.float32) for k in collected[0]}
    return np.stack(collected).astype(np.float32)


def episode_returns(model, env_id):
    """One deterministic episode per seed on a fresh env, stepped by hand."""
    returns = []
    for seed in RETURN_SEEDS:
        env = make_env(env_id)
        obs, _ = env.reset(seed=seed)
        total, done, state, first = 0.0, False, None, True
        while not done:
            # A recurrent policy carries its state along the episode (reset at its start);
            # the others ignore state and episode_start.
            action, state = model.predict(obs, state=state, episode_start=np.array([first]),
                                          deterministic=True)
            first = False
            obs, reward, terminated, truncated, _ = env.step(action)
            total += float(reward)
            done = terminated or truncated
        env.close()
        returns.append(total)
    return returns


def save_network_outputs(model, observations, case_dir):
    """Writes the raw network outputs behind the actions (see the module docstring); returns
    {file name: smallest gap between the two highest entries per row} for the discrete ones
    (how close the closest observation is to an argmax tie), or None for values.npy."""
    written = {}
    policy = model.policy
    with torch.no_grad():
        obs_t, _ = policy.obs_to_tensor(observations)
        outputs = {}
        if isinstance(model, DQN):
            outputs["q_values.npy"] = policy.q_net(obs_t)
        elif isinstance(model, (PPO, A2C)):
            if isinstance(model.action_space, gym.spaces.Discrete):
                outputs["action_log_probs.npy"] = policy.get_distribution(obs_t).distribution.logits
            outputs["values.npy"] = policy.predict_values(obs_t)
    for file_name, tensor in outputs.items():
        array = tensor.cpu().numpy().astype(np.float32)
        np.save(os.path.join(case_dir, file_name), array)
        gap = None
        if file_name != "values.npy":
            top2 = np.sort(array, axis=1)[:, -2:]
            gap = float((top2[:, 1] - top2[:, 0]).min())
        written[file_name] = gap
    return written


def make_case(out_dir, name, spec):
    algo, policy, env_id, kwargs, steps = spec
    case_dir = os.path.join(out_dir, name)
    os.makedirs(case_dir, exist_ok=True)
    # The env the model trains on; SB3 wraps it in a DummyVecEnv (and Monitor) itself.
    env = make_env(env_id)
    if sb3_contrib is not None and algo is MaskablePPO:
        env = ActionMasker(env, lambda e: np.ones(e.action_space.n, dtype=bool))
    model = algo(policy, env, seed=0, device="cpu", verbose=0, **kwargs)
    model.learn(total_timesteps=steps)
    model.save(os.path.join(case_dir, "model.zip"))

    observations = gather_observations(env_id)
    actions = model.predict(observations, deterministic=True)[0]
    if isinstance(observations, dict):
        np.savez(os.path.join(case_dir, "observations.npz"), **observations)
    else:
        np.save(os.path.join(case_dir, "observations.npy"), observations)
    np.save(os.path.join(case_dir, "actions.npy"), actions)
    extra = save_network_outputs(model, observations, case_dir)

    with open(os.path.join(case_dir, "returns.json"), "w") as f:
        json.dump({"seeds": RETURN_SEEDS, "episode_returns": episode_returns(model, env_id)}, f, indent=2)
        f.write("\n")

    info = {
        "algorithm": algo.__name__,
        "env_id": env_id,
        "policy": policy,
        "policy_kwargs": repr(kwargs.get("policy_kwargs", {})),
        "other_kwargs": repr({k: v for k, v in kwargs.items() if k != "policy_kwargs"}),
        "seed": 0,
        "device": "cpu",
        "training_timesteps": steps,
        "num_timesteps_after_training": int(model.num_timesteps),
        "observation_seed": OBS_SEED,
        "actions_dtype": str(actions.dtype),
        "actions_shape": list(actions.shape),
        "network_outputs": extra,
        "stable_baselines3": stable_baselines3.__version__,
        "torch": torch.__version__,
        "gymnasium": gym.__version__,
        "numpy": np.__version__,
        "python": platform.python_version(),
    }
    if algo.__module__.startswith("sb3_contrib"):
        info["sb3_contrib"] = sb3_contrib.__version__
    if env_id == "DictObsEnv":
        info["env_note"] = "DictObsEnv is defined in scripts/data/make_sb3_models.py"
    with open(os.path.join(case_dir, "info.json"), "w") as f:
        json.dump(info, f, indent=2)
        f.write("\n")
    print(f"{name}: {info['actions_dtype']} {info['actions_shape']} returns written", flush=True)


VEC_NORMALIZE_CASE = "ppo_pendulum_vecnormalize"


FRAME_STACK_CASE = "ppo_cartpole_framestack"


def make_frame_stack_case(out_dir):
    """PPO on CartPole-v1 trained inside VecFrameStack(n_stack=2), as rl-zoo's `frame_stack: 2`
    wraps the env: observations.npy holds stacked observations (oldest frame first) met by a
    seeded random walk through a VecFrameStack; returns.json one deterministic episode per seed
    through a fresh VecFrameStack (zero padding after reset), as rl_zoo3.enjoy plays it."""
    case_dir = os.path.join(out_dir, FRAME_STACK_CASE)
    os.makedirs(case_dir, exist_ok=True)

    def stacked():
        return VecFrameStack(DummyVecEnv([lambda: make_env("CartPole-v1")]), n_stack=2)

    model = PPO("MlpPolicy", stacked(), seed=0, device="cpu", verbose=0, n_steps=256,
                batch_size=64, policy_kwargs=dict(net_arch=[16]))
    model.learn(total_timesteps=512)
    model.save(os.path.join(case_dir, "model.zip"))
    venv = stacked()
    venv.seed(OBS_SEED)
    venv.action_space.seed(OBS_SEED)
    obs = venv.reset()
    collected = []
    while len(collected) < N_OBS:
        collected.append(obs[0])
        obs, _, _, _ = venv.step(np.array([venv.action_space.sample()]))
    observations = np.stack(collected).astype(np.float32)
    np.save(os.path.join(case_dir, "observations.npy"), observations)
    np.save(os.path.join(case_dir, "actions.npy"),
            model.predict(observations, deterministic=True)[0])
    returns = []
    for seed in RETURN_SEEDS:
        venv = stacked()
        venv.seed(seed)
        obs = venv.reset()
        total, done = 0.0, False
        while not done:
            obs, reward, dones, _ = venv.step(model.predict(obs, deterministic=True)[0])
            total += float(reward[0])
            done = bool(dones[0])
        returns.append(total)
    with open(os.path.join(case_dir, "returns.json"), "w") as f:
        json.dump({"seeds": RETURN_SEEDS, "episode_returns": returns}, f, indent=2)
        f.write("\n")
    info = {"algorithm": "PPO", "env_id": "CartPole-v1", "policy": "MlpPolicy",
            "policy_kwargs": "{'net_arch': [16]}", "frame_stack": "VecFrameStack(n_stack=2)",
            "training_timesteps": 512, "stable_baselines3": stable_baselines3.__version__,
            "torch": torch.__version__, "gymnasium": gym.__version__, "numpy": np.__version__}
    with open(os.path.join(case_dir, "info.json"), "w") as f:
        json.dump(info, f, indent=2)
        f.write("\n")
    print(f"{FRAME_STACK_CASE}: returns written", flush=True)


def make_vec_normalize_case(out_dir):
    """PPO on Pendulum-v1 trained inside VecNormalize (observations and rewards, gamma 0.98),
    saved as rl-zoo saves a run: model.zip and vecnormalize.pkl side by side. observations.npy
    holds the env's raw observations; actions.npy and returns.json are SB3's with the
    statistics frozen (training=False, norm_reward=False), as rl_zoo3.enjoy plays a model."""
    case_dir = os.path.join(out_dir, VEC_NORMALIZE_CASE)
    os.makedirs(case_dir, exist_ok=True)
    venv = VecNormalize(DummyVecEnv([lambda: make_env("Pendulum-v1")]), gamma=0.98)
    model = PPO("MlpPolicy", venv, seed=0, device="cpu", verbose=0, n_steps=256, batch_size=64,
                gamma=0.98, policy_kwargs=dict(net_arch=[16]))
    model.learn(total_timesteps=512)
    model.save(os.path.join(case_dir, "model.zip"))
    pkl = os.path.join(case_dir, "vecnormalize.pkl")
    venv.save(pkl)
    frozen = VecNormalize.load(pkl, DummyVecEnv([lambda: make_env("Pendulum-v1")]))
    frozen.training = False
    frozen.norm_reward = False

    def act(obs):
        return model.predict(frozen.normalize_obs(obs), deterministic=True)[0]

    observations = gather_observations("Pendulum-v1")
    np.save(os.path.join(case_dir, "observations.npy"), observations)
    np.save(os.path.join(case_dir, "actions.npy"), act(observations))
    returns = []
    for seed in RETURN_SEEDS:
        env = make_env("Pendulum-v1")
        obs, _ = env.reset(seed=seed)
        total, done = 0.0, False
        while not done:
            obs, reward, terminated, truncated, _ = env.step(act(obs))
            total += float(reward)
            done = terminated or truncated
        returns.append(total)
    with open(os.path.join(case_dir, "returns.json"), "w") as f:
        json.dump({"seeds": RETURN_SEEDS, "episode_returns": returns}, f, indent=2)
        f.write("\n")
    info = {"algorithm": "PPO", "env_id": "Pendulum-v1", "policy": "MlpPolicy",
            "policy_kwargs": "{'net_arch': [16]}", "vec_normalize": "VecNormalize(gamma=0.98)",
            "training_timesteps": 512, "stable_baselines3": stable_baselines3.__version__,
            "torch": torch.__version__, "gymnasium": gym.__version__, "numpy": np.__version__}
    with open(os.path.join(case_dir, "info.json"), "w") as f:
        json.dump(info, f, indent=2)
        f.write("\n")
    print(f"{VEC_NORMALIZE_CASE}: written", flush=True)


CNN_CASE = "ppo_cnn_gripper_pixels"
CNN_OBSERVATIONS = 32  # 36x36x3 uint8 images: 124 KB of observations.npy


class PixelStand(gym.Env):
    """An env with an rlrun task's image spaces and random images: SB3 builds and updates its
    CnnPolicy (NatureCNN after VecTransposeImage) on it. No physics: only the spaces matter to
    the file, and the test compares predictions on the saved images. By default the spaces of
    rlrun's GripperLift-v0 with obs_type: pixels, image_size: 36 (a uint8 camera image, Box(4)
    moves in [-1, 1])."""

    def __init__(self, shape=(36, 36, 3), action_space=None):
        self.observation_space = gym.spaces.Box(0, 255, shape, np.uint8)
        self.action_space = action_space or gym.spaces.Box(-1.0, 1.0, (4,), np.float32)
        self.t = 0

    def reset(self, seed=None, options=None):
        super().reset(seed=seed)
        self.t = 0
        return self.observation_space.sample(), {}

    def step(self, action):
        self.t += 1
        obs = self.np_random.integers(0, 256, self.observation_space.shape, dtype=np.uint8)
        reward = float(-np.sum(np.square(np.asarray(action, dtype=np.float64))))
        return obs, reward, False, self.t >= 50, {}


def make_cnn_case(out_dir):
    """PPO with SB3's CnnPolicy (NatureCNN, features_dim 64 to keep the file small) after one
    update on PixelStand: model.zip, CNN_OBSERVATIONS images (HWC, as the env gives them) and
    SB3's deterministic actions and values for them."""
    env = PixelStand()
    env.reset(seed=0)
    model = PPO("CnnPolicy", env, n_steps=64, batch_size=32, n_epochs=1, seed=0,
                policy_kwargs=dict(features_extractor_kwargs=dict(features_dim=64)))
    model.learn(64)
    rng = np.random.default_rng(OBS_SEED)
    observations = rng.integers(0, 256, (CNN_OBSERVATIONS, 36, 36, 3), dtype=np.uint8)
    case_dir = os.path.join(out_dir, CNN_CASE)
    os.makedirs(case_dir, exist_ok=True)
    model.save(os.path.join(case_dir, "model.zip"))
    np.save(os.path.join(case_dir, "observations.npy"), observations)
    np.save(os.path.join(case_dir, "actions.npy"), model.predict(observations, deterministic=True)[0])
    with torch.no_grad():
        obs_t, _ = model.policy.obs_to_tensor(observations)
        np.save(os.path.join(case_dir, "values.npy"),
                model.policy.predict_values(obs_t).cpu().numpy().astype(np.float32))
    info = {"algo": "PPO", "policy": "CnnPolicy", "env": "GripperLift-v0 (obs_type: pixels, "
            "image_size: 36) spaces, PixelStand in scripts/data/make_sb3_models.py",
            "training_timesteps": 64, "stable_baselines3": stable_baselines3.__version__,
            "torch": torch.__version__, "gymnasium": gym.__version__, "numpy": np.__version__}
    with open(os.path.join(case_dir, "info.json"), "w") as f:
        json.dump(info, f, indent=2)
        f.write("\n")
    print(f"{CNN_CASE}: written", flush=True)


def save_without_optimizers(model, case_dir):
    """model.zip as SB3 saves it, less the optimizers' files (*optimizer.pth): rlrun does not
    read them, and with a CNN each holds two more copies of every extractor's weights."""
    full = os.path.join(case_dir, "full.zip")
    model.save(full)
    with zipfile.ZipFile(full) as zin, zipfile.ZipFile(os.path.join(case_dir, "model.zip"), "w",
                                                       zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            if not item.filename.endswith("optimizer.pth"):
                zout.writestr(item, zin.read(item.filename))
    os.remove(full)


def write_info(case_dir, info):
    """info.json: how the case was made, with the versions that made it."""
    info = dict(info, stable_baselines3=stable_baselines3.__version__, torch=torch.__version__,
                gymnasium=gym.__version__, numpy=np.__version__)
    with open(os.path.join(case_dir, "info.json"), "w") as f:
        json.dump(info, f, indent=2)
        f.write("\n")


# SB3's off-policy CnnPolicy: each network (DQN's q_net and its target; SAC's actor, critic
# and critic target) has its own NatureCNN. On the spaces of rlrun's pixel CartPole-v1 and
# Pendulum-v1: wrappers AddRenderObservation (36x36) and GrayscaleObservation (keep_dim), so
# Box(0, 255, (36, 36, 1), uint8). The optimizers' files are left out of the fixture (rlrun
# does not read them; each would hold two more copies of every extractor's weights).
OFF_POLICY_CNN_CASES = {
    "dqn_cnn_cartpole_pixels": (DQN, gym.spaces.Discrete(2), "CartPole-v1",
                                dict(learning_starts=32, buffer_size=200, batch_size=16,
                                     target_update_interval=16)),
    "sac_cnn_pendulum_pixels": (SAC, gym.spaces.Box(-2.0, 2.0, (1,), np.float32), "Pendulum-v1",
                                dict(learning_starts=32, buffer_size=200, batch_size=16,
                                     policy_kwargs=dict(net_arch=[32]))),
}


def make_off_policy_cnn_case(out_dir, name):
    algo, action_space, env_id, kwargs = OFF_POLICY_CNN_CASES[name]
    env = PixelStand((36, 36, 1), action_space)
    env.reset(seed=0)
    kwargs = dict(kwargs)
    policy_kwargs = dict(kwargs.pop("policy_kwargs", {}))
    policy_kwargs["features_extractor_kwargs"] = dict(features_dim=16)
    model = algo("CnnPolicy", env, seed=0, policy_kwargs=policy_kwargs, **kwargs)
    model.learn(64)
    rng = np.random.default_rng(OBS_SEED)
    observations = rng.integers(0, 256, (CNN_OBSERVATIONS, 36, 36, 1), dtype=np.uint8)
    case_dir = os.path.join(out_dir, name)
    os.makedirs(case_dir, exist_ok=True)
    save_without_optimizers(model, case_dir)
    np.save(os.path.join(case_dir, "observations.npy"), observations)
    np.save(os.path.join(case_dir, "actions.npy"),
            model.predict(observations, deterministic=True)[0])
    info = {"algo": algo.__name__, "policy": "CnnPolicy",
            "env": f"{env_id} with wrappers AddRenderObservation (36x36), GrayscaleObservation "
                   "(keep_dim) spaces, PixelStand in scripts/data/make_sb3_models.py",
            "training_timesteps": 64, "left_out": "the optimizers' files (*optimizer.pth)"}
    write_info(case_dir, info)
    print(f"{name}: written", flush=True)


class PixelStateStand(gym.Env):
    """The spaces of rlrun's GripperLift-v0 with obs_type: both, image_size: 36 (Dict of a uint8
    camera image and the 26-float state; Box(4) moves), with random values, for SB3's
    MultiInputPolicy (CombinedExtractor: a NatureCNN for the image key after VecTransposeImage,
    the state flattened)."""

    def __init__(self):
        self.observation_space = gym.spaces.Dict({
            "pixels": gym.spaces.Box(0, 255, (36, 36, 3), np.uint8),
            "state": gym.spaces.Box(-np.inf, np.inf, (26,), np.float32)})
        self.action_space = gym.spaces.Box(-1.0, 1.0, (4,), np.float32)
        self.t = 0

    def _obs(self):
        return {"pixels": self.np_random.integers(0, 256, (36, 36, 3), dtype=np.uint8),
                "state": self.np_random.normal(size=26).astype(np.float32)}

    def reset(self, seed=None, options=None):
        super().reset(seed=seed)
        self.t = 0
        return self._obs(), {}

    def step(self, action):
        self.t += 1
        return self._obs(), float(-np.sum(np.square(action))), False, self.t >= 50, {}


# MultiInputPolicy over an image and a vector: PPO's one CombinedExtractor under SB3's three
# names (an off-policy one, an extractor per network, is checked against SB3 itself by
# scripts/data/check_sb3_export.sh rather than shipped: each NatureCNN over three channels is
# 0.3 MB). cnn_output_dim 16; the optimizers' files left out.
MULTI_INPUT_CNN_CASES = {
    "ppo_multi_input_gripper_both": (PPO, dict(n_steps=64, batch_size=32, n_epochs=1)),
}


def make_multi_input_cnn_case(out_dir, name):
    algo, kwargs = MULTI_INPUT_CNN_CASES[name]
    env = PixelStateStand()
    env.reset(seed=0)
    kwargs = dict(kwargs)
    policy_kwargs = dict(kwargs.pop("policy_kwargs", {}))
    policy_kwargs["features_extractor_kwargs"] = dict(cnn_output_dim=16)
    model = algo("MultiInputPolicy", env, seed=0, policy_kwargs=policy_kwargs, **kwargs)
    model.learn(64)
    rng = np.random.default_rng(OBS_SEED)
    observations = {"pixels": rng.integers(0, 256, (CNN_OBSERVATIONS, 36, 36, 3), dtype=np.uint8),
                    "state": rng.normal(size=(CNN_OBSERVATIONS, 26)).astype(np.float32)}
    case_dir = os.path.join(out_dir, name)
    os.makedirs(case_dir, exist_ok=True)
    save_without_optimizers(model, case_dir)
    np.savez(os.path.join(case_dir, "observations.npz"), **observations)
    np.save(os.path.join(case_dir, "actions.npy"),
            model.predict(observations, deterministic=True)[0])
    info = {"algo": algo.__name__, "policy": "MultiInputPolicy",
            "env": "GripperLift-v0 (obs_type: both, image_size: 36) spaces, PixelStateStand in "
                   "scripts/data/make_sb3_models.py",
            "training_timesteps": 64, "left_out": "the optimizers' files (*optimizer.pth)"}
    write_info(case_dir, info)
    print(f"{name}: written", flush=True)


GYM_ERA_CASE = "ppo_cartpole_gym_era"


def gym_named(space_class, **kwargs):
    """A Gymnasium space that pickles under gym's module name (gym.spaces.<file>.<Class>), as
    SB3 1.x files with gym 0.21 spaces name theirs, without gym installed: a subclass placed in
    a stand-in module of that name, which is all pickle records of a class."""
    import types

    file = space_class.__module__.rsplit(".", 1)[1]
    module_name = "gym.spaces." + file
    for parent in ("gym", "gym.spaces"):  # pickle imports the module, so its parents too
        sys.modules.setdefault(parent, types.ModuleType(parent))
    module = sys.modules.setdefault(module_name, types.ModuleType(module_name))
    named = type(space_class.__name__, (space_class,), {"__module__": module_name})
    setattr(module, space_class.__name__, named)
    return named(**kwargs)


def make_gym_era_case(out_dir):
    """ppo_cartpole's model as SB3 1.x and gym 0.21 would have saved it: spaces under gym's
    module names, pickled with protocol 4 (numpy arrays through _reconstruct), and gym's
    CartPole bounds (the velocities bounded by float32's largest value where Gymnasium 1.0 has
    infinity). Same weights, so ppo_cartpole's observations and actions apply."""
    src = os.path.join(out_dir, "ppo_cartpole", "model.zip")
    with zipfile.ZipFile(src) as z:
        data = json.loads(z.read("data"))
    big = np.finfo(np.float32).max
    high = np.array([4.8, big, 0.41887903, big], dtype=np.float32)
    observation_space = gym_named(gym.spaces.Box, low=-high, high=high, dtype=np.float32)
    action_space = gym_named(gym.spaces.Discrete, n=2)
    for key, space in (("observation_space", observation_space), ("action_space", action_space)):
        data[key][":serialized:"] = base64.b64encode(pickle.dumps(space, protocol=4)).decode()
        data[key][":type:"] = str(type(space)).replace("gymnasium.spaces", "gym.spaces")
    case_dir = os.path.join(out_dir, GYM_ERA_CASE)
    os.makedirs(case_dir, exist_ok=True)
    rewrite_zip(src, os.path.join(case_dir, "model.zip"), {"data": json.dumps(data, indent=4).encode()})
    print(f"{GYM_ERA_CASE}: written", flush=True)


class _EvilReduce:
    """Pickles as a call of os.system(EVIL_COMMAND). Only ever pickled here, never unpickled."""

    def __reduce__(self):
        return (os.system, (EVIL_COMMAND,))


def evil_pickle():
    # protocol 5 as asked: STACK_GLOBAL 'posix' 'system' (os.system's module on Linux), then REDUCE.
    return pickle.dumps(_EvilReduce(), protocol=5)


def rewrite_zip(src, dst, replace):
    """Copies zip src to dst member by member, in order and with each member's own compression,
    replacing the bytes of members named in `replace` (name -> new bytes)."""
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w") as zout:
        for item in zin.infolist():
            data = replace.get(item.filename, zin.read(item.filename))
            info = zipfile.ZipInfo(item.filename, date_time=item.date_time)
            info.compress_type = item.compress_type
            info.external_attr = item.external_attr
            zout.writestr(info, data)


def make_evil(out_dir):
    src = os.path.join(out_dir, "ppo_cartpole", "model.zip")
    payload = evil_pickle()

    # 1) The data JSON's policy_class ":serialized:" (SB3 would cloudpickle.loads it on load).
    with zipfile.ZipFile(src) as z:
        data = json.loads(z.read("data"))
    data["policy_class"][":serialized:"] = base64.b64encode(payload).decode()
    os.makedirs(os.path.join(out_dir, "evil_os_system"), exist_ok=True)
    rewrite_zip(src, os.path.join(out_dir, "evil_os_system", "model.zip"), {"data": json.dumps(data, indent=4).encode()})

    # 2) policy.pth's archive/data.pkl (torch.load would unpickle it); the rest of the inner
    # torch zip (version, data/0.. tensor storages) is kept as it was.
    with zipfile.ZipFile(src) as z:
        pth = z.read("policy.pth")
    inner_out = io.BytesIO()
    with zipfile.ZipFile(io.BytesIO(pth)) as zin, zipfile.ZipFile(inner_out, "w") as zout:
        names = [i.filename for i in zin.infolist()]
        pkl_names = [n for n in names if n.endswith("/data.pkl")]
        assert len(pkl_names) == 1, names
        for item in zin.infolist():
            body = payload if item.filename == pkl_names[0] else zin.read(item.filename)
            info = zipfile.ZipInfo(item.filename, date_time=item.date_time)
            info.compress_type = item.compress_type
            zout.writestr(info, body)
    os.makedirs(os.path.join(out_dir, "evil_torch"), exist_ok=True)
    rewrite_zip(src, os.path.join(out_dir, "evil_torch", "model.zip"), {"policy.pth": inner_out.getvalue()})
    print("evil_os_system, evil_torch written", flush=True)


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join("tests", "data", "sb3")
    only = sys.argv[2:]  # optional case names, to remake just those
    # One thread and fixed seeds: the training run (and so the weights) is reproducible on CPU.
    torch.set_num_threads(1)
    for name, spec in CASES.items():
        if not only or name in only:
            make_case(out_dir, name, spec)
    if not only or VEC_NORMALIZE_CASE in only:
        make_vec_normalize_case(out_dir)
    if not only or FRAME_STACK_CASE in only:
        make_frame_stack_case(out_dir)
    if not only or CNN_CASE in only:
        make_cnn_case(out_dir)
    for name in OFF_POLICY_CNN_CASES:
        if not only or name in only:
            make_off_policy_cnn_case(out_dir, name)
    for name in MULTI_INPUT_CNN_CASES:
        if not only or name in only:
            make_multi_input_cnn_case(out_dir, name)
    if not only or GYM_ERA_CASE in only or "ppo_cartpole" in only:
        make_gym_era_case(out_dir)
    make_evil(out_dir)


if __name__ == "__main__":
    main()
