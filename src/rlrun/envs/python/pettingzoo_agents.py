# PettingZoo envs in rlrun's Python worker: `env.id: pettingzoo:<module>:<function>` builds
# function(**env.kwargs), a PettingZoo env (pettingzoo/utils/env.py: ParallelEnv or AECEnv),
# and this file makes it the multi-agent env rlrun trains (include/rlrun/env.hpp): every agent
# a column of one shared policy, as SuperSuit's pettingzoo_env_to_vec_env_v1 makes it for SB3.
# CMake puts this file before worker.py in the one script a worker runs (CMakeLists.txt); the
# names it uses from worker.py (fail, Codec) are looked up when called.
#
#   Parallel envs        all agents act each step. Agents that leave early are "black death"
#                        agents until the episode ends (SuperSuit's black_death_v3): zero
#                        observations, reward 0, actions ignored, and their termination or
#                        truncation reported when the last agent ends (rlrun's agents end
#                        together).
#   AEC envs             `metadata["is_parallelizable"]`: through PettingZoo's own
#                        aec_to_parallel, then as above. Turn-based games (tic-tac-toe, connect
#                        four): one agent. env.opponent "self" (default): it plays whichever
#                        seat is to move, as PettingZoo's SB3 tutorial trains them (tutorials/
#                        SB3/connect_four/sb3_connect_four_action_mask.py): the observation of
#                        the seat to move, the mover's reward for its move, the game's end ending
#                        the episode. "random": it plays one seat (env.learner_side) against
#                        random legal moves made inside the env.
#
# The agents share one policy, so their spaces must be equal; an observation that is a dict of
# "observation" and "action_mask" (PettingZoo classic's) is the observation plus the mask
# (the mask in info["action_mask"] is read too), for MaskablePPO. env.agent_indicator adds
# which agent (or agent type) observes to its observation, as SuperSuit's agent_indicator_v0
# does, so that the shared policy can act differently per agent (AgentIndicator below).


def agent_space(env, kind, agent):
    """env.observation_space(agent) (PettingZoo >= 1.18), else env.observation_spaces[agent]."""
    method = getattr(env, f"{kind}_space", None)
    if callable(method):
        return method(agent)
    spaces = getattr(env, f"{kind}_spaces", None)
    if spaces is None:
        fail(f"the env has no {kind}_space(agent) method and no {kind}_spaces dict; it is not a "
             "PettingZoo env")
    return spaces[agent]


def split_masked_space(space):
    """(observation space, True) for PettingZoo classic's {"observation", "action_mask"} Dict."""
    spaces = getattr(space, "spaces", None)
    if hasattr(spaces, "keys") and set(spaces.keys()) == {"observation", "action_mask"}:
        return spaces["observation"], True
    return space, False


class IndicatedBox:
    """A Box space by its attributes (worker.py's Codec reads shape, dtype, low and high)."""

    def __init__(self, low, high, dtype):
        self.low, self.high, self.dtype, self.shape = low, high, dtype, low.shape


class IndicatedDiscrete:
    def __init__(self, n):
        self.n, self.start = n, 0


