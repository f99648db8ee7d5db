#pragma once
// CarRacing-v3: gymnasium/envs/box2d/car_racing.py (Gymnasium 1.0.0, by Oleg Klimov) on
// Debian's Box2D 2.4 (docs/car_racing.md says what differs from pybox2d 2.3 and why).
//
//   observation  Box(0, 255, (96, 96, 3), uint8): the top-down view that follows the car
//                (car_racing_render.cpp), with the indicator bar at the bottom
//   action       continuous (default): Box([-1, 0, 0], [1, 1, 1]): steer, gas, brake;
//                continuous: false: Discrete(5): nothing, left, right, gas, brake
//   reward       -0.1 a frame, +1000/N the first time any wheel touches each of the N tiles;
//                -100 (alone) when the car leaves the playfield
//   termination  every tile visited, or tile 0 reached again after lap_complete_percent of
//                them ("lap_finished" 1), or the car off the playfield ("lap_finished" 0);
//                TimeLimit 1000 steps (gymnasium/envs/__init__.py)
#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/env.hpp"
#include "rlrun/env/race_track_state.hpp"
#include "rlrun/env_seeding.hpp"
#include "rlrun/envs/car_racing/race_track.hpp"
#include "rlrun/info.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

class PolygonCanvas;
namespace car_racing {
class Car;
}

// gymnasium.make("CarRacing-v3", **kwargs) keyword arguments (CarRacing.__init__).
struct CarRacingConfig {
  bool continuous = true;
  bool domain_randomize = false;
  double lap_complete_percent = 0.95;

  template <class V>
  void visit(V& v) {
    v("continuous", continuous,
      "Box([-1, 0, 0], [1, 1, 1]) steer, gas, brake; false: Discrete(5) nothing, left, right, "
      "gas, brake");
    v("domain_randomize", domain_randomize,
      "new random road, background and grass colours at every reset");
    v("lap_complete_percent", lap_complete_percent,
      "fraction of the tiles to visit before reaching tile 0 again ends the lap", unit_interval());
  }
};

// The scene's colours (CarRacing._init_colors), 0-255 floats as Gymnasium keeps them.
struct CarRacingColors {
  std::array<double, 3> road{102, 102, 102}, bg{102, 204, 102}, grass{102, 230, 102};
};

class CarRacing : public Env, public RaceTrackState {
 public:
  using Config = CarRacingConfig;
  static constexpr int kMaxEpisodeSteps = 1000;  // registered max_episode_steps
  static constexpr int kStateSize = 96;          // STATE_W, STATE_H
  static constexpr double kFps = 50;             // FPS

  // Throws std::invalid_argument unless 0 <= lap_complete_percent <= 1.
  explicit CarRacing(const Config& config = {});
  ~CarRacing() override;
  CarRacing(const CarRacing&) = delete;
  CarRacing& operator=(const CarRacing&) = delete;

  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  const Info& info() const override { return info_; }
  std::string id() const override { return "CarRacing-v3"; }

  // New colours (domain_randomize), a new track (drawn until one closes, or the one set by
  // set_next_track), the car at rest on its first point, then one step without controls
  // whose picture is the first observation (Gymnasium: self.step(None)[0]).
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  // render_mode "rgb_array": VIDEO_W x VIDEO_H = 600 x 400 at FPS, with skid marks.
  RenderSpec render_spec() const override { return {600, 400, kFps}; }
  bool render(Frame& frame) const override;

  // RaceTrackState (rlrun/env/race_track_state.hpp).
  std::span<const TrackPoint> track() const override { return track_; }
  void set_next_track(std::vector<TrackPoint> track) override;
  void set_next_randomize(bool randomize) override { next_randomize_ = randomize; }
  CarState car() const override;
  double episode_reward() const override { return reward_; }
  int tiles_visited() const override { return tile_visited_count_; }
  double time() const override { return t_; }

  const Config& config() const { return config_; }
  const CarRacingColors& colors() const { return colors_; }
  const car_racing::Road& road() const { return road_; }
  bool tile_visited(int tile) const { return tile_visited_[tile]; }
  bool tile_touched(int tile) const { return tile_touched_[tile]; }

  // The Box2D world, the tiles and the car (car_racing.cpp); its contact listener is
  // Gymnasium's FrictionDetector.
  struct Physics;
  friend struct Physics;

 private:
  void draw_colors();
  const car_racing::Car& car_model() const;  // after the first reset
  void apply_action(std::span<const float> action);
  StepResult advance(std::optional<std::span<const float>> action, std::span<float> obs);
  void on_tile_contact(int tile, int wheel, bool begin);
  // The picture Gymnasium's _render(mode) draws (car_racing_render.cpp): the state pixels
  // (no skid marks) into `canvas` of any size.
  void draw_scene(PolygonCanvas& canvas, bool skid_marks) const;

  Config config_;
  Space observation_space_;
  Space action_space_;
  Info info_;
  int lap_finished_key_;
  EnvSeeding seeding_;
  CarRacingColors colors_;
  bool colors_drawn_ = false;
  bool next_randomize_ = true;
  std::optional<std::vector<TrackPoint>> next_track_;
  std::vector<TrackPoint> track_;
  car_racing::Road road_;
  // Gymnasium shades tiles 0, 1, 2 % 3 slightly apart and recolours a tile plain road once
  // anything touches it (FrictionDetector: tile.color[:] = env.road_color).
  std::vector<bool> tile_touched_;
  std::vector<bool> tile_visited_;
  std::unique_ptr<Physics> physics_;  // null before the first reset
  double reward_ = 0, prev_reward_ = 0, t_ = 0;
  int tile_visited_count_ = 0;
  bool new_lap_ = false;
  std::unique_ptr<PolygonCanvas> state_canvas_;
  std::vector<uint8_t> state_pixels_;
};

}  // namespace rlrun
