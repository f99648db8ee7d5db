// GoLeft-v0: Stable-Baselines3's custom-env tutorial env ("GoLeftEnv", SB3 docs
// guide/custom_env and the 5_custom_gym_env notebook) as an rlrun plugin.
// The agent stands on a 1D grid and must walk to the leftmost cell.
//
// It derives from rlrun::EnvBase (on rlrun::Env, the interface of rlrun's own envs), so rlrun
// can do with it all it does with a built-in env: train, evaluate, record a video (render())
// and resume a run exactly (write_state() / read_state()).
#include <rlrun/frame.hpp>
#include <rlrun/plugin.hpp>
#include <stdexcept>
#include <string>

using rlrun::Space;
using rlrun::StepResult;

class GoLeft : public rlrun::EnvBase {
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
    seeding_.on_reset(seed);  // super().reset(seed=seed)
    position_ = config_.random_start ? 1 + static_cast<int>(seeding_.rng().below(
                                               static_cast<uint64_t>(config_.grid_size - 1)))
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

  // Exact resume: everything the next step depends on besides the Config.
  bool can_save_state() const override { return true; }
  void write_state(rlrun::StateWriter& out) const override {
    seeding_.write_state(out);
    out.put_int("position", position_);
  }
  void read_state(const rlrun::StateReader& in) override {
    seeding_.read_state(in);
    position_ = static_cast<int>(in.get_int_in("position", 0, config_.grid_size - 1));
  }

  // Video (render_mode="rgb_array"): the grid as squares, the agent as a circle, the goal green.
  rlrun::RenderSpec render_spec() const override { return {60 * config_.grid_size, 60, 4.0}; }
  bool render(rlrun::Frame& frame) const override {
    frame.begin_scene(config_.grid_size, 1.0, {255, 255, 255});
    for (int cell = 0; cell < config_.grid_size; ++cell) {
      const double x = cell;
      const rlrun::Point square[] = {
          {x + 0.05, 0.05}, {x + 0.95, 0.05}, {x + 0.95, 0.95}, {x + 0.05, 0.95}};
      frame.polygon(square, cell == 0 ? rlrun::Rgb{120, 200, 120} : rlrun::Rgb{220, 220, 220});
    }
    frame.circle({position_ + 0.5, 0.5}, 0.3, {60, 90, 200});
    frame.end_scene();
    return true;
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
