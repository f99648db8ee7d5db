"""CarRacing-v3 from Python as Gymnasium's CarRacing offers it: uint8 (96, 96, 3) observations,
env.unwrapped.track, .car (hull and wheels under Box2D's and car_dynamics.py's names), .reward,
.tile_visited_count, .t, and a track given back (set_track, reset(options={"track": ...}))
rebuilding the same road, so a transition can be compared with Gymnasium's on one track.
Skipped when this build has no Box2D component."""

import unittest

import numpy as np

import rlrun


def have_box2d():
    try:
        rlrun.make("CarRacing-v3").close()
        return True
    except Exception:  # the component's placeholder entry says how to get it
        return False


@unittest.skipUnless(have_box2d(), "this build has no Box2D envs (RLRUN_WITH_BOX2D)")
class CarRacingTest(unittest.TestCase):
    def test_observation_and_state(self):
        env = rlrun.make("CarRacing-v3")
        obs, info = env.reset(seed=3)
        self.assertEqual(obs.dtype, np.uint8)
        self.assertEqual(obs.shape, (96, 96, 3))
        self.assertTrue(env.observation_space.contains(obs))
        self.assertEqual(info, {})
        u = env.unwrapped
        track = u.track
        self.assertGreater(len(track), 200)
        self.assertEqual(len(track[0]), 4)  # (alpha, beta, x, y)
        car = u.car
        # The car starts at rest on the first track point, heading beta.
        self.assertAlmostEqual(car.hull.position[0], track[0][2], places=3)
        self.assertAlmostEqual(car.hull.position[1], track[0][3], places=3)
        self.assertAlmostEqual(car.hull.angle, track[0][1], delta=0.02)  # after the reset's step
        self.assertEqual(len(car.wheels), 4)
        self.assertAlmostEqual(u.t, 0.02)
        self.assertEqual(u.reward, 1000.0 / len(track) * u.tile_visited_count)
        total = 0.0
        for _ in range(40):
            obs, reward, terminated, truncated, info = env.step(np.array([0.0, 1.0, 0.0], np.float32))
            total += reward
        self.assertEqual(obs.dtype, np.uint8)
        self.assertGreater(u.car.wheels[2].omega, 1.0)
        self.assertEqual(u.car.wheels[2].gas, 1.0)
        self.assertAlmostEqual(total, u.reward, places=6)
        self.assertFalse(hasattr(rlrun.make("CartPole-v1").unwrapped, "track"))

    def test_a_track_given_back_replays(self):
        a, b = rlrun.make("CarRacing-v3"), rlrun.make("CarRacing-v3")
        oa, _ = a.reset(seed=8)
        track = a.unwrapped.track
        ob, _ = b.reset(seed=1, options={"track": track})
        np.testing.assert_array_equal(oa, ob)
        self.assertEqual(b.unwrapped.track, track)
        actions = np.random.default_rng(0).uniform([-1, 0, 0], [1, 1, 0.3], size=(60, 3)).astype(np.float32)
        for action in actions:
            ra = a.step(action)
            rb = b.step(action)
            np.testing.assert_array_equal(ra[0], rb[0])
            self.assertEqual(ra[1], rb[1])
        self.assertEqual(a.unwrapped.car.hull.position, b.unwrapped.car.hull.position)
        b.unwrapped.set_track(track)
        ob, _ = b.reset()
        np.testing.assert_array_equal(oa, ob)
        with self.assertRaisesRegex(ValueError, "set_track"):
            b.unwrapped.set_track([(0.0, 0.0, 0.0, 0.0)] * 2)
        with self.assertRaisesRegex(ValueError, "alpha, beta, x, y"):
            b.unwrapped.set_track([(0.0, 0.0)] * 5)

    def test_domain_randomize_options(self):
        env = rlrun.make("CarRacing-v3", domain_randomize=True)

        def background(_reset_result):  # the commonest colour above the bar, zoomed in after 1 s
            for _ in range(55):
                obs = env.step(np.zeros(3, np.float32))[0]
            colours, counts = np.unique(obs[:84].reshape(-1, 3), axis=0, return_counts=True)
            return tuple(colours[np.argmax(counts)])

        first = background(env.reset(seed=2))
        second = background(env.reset(options={"randomize": False}))
        third = background(env.reset(options={"randomize": True}))
        self.assertNotIn(first, [(102, 204, 102), (102, 230, 102)])
        self.assertEqual(first, second)
        self.assertNotEqual(second, third)

    def test_discrete(self):
        env = rlrun.make("CarRacing-v3", continuous=False)
        self.assertEqual(env.action_space.n, 5)
        env.reset(seed=0)
        for _ in range(5):
            env.step(3)
        self.assertAlmostEqual(env.unwrapped.car.wheels[3].gas, 0.2)


if __name__ == "__main__":
    unittest.main()
