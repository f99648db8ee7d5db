"""A pure-Python port of Gymnasium's CartPole-v1 (gymnasium/envs/classic_control/
cartpole.py): the same physics, termination and float32 observations; reset draws the state
uniformly in [-0.05, 0.05] from numpy's PCG64 seeded by reset(seed=...)."""
import math

import numpy as np

from rlrun_test_envs.spaces import Box, Discrete


class CartPolePort:
    metadata = {"render_modes": ["rgb_array"], "render_fps": 50}

    def __init__(self, render_mode=None, sutton_barto_reward=False):
        self.gravity, self.masscart, self.masspole = 9.8, 1.0, 0.1
        self.total_mass = self.masspole + self.masscart
        self.length = 0.5
        self.polemass_length = self.masspole * self.length
        self.force_mag, self.tau = 10.0, 0.02
        self.theta_threshold_radians = 12 * 2 * math.pi / 360
        self.x_threshold = 2.4
        high = np.array([self.x_threshold * 2, np.finfo(np.float32).max,
                         self.theta_threshold_radians * 2, np.finfo(np.float32).max],
                        dtype=np.float32)
        self.action_space = Discrete(2)
        self.observation_space = Box(-high, high, dtype=np.float32)
        self.render_mode = render_mode
        self.sutton_barto_reward = sutton_barto_reward
        self.np_random = np.random.default_rng()
        self.state = None
        self.steps_beyond_terminated = None

    def reset(self, *, seed=None, options=None):
        if seed is not None:
            self.np_random = np.random.default_rng(seed)
        self.state = self.np_random.uniform(low=-0.05, high=0.05, size=(4,))
        self.steps_beyond_terminated = None
        return np.array(self.state, dtype=np.float32), {}

    def step(self, action):
        assert action in (0, 1), f"{action!r} invalid"
        x, x_dot, theta, theta_dot = self.state
        force = self.force_mag if action == 1 else -self.force_mag
        costheta, sintheta = math.cos(theta), math.sin(theta)
        temp = (force + self.polemass_length * theta_dot**2 * sintheta) / self.total_mass
        thetaacc = (self.gravity * sintheta - costheta * temp) / (
            self.length * (4.0 / 3.0 - self.masspole * costheta**2 / self.total_mass))
        xacc = temp - self.polemass_length * thetaacc * costheta / self.total_mass
        x = x + self.tau * x_dot
        x_dot = x_dot + self.tau * xacc
        theta = theta + self.tau * theta_dot
        theta_dot = theta_dot + self.tau * thetaacc
        self.state = (x, x_dot, theta, theta_dot)
        terminated = bool(x < -self.x_threshold or x > self.x_threshold or
                          theta < -self.theta_threshold_radians or
                          theta > self.theta_threshold_radians)
        reward = 1.0 if not terminated else (0.0 if self.sutton_barto_reward else 1.0)
        return np.array(self.state, dtype=np.float32), reward, terminated, False, {}

    def render(self):
        """A 200x300 picture: white background, a black cart and a brown pole."""
        if self.render_mode != "rgb_array" or self.state is None:
            return None
        frame = np.full((200, 300, 3), 255, dtype=np.uint8)
        x, _, theta, _ = self.state
        cart_x = int(150 + x * 50)
        frame[140:160, max(0, cart_x - 20):min(300, cart_x + 20)] = 0
        for t in np.linspace(0, 1, 60):
            px = int(cart_x + t * 80 * math.sin(theta))
            py = int(140 - t * 80 * math.cos(theta))
            if 0 <= px < 300 and 0 <= py < 200:
                frame[max(0, py - 2):py + 2, max(0, px - 2):px + 2] = (202, 152, 101)
        return frame

    def close(self):
        pass