class AgentIndicator:
    """Which agent observes, added to its observation (SuperSuit's agent_indicator_v0 layout,
    supersuit/utils/agent_indicator.py): `mode` "agent" gives each agent of `names` its own
    indicator, "type" one per type of the `<type>_<n>` names (pursuers, evaders, ...). A flat
    Box gets one column per indicator (1 for the observing agent's, else 0); an image Box (H, W)
    or (H, W, C) one channel per indicator (the Box's lowest high, 255 for uint8 images, in the
    observing agent's channel); a Discrete n becomes n * indicators (value * indicators +
    index)."""

    def __init__(self, mode, names, space, np):
        self.np = np
        if mode == "type":
            bad = [a for a in names if "_" not in str(a) or not str(a).rsplit("_", 1)[1].isdigit()]
            if bad:
                fail(f"agent_indicator: type needs agents named <type>_<n>; {bad!r} are not")
            kinds = list(dict.fromkeys(str(a).rsplit("_", 1)[0] for a in names))
            self.index = {a: kinds.index(str(a).rsplit("_", 1)[0]) for a in names}
        else:
            self.index = {a: i for i, a in enumerate(names)}
        self.count = max(self.index.values()) + 1
        kind = space_kind(space, "the observation space")
        self.kind = kind
        if kind == "Discrete":
            if int(getattr(space, "start", 0)) != 0:
                fail("agent_indicator: a Discrete observation space must start at 0")
            self.n = int(space.n)
            self.space = IndicatedDiscrete(self.n * self.count)
            return
        shape = tuple(getattr(space, "shape", None) or ())
        if kind != "Box" or len(shape) not in (1, 2, 3):
            fail(f"agent_indicator: the observation space must be a Box of 1, 2 or 3 dimensions "
                 f"or a Discrete (SuperSuit's rule), not {space}")
        dtype = np.dtype(space.dtype)
        low = np.broadcast_to(np.asarray(space.low, dtype), shape)
        high = np.broadcast_to(np.asarray(space.high, dtype), shape)
        if len(shape) == 1:
            self.value = 1
            extra = (self.count,)
            axis = 0
        else:
            self.value = np.min(high)
            if len(shape) == 2:
                low, high = low[:, :, None], high[:, :, None]
            extra = low.shape[:2] + (self.count,)
            axis = 2
        self.image = len(shape) > 1
        self.space = IndicatedBox(np.concatenate([low, np.zeros(extra, dtype)], axis=axis),
                                  np.concatenate([high, np.full(extra, self.value, dtype)],
                                                 axis=axis), dtype)

    def apply(self, agent, value):
        np, k = self.np, self.index[agent]
        if self.kind == "Discrete":
            return int(value) * self.count + k
        value = np.asarray(value, dtype=self.space.dtype)
        if not self.image:
            out = np.zeros(value.shape[0] + self.count, self.space.dtype)
            out[:value.shape[0]] = value
            out[value.shape[0] + k] = self.value
            return out
        if value.ndim == 2:
            value = value[:, :, None]
        out = np.zeros(value.shape[:2] + (value.shape[2] + self.count,), self.space.dtype)
        out[:, :, :value.shape[2]] = value
        out[:, :, value.shape[2] + k] = self.value
        return out


class PettingZooAgents:
    """What the worker needs of a PettingZoo env: one agent's spaces (the same for all), the
    agents' names, and reset / step of all agents at once as flat rows."""

    def __init__(self, env, np, agents, describe_env, indicator="none"):
        self.env, self.np, self.names = env, np, list(agents)
        if not self.names:
            fail(f"{describe_env} has no agents (possible_agents is empty)")
        seen, twice = set(), set()
        for a in self.names:
            (twice if a in seen else seen).add(a)
        twice = sorted(repr(a) for a in twice)
        if twice:
            fail(f"{describe_env}'s possible_agents name {', '.join(twice)} more than once: each "
                 "agent needs its own id")
        self.obs_codec = self.act_codec = None
        self.masked_obs = False
        for agent in self.names:
            obs_space, masked = split_masked_space(agent_space(env, "observation", agent))
            obs_codec = Codec(obs_space, f"observation_space('{agent}')", np)
            act_codec = Codec(agent_space(env, "action", agent), f"action_space('{agent}')", np)
            if self.obs_codec is None:
                self.obs_codec, self.act_codec, self.masked_obs = obs_codec, act_codec, masked
            elif (obs_codec.describe != self.obs_codec.describe or
                  act_codec.describe != self.act_codec.describe or masked != self.masked_obs):
                fail(f"the agents' spaces differ ('{self.names[0]}' and '{agent}'): rlrun's "
                     "agents share one policy, so their observation and action spaces must be "
                     "equal (SuperSuit's pad_observations_v0 and pad_action_space_v0 make them so)")
        if self.act_codec.kind == "Dict":
            self.act_codec.action(None)  # refused with worker.py's reason
        # The indicator of the observing agent (or seat, for a turn-based game's mover).
        self.indicator = None
        if indicator != "none":
            obs_space, _ = split_masked_space(agent_space(env, "observation", self.names[0]))
            self.indicator = AgentIndicator(indicator, self.names, obs_space, np)
            self.obs_codec = Codec(self.indicator.space, "observation_space with agent_indicator",
                                   np)

    def observation(self, value, agent=None):
        """The observation without the mask (with `agent`'s indicator); the mask or None."""
        mask = None
        if self.masked_obs and hasattr(value, "keys"):
            value, mask = value["observation"], value["action_mask"]
        if self.indicator is not None and agent is not None:
            value = self.indicator.apply(agent, value)
        return value, mask

    @staticmethod
    def mask_of(info, from_obs):
        if from_obs is not None:
            return from_obs
        if hasattr(info, "get"):
            return info.get("action_mask")
        return None


