// TrafficSignal-v0 on the real SUMO (installed by scripts/setup.sh): the light's rules, the
// metrics against SUMO's own tripinfo output, process ownership and SUMO failures.
#include <signal.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <vector>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/sumo/network_scenario.hpp"
#include "rlrun/envs/sumo/tripinfo.hpp"
#include "rlrun/envs/traffic/fixed_time_policy.hpp"
#include "rlrun/envs/traffic/traffic_signal.hpp"
#include "runtime/cli_runner.hpp"
#include "runtime/video_probe.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

bool process_exists(pid_t pid) { return pid > 0 && kill(pid, 0) == 0; }

float act(TrafficSignal& env, int action, std::vector<float>& obs, StepResult* out = nullptr) {
  const float a = static_cast<float>(action);
  const StepResult r = env.step({&a, 1}, obs);
  if (out) *out = r;
  return static_cast<float>(r.reward);
}

// Means over the <tripinfo> elements of SUMO's tripinfo XML (a regex, independent of
// read_tripinfo): duration and waitingTime.
struct TripStats {
  int trips = 0;
  double duration = 0, waiting = 0;
};
TripStats read_trips_independently(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  static const std::regex trip(
      R"re(<tripinfo [^>]*duration="([0-9.]+)"[^>]*waitingTime="([0-9.]+)")re");
  TripStats stats;
  for (auto it = std::sregex_iterator(s.begin(), s.end(), trip); it != std::sregex_iterator();
       ++it) {
    ++stats.trips;
    stats.duration += std::stod((*it)[1]);
    stats.waiting += std::stod((*it)[2]);
  }
  if (stats.trips > 0) {
    stats.duration /= stats.trips;
    stats.waiting /= stats.trips;
  }
  return stats;
}

}  // namespace

TEST_CASE("TrafficSignal: spaces, yellow on every switch, min_green", "[traffic]") {
  TrafficSignal::Config config;
  config.num_seconds = 60;
  config.delta_time = 5;
  config.yellow_time = 3;
  config.min_green = 10;
  TrafficSignal env(config);
  CHECK(env.observation_space().describe() == "Box(0.0, 1.0, (10,), float32)");
  CHECK(env.action_space().describe() == "Discrete(4)");
  std::vector<float> obs(10);
  env.reset(7, obs);
  CHECK(env.green_approach() == traffic::kNorth);
  CHECK(obs[8] == 0.0f);
  // Asking for East before min_green keeps North.
  act(env, traffic::kEast, obs);
  CHECK(env.green_approach() == traffic::kNorth);
  act(env, traffic::kEast, obs);  // 11 s of green now
  CHECK(env.green_approach() == traffic::kNorth);
  act(env, traffic::kEast, obs);  // switches: 3 s yellow, then East for 2 s
  CHECK(env.green_approach() == traffic::kEast);
  CHECK(obs[8] == Approx(2.0 / 3.0));
  CHECK(obs[9] == Approx(2.0 / 60.0));
  for (float v : obs) {
    CHECK(v >= 0.0f);
    CHECK(v <= 1.0f);
  }
  // Truncated at num_seconds of simulated time.
  StepResult r;
  int steps = 3;
  do {
    act(env, traffic::kEast, obs, &r);
    ++steps;
  } while (!r.truncated && steps < 100);
  CHECK(r.truncated);
  CHECK_FALSE(r.terminated);
  CHECK(env.sim_time() == Approx(61.0));  // reset's first second + 12 steps of 5 s
}

