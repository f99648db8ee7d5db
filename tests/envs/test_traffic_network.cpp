// TrafficNetwork-v0 (envs/traffic_network/): sumo-rl's per-light rules on hand-made programs;
// then the real SUMO on the shipped scenarios and on networks that SUMO's own tools make
// (netconvert's OpenStreetMap import): fixed-time control equals a plain `sumo` run, both
// backends give the same episode, spaces are padded across lights, bad input is an error
// before SUMO runs, and a SUMO that dies leaves an error and no process.
#include <catch2/catch.hpp>

#include <signal.h>

#include <algorithm>
#include <csignal>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/interrupt.hpp"
#include "rlrun/env/action_mask.hpp"
#include "rlrun/envs/traffic_network/light_agent.hpp"
#include "rlrun/envs/traffic_network/traffic_network.hpp"
#include "rlrun/rng.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::traffic;
using namespace rlrun::testing;

namespace {

const std::string kSource = RLRUN_SOURCE_DIR;

bool process_exists(pid_t pid) { return pid > 0 && kill(pid, 0) == 0; }

// One light, three links (N_0 -> S_0, N_1 -> E_0, W_0 -> E_0) and the given phases.
TrafficLightProgram one_light(const std::vector<std::string>& states) {
  TrafficLightProgram light;
  light.id = "J";
  for (const std::string& s : states) light.phases.push_back({10, s});
  light.links = {{0, "N_0", "S_0"}, {1, "N_1", "E_0"}, {2, "W_0", "E_0"}};
  light.incoming_lanes = {"N_0", "N_1", "W_0"};
  light.outgoing_lanes = {"S_0", "E_0"};
  light.num_links = 3;
  return light;
}

// Lane slots: incoming N_0, N_1, W_0 = 0, 1, 2; outgoing S_0, E_0 = 3, 4.
LightAgent make_agent(const TrafficLightProgram& light) {
  return LightAgent(light, derive_signal_control(light), {0, 1, 2}, {3, 4}, {75.0, 75.0, 150.0});
}

struct Trips {
  int count = 0;
  double duration = 0, waiting = 0, time_loss = 0;
};

// Means over SUMO's tripinfo XML, read with a regex (independently of read_tripinfo).
Trips read_trips(const std::string& path) {
  const std::string s = read_text(path);
  static const std::regex trip(
      R"re(<tripinfo [^>]*duration="([0-9.]+)"[^>]*waitingTime="([0-9.]+)"[^>]*timeLoss="([0-9.]+)")re");
  Trips t;
  for (auto it = std::sregex_iterator(s.begin(), s.end(), trip); it != std::sregex_iterator();
       ++it) {
    ++t.count;
    t.duration += std::stod((*it)[1]);
    t.waiting += std::stod((*it)[2]);
    t.time_loss += std::stod((*it)[3]);
  }
  if (t.count > 0) t.duration /= t.count, t.waiting /= t.count, t.time_loss /= t.count;
  return t;
}

// Runs one whole episode with `policy` choosing every agent's action; returns the info at its end.
template <class Policy>
std::vector<double> run_episode(TrafficNetwork& env, uint64_t seed, Policy policy,
                                std::vector<float>* first_obs = nullptr) {
  const size_t width = static_cast<size_t>(env.observation_space().flat_dim());
  std::vector<float> obs(width * env.num_agents()), actions(env.num_agents());
  std::vector<StepResult> results(env.num_agents());
  env.reset(seed, obs);
  if (first_obs) *first_obs = obs;
  for (int t = 0;; ++t) {
    policy(env, obs, actions, t);
    env.step_agents(actions, obs, results);
    for (int a = 0; a < env.num_agents(); ++a) {
      REQUIRE(
          env.observation_space().contains(std::span<const float>(obs.data() + a * width, width)));
      REQUIRE(std::isfinite(results[a].reward));
    }
    if (results[0].truncated) break;
  }
  return env.info().values();
}

double info_of(const TrafficNetwork& env, const std::string& key) {
  return env.info().get(env.info().find(key));
}

const auto kMaxPressure = [](TrafficNetwork& env, const std::vector<float>&, std::vector<float>& a,
                             int) { env.max_pressure_actions(a); };
const auto kNothing = [](TrafficNetwork&, const std::vector<float>&, std::vector<float>& a, int) {
  std::fill(a.begin(), a.end(), 0.0f);
};

std::string write(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("TrafficNetwork: one light's actions, observation and rewards follow sumo-rl",
          "[traffic_network]") {
  // Greens 0 = "GGr" (N), 1 = "rrG" (W); "yyr" is a transition, not an action.
  LightAgent agent = make_agent(one_light({"GGr", "yyr", "rrG", "rry"}));
  const LightTiming timing{5, 2, 5, 0};
  agent.reset();
  CHECK(agent.num_greens() == 2);
  CHECK(agent.green_state() == "GGr");
  // Before yellow_time + min_green seconds nothing changes (set_next_phase).
  agent.advanced(6);
  CHECK_FALSE(agent.decide(1, timing).change);
  agent.advanced(1);
  // The current green, or an action beyond this light's greens (padding), keeps it.
  CHECK_FALSE(agent.decide(0, timing).change);
  CHECK_FALSE(agent.decide(3, timing).change);
  const LightCommand to_w = agent.decide(1, timing);
  CHECK(to_w.change);
  CHECK(to_w.yellow == "yyr");  // every G of the old green that the new one makes red
  CHECK(to_w.green == "rrG");
  CHECK(agent.green() == 1);
  CHECK(agent.since_change() == 0);

  // Observation: one-hot of 3 (padded), min-green flag, densities and queues of 4 lanes
  // (padded): vehicles / (length / (2.5 + mean vehicle length)), at most 1.
  std::vector<LaneReading> lanes(5);
  lanes[0] = {3, 2, 5.0};    // N_0: 75 m / 7.5 m = 10 vehicles fit
  lanes[1] = {20, 15, 5.0};  // N_1: more than fit -> 1
  lanes[2] = {6, 0, 10.0};   // W_0: 150 / 12.5 = 12 fit
  lanes[3] = {4, 1, 5.0};
  lanes[4] = {1, 1, 5.0};
  std::vector<float> obs(3 + 1 + 2 * 4, -1.0f);
  agent.observe(lanes, timing, 3, 4, obs);
  const std::vector<float> expected{0, 1, 0, 0, 0.3f, 1, 0.5f, 0, 0.2f, 1, 0, 0};
  CHECK(obs == expected);
  agent.advanced(7);
  agent.observe(lanes, timing, 3, 4, obs);
  CHECK(obs[3] == 1.0f);  // min green (after the yellow) has passed

  // Rewards.
  const std::vector<double> waiting{100, 50, 0, 0, 0}, speed{1.0, 0.5, 0.5, 0, 0};
  const std::vector<int> count{2, 1, 1, 0, 0};
  CHECK(agent.reward(RewardFunction::kQueue, lanes, waiting, speed, count) == -17.0);
  CHECK(agent.reward(RewardFunction::kPressure, lanes, waiting, speed, count) ==
        (4 + 1) - (3 + 20 + 6));
  CHECK(agent.reward(RewardFunction::kAverageSpeed, lanes, waiting, speed, count) ==
        Approx(2.0 / 4));
  // diff-waiting-time: the drop of the accumulated waiting time / 100 since the last call.
  CHECK(agent.reward(RewardFunction::kDiffWaitingTime, lanes, waiting, speed, count) ==
        Approx(-1.5));
  const std::vector<double> less{20, 10, 0, 0, 0};
  CHECK(agent.reward(RewardFunction::kDiffWaitingTime, lanes, less, speed, count) == Approx(1.2));
  CHECK_THROWS_AS(parse_reward_function("speed"), std::invalid_argument);

  // Max-pressure: per green, sum over its movements of queue in minus queue out.
  // Green 0 (links 0, 1): (2 - 1) + (15 - 1) = 15; green 1 (link 2): 0 - 1 = -1.
  CHECK(agent.max_pressure_action(lanes) == 0);
  lanes[2].halting = 40;
  CHECK(agent.max_pressure_action(lanes) == 1);

  // max_green: a green held that long goes to the program's next green.
  LightAgent held = make_agent(one_light({"GGr", "yyr", "rrG", "rry"}));
  held.reset();
  const LightTiming capped{5, 2, 5, 20};
  held.advanced(21);
  CHECK_FALSE(held.decide(0, capped).change);
  held.advanced(1);
  const LightCommand forced = held.decide(0, capped);
  CHECK(forced.change);
  CHECK(forced.green == "rrG");
}

TEST_CASE("TrafficNetwork: the min_green rule is each light's action mask", "[traffic_network]") {
  LightAgent agent = make_agent(one_light({"GGr", "yyr", "rrG", "rry"}));
  const LightTiming timing{5, 2, 5, 0};
  agent.reset();
  std::vector<float> mask(3);  // padded to 3 greens: index 2 is never legal
  agent.action_mask(timing, mask);
  CHECK(mask == std::vector<float>{1, 0, 0});  // only the current green before min_green
  agent.advanced(7);
  agent.action_mask(timing, mask);
  CHECK(mask == std::vector<float>{1, 1, 0});
  agent.decide(1, timing);
  agent.action_mask(timing, mask);
  CHECK(mask == std::vector<float>{0, 1, 0});

  // The env reports every agent's mask, agent-major, after reset() and each step.
  TrafficNetwork::Config config;
  config.ts_ids = {"B1", "A0"};
  TrafficNetwork env(config);
  std::vector<float> obs(2 * env.observation_space().flat_dim()), masks(2 * 4);
  env.reset(1, obs);
  ActionMaskReader reader(env.action_space());
  REQUIRE(reader.read(env.info(), 2, masks).empty());
  CHECK(masks == std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0});
  std::vector<StepResult> results(2);
  const std::vector<float> keep{0, 0};
  for (int i = 0; i < 2; ++i) env.step_agents(keep, obs, results);  // 10 s: min_green passed
  REQUIRE(reader.read(env.info(), 2, masks).empty());
  CHECK(masks == std::vector<float>{1, 1, 1, 1, 1, 1, 1, 1});
}

TEST_CASE("TrafficNetwork: the 4x4 grid is 16 agents with padded spaces and grid neighbours",
          "[traffic_network]") {
  TrafficNetwork env;  // scenarios/grid4x4.yaml
  CHECK(env.num_agents() == 16);
  CHECK(env.action_space() == Space::discrete(4));
  // 4 greens + min-green flag + 2 x 12 incoming lanes (2 lanes + a left-turn lane, 4 arms).
  CHECK(env.observation_space().flat_dim() == 4 + 1 + 2 * 12);
  std::map<size_t, int> by_degree;
  for (const auto& n : env.neighbours()) ++by_degree[n.size()];
  CHECK(by_degree == std::map<size_t, int>{{2, 4}, {3, 8}, {4, 4}});  // corners, edges, inside

  TrafficNetwork::Config config;
  config.agent_id = true;
  config.ts_ids = {"B1", "A0"};
  TrafficNetwork two(config);
  CHECK(two.num_agents() == 2);
  CHECK(two.agents()[0].id() == "B1");
  CHECK(two.observation_space().flat_dim() == 4 + 1 + 2 * 12 + 2);
}

TEST_CASE("TrafficNetwork: reward_scope neighbourhood adds the neighbours' rewards",
          "[traffic_network]") {
  TrafficNetwork::Config config;
  config.num_seconds = 200;
  config.reward_fn = "queue";
  TrafficNetwork local(config);
  config.reward_scope = "neighbourhood";
  config.neighbour_weight = 0.5;
  TrafficNetwork near(config);
  const size_t n = static_cast<size_t>(local.num_agents());
  std::vector<float> obs_a(local.observation_space().flat_dim() * n), obs_b(obs_a.size());
  std::vector<StepResult> ra(n), rb(n);
  local.reset(4, obs_a);
  near.reset(4, obs_b);
  double total = 0;
  for (int t = 0; t < 30; ++t) {
    std::vector<float> actions(n);
    for (size_t a = 0; a < n; ++a) actions[a] = static_cast<float>((t / 3 + a) % 4);
    local.step_agents(actions, obs_a, ra);
    near.step_agents(actions, obs_b, rb);
    REQUIRE(obs_a == obs_b);  // the same simulation
    for (size_t a = 0; a < n; ++a) {
      double expected = ra[a].reward;
      for (int b : local.neighbours()[a]) expected += 0.5 * ra[b].reward;
      CHECK(rb[a].reward == Approx(expected));
      total += ra[a].reward;
    }
  }
  CHECK(total < 0);  // queues formed: the comparison was not between zeros
}

TEST_CASE("TrafficNetwork: fixed-time control equals a plain sumo run on every shipped scenario",
          "[traffic_network]") {
  TempDir dir("traffic_network_fixed");
  // The irregular ones (random25, spider15) run 07:00-08:00: their begin holds too.
  for (const std::string name :
       {"grid4x4", "grid4x4_peak", "arterial4x4", "arterial4x4_peak", "random25", "spider15"}) {
    INFO(name);
    TrafficNetwork::Config config;
    config.scenario.value = kSource + "/scenarios/" + name + ".yaml";
    TrafficNetwork env(config);
    env.set_control(TrafficNetwork::Control::kOwnPrograms);
    run_episode(env, 7, kNothing);
    const NetworkScenario& s = env.scenario();
    std::string routes;
    for (const std::string& r : s.files.routes) routes += (routes.empty() ? "" : ",") + r;
    const std::string plain = dir / (name + ".xml");
    const CommandResult sumo =
        run_command("sumo -n '" + s.files.net + "' -r '" + routes + "' -b " +
                    std::to_string(static_cast<int64_t>(s.begin)) + " -e " +
                    std::to_string(static_cast<int64_t>(s.end)) +
                    " --seed 7 --no-step-log --tripinfo-output '" + plain + "'");
    INFO(sumo.output);
    REQUIRE(sumo.exit_code == 0);
    const Trips t = read_trips(plain);
    REQUIRE(t.count > 1000);
    CHECK(info_of(env, "throughput") == t.count);
    CHECK(info_of(env, "mean_delay") == Approx(t.time_loss).epsilon(1e-12));
    CHECK(info_of(env, "avg_waiting_time") == Approx(t.waiting).epsilon(1e-12));
    CHECK(info_of(env, "avg_travel_time") == Approx(t.duration).epsilon(1e-12));
    CHECK(info_of(env, "sim_time") == static_cast<double>(s.end));
  }
}

TEST_CASE("TrafficNetwork: a .sumocfg scenario: its files and times, fixed-time equal to sumo -c",
          "[traffic_network]") {
  TempDir dir("traffic_network_sumocfg");
  const std::string grid = kSource + "/sumo_data/grid4x4/";
  const std::string cfg =
      write(dir / "grid.sumocfg",
            "<configuration>\n  <input>\n    <net-file value=\"" + grid +
                "grid4x4.net.xml\"/>\n    <route-files value=\"" + grid +
                "grid4x4.rou.xml\"/>\n  </input>\n  <time>\n    <begin value=\"0\"/>\n"
                "    <end value=\"900\"/>\n  </time>\n  <processing>\n"
                "    <time-to-teleport value=\"120\"/>\n  </processing>\n</configuration>\n");
  TrafficNetwork::Config config;
  config.scenario.value = cfg;
  TrafficNetwork env(config);
  CHECK(env.scenario().begin == 0);
  CHECK(env.scenario().end == 900);
  CHECK(env.scenario().files.net == grid + "grid4x4.net.xml");
  env.set_control(TrafficNetwork::Control::kOwnPrograms);
  run_episode(env, 7, kNothing);
  const CommandResult sumo = run_command(
      "sumo -c '" + cfg + "' --seed 7 --no-step-log --tripinfo-output '" + dir / "plain.xml" + "'");
  INFO(sumo.output);
  REQUIRE(sumo.exit_code == 0);
  const Trips t = read_trips(dir / "plain.xml");
  CHECK(info_of(env, "throughput") == t.count);
  CHECK(info_of(env, "mean_delay") == Approx(t.time_loss).epsilon(1e-12));
  CHECK(info_of(env, "sim_time") == 900.0);
  // Actuated control keeps the configuration's other settings and adds its programs.
  env.set_control(TrafficNetwork::Control::kActuated);
  run_episode(env, 7, kNothing);
  CHECK(info_of(env, "mean_delay") != Approx(t.time_loss));
  CHECK(info_of(env, "throughput") > 500);
}

TEST_CASE("TrafficNetwork: a scenario's begin holds under every control and backend",
          "[traffic_network]") {
  // Half an hour into the grid's demand (YAML begin/end, and a .sumocfg's <time>): every
  // episode — the agents', max-pressure's, actuated's, the lights' own programs — starts at
  // the scenario's begin (the first decision one second later) and ends at its end, 60
  // decisions of 5 s; the fixed-time episode equals plain `sumo -b 1800 -e 2100`, and the agents'
  // episodes see the same half-hour's traffic (not the 35 minutes from second 0).
  TempDir dir("traffic_network_begin");
  const std::string grid = kSource + "/sumo_data/grid4x4/";
  const std::string yaml =
      write(dir / "late.yaml", "name: late\nnet_file: " + grid + "grid4x4.net.xml\nroute_files: [" +
                                   grid + "grid4x4.rou.xml]\nbegin: 1800\nend: 2100\n");
  const std::string cfg =
      write(dir / "late.sumocfg",
            "<configuration>\n  <input>\n    <net-file value=\"" + grid +
                "grid4x4.net.xml\"/>\n    <route-files value=\"" + grid +
                "grid4x4.rou.xml\"/>\n  </input>\n  <time>\n    <begin value=\"1800\"/>\n"
                "    <end value=\"2100\"/>\n  </time>\n</configuration>\n");
  const CommandResult sumo = run_command("sumo -n '" + grid + "grid4x4.net.xml' -r '" + grid +
                                         "grid4x4.rou.xml' -b 1800 -e 2100 --seed 7 "
                                         "--no-step-log --tripinfo-output '" +
                                         dir / "plain.xml" + "'");
  INFO(sumo.output);
  REQUIRE(sumo.exit_code == 0);
  const Trips plain = read_trips(dir / "plain.xml");
  REQUIRE(plain.count > 100);

  const auto cycling = [](TrafficNetwork&, const std::vector<float>&, std::vector<float>& a,
                          int t) {
    for (size_t i = 0; i < a.size(); ++i) a[i] = static_cast<float>((t / 4 + i) % 4);
  };
  for (const std::string& scenario : {yaml, cfg}) {
    for (const std::string backend : {"libsumo", "traci"}) {
      TrafficNetwork::Config config;
      config.scenario.value = scenario;
      config.backend = backend;
      TrafficNetwork env(config);
      env.watch_outgoing_lanes();
      CHECK(env.scenario().begin == 1800);
      for (const std::string control : {"agents", "max-pressure", "actuated", "fixed-time"}) {
        INFO(scenario << ", " << backend << ", " << control);
        if (control == "actuated") env.set_control(TrafficNetwork::Control::kActuated);
        if (control == "fixed-time") env.set_control(TrafficNetwork::Control::kOwnPrograms);
        std::vector<float> obs(static_cast<size_t>(env.observation_space().flat_dim()) *
                               env.num_agents());
        env.reset(7, obs);
        CHECK(info_of(env, "sim_time") == 1801.0);
        int decisions = 0;
        run_episode(
            env, 7,
            [&](TrafficNetwork& e, const std::vector<float>& o, std::vector<float>& a, int t) {
              ++decisions;
              if (control == "max-pressure")
                kMaxPressure(e, o, a, t);
              else
                cycling(e, o, a, t);
            });
        CHECK(decisions == 60);
        CHECK(info_of(env, "sim_time") == 2100.0);
        const double throughput = info_of(env, "throughput");
        if (control == "fixed-time") {
          CHECK(throughput == plain.count);
          CHECK(info_of(env, "mean_delay") == Approx(plain.time_loss).epsilon(1e-12));
        } else {
          CHECK(throughput > 0.5 * plain.count);
          CHECK(throughput < 1.5 * plain.count);
        }
      }
    }
  }
}

TEST_CASE("TrafficNetwork: agents, max-pressure and actuated control run, libsumo equals traci",
          "[traffic_network]") {
  TrafficNetwork::Config config;
  config.backend = "traci";
  config.num_seconds = 600;
  std::map<std::string, double> delay;
  std::vector<float> first_traci, first_libsumo;
  std::vector<double> traci_info, libsumo_info;
  {
    TrafficNetwork env(config);
    env.watch_outgoing_lanes();  // max-pressure looks at the outgoing lanes too
    traci_info = run_episode(env, 3, kMaxPressure, &first_traci);
    CHECK(process_exists(env.sumo_pid()) == false);  // SUMO closed at the episode's end
    delay["max-pressure"] = info_of(env, "mean_delay");
    CHECK(info_of(env, "sim_time") == 600.0);
    CHECK(info_of(env, "throughput") > 100);
    // The agents' own control: switching every decision where allowed.
    run_episode(env, 3,
                [](TrafficNetwork&, const std::vector<float>&, std::vector<float>& a, int t) {
                  for (size_t i = 0; i < a.size(); ++i) a[i] = static_cast<float>((t / 4 + i) % 4);
                });
    delay["cycling"] = info_of(env, "mean_delay");
    env.set_control(TrafficNetwork::Control::kActuated);
    run_episode(env, 3, kNothing);
    delay["actuated"] = info_of(env, "mean_delay");
    env.set_control(TrafficNetwork::Control::kOwnPrograms);
    run_episode(env, 3, kNothing);
    delay["fixed-time"] = info_of(env, "mean_delay");
  }
  INFO("max-pressure " << delay["max-pressure"] << ", actuated " << delay["actuated"]
                       << ", fixed-time " << delay["fixed-time"] << ", cycling "
                       << delay["cycling"]);
  // Each control is really in charge: four different outcomes, and max-pressure beats the
  // fixed programs on this grid.
  CHECK(std::set<double>{delay["max-pressure"], delay["actuated"], delay["fixed-time"],
                         delay["cycling"]}
            .size() == 4);
  CHECK(delay["max-pressure"] < delay["fixed-time"]);

  // SUMO inside a worker process (own_process, the default) and inside rlrun itself.
  config.backend = "libsumo";
  for (const bool own_process : {true, false}) {
    INFO("libsumo, own_process " << own_process);
    config.own_process = own_process;
    TrafficNetwork libsumo(config);
    libsumo.watch_outgoing_lanes();
    libsumo_info = run_episode(libsumo, 3, kMaxPressure, &first_libsumo);
    CHECK(first_libsumo == first_traci);
    CHECK(libsumo_info == traci_info);
  }
  config.backend = "traci";
  config.own_process = false;  // libtraci in rlrun's process
  TrafficNetwork direct(config);
  direct.watch_outgoing_lanes();
  CHECK(run_episode(direct, 3, kMaxPressure) == traci_info);
}

TEST_CASE(
    "TrafficNetwork: networks from netconvert's OpenStreetMap import, lights of 1 to 6 greens",
    "[traffic_network]") {
  TempDir dir("traffic_network_osm");
  // A main road through four signalised nodes: a 4-way crossing, a T-junction, a lone
  // pedestrian-crossing signal (one green) and a 6-arm junction.
  const std::string osm = write(dir / "city.osm", R"(<?xml version="1.0" encoding="UTF-8"?>
<osm version="0.6" generator="rlrun test">
  <bounds minlat="52.5000" minlon="13.4000" maxlat="52.5100" maxlon="13.4300"/>
  <node id="1" lat="52.5050" lon="13.4000"/>
  <node id="2" lat="52.5050" lon="13.4060"><tag k="highway" v="traffic_signals"/></node>
  <node id="3" lat="52.5050" lon="13.4120"><tag k="highway" v="traffic_signals"/></node>
  <node id="4" lat="52.5050" lon="13.4180"><tag k="highway" v="traffic_signals"/></node>
  <node id="5" lat="52.5050" lon="13.4240"><tag k="highway" v="traffic_signals"/></node>
  <node id="6" lat="52.5050" lon="13.4300"/>
  <node id="11" lat="52.5000" lon="13.4060"/>
  <node id="12" lat="52.5100" lon="13.4060"/>
  <node id="13" lat="52.5100" lon="13.4120"/>
  <node id="21" lat="52.5000" lon="13.4240"/>
  <node id="22" lat="52.5100" lon="13.4240"/>
  <node id="23" lat="52.5100" lon="13.4200"/>
  <node id="24" lat="52.5000" lon="13.4280"/>
  <way id="100"><nd ref="1"/><nd ref="2"/><nd ref="3"/><nd ref="4"/><nd ref="5"/><nd ref="6"/>
    <tag k="highway" v="primary"/><tag k="lanes" v="4"/></way>
  <way id="101"><nd ref="11"/><nd ref="2"/><nd ref="12"/><tag k="highway" v="secondary"/><tag k="lanes" v="2"/></way>
  <way id="102"><nd ref="3"/><nd ref="13"/><tag k="highway" v="residential"/></way>
  <way id="103"><nd ref="21"/><nd ref="5"/><nd ref="22"/><tag k="highway" v="secondary"/></way>
  <way id="104"><nd ref="5"/><nd ref="23"/><tag k="highway" v="tertiary"/></way>
  <way id="105"><nd ref="5"/><nd ref="24"/><tag k="highway" v="tertiary"/></way>
</osm>
)");
  std::set<int> green_counts;
  // netconvert's two common layouts give the same junctions different programs.
  for (const std::string layout : {"opposites", "incoming"}) {
    INFO(layout);
    const std::string net = dir / ("city_" + layout + ".net.xml");
    const CommandResult made =
        run_command("netconvert --osm-files '" + osm +
                    "' --type-files /usr/share/sumo/data/typemap/osmNetconvert.typ.xml "
                    "--xml-validation never --tls.layout " +
                    layout + " -o '" + net + "'");
    INFO(made.output);
    REQUIRE(made.exit_code == 0);
    const std::string routes = dir / ("city_" + layout + ".rou.xml");
    const CommandResult trips = run_command(
        "SUMO_HOME=/usr/share/sumo /usr/bin/python3 /usr/share/sumo/tools/randomTrips.py -n '" +
        net + "' -b 0 -e 600 -p 2 --seed 1 --validate --fringe-factor max -o '" +
        dir / "trips.xml" + "' -r '" + routes + "'");
    INFO(trips.output);
    REQUIRE(trips.exit_code == 0);
    const std::string scenario =
        write(dir / ("city_" + layout + ".yaml"), "name: city\nnet_file: city_" + layout +
                                                      ".net.xml\n"
                                                      "route_files: [city_" +
                                                      layout + ".rou.xml]\nbegin: 0\nend: 600\n");
    TrafficNetwork::Config config;
    config.scenario.value = scenario;
    TrafficNetwork env(config);
    env.watch_outgoing_lanes();
    CHECK(env.num_agents() == 4);
    // randomTrips' routes name an XML schema: SUMO must load them without SUMO_HOME.
    REQUIRE(read_text(routes).find("xsi:noNamespaceSchemaLocation") != std::string::npos);
    const std::string sumo_home = std::getenv("SUMO_HOME") ? std::getenv("SUMO_HOME") : "";
    unsetenv("SUMO_HOME");
    int most_greens = 0, most_lanes = 0;
    for (const LightAgent& agent : env.agents()) {
      green_counts.insert(agent.num_greens());
      most_greens = std::max(most_greens, agent.num_greens());
      most_lanes = std::max(most_lanes, agent.num_incoming());
    }
    CHECK(env.action_space() == Space::discrete(most_greens));
    CHECK(env.observation_space().flat_dim() == most_greens + 1 + 2 * most_lanes);
    // Random actions (within the widest light's greens) and max-pressure run a whole episode.
    Rng rng(5);
    run_episode(env, 1,
                [&](TrafficNetwork& e, const std::vector<float>&, std::vector<float>& a, int) {
                  for (float& x : a) e.action_space().sample(rng, std::span<float>(&x, 1));
                });
    CHECK(info_of(env, "throughput") > 50);
    run_episode(env, 1, kMaxPressure);
    CHECK(info_of(env, "throughput") > 50);
    if (!sumo_home.empty()) setenv("SUMO_HOME", sumo_home.c_str(), 1);
  }
  for (int greens : {1, 2, 3, 6}) {
    INFO(greens << " green phases");
    CHECK(green_counts.count(greens) == 1);
  }
}

TEST_CASE("TrafficNetwork: bad scenarios are clear errors before SUMO runs", "[traffic_network]") {
  TempDir dir("traffic_network_errors");
  const std::string grid = kSource + "/sumo_data/grid4x4/";
  TrafficNetwork::Config config;
  config.backend = "traci";
  config.sumo_binary.value = "/nonexistent/sumo";  // any error below comes before SUMO is needed
  const auto error_of = [&](const std::string& yaml_text) {
    config.scenario.value = write(dir / "s.yaml", yaml_text);
    try {
      TrafficNetwork env(config);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // begin after end: at the YAML line.
  CHECK_THAT(error_of("net_file: " + grid + "grid4x4.net.xml\nroute_files: [" + grid +
                      "grid4x4.rou.xml]\nbegin: 900\nend: 600\n"),
             Catch::Contains("s.yaml:4") && Catch::Contains("must be before end"));
  // A route naming an edge the network lacks: the route file's line and the edge.
  write(dir / "bad.rou.xml",
        "<routes>\n  <vehicle id=\"v\" depart=\"0\">\n    <route edges=\"A0B0 nowhere\"/>\n"
        "  </vehicle>\n</routes>\n");
  CHECK_THAT(error_of("net_file: " + grid + "grid4x4.net.xml\nroute_files: [bad.rou.xml]\n"),
             Catch::Contains("bad.rou.xml:3") && Catch::Contains("'nowhere'") &&
                 Catch::Contains("does not fit the network"));
  // Edges that exist but do not connect (A0B0 ends at B0; A1B1 starts at A1).
  write(dir / "gap.rou.xml", "<routes>\n  <route id=\"r\" edges=\"A0B0 A1B1\"/>\n</routes>\n");
  CHECK_THAT(error_of("net_file: " + grid + "grid4x4.net.xml\nroute_files: [gap.rou.xml]\n"),
             Catch::Contains("gap.rou.xml:2") && Catch::Contains("'A0B0' does not lead to 'A1B1'"));
  write(dir / "trip.rou.xml",
        "<routes>\n<trip id=\"t\" depart=\"0\" from=\"A0B0\" to=\"B0A9\"/>\n</routes>\n");
  CHECK_THAT(error_of("net_file: " + grid + "grid4x4.net.xml\nroute_files: [trip.rou.xml]\n"),
             Catch::Contains("trip.rou.xml:2") && Catch::Contains("'B0A9'"));
  // Missing files, misspelt keys.
  CHECK_THAT(error_of("net_file: missing.net.xml\nroute_files: []\n"),
             Catch::Contains("s.yaml:1") && Catch::Contains("does not exist"));
  CHECK_THAT(error_of("net_file: " + grid + "grid4x4.net.xml\nroute_file: [x]\n"),
             Catch::Contains("route_file") && Catch::Contains("route_files"));
  // A network without traffic lights.
  const CommandResult made =
      run_command("netgenerate --grid --grid.number 2 -o '" + dir / "plain.net.xml" + "'");
  REQUIRE(made.exit_code == 0);
  write(dir / "empty.rou.xml", "<routes/>\n");
  CHECK_THAT(error_of("net_file: plain.net.xml\nroute_files: [empty.rou.xml]\n"),
             Catch::Contains("no traffic light"));
  // ts_ids naming no light: did-you-mean.
  config.ts_ids = {"B2", "C7"};
  CHECK_THAT(error_of("net_file: " + grid + "grid4x4.net.xml\nroute_files: [" + grid +
                      "grid4x4.rou.xml]\n"),
             Catch::Contains("'C7' is not a traffic light") && Catch::Contains("did you mean"));
  config.ts_ids.clear();
  // Only now is SUMO needed: the missing program names the package.
  config.scenario.value.clear();
  TrafficNetwork env(config);
  std::vector<float> obs(static_cast<size_t>(env.observation_space().flat_dim()) *
                         env.num_agents());
  CHECK_THROWS_WITH(env.reset(1, obs), Catch::Contains("install the Debian package 'sumo'"));
  // One agent's buffer for a 16-agent env is an error, not an overrun.
  std::vector<float> one(static_cast<size_t>(env.observation_space().flat_dim()));
  CHECK_THROWS_WITH(env.reset(1, one), Catch::Contains("16 agents"));
}

TEST_CASE("TrafficNetwork: a SUMO that dies is an error with its output, and none is left",
          "[traffic_network]") {
  TrafficNetwork::Config config;
  config.backend = "traci";
  config.num_seconds = 300;
  TrafficNetwork env(config);
  std::vector<float> obs(static_cast<size_t>(env.observation_space().flat_dim()) *
                         env.num_agents());
  std::vector<float> actions(env.num_agents(), 0.0f);
  std::vector<StepResult> results(env.num_agents());
  env.reset(1, obs);
  const pid_t pid = env.sumo_pid();
  REQUIRE(process_exists(pid));
  kill(pid, SIGKILL);
  CHECK_THROWS_WITH(env.step_agents(actions, obs, results),
                    Catch::Contains("SUMO stopped") && Catch::Contains("last lines of its output"));
  env.reset(2, obs);  // a new episode starts a new SUMO
  const pid_t next = env.sumo_pid();
  CHECK(next != pid);
  CHECK(process_exists(next));

  // libsumo: SUMO is the worker process itself; killed, it is an error saying how it ended.
  config.backend = "libsumo";
  TrafficNetwork in_worker(config);
  in_worker.reset(1, obs);
  const pid_t worker = in_worker.sumo_pid();
  REQUIRE(process_exists(worker));
  kill(worker, SIGKILL);
  CHECK_THROWS_WITH(in_worker.step_agents(actions, obs, results),
                    Catch::Contains("SUMO stopped") && Catch::Contains("killed by signal 9"));
}

TEST_CASE("TrafficNetwork: train a shared PPO policy, evaluate, record, compare baselines",
          "[traffic_network][cli]") {
  TempDir dir("traffic_network_cli");
  const std::string shorter = " --set env.kwargs.num_seconds=300";
  const auto trained =
      run_rlrun("train " + kSource + "/configs/traffic_network_ppo.yaml" + shorter +
                " --set env.n_envs=2 --timesteps 4000 --out " + dir.str());
  INFO(trained.output);
  REQUIRE(trained.exit_code == 0);
  // 2 envs x 16 agents = 32 columns of one policy; monitor.csv has the network's metrics.
  const std::string run = dir / "traffic_network_ppo/seed1";
  for (const std::string rank : {"0", "1"}) {
    const std::string monitor = read_text(run + "/" + rank + ".monitor.csv");
    INFO(monitor);
    // SB3's r,l,t, the network's metrics, then each light's own return.
    CHECK(monitor.find(
              "\nr,l,t,mean_delay,avg_waiting_time,avg_travel_time,throughput,mean_queue,r_0,") !=
          std::string::npos);
    CHECK(monitor.find(",r_15\n") != std::string::npos);
    CHECK(std::count(monitor.begin(), monitor.end(), '\n') >= 2 + 2);  // header lines + episodes
  }
  CHECK(read_text(run + "/progress.csv").find("rollout/mean_delay") != std::string::npos);
  const auto eval = run_rlrun("eval --model " + run + "/model.zip --episodes 1" + shorter);
  INFO(eval.output);
  CHECK(eval.exit_code == 0);
  CHECK(eval.output.find("mean_delay") != std::string::npos);
  const auto baseline = run_rlrun("eval --model " + run +
                                  "/model.zip --episodes 1 --baseline max-pressure" + shorter);
  INFO(baseline.output);
  CHECK(baseline.exit_code == 0);
  CHECK(baseline.output.find("max-pressure") != std::string::npos);
  const auto video = run_rlrun("record --model " + run +
                               "/model.zip --set env.kwargs.num_seconds=60"
                               " --set env.kwargs.render_focus=B1 --output " +
                               dir / "v.mp4");
  INFO(video.output);
  CHECK(video.exit_code == 0);
  CHECK(std::filesystem::file_size(dir / "v.mp4") > 1000);
  // DQN: one replay buffer and one Q-network for all lights (RESCO's IDQN with sharing).
  const auto dqn =
      run_rlrun("train " + kSource + "/configs/traffic_network_dqn.yaml" + shorter +
                " --set algo.learning_starts=500 --timesteps 2000 --out " + dir / "dqn");
  INFO(dqn.output);
  CHECK(dqn.exit_code == 0);
  CHECK(std::filesystem::exists(dir / "dqn/traffic_network_dqn/seed1/model.zip"));
  // libsumo, two envs and an eval env at once: each SUMO in a worker process of its own
  // (sumo-rl's LIBSUMO_AS_TRACI allows one simulation in all).
  const auto libsumo =
      run_rlrun("train " + kSource + "/configs/traffic_network_ppo.yaml" + shorter +
                " --set env.kwargs.backend=libsumo --set env.n_envs=2"
                " --set eval.freq=4096 --set eval.n_episodes=1 --timesteps 4000 --out " +
                dir / "libsumo");
  INFO(libsumo.output);
  CHECK(libsumo.exit_code == 0);
  CHECK(read_text(dir / "libsumo/traffic_network_ppo/seed1/evaluations.csv").find("mean_delay") !=
        std::string::npos);
  // In rlrun's own process, libsumo allows one simulation, and says so.
  const auto two = run_rlrun("train " + kSource + "/configs/traffic_network_ppo.yaml" + shorter +
                             " --set env.kwargs.backend=libsumo --set env.kwargs.own_process=false"
                             " --set env.n_envs=2 --timesteps 300 --out " +
                             dir / "two");
  CHECK(two.exit_code != 0);
  CHECK(two.output.find("one simulation per process") != std::string::npos);
}

TEST_CASE(
    "TrafficNetwork: after one Ctrl-C, SUMO still starts at a reset (training's rollout "
    "reaches its safe point)",
    "[traffic_network]") {
  // SUMO starts again at every reset; a first Ctrl-C in a rollout that crosses an episode's end
  // must let it start, or the run stops without its model (it did, 2 Ctrl-Cs in 3). Every way
  // SUMO is started: in a worker process (libsumo, traci) and as rlrun's own TraCI client.
  for (const auto& [backend, own_process] : std::vector<std::pair<std::string, bool>>{
           {"libsumo", true}, {"traci", true}, {"traci", false}}) {
    INFO(backend << (own_process ? " in a worker" : " in rlrun"));
    TrafficNetwork::Config config;
    config.scenario.value = kSource + "/scenarios/spider15.yaml";
    config.backend = backend;
    config.own_process = own_process;
    TrafficNetwork env(config);
    std::vector<float> obs(static_cast<size_t>(env.observation_space().flat_dim()) *
                           env.num_agents());
    install_interrupt_handlers();
    std::raise(SIGINT);
    REQUIRE(interrupt_count() == 1);
    CHECK_NOTHROW(env.reset(1, obs));
    CHECK(info_of(env, "sim_time") == 25201.0);
    clear_interrupts();
    use_default_interrupt_actions();
  }
}
