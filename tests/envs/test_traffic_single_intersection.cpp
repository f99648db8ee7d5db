// TrafficSignal-v0 is TrafficNetwork-v0's single-intersection case (issue 42 item 7): one SUMO
// backend (envs/sumo/), one set of per-light rules and one parse of their names
// (envs/traffic_network/light_agent.hpp). The parser is checked on its own; then the two envs
// run the same scenario with the same settings on the real SUMO and must agree number for
// number.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "rlrun/envs/traffic/traffic_signal.hpp"
#include "rlrun/envs/traffic_network/light_agent.hpp"
#include "rlrun/envs/traffic_network/traffic_network.hpp"

using namespace rlrun;
using namespace rlrun::traffic;

TEST_CASE("Traffic envs: one reward-name parser, one default reward", "[traffic_network]") {
  const std::vector<std::string> names{"diff-waiting-time", "queue", "pressure", "average-speed"};
  CHECK(reward_function_names() == names);
  CHECK(parse_reward_function("diff-waiting-time") == RewardFunction::kDiffWaitingTime);
  CHECK(parse_reward_function("queue") == RewardFunction::kQueue);
  CHECK(parse_reward_function("pressure") == RewardFunction::kPressure);
  CHECK(parse_reward_function("average-speed") == RewardFunction::kAverageSpeed);
  CHECK_THROWS_WITH(parse_reward_function("speed"),
                    Catch::Contains("unknown reward_fn 'speed'") &&
                        Catch::Contains("diff-waiting-time, queue, pressure or average-speed"));
  CHECK_THROWS_AS(parse_reward_function("Queue"), std::invalid_argument);  // names are exact
  CHECK_THROWS_AS(parse_reward_function(""), std::invalid_argument);
  // The one default: sumo-rl's, the first name, in both envs.
  CHECK(TrafficNetwork::Config{}.reward_fn == names.front());
  CHECK(TrafficSignal::Config{}.reward_fn == names.front());

  CHECK(parse_observation_function("sumo-rl") == ObservationFunction::kSumoRl);
  CHECK(parse_observation_function("approach") == ObservationFunction::kApproach);
  CHECK_THROWS_WITH(parse_observation_function("lanes"), Catch::Contains("unknown observation"));
  CHECK(TrafficSignal::Config{}.observation == "approach");
  CHECK(TrafficNetwork::Config{}.observation == "sumo-rl");
}

namespace {

// TrafficSignal-v0's settings spelled out as TrafficNetwork-v0 kwargs.
TrafficNetwork::Config as_network(const TrafficSignal::Config& signal) {
  TrafficNetwork::Config network;
  network.scenario.value = "scenarios/single_intersection.yaml";
  network.backend = signal.backend;
  network.own_process = false;
  network.delta_time = signal.delta_time;
  network.yellow_time = signal.yellow_time;
  network.min_green = signal.min_green;
  network.max_green = signal.max_green;
  network.max_green_switch = false;
  network.num_seconds = signal.num_seconds + 1;  // the reset's first second, then the decisions
  network.reward_fn = signal.reward_fn;
  network.observation = signal.observation;
  network.phases = "approaches";
  return network;
}

}  // namespace

TEST_CASE("TrafficSignal-v0 equals the one-light TrafficNetwork-v0 step for step", "[traffic]") {
  for (const auto& [observation, reward_fn] : std::vector<std::pair<std::string, std::string>>{
           {"approach", "queue"}, {"approach", "diff-waiting-time"}, {"sumo-rl", "pressure"}}) {
    INFO(observation << ", " << reward_fn);
    TrafficSignal::Config config;
    config.num_seconds = 300;
    config.observation = observation;
    config.reward_fn = reward_fn;
    TrafficSignal signal(config);
    TrafficNetwork network(as_network(config));
    REQUIRE(network.num_agents() == 1);
    REQUIRE(signal.observation_space() == network.observation_space());
    REQUIRE(signal.action_space() == Space::discrete(4));
    REQUIRE(network.action_space() == Space::discrete(4));
    std::vector<float> obs_s(signal.observation_space().flat_dim()), obs_n(obs_s.size());
    signal.reset(7, obs_s);
    network.reset(7, obs_n);
    CHECK(obs_s == obs_n);
    StepResult rs, rn;
    int steps = 0;
    double returns = 0;
    do {
      const float action = static_cast<float>((steps * 7 / 5) % 4);
      rs = signal.step({&action, 1}, obs_s);
      rn = network.step({&action, 1}, obs_n);
      REQUIRE(obs_s == obs_n);
      REQUIRE(rs.reward == rn.reward);
      REQUIRE(rs.truncated == rn.truncated);
      returns += rs.reward;
      ++steps;
    } while (!rs.truncated);
    CHECK(steps == 60);   // 300 s of 5 s decisions
    CHECK(returns != 0);  // traffic came: the comparison was not between zeros
    CHECK(signal.sim_time() == network.sim_time());
    for (const char* key : {"avg_waiting_time", "avg_travel_time", "throughput"})
      CHECK(signal.info().get(signal.info().find(key)) ==
            network.info().get(network.info().find(key)));
  }
}

TEST_CASE("TrafficSignal-v0: Discrete(4) gives each approach green alone", "[traffic]") {
  // The light's links in tls.tll.xml's order: N, S, E, W approaches (4 links each).
  const std::string greens[] = {"GGGGrrrrrrrrrrrr", "rrrrrrrrGGGGrrrr", "rrrrGGGGrrrrrrrr",
                                "rrrrrrrrrrrrGGGG"};
  TrafficSignal::Config config;
  config.num_seconds = 200;
  config.min_green = 0;
  TrafficSignal env(config);
  std::vector<float> obs(10);
  env.reset(1, obs);
  CHECK(env.agents().front().green_state() == greens[kNorth]);
  for (int approach : {kSouth, kEast, kWest, kNorth}) {
    const float action = static_cast<float>(approach);
    env.step({&action, 1}, obs);
    CHECK(env.green_approach() == approach);
    CHECK(env.agents().front().green_state() == greens[approach]);
    CHECK(obs[8] == Approx(approach / 3.0));
  }
}