// The env's light control reproduces a plain `sumo` run of the same timeline: 900 s with
// N green from the start, then every 30 s a switch (3 s yellow, 27 s green) to S, E, W, N...
// written as a static SUMO program. Same seed, same signal states second by second: the same
// trips, so the env's episode metrics must equal that independent run's tripinfo (issue:
// within 1 %), and the env's own tripinfo file too.
TEST_CASE("TrafficSignal: metrics equal a plain SUMO run of the same signal plan", "[traffic]") {
  TempDir dir("traffic_tripinfo");
  const std::string links[] = {"GGGGrrrrrrrrrrrr", "rrrrrrrrGGGGrrrr", "rrrrGGGGrrrrrrrr",
                               "rrrrrrrrrrrrGGGG"};  // N, S, E, W (tls.tll.xml's link order)
  const auto yellow = [](std::string state) {
    for (char& c : state) c = c == 'G' ? 'y' : c;
    return state;
  };
  std::string phases = "<phase duration=\"31\" state=\"" + links[0] + "\"/>";
  for (int switch_no = 1; 31 + 30 * (switch_no - 1) < 900; ++switch_no)
    phases += "<phase duration=\"3\" state=\"" + yellow(links[(switch_no - 1) % 4]) + "\"/>" +
              "<phase duration=\"27\" state=\"" + links[switch_no % 4] + "\"/>";
  std::ofstream(dir / "plan.xml") << "<additional><tlLogic id=\"C\" type=\"static\" "
                                     "programID=\"plan\" offset=\"0\">"
                                  << phases << "</tlLogic></additional>";
  const std::string cfg =
      traffic::load_network_scenario("scenarios/single_intersection.yaml").files.sumocfg;
  const auto plain = run_command("sumo -c " + cfg + " --additional-files " + dir / "plan.xml" +
                                 // the env runs SUMO with --end num_seconds + 1 too: the
                                 // arrivals of the step that reaches 900 s count
                                 " --seed 3 --end 901 --no-step-log true --no-warnings true" +
                                 " --tripinfo-output " + dir / "plain.xml");
  INFO(plain.output);
  REQUIRE(plain.exit_code == 0);

  TrafficSignal::Config config;
  config.num_seconds = 900;
  config.tripinfo_output.value = dir / "env.xml";
  TrafficSignal env(config);
  std::vector<float> obs(10);
  env.reset(3, obs);
  StepResult r;
  int step = 0;
  const Info& info = env.info();
  do {
    act(env, (step++ / 6) % 4, obs, &r);  // N for the reset's second + 30 s, then 30 s each
    if (!r.truncated) CHECK(info.get(info.find("throughput")) == 0);  // known at the end
  } while (!r.truncated);
  const double waiting = info.get(info.find("avg_waiting_time"));
  const double travel = info.get(info.find("avg_travel_time"));
  const double throughput = info.get(info.find("throughput"));
  const TripStats trips = read_trips_independently(dir / "plain.xml");
  const TripStats own = read_trips_independently(dir / "env.xml");
  INFO("plain sumo: " << trips.trips << " trips, duration " << trips.duration << ", waiting "
                      << trips.waiting << "; env: " << throughput << ", " << travel << ", "
                      << waiting);
  REQUIRE(trips.trips > 300);
  CHECK(throughput == trips.trips);  // in fact exactly the same trips
  CHECK(throughput == Approx(trips.trips).epsilon(0.01));
  CHECK(travel == Approx(trips.duration).epsilon(0.01));
  CHECK(waiting == Approx(trips.waiting).epsilon(0.01));
  CHECK(throughput == own.trips);
  CHECK(travel == Approx(own.duration).epsilon(1e-12));
  CHECK(waiting == Approx(own.waiting).epsilon(1e-12));
}

TEST_CASE("read_tripinfo: means over the trips, clear errors", "[traffic]") {
  TempDir dir("traffic_tripinfo_reader");
  std::ofstream(dir / "t.xml")
      << "<tripinfos>\n  <tripinfo id=\"a\" depart=\"1.00\" duration=\"10.00\" routeLength=\"5\""
         " waitingTime=\"4.00\" waitingCount=\"1\" timeLoss=\"6.00\"/>\n  <tripinfo id=\"b\""
         " duration=\"20.00\" waitingTime=\"0.00\" timeLoss=\"1.00\"/>\n</tripinfos>\n";
  const TripinfoSummary s = rlrun::read_tripinfo(dir / "t.xml");
  CHECK(s.trips == 2);
  CHECK(s.mean_duration == 15.0);
  CHECK(s.mean_waiting == 2.0);
  CHECK(s.mean_time_loss == 3.5);
  std::ofstream(dir / "bad.xml") << "<tripinfos><tripinfo id=\"a\" duration=\"3\"/></tripinfos>";
  CHECK_THROWS_WITH(rlrun::read_tripinfo(dir / "bad.xml"),
                    Catch::Contains("without duration, waitingTime and timeLoss"));
  CHECK_THROWS_WITH(rlrun::read_tripinfo(dir / "none.xml"), Catch::Contains("is missing"));
}

