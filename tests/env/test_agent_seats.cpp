// Agent seats (src/rlrun/env/agent_seats.hpp): k learners' single-agent views of one shared
// multi-agent env, meeting at every reset and step. Checked against the multi-agent VecEnv
// stepping the same env with the same seed and actions; a learner that leaves, or an env that
// throws, stops the others with the reason instead of leaving them waiting.
#include <catch2/catch.hpp>
#include <memory>
#include <thread>

#include "fakes/agents_env.hpp"
#include "rlrun/env/agent_seats.hpp"
#include "rlrun/env/vec_env.hpp"

using namespace rlrun;
using rlrun::testing::AgentsEnv;

namespace {

constexpr int kAgents = 3;
constexpr int kCopies = 2;

// Agent a's VecEnv of kCopies seats, claimed as a learner's env factory would.
VecEnv seats_of(SeatTable& table, int agent, int episode_length) {
  std::vector<EnvPtr> seats;
  for (int c = 0; c < kCopies; ++c)
    seats.push_back(std::make_unique<AgentSeat>(
        table.claim(agent, [&] { return std::make_unique<AgentsEnv>(kAgents, episode_length); }),
        agent));
  return VecEnv(std::move(seats));
}

// Action of agent a at step t: its target at even steps, the other value at odd ones (so the
// rewards differ between steps).
float action_for(const Eigen::MatrixXf& obs, int column, int t) {
  const float target = obs(1, column);
  return t % 2 == 0 ? target : 1.0f - target;
}

}  // namespace

TEST_CASE(
    "agent seats: each learner sees its agent of the shared env, as the multi-agent "
    "VecEnv gives it",
    "[env][multi_agent][agent_seats]") {
  constexpr int kSteps = 25;
  // The reference: one VecEnv of kCopies three-agent envs (columns copy-major, agent-minor).
  std::vector<EnvPtr> envs;
  for (int c = 0; c < kCopies; ++c) envs.push_back(std::make_unique<AgentsEnv>(kAgents, 7));
  VecEnv reference(std::move(envs));
  reference.seed(11);
  reference.reset();
  std::vector<Eigen::MatrixXf> expected_obs{reference.obs()};
  std::vector<Eigen::VectorXd> expected_rewards;
  for (int t = 0; t < kSteps; ++t) {
    Eigen::MatrixXf actions(1, kCopies * kAgents);
    for (int i = 0; i < kCopies * kAgents; ++i) actions(0, i) = action_for(reference.obs(), i, t);
    reference.step(actions);
    expected_obs.push_back(reference.obs());
    expected_rewards.push_back(reference.rewards());
  }

  SeatTable table({"a", "b", "c"});
  std::vector<std::vector<Eigen::MatrixXf>> seen_obs(kAgents);
  std::vector<std::vector<Eigen::VectorXd>> seen_rewards(kAgents);
  std::vector<std::thread> learners;
  for (int a = 0; a < kAgents; ++a)
    learners.emplace_back([&, a] {
      VecEnv env = seats_of(table, a, 7);
      env.seed(11);  // every learner seeds alike; agent 0's seed is the one used
      env.reset();
      seen_obs[a].push_back(env.obs());
      for (int t = 0; t < kSteps; ++t) {
        Eigen::MatrixXf actions(1, kCopies);
        for (int c = 0; c < kCopies; ++c) actions(0, c) = action_for(env.obs(), c, t);
        env.step(actions);
        seen_obs[a].push_back(env.obs());
        seen_rewards[a].push_back(env.rewards());
      }
      table.leave(a, "finished");
    });
  for (std::thread& learner : learners) learner.join();

  for (int a = 0; a < kAgents; ++a)
    for (int c = 0; c < kCopies; ++c) {
      const int column = c * kAgents + a;
      for (size_t t = 0; t < expected_obs.size(); ++t) {
        INFO("agent " << a << " copy " << c << " step " << t);
        CHECK(seen_obs[a][t].col(c) == expected_obs[t].col(column));
        if (t > 0) CHECK(seen_rewards[a][t - 1][c] == expected_rewards[t - 1][column]);
      }
    }
}

