"""rlrun.parallel_env / rlrun.env: rlrun's multi-agent env (TrafficNetwork-v0, real SUMO) under
PettingZoo's Parallel and AEC APIs (python/rlrun/_pettingzoo.py).

The checks are what PettingZoo's own tests assert (pettingzoo/test/parallel_test.py and
api_test.py: dict keys per live agent, spaces returned as the same object, agents removed when
done, last() giving the rewards accumulated since the agent acted, dead agents stepping None),
plus agreement with make_vec's columns on the same seed and actions. When PettingZoo is
importable its own parallel_api_test and api_test run as well."""

import os
import re
import shutil
import tempfile
import unittest
import warnings

import numpy as np

import rlrun
from rlrun_testing import run_rlrun

NETWORK = "TrafficNetwork-v0"
KWARGS = dict(num_seconds=60)  # grid4x4: 16 lights, 12 decisions of 5 s


def have_sumo() -> bool:
    return shutil.which("sumo") is not None and NETWORK in rlrun.list_envs()


def random_actions(env, obs_infos, rng):
    actions = {}
    for agent in env.agents:
        mask = obs_infos[agent].get("action_mask")
        legal = np.flatnonzero(mask) if mask is not None else np.arange(env.action_space(agent).n)
        actions[agent] = int(rng.choice(legal))
    return actions


@unittest.skipUnless(have_sumo(), "needs SUMO and a build with TrafficNetwork-v0")
class ParallelApiTest(unittest.TestCase):
    def setUp(self):
        self.env = rlrun.parallel_env(NETWORK, **KWARGS)

    def tearDown(self):
        self.env.close()

    def test_agents_are_the_lights(self):
        env = self.env
        self.assertEqual(len(env.possible_agents), 16)
        self.assertEqual(len(set(env.possible_agents)), 16)
        self.assertTrue(all(isinstance(a, str) and not a.startswith("agent_") for a in env.possible_agents))
        self.assertEqual(env.agents, [])
        self.assertEqual(env.max_num_agents, 16)
        for agent in env.possible_agents:
            self.assertIs(env.observation_space(agent), env.observation_space(agent))
            self.assertIs(env.action_space(agent), env.action_space(agent))
        self.assertEqual(env.metadata["name"], NETWORK)
        self.assertTrue(env.metadata["is_parallelizable"])

    def test_episode(self):
        env, rng = self.env, np.random.default_rng(0)
        obs, infos = env.reset(seed=3, options={"ignored": 1})
        self.assertEqual(set(obs), set(env.possible_agents))
        self.assertEqual(set(infos), set(env.possible_agents))
        self.assertEqual(env.agents, env.possible_agents)
        steps = 0
        while env.agents:
            live = set(env.agents)
            obs, rewards, terminations, truncations, infos = env.step(random_actions(env, infos, rng))
            steps += 1
            for d in (obs, rewards, terminations, truncations, infos):
                self.assertEqual(set(d), live)
            for agent in live:
                self.assertTrue(env.observation_space(agent).contains(obs[agent]))
                self.assertEqual(obs[agent].dtype, env.observation_space(agent).dtype)
                self.assertIsInstance(rewards[agent], float)
                self.assertIsInstance(terminations[agent], bool)
                self.assertIn("sim_time", infos[agent])
                mask = infos[agent]["action_mask"]
                self.assertEqual(mask.dtype, np.int8)
                self.assertEqual(mask.shape, (env.action_space(agent).n,))
        self.assertEqual(steps, 12)
        self.assertTrue(all(truncations.values()))
        self.assertEqual(env.agents, [])
        self.assertEqual(env.state().shape, env.state_space.shape)
        with self.assertRaisesRegex(RuntimeError, "reset"):
            env.step({})

    def test_same_as_make_vec(self):
        # The same seed and actions: the same observations and per-light rewards as make_vec's
        # columns (one env, 16 agent columns).
        env, rng = self.env, np.random.default_rng(1)
        vec = rlrun.make_vec(NETWORK, 1, **KWARGS)
        try:
            obs, infos = env.reset(seed=7)
            vobs, _ = vec.reset(seed=7)
            np.testing.assert_array_equal(np.stack([obs[a] for a in env.possible_agents]), vobs)
            for _ in range(5):
                actions = random_actions(env, infos, rng)
                obs, rewards, _, _, infos = env.step(actions)
                vobs, vrewards, _, _, _ = vec.step(np.array([actions[a] for a in env.possible_agents]))
                np.testing.assert_array_equal(np.stack([obs[a] for a in env.possible_agents]), vobs)
                np.testing.assert_allclose([rewards[a] for a in env.possible_agents], vrewards,
                                           rtol=0, atol=1e-6)
        finally:
            vec.close()

    def test_bad_actions(self):
        env = self.env
        obs, _ = env.reset(seed=0)
        some = dict.fromkeys(env.agents[1:], 0)
        with self.assertRaisesRegex(ValueError, "no action for agent"):
            env.step(some)
        with self.assertRaisesRegex(ValueError, "unknown agent"):
            env.step({**dict.fromkeys(env.agents, 0), "nobody": 0})
        with self.assertRaisesRegex(ValueError, "not in Discrete"):
            env.step({**dict.fromkeys(env.agents, 0), env.agents[0]: 99})

    def test_unknown_kwarg(self):
        with self.assertRaises(rlrun.ConfigError):
            rlrun.parallel_env(NETWORK, num_second=60)

    @unittest.skipUnless(rlrun._pettingzoo.HAVE_PETTINGZOO, "PettingZoo is not importable")
    def test_pettingzoo_parallel_api_test(self):
        from pettingzoo.test import parallel_api_test

        import pettingzoo

        self.assertIsInstance(self.env, pettingzoo.ParallelEnv)
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # PettingZoo reports problems as warnings too
            parallel_api_test(self.env, num_cycles=30)