// backend: libsumo runs the same client code in-process: the same episode, number for number.
TEST_CASE("TrafficSignal: libsumo and traci backends give the same episode", "[traffic]") {
  std::vector<std::vector<double>> traces;
  for (const char* backend : {"traci", "libsumo"}) {
    for (const char* reward_fn : {"queue", "diff-waiting-time", "pressure"}) {
      TrafficSignal::Config config;
      config.backend = backend;
      config.reward_fn = reward_fn;
      config.num_seconds = 400;
      TrafficSignal env(config);
      std::vector<float> obs(10);
      std::vector<double> trace;
      env.reset(5, obs);
      StepResult r;
      int step = 0;
      do {
        trace.push_back(act(env, (step * 7 / 5) % 4, obs, &r));
        trace.insert(trace.end(), obs.begin(), obs.end());
        ++step;
      } while (!r.truncated);
      for (double v : env.info().values()) trace.push_back(v);
      traces.push_back(trace);
    }
  }
  REQUIRE(traces.size() == 6);
  for (int i = 0; i < 3; ++i) {
    INFO("reward function " << i);
    CHECK(traces[i] == traces[3 + i]);
  }
}

TEST_CASE("TrafficSignal: libsumo runs one simulation per process and says so", "[traffic]") {
  TrafficSignal::Config config;
  config.backend = "libsumo";
  config.num_seconds = 60;
  std::vector<float> obs(10);
  {
    TrafficSignal first(config), second(config);
    first.reset(1, obs);
    CHECK(first.sumo_pid() == -1);  // in-process
    CHECK_THROWS_WITH(second.reset(1, obs), Catch::Contains("one simulation per process") &&
                                                Catch::Contains("backend: traci"));
  }
  TrafficSignal again(config);  // the first one's simulation closed with it
  CHECK_NOTHROW(again.reset(2, obs));
  config.gui = true;
  CHECK_THROWS_WITH(TrafficSignal(config), Catch::Contains("gui: true needs backend: traci"));
  config.gui = false;
  config.backend = "libsumo2";
  CHECK_THROWS_WITH(TrafficSignal(config), Catch::Contains("unknown backend 'libsumo2'"));
}

TEST_CASE("TrafficSignal: scenario files", "[traffic]") {
  // The shipped rush-hour scenario: 1.5 x the demand, so more vehicles arrive in 10 minutes.
  std::vector<double> arrived;
  for (const char* scenario : {"", "scenarios/single_intersection_rush.yaml"}) {
    TrafficSignal::Config config;
    config.scenario.value = scenario;
    config.num_seconds = 600;
    TrafficSignal env(config);
    std::vector<float> obs(10);
    env.reset(1, obs);
    StepResult r;
    int step = 0;
    do act(env, (step++ / 4) % 4, obs, &r);
    while (!r.truncated);
    arrived.push_back(env.info().get(env.info().find("throughput")));
  }
  INFO("default " << arrived[0] << ", rush " << arrived[1]);
  CHECK(arrived[1] > arrived[0] * 1.1);  // 20 s greens cannot clear all of 1.5 x
  CHECK(traffic::load_network_scenario("scenarios/single_intersection_rush.yaml").scale == 1.5);

  TempDir dir("traffic_scenario");
  std::ofstream(dir / "typo.yaml") << "name: x\nsumocfg: ../x.sumocfg\nscael: 2\n";
  CHECK_THROWS_WITH(traffic::load_network_scenario(dir / "typo.yaml"),
                    Catch::Contains("typo.yaml:3:1") && Catch::Contains("did you mean 'scale'"));
  std::ofstream(dir / "nocfg.yaml") << "name: x\nsumocfg: missing.sumocfg\n";
  CHECK_THROWS_WITH(traffic::load_network_scenario(dir / "nocfg.yaml"),
                    Catch::Contains("nocfg.yaml:2") && Catch::Contains("does not exist"));
  CHECK_THROWS_WITH(traffic::load_network_scenario("no/such/scenario.yaml"),
                    Catch::Contains("does not exist"));
}