class ParallelAgents(PettingZooAgents):
    """A ParallelEnv: every live agent acts each step."""

    def __init__(self, env, np, indicator="none"):
        names = getattr(env, "possible_agents", None)
        if names is None:
            fail("the parallel env has no possible_agents: rlrun needs the agents up front")
        super().__init__(env, np, names, "the parallel env", indicator)
        self.index = {a: i for i, a in enumerate(self.names)}
        self.finished = {}
        self.live = list(self.names)

    def reset(self, has_seed, seed):
        result = self.env.reset(seed=seed) if has_seed else self.env.reset()
        obs, infos = result if isinstance(result, tuple) and len(result) == 2 else (result, {})
        self.finished = {}
        self.live = self.live_agents("reset()")
        self.check_dicts("reset()", self.live, observations=obs, infos=infos)
        return self.rows(obs, infos, {}, over=False, gone=set())

    def live_agents(self, call):
        """env.agents after `call`, each one of possible_agents (once)."""
        live = list(getattr(self.env, "agents", self.names))
        unknown = [a for a in live if a not in self.index]
        if unknown:
            fail(f"after {call} env.agents holds {unknown!r}, which possible_agents does not "
                 f"name (possible_agents: {self.names!r})")
        if len(set(live)) != len(live):
            fail(f"after {call} env.agents names an agent twice: {live!r}")
        return live

    def check_dicts(self, call, live, **dicts):
        """Each dict a call returned is keyed by known agents and holds every live one."""
        for what, values in dicts.items():
            if not hasattr(values, "keys"):
                fail(f"{call} returned {what} as a {type(values).__name__}, not a dict keyed "
                     "by agent")
            unknown = [a for a in values.keys() if a not in self.index]
            if unknown:
                fail(f"{call} returned {what} for {unknown!r}, which possible_agents does not "
                     f"name (possible_agents: {self.names!r})")
            missing = [a for a in live if a not in values] if what != "infos" else []
            if missing:
                fail(f"{call} returned no {what} for the live agent(s) {missing!r} (the dict "
                     f"has {list(values.keys())!r})")

    def step(self, rows):
        live = self.live  # env.agents as the last reset or step left it (checked then)
        index = self.index
        actions = {a: self.act_codec.action(rows[index[a]]) for a in live}
        gone = set(self.finished)  # agents that left in earlier steps: black death
        result = self.env.step(actions)
        if not isinstance(result, tuple) or len(result) != 5:
            fail("step() returned " + (f"{len(result)} values" if isinstance(result, tuple)
                 else f"a {type(result).__name__}") + "; PettingZoo's parallel step returns "
                 "(observations, rewards, terminations, truncations, infos)")
        obs, rewards, terminations, truncations, infos = result
        self.check_dicts("step()", live, observations=obs, rewards=rewards,
                         terminations=terminations, truncations=truncations, infos=infos)
        self.live = self.live_agents("step()")
        for a in self.names:
            if a not in self.finished and (terminations.get(a) or truncations.get(a)):
                self.finished[a] = (bool(terminations.get(a)), bool(truncations.get(a)))
        over = not getattr(self.env, "agents", None) or len(self.finished) == len(self.names)
        return self.rows(obs, infos, rewards, over, gone)

    def rows(self, obs, infos, rewards, over, gone):
        """Per agent: (observation or None, mask or None, reward, terminated, truncated), and
        the info of the first agent that has one (the env's info for rlrun)."""
        out, info = [], None
        for a in self.names:
            value = mask = agent_info = None
            reward = 0.0
            if a not in gone:
                if a in obs:
                    value, mask = self.observation(obs[a], a)
                agent_info = infos.get(a) if hasattr(infos, "get") else None
                mask = self.mask_of(agent_info, mask)
                reward = rewards.get(a, 0.0)
            if info is None and agent_info:
                info = agent_info
            # Flags only when the last agent ends (rlrun's agents end together); an agent that
            # never said it ended (the env emptied `agents`) counts as truncated.
            terminated, truncated = self.finished.get(a, (False, True)) if over else (False, False)
            out.append((value, mask, reward, terminated, truncated))
        return out, info or {}