@unittest.skipUnless(have_sumo(), "needs SUMO and a build with TrafficNetwork-v0")
class AecApiTest(unittest.TestCase):
    def setUp(self):
        self.env = rlrun.env(NETWORK, **KWARGS)

    def tearDown(self):
        self.env.close()

    def test_turns_rewards_and_dead_steps(self):
        # PettingZoo's play_test invariants (pettingzoo/test/api_test.py), and the episode's
        # rewards equal to the parallel env's on the same seed and actions.
        env, rng = self.env, np.random.default_rng(2)
        env.reset(seed=5)
        self.assertEqual(env.agent_selection, env.possible_agents[0])
        actions = []
        accumulated = dict.fromkeys(env.possible_agents, 0.0)
        finished, turns = [], 0
        for agent in env.agent_iter():
            obs, reward, terminated, truncated, info = env.last()
            self.assertEqual(reward, accumulated[agent])
            accumulated[agent] = 0.0
            if terminated or truncated:
                with self.assertRaisesRegex(ValueError, "None"):
                    env.step(0)
                action = None
                finished.append(agent)
            else:
                self.assertTrue(env.observation_space(agent).contains(obs))
                legal = np.flatnonzero(info["action_mask"])
                action = int(rng.choice(legal))
                actions.append((agent, action))
            self.assertIsNone(env.step(action))
            turns += 1
            for a, r in env.rewards.items():
                accumulated[a] += r
            for table in (env.rewards, env.terminations, env.truncations, env.infos,
                          env._cumulative_rewards):
                self.assertEqual(set(table), set(env.agents))
            self.assertEqual(env.num_agents, len(env.agents))
        self.assertEqual(sorted(finished), sorted(env.possible_agents))
        self.assertEqual(turns, 12 * 16 + 16)
        self.assertEqual(env.agents, [])

        # The same actions through the parallel API.
        par = rlrun.parallel_env(NETWORK, **KWARGS)
        try:
            par.reset(seed=5)
            totals = dict.fromkeys(par.possible_agents, 0.0)
            for cycle in range(12):
                step = dict(actions[cycle * 16:(cycle + 1) * 16])
                _, rewards, _, _, _ = par.step(step)
                for a, r in rewards.items():
                    totals[a] += r
        finally:
            par.close()
        aec_totals = dict.fromkeys(env.possible_agents, 0.0)
        env.reset(seed=5)
        it = iter(actions)
        for agent in env.agent_iter():
            _, reward, terminated, truncated, _ = env.last()
            aec_totals[agent] += reward
            env.step(None if terminated or truncated else next(it)[1])
        for a in env.possible_agents:
            self.assertAlmostEqual(aec_totals[a], totals[a], places=9)

    def test_last_without_observing(self):
        self.env.reset(seed=0)
        obs, reward, terminated, truncated, info = self.env.last(observe=False)
        self.assertIsNone(obs)
        self.assertEqual((reward, terminated, truncated), (0.0, False, False))
        self.env.step(np.int32(1))  # numpy integers are actions too

    @unittest.skipUnless(rlrun._pettingzoo.HAVE_PETTINGZOO, "PettingZoo is not importable")
    def test_pettingzoo_api_test(self):
        import pettingzoo
        from pettingzoo.test import api_test

        self.assertIsInstance(self.env, pettingzoo.AECEnv)
        api_test(self.env, num_cycles=20)


