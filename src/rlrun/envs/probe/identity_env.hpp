#pragma once
// Identity probe envs: SB3's IdentityEnv family (stable_baselines3/common/envs/identity_env.py),
// the smallest test that an algorithm acts in a space. Observation and action space are the
// same space; every observation is a fresh uniform sample of it (the env's own stream), and
// the reward is 1 when the action equals the observed state (all entries), else 0:
//
//   IdentityEnv-v0               Discrete(dim)
//   IdentityEnvBox-v0            Box(low, high, (1,)); an action within eps of the state counts
//   IdentityEnvMultiDiscrete-v0  MultiDiscrete([dim, dim])
//   IdentityEnvMultiBinary-v0    MultiBinary(dim)
//
// Episodes never terminate; the registered TimeLimit truncates them after 100 steps (SB3's
// ep_length), so the best return is the episode length. `dim` defaults to 4, the size SB3's
// tests use (tests/test_identity.py); SB3's classes default to 1, a one-value space.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/env_base.hpp"

namespace rlrun {

class IdentityEnv : public EnvBase {
 public:
  static constexpr int kMaxEpisodeSteps = 100;  // SB3 IdentityEnv ep_length

  // `space` is the observation and the action space; `eps` is the Box tolerance.
  IdentityEnv(const Space& space, std::string id, double eps = 0.0);

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  bool can_save_state() const override { return true; }
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;

  RenderSpec render_spec() const override;
  bool render(Frame& frame) const override;
  bool render_observation(std::span<const float> obs, Frame& frame) const override;

 private:
  // The reward rule: every entry equal (Box: within eps).
  bool matches(std::span<const float> action, std::span<const float> state) const;
  // One row per entry: the cells of its values (a number line for a Box), the state
  // green, the last action (when `action` is not empty) a disc, blue when rewarded.
  void draw(std::span<const float> state, std::span<const float> action, Frame& frame) const;

  double eps_;
  bool has_state_ = false;
  bool has_action_ = false;
  std::vector<float> state_, last_state_, last_action_;
};

class IdentityDiscrete : public IdentityEnv {
 public:
  struct Config {
    int dim = 4;
    template <class V>
    void visit(V& v) {
      v("dim", dim, "number of values: Discrete(dim)", in_range(1, 1000));
    }
  };
  explicit IdentityDiscrete(const Config& config);
};

class IdentityBox : public IdentityEnv {
 public:
  struct Config {
    double low = -1.0;
    double high = 1.0;
    double eps = 0.05;
    template <class V>
    void visit(V& v) {
      v("low", low, "lower bound of the Box(low, high, (1,))", in_range(-1e6, 1e6));
      v("high", high, "upper bound of the Box (> low)", in_range(-1e6, 1e6));
      v("eps", eps, "an action within eps of the state is rewarded", non_negative());
    }
  };
  // Throws std::invalid_argument unless low < high.
  explicit IdentityBox(const Config& config);
};

class IdentityMultiDiscrete : public IdentityEnv {
 public:
  struct Config {
    int dim = 4;
    template <class V>
    void visit(V& v) {
      v("dim", dim, "values per entry: MultiDiscrete([dim, dim])", in_range(1, 1000));
    }
  };
  explicit IdentityMultiDiscrete(const Config& config);
};

class IdentityMultiBinary : public IdentityEnv {
 public:
  struct Config {
    int dim = 4;
    template <class V>
    void visit(V& v) {
      v("dim", dim, "number of bits: MultiBinary(dim)", in_range(1, 64));
    }
  };
  explicit IdentityMultiBinary(const Config& config);
};

}  // namespace rlrun