TEST_CASE("TrafficSignal: same seed, same episode, reward functions", "[traffic]") {
  TrafficSignal::Config config;
  config.num_seconds = 120;
  for (const char* reward_fn : {"queue", "diff-waiting-time", "average-speed", "pressure"}) {
    config.reward_fn = reward_fn;
    std::vector<std::vector<float>> runs;
    for (int run = 0; run < 2; ++run) {
      TrafficSignal env(config);
      std::vector<float> obs(10), trace;
      env.reset(11, obs);
      for (int step = 0; step < 20; ++step) {
        trace.push_back(act(env, (step / 3) % 4, obs));
        trace.insert(trace.end(), obs.begin(), obs.end());
      }
      runs.push_back(trace);
    }
    INFO(reward_fn);
    CHECK(runs[0] == runs[1]);
  }
  config.reward_fn = "speed";
  CHECK_THROWS_WITH(TrafficSignal(config), Catch::Contains("unknown reward_fn 'speed'"));
}

TEST_CASE("TrafficSignal: SUMO processes end with their env, also when SUMO dies", "[traffic]") {
  TrafficSignal::Config config;
  config.num_seconds = 300;
  std::vector<float> obs(10);
  pid_t first = -1, second = -1;
  {
    TrafficSignal env(config);
    env.reset(1, obs);
    first = env.sumo_pid();
    CHECK(process_exists(first));
    env.reset(2, obs);  // every reset restarts SUMO
    second = env.sumo_pid();
    CHECK(second != first);
    CHECK_FALSE(process_exists(first));
  }
  CHECK_FALSE(process_exists(second));

  // SUMO killed mid-episode: the next step says so, with SUMO's last output; nothing is left.
  TrafficSignal env(config);
  env.reset(1, obs);
  const pid_t pid = env.sumo_pid();
  kill(pid, SIGKILL);
  const float a = 0.0f;
  CHECK_THROWS_AS(env.step({&a, 1}, obs), RuntimeFailure);
  try {
    env.step({&a, 1}, obs);
  } catch (const RuntimeFailure& e) {
    CHECK(std::string(e.what()).find("SUMO stopped") != std::string::npos);
  }
}

TEST_CASE("TrafficSignal: a missing sumo binary names the package", "[traffic]") {
  TrafficSignal::Config config;
  config.sumo_binary.value = "/nonexistent/sumo";
  TrafficSignal env(config);
  std::vector<float> obs(10);
  CHECK_THROWS_WITH(env.reset(1, obs), Catch::Contains("install the Debian package 'sumo'"));
}

TEST_CASE("TrafficSignal: no SUMO survives rlrun being killed", "[traffic][cli]") {
  TempDir dir("traffic_kill");
  // A long training run, killed with SIGKILL: its SUMO must go too (PR_SET_PDEATHSIG).
  const std::string cmd =
      std::string(RLRUN_BINARY) + " train " + std::string(RLRUN_SOURCE_DIR) +
      "/configs/cartpole_ppo.yaml" +
      " --set env.id=TrafficSignal-v0 --set 'algo.policy.net_arch=[8]'" +
      " --set env.n_envs=2 --set env.kwargs.scale=1.0001" +
      " --set env.kwargs.num_seconds=100000" +  // no SUMO restart within the test
      " --timesteps 100000000 --out " + dir.str() + " > " + dir / "out.txt" +
      " 2>&1 & pid=$!; sleep 2; " +
      "pgrep -P $pid -x sumo | wc -l; kill -9 $pid; wait $pid; sleep 0.5; " +
      "pgrep -f 'scale 1[.]000100' | wc -l";  // [.]: not this shell's own command line
  const auto r = run_command(cmd);
  INFO(r.output);
  std::istringstream lines(r.output);
  int before = -1, after = -1;
  lines >> before >> after;
  CHECK(before == 2);  // one SUMO per env
  CHECK(after == 0);
}

TEST_CASE("TrafficSignal: Ctrl-C stops training, saves the model, leaves no SUMO",
          "[traffic][cli]") {
  TempDir dir("traffic_sigint");
  const std::string cmd = std::string(RLRUN_BINARY) + " train " + std::string(RLRUN_SOURCE_DIR) +
                          "/configs/traffic_dqn.yaml --set env.n_envs=2" +
                          " --set env.kwargs.scale=1.0002 --set env.kwargs.num_seconds=100000" +
                          " --out " + dir.str() + " > " + dir / "out.txt" +
                          " 2>&1 & pid=$!; sleep 2; " +
                          "pgrep -P $pid -x sumo | wc -l; kill -INT $pid; wait $pid; echo $?; " +
                          "sleep 0.2; pgrep -f 'scale 1[.]000200' | wc -l";
  const auto r = run_command(cmd);
  std::ifstream out_file(dir / "out.txt");
  std::stringstream out;
  out << out_file.rdbuf();
  INFO(r.output << "\n" << out.str());
  std::istringstream lines(r.output);
  int before = -1, exit_code = -1, after = -1;
  lines >> before >> exit_code >> after;
  CHECK(before == 2);
  CHECK(exit_code == 130);
  CHECK(after == 0);
  // SUMO cannot snapshot its simulation: the model is saved, but there is no resumable state.
  CHECK(out.str().find("interrupted after") != std::string::npos);
  CHECK(std::filesystem::exists(dir / "traffic_dqn/seed1/model.zip"));
}