class SingleAgentTest(unittest.TestCase):
    def test_cartpole_is_one_agent(self):
        env = rlrun.parallel_env("CartPole-v1")
        self.assertEqual(env.possible_agents, ["agent_0"])
        obs, _ = env.reset(seed=0)
        single = rlrun.make("CartPole-v1")
        sobs, _ = single.reset(seed=0)
        np.testing.assert_array_equal(obs["agent_0"], sobs)
        steps = 0
        while env.agents:
            obs, rewards, terminations, truncations, _ = env.step({"agent_0": 1})
            sobs, sreward, sterm, strunc, _ = single.step(1)
            np.testing.assert_array_equal(obs["agent_0"], sobs)
            self.assertEqual((rewards["agent_0"], terminations["agent_0"]), (sreward, sterm))
            steps += 1
        self.assertTrue(sterm)
        self.assertLess(steps, 500)
        env.close()
        single.close()


def have_pettingzoo_classic() -> bool:
    try:
        from pettingzoo.classic import tictactoe_v3  # noqa: F401 (needs pygame too)
        return True
    except ImportError:
        return False


class BoardGameSeatsTest(unittest.TestCase):
    """rlrun.env("TicTacToe-v0") / ("ConnectFour-v0"): both seats under the AEC API, with
    PettingZoo classic's agents, observations, masks, rewards and illegal-move ending
    (python/rlrun/_board_games.py)."""

    def play(self, env, moves):
        """Plays `moves` in turn from a reset; returns the agents that moved, in order."""
        env.reset(seed=0)
        movers = []
        for move in moves:
            movers.append(env.agent_selection)
            env.step(move)
        return movers

    def finish(self, env):
        """The dead steps after a game's end: every agent steps with None and leaves."""
        left = []
        while env.agents:
            self.assertTrue(env.terminations[env.agent_selection])
            left.append(env.agent_selection)
            env.step(None)
        return left

    def test_tictactoe_win_rewards_and_dead_steps(self):
        env = rlrun.env("TicTacToe-v0")
        self.assertEqual(env.possible_agents, ["player_1", "player_2"])
        self.assertIs(env.observation_space("player_1"), env.observation_space("player_1"))
        env.reset(seed=3)
        obs = env.observe("player_1")
        self.assertEqual(obs["observation"].shape, (3, 3, 2))
        self.assertEqual(obs["observation"].dtype, np.int8)
        np.testing.assert_array_equal(obs["action_mask"], np.ones(9, np.int8))
        np.testing.assert_array_equal(env.observe("player_2")["action_mask"], np.zeros(9, np.int8))
        # player_1 takes squares 0, 3, 6 (a line: squares run down the columns, board.py),
        # player_2 takes 1 and 4.
        movers = self.play(env, [0, 1, 3, 4, 6])
        self.assertEqual(movers, ["player_1", "player_2"] * 2 + ["player_1"])
        self.assertEqual(env.rewards, {"player_1": 1, "player_2": -1})
        self.assertTrue(all(env.terminations.values()))
        self.assertFalse(any(env.truncations.values()))
        # The loser is selected after the end; its plane 1 holds the winner's three marks.
        self.assertEqual(env.agent_selection, "player_2")
        obs, reward, terminated, _, _ = env.last()
        self.assertEqual((reward, terminated), (-1, True))
        self.assertEqual(int(obs["observation"][:, :, 1].sum()), 3)
        # Square k sits at [k // 3][k % 3] (observe(): squares reshaped to 3 x 3).
        np.testing.assert_array_equal(obs["observation"][:, 0, 1], [1, 1, 1])
        self.assertEqual(self.finish(env), ["player_2", "player_1"])
        self.assertEqual(env.agents, [])

    def test_connect_four_draw_free_win_and_illegal_move(self):
        env = rlrun.env("ConnectFour-v0")
        self.assertEqual(env.possible_agents, ["player_0", "player_1"])
        # player_0 stacks four in column 3, player_1 plays column 0 between.
        self.play(env, [3, 0, 3, 0, 3, 0, 3])
        self.assertEqual(env.rewards, {"player_0": 1, "player_1": -1})
        board = env.observe("player_0")["observation"]
        self.assertEqual(board.shape, (6, 7, 2))
        np.testing.assert_array_equal(board[2:, 3, 0], [1, 1, 1, 1])  # pieces fall to the bottom
        self.finish(env)
        # A full column is illegal: the mover loses (-1), the other gets 0, everyone is done.
        movers = self.play(env, [0, 0, 0, 0, 0, 0])
        self.assertEqual(env.observe(env.agent_selection)["action_mask"][0], 0)
        mover = env.agent_selection
        env.step(0)
        self.assertEqual(env._cumulative_rewards[mover], -1.0)
        self.assertEqual(sum(env._cumulative_rewards.values()), -1.0)
        self.assertTrue(all(env.terminations.values()) and all(env.truncations.values()))
        self.assertEqual(len(self.finish(env)), 2)
        self.assertEqual(movers[0], "player_0")

    def test_bad_input(self):
        env = rlrun.env("TicTacToe-v0")
        env.reset()
        with self.assertRaises(ValueError):
            env.step(9)  # not in Discrete(9)
        with self.assertRaises(ValueError):
            env.step(None)  # a live agent must move
        with self.assertRaisesRegex(ValueError, "rlrun.make"):
            rlrun.env("TicTacToe-v0", opponent="minimax")
        with self.assertRaisesRegex(ValueError, "turn-based"):
            rlrun.parallel_env("ConnectFour-v0")

    def test_render(self):
        env = rlrun.env("ConnectFour-v0", render_mode="rgb_array")
        self.play(env, [3])
        frame = env.render()
        self.assertEqual(frame.shape, (600, 700, 3))
        self.assertEqual(frame.dtype, np.uint8)
        self.assertIsNone(rlrun.env("TicTacToe-v0").render())

    @unittest.skipUnless(rlrun._pettingzoo.HAVE_PETTINGZOO, "PettingZoo is not importable")
    def test_pettingzoo_api_test(self):
        import pettingzoo
        from pettingzoo.test import api_test

        for id in ("TicTacToe-v0", "ConnectFour-v0"):
            env = rlrun.env(id)
            self.assertIsInstance(env, pettingzoo.AECEnv)
            api_test(env, num_cycles=1000)

    @unittest.skipUnless(have_pettingzoo_classic(), "PettingZoo's classic games are not importable")
    def test_same_games_as_pettingzoo(self):
        """The same moves in rlrun's game and PettingZoo's own (random legal games, an illegal
        move in some): the same agents, selections, observations, masks, rewards and flags."""
        from pettingzoo.classic import connect_four_v3, tictactoe_v3

        rng = np.random.default_rng(0)
        for id, upstream in (("TicTacToe-v0", tictactoe_v3), ("ConnectFour-v0", connect_four_v3)):
            for game in range(150):
                ours, theirs = rlrun.env(id), upstream.env()
                ours.reset(seed=game)
                theirs.reset(seed=game)
                step = 0
                while theirs.agents or ours.agents:
                    self.assertEqual(ours.agents, theirs.agents)
                    self.assertEqual(ours.agent_selection, theirs.agent_selection)
                    for agent in theirs.agents:
                        a, b = ours.observe(agent), theirs.observe(agent)
                        np.testing.assert_array_equal(a["observation"], b["observation"])
                        np.testing.assert_array_equal(a["action_mask"], b["action_mask"])
                    self.assertEqual(ours.rewards, theirs.rewards)
                    self.assertEqual(ours._cumulative_rewards, theirs._cumulative_rewards)
                    self.assertEqual(ours.terminations, theirs.terminations)
                    self.assertEqual(ours.truncations, theirs.truncations)
                    obs, _, terminated, truncated, _ = theirs.last()
                    if terminated or truncated:
                        action = None
                    elif game % 10 == 0 and step == 3 and not obs["action_mask"].all():
                        action = int(np.flatnonzero(obs["action_mask"] == 0)[0])  # illegal
                    else:
                        action = int(rng.choice(np.flatnonzero(obs["action_mask"])))
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")
                        ours.step(action)
                        theirs.step(action)
                    step += 1


