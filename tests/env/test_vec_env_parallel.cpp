// VecEnv stepping envs that wait on other processes in two halves (vec_env.hpp, SplitStep:
// start every copy's step before finishing any) must give exactly what stepping one copy
// after another gives, through the wrappers that forward the halves.
#include <catch2/catch.hpp>

#include <atomic>
#include <memory>
#include <stdexcept>
#include <vector>

#include "env/vec_env_trace.hpp"
#include "fakes/counter_env.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/wrappers/clip_action.hpp"
#include "rlrun/wrappers/monitor.hpp"
#include "rlrun/wrappers/normalize_observation.hpp"
#include "rlrun/wrappers/rescale_action.hpp"
#include "rlrun/wrappers/time_limit.hpp"
#include "rlrun/wrappers/transform_reward.hpp"

using namespace rlrun;
using rlrun::testing::CounterEnv;
using rlrun::testing::trace_random_steps;
using rlrun::testing::VecEnvTrace;

namespace {

// A CounterEnv stepped in halves: start_step keeps the action, finish_step steps. It counts
// how many steps are started and not yet finished across all copies, so a test can see that
// the VecEnv started every copy before it finished any.
class SplitCounter : public CounterEnv, public SplitStep {
 public:
  SplitCounter(int length, std::atomic<int>& in_flight, int& most_in_flight)
      : CounterEnv(length), in_flight_(in_flight), most_(most_in_flight) {}
  bool steps_asynchronously() const override { return true; }
  void start_step(std::span<const float> action) override {
    action_.assign(action.begin(), action.end());
    most_ = std::max(most_, ++in_flight_);
  }
  StepResult finish_step(std::span<float> obs) override {
    --in_flight_;
    if (++finished_ == fail_at_) throw std::runtime_error("worker failed");
    return step(action_, obs);
  }
  int fail_at_ = -1;  // finish_step number that throws (-1: none)

 private:
  std::vector<float> action_;
  int finished_ = 0;
  std::atomic<int>& in_flight_;
  int& most_;
};

}  // namespace

TEST_CASE("VecEnv starts every copy's step before finishing any (SplitStep)", "[vec_env]") {
  std::atomic<int> in_flight{0};
  int most = 0;
  std::vector<EnvPtr> split, plain;
  for (int i = 0; i < 4; ++i) {
    // TimeLimit and Monitor forward the halves, so the stack stays asynchronous.
    split.push_back(std::make_unique<Monitor>(
        std::make_unique<TimeLimit>(std::make_unique<SplitCounter>(7, in_flight, most), 5), "", 0.0,
        std::vector<std::string>{"is_success"}, false));
    plain.push_back(
        std::make_unique<Monitor>(std::make_unique<TimeLimit>(std::make_unique<CounterEnv>(7), 5),
                                  "", 0.0, std::vector<std::string>{"is_success"}, false));
    // Shared running statistics, as make_vec_env links them: finished in copy order, the
    // split steps update them in the same sequence as whole steps.
    split.back() = std::make_unique<NormalizeObservation>(std::move(split.back()),
                                                          NormalizeObservation::Config{});
    plain.back() = std::make_unique<NormalizeObservation>(std::move(plain.back()),
                                                          NormalizeObservation::Config{});
  }
  for (int i = 1; i < 4; ++i) {
    dynamic_cast<ModelStatistics&>(*split[i]).share_statistics_with(
        dynamic_cast<ModelStatistics&>(*split[0]));
    dynamic_cast<ModelStatistics&>(*plain[i]).share_statistics_with(
        dynamic_cast<ModelStatistics&>(*plain[0]));
  }
  VecEnv a(std::move(split)), b(std::move(plain));
  const VecEnvTrace ta = trace_random_steps(a, 40, 3), tb = trace_random_steps(b, 40, 3);
  CHECK(most == 4);
  CHECK(in_flight == 0);
  CHECK(ta.obs == tb.obs);
  CHECK(ta.final_obs == tb.final_obs);
  CHECK(ta.rewards == tb.rewards);
  CHECK(ta.dones == tb.dones);
  for (int c = 0; c < 4; ++c) CHECK(a.info(c).keys() == b.info(c).keys());
}

TEST_CASE("VecEnv finishes every started step when one copy fails", "[vec_env]") {
  // Otherwise a worker's unread reply would answer the copy's next request.
  std::atomic<int> in_flight{0};
  int most = 0;
  std::vector<EnvPtr> envs;
  for (int i = 0; i < 4; ++i) envs.push_back(std::make_unique<SplitCounter>(100, in_flight, most));
  static_cast<SplitCounter&>(*envs[1]).fail_at_ = 3;
  VecEnv vec(std::move(envs));
  vec.seed(0);
  vec.reset();
  const Eigen::MatrixXf actions = Eigen::MatrixXf::Zero(1, 4);
  vec.step(actions);
  vec.step(actions);
  CHECK_THROWS_WITH(vec.step(actions), "worker failed");
  CHECK(in_flight == 0);
}

TEST_CASE("The action and reward wrappers forward split steps too", "[vec_env]") {
  // ClipAction -> RescaleAction -> TransformReward on a split env: still asynchronous, and the
  // same rewards and observations as whole steps.
  std::atomic<int> in_flight{0};
  int most = 0;
  auto stack = [](EnvPtr env) -> EnvPtr {
    TransformReward::Config reward;
    reward.scale = 0.5;
    env = std::make_unique<TransformReward>(std::move(env), reward);
    RescaleAction::Config rescale;
    rescale.min_action = {{-2.0}};
    rescale.max_action = {{2.0}};
    env = std::make_unique<RescaleAction>(std::move(env), rescale);
    return std::make_unique<ClipAction>(std::move(env));
  };
  std::vector<EnvPtr> split, plain;
  for (int i = 0; i < 3; ++i) {
    split.push_back(stack(std::make_unique<SplitCounter>(6, in_flight, most)));
    plain.push_back(stack(std::make_unique<CounterEnv>(6)));
  }
  REQUIRE(asynchronous_steps(*split[0]) != nullptr);
  VecEnv a(std::move(split)), b(std::move(plain));
  const VecEnvTrace ta = trace_random_steps(a, 30, 5), tb = trace_random_steps(b, 30, 5);
  CHECK(most == 3);
  CHECK(ta.rewards == tb.rewards);
  CHECK(ta.obs == tb.obs);
  CHECK(ta.dones == tb.dones);
}
