// GoLeft-v0: Stable-Baselines3's custom-env tutorial env ("GoLeftEnv", SB3 docs
// guide/custom_env and the 5_custom_gym_env notebook) as an rlrun plugin.
// The agent stands on a 1D grid and must walk to the leftmost cell.
#include <rlrun/plugin.hpp>
#include <stdexcept>
#include <string>

using rlrun::api::Space;
using rlrun::api::StepResult;

class GoLeft : public rlrun::api::Env {
 public:
  // Parameters, set in YAML under env.kwargs (`rlrun list GoLeft-v0 --plugin ...` prints them).
  struct Config {
    int grid_size = 10;         // number of cells
    bool random_start = false;  // start in a random cell instead of the rightmost one

    template <class V>
    void visit(V& v) {
      v("grid_size", grid_size, "number of cells; the goal is cell 0");
      v("random_start", random_start, "start in a random cell instead of the rightmost one");
    }
  };

  static constexpr int kLeft = 0;
  static constexpr int kRight = 1;

  // gymnasium.Env.__init__: define the spaces (and declare the info keys).
  explicit GoLeft(const Config& config) : config_(config) {
    if (config_.grid_size < 2) throw std::invalid_argument("grid_size must be >= 2");
    observation_space_ = Space::box(0.0f, static_cast<float>(config_.grid_size), {1});
    action_space_ = Space::discrete(2);
    is_success_ = info_.add_key("is_success");
  }

  // gymnasium.Env.reset(seed=...)
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override {
    seed_rng(seed);  // super().reset(seed=seed)
    position_ = config_.random_start ? static_cast<int>(integers(1, config_.grid_size))
                                     : config_.grid_size - 1;
    info_.clear();
    obs[0] = static_cast<float>(position_);
  }

  // gymnasium.Env.step(action) -> obs, reward, terminated, truncated, info
  StepResult step(std::span<const float> action, std::span<float> obs) override {
    const int a = static_cast<int>(action[0]);
    if (a == kLeft) {
      position_ -= 1;
    } else if (a == kRight) {
      position_ += 1;
    } else {
      throw std::invalid_argument("invalid action " + std::to_string(a));
    }
    position_ =
        position_ < 0 ? 0 : (position_ >= config_.grid_size ? config_.grid_size - 1 : position_);
    const bool terminated = position_ == 0;  // reached the goal
    info_.clear();
    info_.set(is_success_, terminated ? 1.0 : 0.0);
    obs[0] = static_cast<float>(position_);
    // Truncation (a time limit) is added by rlrun's TimeLimit, from the registration below.
    return {terminated ? 1.0 : 0.0, terminated, false};
  }

 private:
  Config config_;
  int position_ = 0;
  int is_success_ = 0;
};

// gymnasium.register(id="GoLeft-v0", entry_point=GoLeft, max_episode_steps=100)
RLRUN_PLUGIN(registrar) {
  registrar.add_env<GoLeft>("GoLeft-v0", "walk left to cell 0 of a 1D grid (SB3's GoLeftEnv)",
                            /*max_episode_steps=*/100);
}
