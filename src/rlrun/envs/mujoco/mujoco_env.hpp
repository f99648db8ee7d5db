#pragma once
// The base of the MuJoCo tasks: Gymnasium 1.0's MujocoEnv (gymnasium/envs/mujoco/mujoco_env.py)
// on MuJoCo's C API. It owns the model and its simulation state and does what every task shares:
//
//   action space   Box(actuator_ctrlrange) float32, one entry per actuator (_set_action_space)
//   reset          the seed rule of every Gymnasium env (EnvSeeding), mj_resetData, then the
//                  task's reset_model(), which adds noise to init_qpos / init_qvel and calls
//                  set_state (qpos, qvel, then mj_forward)
//   do_simulation  ctrl = action as given (MuJoCo clamps it to ctrlrange inside; the tasks' control
//                  costs read the action, or data.ctrl, unclamped, as Gymnasium's do), frame_skip
//                  mj_step calls, then mj_rnePostConstraint so cacc / cfrc_int / cfrc_ext hold
//                  this state's values (they are computed only for force sensors otherwise)
//   dt             timestep * frame_skip; render fps round(1 / dt)
//
// Instability: when MuJoCo finds NaN, Inf or a huge value in qpos, qvel or qacc it resets the
// simulation to the model's rest pose and counts a warning (mj_checkPos/Vel/Acc). Gymnasium
// prints the warning once and carries on from the reset pose; rlrun ends the episode there
// (truncated, since the task did not reach a terminal state) and says so on stderr, so a learner
// never sees a teleport as a transition.
//
// Observations are float32 (Gymnasium's are float64; SB3's policies read float32 either way).
#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rlrun/env.hpp"
#include "rlrun/env/physics_state.hpp"
#include "rlrun/env_seeding.hpp"
#include "rlrun/envs/mujoco/default_camera.hpp"
#include "rlrun/envs/mujoco/mujoco_model.hpp"
#include "rlrun/info.hpp"
#include "rlrun/space.hpp"

namespace rlrun::mujoco {

class MujocoRenderer;  // mujoco_renderer.hpp

// init + U(low, high) per entry (numpy's uniform(low, high, size=n)), and init + scale * N(0, 1):
// the reset noise of the tasks' reset_model.
std::vector<double> uniform_around(std::span<const double> init, double low, double high, Rng& rng);
std::vector<double> normal_around(std::span<const double> init, double scale, Rng& rng);

// np.sum(np.square(action)) of a float32 action, as numpy computes it (in float32, pairwise),
// then widened: Gymnasium's control costs `weight * np.sum(np.square(action))` multiply a
// Python float by that float32 scalar, which NumPy 1.x (Debian 12's 1.24) does in float64.
double sum_of_squares(std::span<const float> action);
// np.sum(np.square(values)) of a float64 array (data.ctrl, cfrc_ext).
double sum_of_squares(std::span<const double> values);

// Writes an observation as the concatenation of parts (Gymnasium's np.concatenate), as float32.
class ObservationWriter {
 public:
  explicit ObservationWriter(std::span<float> obs) : obs_(obs) {}
  ObservationWriter& put(std::span<const double> values) {
    for (double v : values) obs_[next_++] = static_cast<float>(v);
    return *this;
  }
  // numpy.clip(values, low, high).
  ObservationWriter& put_clipped(std::span<const double> values, double low, double high) {
    for (double v : values) obs_[next_++] = static_cast<float>(std::clamp(v, low, high));
    return *this;
  }
  ObservationWriter& put(double value) {
    obs_[next_++] = static_cast<float>(value);
    return *this;
  }
  size_t written() const { return next_; }

 private:
  std::span<float> obs_;
  size_t next_ = 0;
};

class MujocoEnv : public Env, public PhysicsState {
 public:
  // `model_path`: the MJCF file (shipped_model_path or the user's); `frame_skip`: physics steps
  // per env step; `observation_size`: the length of what observe() writes.
  MujocoEnv(std::string id, const std::string& model_path, int frame_skip, int observation_size);
  ~MujocoEnv() override;

  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  const Info& info() const override { return info_; }
  std::string id() const override { return id_; }

  void reset(std::optional<uint64_t> seed, std::span<float> obs) final;

  bool can_save_state() const override { return true; }
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;

  // Gymnasium's rgb_array: 480 x 480 (its DEFAULT_SIZE), metadata["render_fps"] = round(1 / dt);
  // render() draws with MuJoCo's renderer at the frame's size (mujoco_renderer.hpp).
  RenderSpec render_spec() const override;
  bool render(Frame& frame) const override;

  // PhysicsState
  std::span<const double> qpos() const override;
  std::span<const double> qvel() const override;
  std::span<const double> init_qpos() const override { return init_qpos_; }
  std::span<const double> init_qvel() const override { return init_qvel_; }
  void set_state(std::span<const double> qpos, std::span<const double> qvel) override;
  std::span<const double> qacc_warmstart() const override;
  void set_qacc_warmstart(std::span<const double> values) override;
  double dt() const override { return model_->opt.timestep * frame_skip_; }
  int frame_skip() const override { return frame_skip_; }

  const mjModel& model() const { return *model_; }
  const mjData& data() const { return *data_; }

 protected:
  // The task's reset_model(): noise on init_qpos / init_qvel from `rng`, then set_state.
  virtual void reset_model(Rng& rng) = 0;

  // Gymnasium's do_simulation(action, frame_skip). Returns false when MuJoCo reset an unstable
  // simulation during these steps: the task then returns end_unstable(obs).
  bool do_simulation(std::span<const float> action);
  // Observes the (reset) state, reports the instability once per env on stderr, and returns a
  // truncated step with reward 0.
  StepResult end_unstable(std::span<float> obs);

  // The world position of body `name`'s frame (Gymnasium's get_body_com: data.xpos).
  const double* body_xpos(int body) const { return data_->xpos + 3 * body; }
  int body_id(const char* name) const;  // throws ConfigError when the model has no such body

  // Called by a task's constructor with its DEFAULT_CAMERA_CONFIG (rendering reads it).
  void set_default_camera(const DefaultCamera& camera) { default_camera_ = camera; }
  const DefaultCamera& default_camera() const { return default_camera_; }

  mjData& mutable_data() { return *data_; }
  Info& mutable_info() { return info_; }

 private:
  // What mj_step reads of mjData besides ctrl: enough to recompute everything it derives.
  struct PhysicsInputs {
    explicit PhysicsInputs(const mjModel& m);
    void take_from(const mjData& d);
    void give_to(mjData& d) const;
    std::vector<double> qpos, qvel, act, qacc_warmstart;
    double time = 0.0;
  };

  int unstable_warnings() const;

  std::string id_;
  ModelPtr model_;
  DataPtr data_;
  int frame_skip_;
  std::vector<double> init_qpos_, init_qvel_;
  Space observation_space_, action_space_;
  Info info_;
  EnvSeeding seeding_;
  bool reported_instability_ = false;
  DefaultCamera default_camera_;
  // The inputs of the last physics step, from which mjData's derived quantities (xpos, cinert,
  // cfrc_ext, ...) were computed (true after a step, false after set_state or a reset).
  PhysicsInputs previous_;
  bool derived_from_previous_ = false;
  mutable std::unique_ptr<MujocoRenderer> renderer_;  // made by the first render()
};

}  // namespace rlrun::mujoco