TEST_CASE("rlrun train with backend: libsumo (SUMO inside rlrun)", "[traffic][cli]") {
  TempDir dir("traffic_libsumo");
  const auto r = run_rlrun("train " + std::string(RLRUN_SOURCE_DIR) +
                           "/configs/traffic_dqn.yaml --set env.kwargs.backend=libsumo" +
                           " --set env.kwargs.num_seconds=300 --timesteps 300" +
                           " --set algo.learning_starts=100 --out " + dir.str());
  INFO(r.output);
  CHECK(r.exit_code == 0);
  const auto two = run_rlrun("train " + std::string(RLRUN_SOURCE_DIR) +
                             "/configs/traffic_dqn.yaml --set env.kwargs.backend=libsumo" +
                             " --set env.n_envs=2 --timesteps 300 --out " + dir / "two");
  INFO(two.output);
  CHECK(two.exit_code != 0);
  CHECK(two.output.find("one simulation per process") != std::string::npos);
}

TEST_CASE("FixedTimePolicy: N, S, E, W, each for green_time rounded up to decisions", "[traffic]") {
  FixedTimePolicy plan(12, 5);  // 12 s green at 5 s per decision: 3 decisions per approach
  std::vector<int> actions;
  for (int i = 0; i < 13; ++i) actions.push_back(plan.next_action(i == 0));
  CHECK(actions == std::vector<int>{0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 0});
  CHECK(plan.next_action(true) == 0);  // a new episode restarts the cycle
  CHECK_THROWS(FixedTimePolicy(0, 5));
}

TEST_CASE("eval --baseline fixed-time: both policies on the same episodes, metrics in the CSV",
          "[traffic][cli]") {
  TempDir dir("traffic_eval");
  const auto train = run_rlrun(
      "train " + std::string(RLRUN_SOURCE_DIR) + "/configs/traffic_dqn.yaml --timesteps 200" +
      " --set env.kwargs.num_seconds=300 --set algo.learning_starts=50 --out " + dir.str());
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const std::string model = dir / "traffic_dqn/seed1/model.zip";
  const auto r = run_rlrun("eval --model " + model + " --episodes 2 --baseline fixed-time" +
                           " --green-time 20 --csv " + dir / "eval.csv");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("fixed-time on TrafficSignal-v0, 2 episodes (green_time 20): mean_reward") !=
        std::string::npos);
  std::ifstream in(dir / "eval.csv");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  // One tidy table: a row per episode of each policy, no summary rows (the means are printed).
  REQUIRE(lines.size() == 5);
  CHECK(lines[0] ==
        "policy,episode,return,length,avg_waiting_time,avg_travel_time,total_queue_length,"
        "throughput,sim_time");
  CHECK(lines[1].rfind("DQN,0,", 0) == 0);
  CHECK(lines[2].rfind("DQN,1,", 0) == 0);
  CHECK(lines[3].rfind("fixed-time,0,", 0) == 0);
  CHECK(lines[4].rfind("fixed-time,1,", 0) == 0);
  // The baseline is the traffic task's: other models are refused.
  const auto other = run_rlrun("train " + std::string(RLRUN_SOURCE_DIR) +
                               "/configs/cartpole_ppo.yaml --timesteps 256 --out " + dir / "cp");
  REQUIRE(other.exit_code == 0);
  const auto refused = run_rlrun("eval --model " + dir / "cp/cartpole_ppo/seed1/model.zip" +
                                 " --episodes 1 --baseline fixed-time");
  CHECK(refused.exit_code == 2);
  CHECK(refused.output.find("policy 'fixed-time' does not come with CartPole-v1") !=
        std::string::npos);
}