TEST_CASE("agent seats: a learner that stops releases the others with the reason",
          "[env][multi_agent][agent_seats]") {
  SeatTable table({"a", "b", "c"});
  std::vector<std::string> errors(kAgents);
  std::vector<std::thread> learners;
  for (int a = 0; a < kAgents; ++a)
    learners.emplace_back([&, a] {
      try {
        VecEnv env = seats_of(table, a, 0);
        env.seed(1);
        env.reset();
        const int steps = a == 1 ? 5 : 1000;  // agent b's learner stops early
        for (int t = 0; t < steps; ++t) env.step(Eigen::MatrixXf::Zero(1, kCopies));
      } catch (const SeatsStopped& e) {
        errors[a] = e.what();
      }
      table.leave(a, a == 1 ? "diverged at step 5" : "stopped");
    });
  for (std::thread& learner : learners) learner.join();
  CHECK(errors[1].empty());
  for (int a : {0, 2}) {
    INFO(errors[a]);
    CHECK(errors[a].find("agent b's learner stopped (diverged at step 5)") != std::string::npos);
  }
}

TEST_CASE("agent seats: an env that throws fails every learner's step with its message",
          "[env][multi_agent][agent_seats]") {
  struct FailingEnv : AgentsEnv {
    FailingEnv() : AgentsEnv(2, 0) {}
    void step_agents(std::span<const float> actions, std::span<float> obs,
                     std::span<StepResult> results) override {
      if (++steps == 3) throw RuntimeFailure("the simulator crashed");
      AgentsEnv::step_agents(actions, obs, results);
    }
    int steps = 0;
  };
  SeatTable table({"x", "y"});
  std::vector<std::string> errors(2);
  std::vector<std::thread> learners;
  for (int a = 0; a < 2; ++a)
    learners.emplace_back([&, a] {
      try {
        AgentSeat seat(table.claim(a, [] { return std::make_unique<FailingEnv>(); }), a);
        std::vector<float> obs(2), action(1, 0.0f);
        seat.reset(1, obs);
        for (int t = 0; t < 10; ++t) seat.step(action, obs);
      } catch (const std::exception& e) {
        errors[a] = e.what();
      }
      table.leave(a, errors[a]);
    });
  for (std::thread& learner : learners) learner.join();
  CHECK(errors[0] == "the simulator crashed");
  CHECK(errors[1] == "the simulator crashed");
}

TEST_CASE("agent seats: each seat reads its own agent's action mask",
          "[env][multi_agent][agent_seats]") {
  // Two agents of Discrete(2): agent 0 may only take 0, agent 1 only 1.
  struct MaskedEnv : AgentsEnv {
    MaskedEnv() : AgentsEnv(2, 0) {
      for (int k = 0; k < 4; ++k) mask_keys[k] = info_.add_key("action_mask." + std::to_string(k));
      step_key = info_.add_key("step");
    }
    void reset(std::optional<uint64_t> seed, std::span<float> obs) override {
      AgentsEnv::reset(seed, obs);
      write_info(0);
    }
    void step_agents(std::span<const float> actions, std::span<float> obs,
                     std::span<StepResult> results) override {
      AgentsEnv::step_agents(actions, obs, results);
      write_info(++steps);
    }
    void write_info(int step) {
      const float masks[4] = {1, 0, 0, 1};
      for (int k = 0; k < 4; ++k) info_.set(mask_keys[k], masks[k]);
      info_.set(step_key, step);
    }
    int mask_keys[4] = {};
    int step_key = 0;
    int steps = 0;
  };
  SeatTable table({"x", "y"});
  std::vector<std::vector<double>> seen(2);
  std::vector<std::thread> learners;
  for (int a = 0; a < 2; ++a)
    learners.emplace_back([&, a] {
      AgentSeat seat(table.claim(a, [] { return std::make_unique<MaskedEnv>(); }), a);
      std::vector<float> obs(2), action(1, 0.0f);
      seat.reset(1, obs);
      seat.step(action, obs);
      const Info& info = seat.info();
      CHECK(info.find("action_mask.2") < 0);  // the other agent's entries are not this seat's
      seen[a] = {info.get(info.find("action_mask.0")), info.get(info.find("action_mask.1")),
                 info.get(info.find("step"))};
      table.leave(a, "finished");
    });
  for (std::thread& learner : learners) learner.join();
  CHECK(seen[0] == std::vector<double>{1, 0, 1});
  CHECK(seen[1] == std::vector<double>{0, 1, 1});
}