class TurnBasedAgents(PettingZooAgents):
    """A turn-based AECEnv as one agent. `opponent` "self": the agent plays whichever seat is
    to move (PettingZoo's SB3 tutorial); its reward is the mover's for its move, so a loss is
    never seen by the losing side's moves. "random": the agent plays one seat (`learner_side`:
    first, second, or alternate by episode) and random legal moves play the others inside the
    env, so its reward is its own over its move and the replies (+1 a win, -1 a loss)."""

    def __init__(self, env, np, opponent="self", learner_side="alternate", indicator="none"):
        names = getattr(env, "possible_agents", None)
        if not names:
            fail("the AEC env has no possible_agents")
        super().__init__(env, np, names, "the AEC env", indicator)
        self.seats = list(names)
        self.names = ["mover" if opponent == "self" else "learner"]  # one column
        self.opponent, self.learner_side = opponent, learner_side
        self.learner = None
        self.episode = -1
        self.rng = np.random.default_rng()

    def game_over(self):
        env = self.env
        return (not env.agents or any(env.terminations.values()) or
                any(env.truncations.values()))

    def reset(self, has_seed, seed):
        self.env.reset(seed=seed) if has_seed else self.env.reset()
        if has_seed:  # the opponent's moves follow the seed too
            self.rng = self.np.random.default_rng([seed, 0x5eed])
        self.episode += 1
        if self.opponent == "self":
            return self.current(self.env.agent_selection, 0.0, False, False)
        sides = {"first": 0, "second": 1}
        seat = sides.get(self.learner_side, self.episode % len(self.seats))
        self.learner = self.seats[min(seat, len(self.seats) - 1)]
        reward = self.replies()
        return self.current(self.learner, reward, *self.end_flags())

    def step(self, rows):
        env = self.env
        mover = env.agent_selection if self.opponent == "self" else self.learner
        if mover not in self.seats:
            fail(f"agent_selection is {mover!r}, which possible_agents does not name "
                 f"(possible_agents: {self.seats!r})")
        if env.agent_selection != mover:
            fail(f"it is '{env.agent_selection}''s turn, not the learner's ('{mover}')")
        env.step(self.act_codec.action(rows[0]))
        reward = float(env.rewards.get(mover, 0.0))
        if self.opponent == "self":
            over = self.game_over()
            terminated = over and any(env.terminations.values())
            return self.current(env.agent_selection, reward, terminated, over and not terminated)
        reward += self.replies()
        return self.current(self.learner, reward, *self.end_flags())

    def end_flags(self):
        if not self.game_over():
            return False, False
        terminated = any(self.env.terminations.values())
        return terminated, not terminated

    def replies(self):
        """The random seats move until it is the learner's turn or the game is over; the
        learner's reward over those moves."""
        env, np = self.env, self.np
        reward = 0.0
        while not self.game_over() and env.agent_selection != self.learner:
            seat = env.agent_selection
            _, mask = self.observation(env.observe(seat))
            mask = self.mask_of(env.infos.get(seat, {}), mask)
            space = agent_space(env, "action", seat)
            if mask is not None:
                action = int(self.rng.choice(np.flatnonzero(np.asarray(mask))))
            else:
                space.seed(int(self.rng.integers(2**31)))
                action = space.sample()
            env.step(action)
            reward += float(env.rewards.get(self.learner, 0.0))
        return reward

    def current(self, agent, reward, terminated, truncated):
        env = self.env
        value, mask = self.observation(env.observe(agent), agent)
        info = env.infos.get(agent, {}) if hasattr(env, "infos") else {}
        return [(value, self.mask_of(info, mask), reward, terminated, truncated)], info


def pettingzoo_agents(env, np, turn_based=None, indicator="none"):
    """The PettingZooAgents of a PettingZoo env, as its API and metadata say; `turn_based`:
    {"opponent", "learner_side"} for a turn-based game (env.opponent, env.learner_side);
    `indicator`: env.agent_indicator (none, agent or type)."""
    if not hasattr(env, "agent_iter"):
        return ParallelAgents(env, np, indicator)
    metadata = getattr(env, "metadata", None) or {}
    if metadata.get("is_parallelizable"):
        try:
            from pettingzoo.utils.conversions import aec_to_parallel
        except ImportError as e:
            fail(f"the AEC env is parallelizable but pettingzoo.utils cannot be imported: {e}")
        return ParallelAgents(aec_to_parallel(env), np, indicator)
    turn_based = turn_based or {}
    return TurnBasedAgents(env, np, turn_based.get("opponent", "self"),
                           turn_based.get("learner_side", "alternate"), indicator)