TEST_CASE("record --policy fixed-time: an mp4 of the intersection from above", "[traffic][cli]") {
  TempDir dir("traffic_record");
  const auto r = run_rlrun("record --config " + std::string(RLRUN_SOURCE_DIR) +
                           "/configs/traffic_dqn.yaml --set env.kwargs.num_seconds=100" +
                           " --policy fixed-time --green-time 10 --output " + dir / "ft.mp4" +
                           " --frames " + dir / "frames");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  // 100 s at 5 s per decision: 20 steps, plus the frame after reset.
  CHECK(probe_video(dir / "ft.mp4").find("h264,600,600,21") != std::string::npos);
  CHECK(std::filesystem::exists(dir / "frames/frame_000020.png"));
  const auto refused =
      run_rlrun("record --env CartPole-v1 --policy fixed-time --output " + dir / "x.mp4");
  CHECK(refused.exit_code == 2);
}

namespace {

// A PNG's pixels as rgb24 bytes (ffmpeg decodes it).
std::vector<unsigned char> png_pixels(const std::string& png, const std::string& raw) {
  const auto r = run_command("ffmpeg -v error -y -i " + png + " -f rawvideo -pix_fmt rgb24 " + raw);
  REQUIRE(r.exit_code == 0);
  const std::string bytes = read_text(raw);
  return {bytes.begin(), bytes.end()};
}

}  // namespace

TEST_CASE("record: the overlay covers only grass, never a road", "[traffic][cli]") {
  // The same episode filmed with and without the overlay: every pixel the overlay changed must
  // be grass in the picture without it (the box once covered the top of the north arm).
  TempDir dir("traffic_overlay");
  for (const char* variant : {"with", "without"}) {
    const auto r = run_rlrun("record --config " + std::string(RLRUN_SOURCE_DIR) +
                             "/configs/traffic_dqn.yaml --set env.kwargs.num_seconds=50" +
                             " --policy fixed-time --frames " + dir / variant +
                             (std::string(variant) == "without" ? " --no-overlay" : ""));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
  }
  const auto with = png_pixels(dir / "with/frame_000005.png", dir / "with.rgb");
  const auto without = png_pixels(dir / "without/frame_000005.png", dir / "without.rgb");
  REQUIRE(with.size() == 600 * 600 * 3);
  REQUIRE(without.size() == with.size());
  int changed = 0, road = 0;
  for (size_t i = 0; i < with.size(); i += 3) {
    if (with[i] == without[i] && with[i + 1] == without[i + 1] && with[i + 2] == without[i + 2])
      continue;
    ++changed;
    const bool grass = without[i] == 96 && without[i + 1] == 140 && without[i + 2] == 80;
    road += !grass;
  }
  CHECK(changed > 1000);  // the overlay is there
  CHECK(road == 0);
}

// The issue's bar: configs/traffic_dqn.yaml as shipped (5e4 decisions, ~50 s) beats the fixed
// 30 s cycle on average waiting time over 5 evaluation hours. Hidden: a minute of training.
TEST_CASE("traffic_dqn beats fixed-time on average waiting time", "[.slow][traffic_learning]") {
  TempDir dir("traffic_learning");
  const auto train = run_rlrun("train " + std::string(RLRUN_SOURCE_DIR) +
                               "/configs/traffic_dqn.yaml --out " + dir.str());
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const auto r = run_rlrun("eval --model " + dir / "traffic_dqn/seed1/model.zip" +
                           " --episodes 5 --baseline fixed-time --csv " + dir / "eval.csv");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  // Mean avg_waiting_time (column 4) per policy over the episode rows.
  std::ifstream in(dir / "eval.csv");
  std::string header;
  std::getline(in, header);
  REQUIRE(header.rfind("policy,episode,return,length,avg_waiting_time,", 0) == 0);
  double sums[2] = {0, 0};
  int counts[2] = {0, 0};
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    REQUIRE(cells.size() > 4);
    const int k = cells[0] == "DQN" ? 0 : 1;
    sums[k] += std::stod(cells[4]);
    ++counts[k];
  }
  REQUIRE(counts[0] == 5);
  REQUIRE(counts[1] == 5);
  const double dqn = sums[0] / counts[0], fixed = sums[1] / counts[1];
  INFO("avg waiting: DQN " << dqn << " s, fixed-time " << fixed << " s");
  REQUIRE(dqn > 0);
  REQUIRE(fixed > 0);
  CHECK(dqn < fixed);
}
