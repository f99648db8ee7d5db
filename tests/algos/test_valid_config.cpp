// Validation once (issue 42): an algorithm's constructor checks a Config built in code against
// the same visit() constraints that read_config applies to a file, so a constraint lives in
// one place. Before, each constructor had its own hand-written subset: PPO knew nothing of
// gamma, SAC nothing of its policy's n_critics or the entropy target, TD3 nothing of its
// learning rate, and a constraint added to visit() did not reach them.
#include <catch2/catch.hpp>

#include <stdexcept>

#include "rlrun/algos/a2c/a2c.hpp"
#include "rlrun/algos/dqn/dqn.hpp"
#include "rlrun/algos/ppo/ppo.hpp"
#include "rlrun/algos/sac/sac.hpp"
#include "rlrun/algos/td3/td3.hpp"
#include "rlrun/algos/tqc/tqc.hpp"
#include "rlrun/core/config_validation.hpp"

using namespace rlrun;
using Catch::Matchers::Contains;

namespace {

AlgorithmSetup box_setup() {
  return AlgorithmSetup{Space::box(-1.0f, 1.0f, {3}), Space::box(-1.0f, 1.0f, {2}), 1, 0};
}
AlgorithmSetup discrete_setup() {
  return AlgorithmSetup{Space::box(-1.0f, 1.0f, {3}), Space::discrete(2), 1, 0};
}

}  // namespace

TEST_CASE("valid_config: every visit() constraint, nested sections as key paths",
          "[algos][config]") {
  SAC::Config c;
  CHECK(&valid_config(c, "SAC") == &c);
  c.off_policy.gamma = 2.0;
  c.policy.n_critics = 0;
  c.target_entropy = "lots";
  try {
    valid_config(c, "SAC");
    FAIL("no throw");
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    CHECK_THAT(message, Contains("SAC: gamma must be in [0, 1], got 2"));
    CHECK_THAT(message, Contains("policy.n_critics must be in [1, 100], got 0"));
    CHECK_THAT(message, Contains("target_entropy"));
  }
}

TEST_CASE("algorithm constructors check their Config's visit() constraints", "[algos][config]") {
  {
    PPO::Config c;
    c.gamma = 1.5;  // PPO's constructor checked only n_steps, batch_size and n_epochs
    CHECK_THROWS_WITH(PPO(c, discrete_setup()), Contains("PPO: gamma must be in [0, 1], got 1.5"));
    c = {};
    c.batch_size = 1;
    CHECK_THROWS_WITH(PPO(c, discrete_setup()), Contains("PPO: batch_size must be in [2,"));
  }
  {
    A2C::Config c;
    c.n_steps = 0;  // A2C's constructor checked nothing
    CHECK_THROWS_WITH(A2C(c, discrete_setup()), Contains("A2C: n_steps must be in [1,"));
  }
  {
    SAC::Config c;
    c.policy.n_critics = 0;
    CHECK_THROWS_WITH(SAC(c, box_setup()), Contains("SAC: policy.n_critics must be in [1, 100]"));
    c = {};
    c.target_update_interval = 0;
    CHECK_THROWS_WITH(SAC(c, box_setup()), Contains("SAC: target_update_interval must be >= 1"));
  }
  {
    TQC::Config c;
    c.policy.n_quantiles = 0;
    CHECK_THROWS_WITH(TQC(c, box_setup()), Contains("TQC: policy.n_quantiles must be"));
  }
  {
    TD3::Config c;
    c.learning_rate = Schedule::constant(-1.0);
    CHECK_THROWS_WITH(TD3(c, box_setup()), Contains("TD3: learning_rate must be >= 0, got -1"));
    c = {};
    c.off_policy.gradient_steps = -2;  // -1 means "as many as env steps"; below is nothing
    CHECK_THROWS_WITH(TD3(c, box_setup()), Contains("TD3: gradient_steps must be >= -1, got -2"));
  }
  {
    DQN::Config c;
    c.exploration_final_eps = 1.5;
    CHECK_THROWS_WITH(DQN(c, discrete_setup()),
                      Contains("DQN: exploration_final_eps must be in [0, 1], got 1.5"));
    // What visit() cannot say stays in the constructor: a target network that moves.
    c = {};
    c.off_policy.tau = 0.0;
    CHECK_THROWS_WITH(DQN(c, discrete_setup()), Contains("DQN: tau must be in (0, 1]"));
  }
}
