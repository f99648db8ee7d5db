"""SB3's evaluate_policy (stable_baselines3/common/evaluation.py) for rlrun models.

Runs ``n_eval_episodes`` episodes split over the envs as SB3 does (env i runs
``(n_eval_episodes + i) // n_envs`` of them) and returns the mean and standard deviation of the
episodes' returns, or every episode's return and length with ``return_episode_rewards=True``.
``env`` is a Gymnasium env, an SB3-style VecEnv (``model.get_env()``) or an env id.
"""

from __future__ import annotations

import numpy as np

from ._vec_env import DummyVecEnv


def _as_vec_env(env):
    if isinstance(env, str):
        from . import make
        return DummyVecEnv([make(env)])
    if hasattr(env, "num_envs") and hasattr(env, "step") and not hasattr(env, "unwrapped"):
        return env
    return DummyVecEnv([env])


def evaluate_policy(model, env, n_eval_episodes: int = 10, deterministic: bool = True,
                    render: bool = False, callback=None, reward_threshold=None,
                    return_episode_rewards: bool = False, warn: bool = True):
    env = _as_vec_env(env)
    n_envs = env.num_envs
    episode_rewards, episode_lengths = [], []
    episode_counts = np.zeros(n_envs, dtype=int)
    episode_count_targets = np.array([(n_eval_episodes + i) // n_envs for i in range(n_envs)],
                                     dtype=int)
    current_rewards = np.zeros(n_envs)
    current_lengths = np.zeros(n_envs, dtype=int)
    observations = env.reset()
    states = None
    episode_starts = np.ones((n_envs,), dtype=bool)
    while (episode_counts < episode_count_targets).any():
        actions, states = model.predict(observations, state=states, episode_start=episode_starts,
                                        deterministic=deterministic)
        new_observations, rewards, dones, infos = env.step(actions)
        current_rewards += rewards
        current_lengths += 1
        for i in range(n_envs):
            if episode_counts[i] < episode_count_targets[i]:
                episode_starts[i] = dones[i]
                if callback is not None:
                    callback(locals(), globals())
                if dones[i]:
                    episode_rewards.append(float(current_rewards[i]))
                    episode_lengths.append(int(current_lengths[i]))
                    episode_counts[i] += 1
                    current_rewards[i] = 0
                    current_lengths[i] = 0
        observations = new_observations
        if render:
            env.render()
    mean_reward = float(np.mean(episode_rewards))
    std_reward = float(np.std(episode_rewards))
    if reward_threshold is not None:
        assert mean_reward > reward_threshold, (
            f"Mean reward below threshold: {mean_reward:.2f} < {reward_threshold:.2f}")
    if return_episode_rewards:
        return episode_rewards, episode_lengths
    return mean_reward, std_reward