@unittest.skipUnless(have_pettingzoo_classic(), "PettingZoo's classic games are not importable")
class TrainPettingZooEnvsTest(unittest.TestCase):
    """PettingZoo's own envs trained by the rlrun binary (env.id: pettingzoo:module:function);
    the worker imports them from the PYTHONPATH this test runs with."""

    def test_tictactoe_against_random(self):
        with tempfile.TemporaryDirectory() as tmp:
            config = os.path.join(tmp, "ttt.yaml")
            with open(config, "w") as f:
                f.write(f"run: {{name: ttt, seed: 1, total_timesteps: 30000, out_dir: {tmp}/runs}}\n"
                        "env: {id: 'pettingzoo:pettingzoo.classic.tictactoe_v3:env', n_envs: 4, "
                        "opponent: random}\n"
                        "algo: {id: MaskablePPO, n_steps: 128, batch_size: 64}\n")
            run_rlrun("train", config)
            _, out = run_rlrun("eval", "--model", f"{tmp}/runs/ttt/seed1/model.zip", "--episodes", 200,
                               "--trust")
            trained = float(re.search(r"mean_reward = (-?[0-9.]+)", out).group(1))
            self.assertGreater(trained, 0.5, out)  # +1 a win, -1 a loss, seats alternating

    def test_parallel_envs_pass_check_env(self):
        for target, agents in (("pettingzoo.classic.rps_v2:parallel_env", 2),
                               ("pettingzoo.classic.rps_v2:env", 2)):
            _, out = run_rlrun("check-env", f"pettingzoo:{target}", "--episodes", 2)
            self.assertIn(f"agents             {agents}", out)
            self.assertIn("check_env: passed", out)


if __name__ == "__main__":
    unittest.main()
