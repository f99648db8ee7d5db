#include "rlrun/envs/mujoco/mujoco_env.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <stdexcept>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/pairwise_sum.hpp"
#include "rlrun/envs/mujoco/mujoco_renderer.hpp"

namespace rlrun::mujoco {

namespace {

Space ctrl_range_space(const mjModel& m) {
  std::vector<float> low(static_cast<size_t>(m.nu)), high(static_cast<size_t>(m.nu));
  for (int i = 0; i < m.nu; ++i) {
    // Gymnasium: model.actuator_ctrlrange.astype(np.float32).
    low[static_cast<size_t>(i)] = static_cast<float>(m.actuator_ctrlrange[2 * i]);
    high[static_cast<size_t>(i)] = static_cast<float>(m.actuator_ctrlrange[2 * i + 1]);
  }
  return Space::box(std::move(low), std::move(high), {m.nu});
}

// The most actuators a task's action has (Humanoid: 17); more would be another model.
constexpr size_t kMaxSummed = 64;

void copy_into(std::span<const double> from, double* to) {
  std::copy(from.begin(), from.end(), to);
}

}  // namespace

std::vector<double> uniform_around(std::span<const double> init, double low, double high,
                                   Rng& rng) {
  std::vector<double> out(init.begin(), init.end());
  for (double& v : out) v += rng.uniform(low, high);
  return out;
}

std::vector<double> normal_around(std::span<const double> init, double scale, Rng& rng) {
  std::vector<double> out(init.begin(), init.end());
  for (double& v : out) v += scale * rng.normal();
  return out;
}

double sum_of_squares(std::span<const float> action) {
  float squares[kMaxSummed];
  if (action.size() > kMaxSummed) throw std::invalid_argument("sum_of_squares: too many values");
  for (size_t i = 0; i < action.size(); ++i) squares[i] = action[i] * action[i];
  return pairwise_sum<float>({squares, action.size()});
}

double sum_of_squares(std::span<const double> values) {
  std::vector<double> squares(values.size());
  for (size_t i = 0; i < values.size(); ++i) squares[i] = values[i] * values[i];
  return pairwise_sum<double>(squares);
}

MujocoEnv::MujocoEnv(std::string id, const std::string& model_path, int frame_skip,
                     int observation_size)
    : id_(std::move(id)),
      model_(load_model(model_path)),
      data_(make_data(*model_)),
      frame_skip_(frame_skip),
      init_qpos_(data_->qpos, data_->qpos + model_->nq),
      init_qvel_(data_->qvel, data_->qvel + model_->nv),
      observation_space_(Space::box(-std::numeric_limits<float>::infinity(),
                                    std::numeric_limits<float>::infinity(), {observation_size})),
      action_space_(ctrl_range_space(*model_)),
      previous_(*model_) {}

MujocoEnv::~MujocoEnv() = default;

MujocoEnv::PhysicsInputs::PhysicsInputs(const mjModel& m)
    : qpos(static_cast<size_t>(m.nq)),
      qvel(static_cast<size_t>(m.nv)),
      act(static_cast<size_t>(m.na)),
      qacc_warmstart(static_cast<size_t>(m.nv)) {}

void MujocoEnv::PhysicsInputs::take_from(const mjData& d) {
  std::copy(d.qpos, d.qpos + qpos.size(), qpos.begin());
  std::copy(d.qvel, d.qvel + qvel.size(), qvel.begin());
  std::copy(d.act, d.act + act.size(), act.begin());
  std::copy(d.qacc_warmstart, d.qacc_warmstart + qacc_warmstart.size(), qacc_warmstart.begin());
  time = d.time;
}

void MujocoEnv::PhysicsInputs::give_to(mjData& d) const {
  copy_into(qpos, d.qpos);
  copy_into(qvel, d.qvel);
  copy_into(act, d.act);
  copy_into(qacc_warmstart, d.qacc_warmstart);
  d.time = time;
}

void MujocoEnv::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  seeding_.on_reset(seed);
  mj_resetData(model_.get(), data_.get());
  info_.clear();
  reset_model(seeding_.rng());
  observe(obs);
}

std::span<const double> MujocoEnv::qpos() const {
  return {data_->qpos, static_cast<size_t>(model_->nq)};
}

std::span<const double> MujocoEnv::qvel() const {
  return {data_->qvel, static_cast<size_t>(model_->nv)};
}

void MujocoEnv::set_state(std::span<const double> qpos, std::span<const double> qvel) {
  if (qpos.size() != static_cast<size_t>(model_->nq) ||
      qvel.size() != static_cast<size_t>(model_->nv))
    throw std::invalid_argument(
        id_ + ": set_state needs qpos of size " + std::to_string(model_->nq) +
        " and qvel of size " + std::to_string(model_->nv) + ", got " + std::to_string(qpos.size()) +
        " and " + std::to_string(qvel.size()));
  copy_into(qpos, data_->qpos);
  copy_into(qvel, data_->qvel);
  mj_forward(model_.get(), data_.get());
  derived_from_previous_ = false;
}

std::span<const double> MujocoEnv::qacc_warmstart() const {
  return {data_->qacc_warmstart, static_cast<size_t>(model_->nv)};
}

void MujocoEnv::set_qacc_warmstart(std::span<const double> values) {
  if (values.size() != static_cast<size_t>(model_->nv))
    throw std::invalid_argument(id_ + ": qacc_warmstart needs " + std::to_string(model_->nv) +
                                " values, got " + std::to_string(values.size()));
  copy_into(values, data_->qacc_warmstart);
}

int MujocoEnv::unstable_warnings() const {
  return data_->warning[mjWARN_BADQPOS].number + data_->warning[mjWARN_BADQVEL].number +
         data_->warning[mjWARN_BADQACC].number;
}

bool MujocoEnv::do_simulation(std::span<const float> action) {
  if (action.size() != static_cast<size_t>(model_->nu))
    throw std::invalid_argument(id_ + ": action dimension mismatch: expected " +
                                std::to_string(model_->nu) + ", found " +
                                std::to_string(action.size()));
  std::copy(action.begin(), action.end(), data_->ctrl);
  const int warnings_before = unstable_warnings();
  for (int i = 0; i < frame_skip_; ++i) {
    // After mj_step, the positions MuJoCo computed (xpos, cinert, ...) are not those of the new
    // state: the Euler integrator leaves those of the state at the start of the last step, RK4
    // those of a stage inside its integration. Rewards read them. A checkpoint keeps the inputs of
    // the last step to recompute them (read_state).
    if (i + 1 == frame_skip_) previous_.take_from(*data_);
    mj_step(model_.get(), data_.get());
  }
  mj_rnePostConstraint(model_.get(), data_.get());
  derived_from_previous_ = true;
  return unstable_warnings() == warnings_before;
}

StepResult MujocoEnv::end_unstable(std::span<float> obs) {
  if (!reported_instability_) {
    std::cerr << id_ << ": MuJoCo found NaN, Inf or a huge value in the simulation (time "
              << data_->time << ") and reset it; the episode ends here (truncated). Further "
              << "instabilities of this env are not reported.\n";
    reported_instability_ = true;
  }
  observe(obs);
  return {0.0, false, true};
}

int MujocoEnv::body_id(const char* name) const {
  const int id = mj_name2id(model_.get(), mjOBJ_BODY, name);
  if (id < 0)
    throw ConfigError(id_ + ": the MuJoCo model has no body named '" + std::string(name) + "'");
  return id;
}

// Gymnasium's MujocoEnv: width = height = DEFAULT_SIZE (480); render_fps int(np.round(1.0 / dt)),
// which rounds halves to even, as nearbyint does in the default rounding mode.
RenderSpec MujocoEnv::render_spec() const { return {480, 480, std::nearbyint(1.0 / dt())}; }

bool MujocoEnv::render(Frame& frame) const {
  if (!renderer_) renderer_ = std::make_unique<MujocoRenderer>(*model_, *data_, default_camera_);
  // MuJoCo's mjv_updateScene takes mjData* to read the state (mujoco_renderer.hpp).
  renderer_->render(*model_, *data_, frame);
  return true;
}

// The state is the physics' inputs (qpos, qvel, act, ctrl, the solver's warm start, time), and
// those before the last physics step when the derived quantities come from there: restoring
// runs that mj_step again from them (then mj_rnePostConstraint), which computes exactly what
// the last mj_step computed whatever the integrator (mj_forward on them did only for Euler:
// Reacher-v4, RK4, read other fingertip positions after a resume), so the next rewards match an
// uninterrupted run bit for bit. Nothing else of mjData is read from the file, so a crafted
// checkpoint can hand MuJoCo only numbers of the right count (NaN included: MuJoCo resets an
// unstable state).
void MujocoEnv::write_state(StateWriter& out) const {
  seeding_.write_state(out);
  PhysicsInputs now(*model_);
  now.take_from(*data_);
  out.put_vector("qpos", now.qpos);
  out.put_vector("qvel", now.qvel);
  out.put_vector("act", now.act);
  out.put_vector("qacc_warmstart", now.qacc_warmstart);
  out.put_double("time", now.time);
  out.put_span<double>("ctrl", {data_->ctrl, static_cast<size_t>(model_->nu)});
  out.put_bool("derived_from_previous", derived_from_previous_);
  out.put_vector("previous_qpos", previous_.qpos);
  out.put_vector("previous_qvel", previous_.qvel);
  out.put_vector("previous_act", previous_.act);
  out.put_vector("previous_qacc_warmstart", previous_.qacc_warmstart);
  out.put_double("previous_time", previous_.time);
  out.put_bool("reported_instability", reported_instability_);
}

void MujocoEnv::read_state(const StateReader& in) {
  seeding_.read_state(in);
  const auto read_inputs = [&](const std::string& prefix, PhysicsInputs& into) {
    in.get_into<double>(prefix + "qpos", into.qpos);
    in.get_into<double>(prefix + "qvel", into.qvel);
    in.get_into<double>(prefix + "act", into.act);
    in.get_into<double>(prefix + "qacc_warmstart", into.qacc_warmstart);
    into.time = in.get_double(prefix + "time");
  };
  PhysicsInputs now(*model_);
  read_inputs("", now);
  read_inputs("previous_", previous_);
  derived_from_previous_ = in.get_bool("derived_from_previous");
  reported_instability_ = in.get_bool("reported_instability");
  mj_resetData(model_.get(), data_.get());
  in.get_into<double>("ctrl", std::span<double>(data_->ctrl, static_cast<size_t>(model_->nu)));
  if (derived_from_previous_) {
    previous_.give_to(*data_);
    mj_step(model_.get(), data_.get());
    mj_rnePostConstraint(model_.get(), data_.get());
  }
  now.give_to(*data_);
  if (!derived_from_previous_) mj_forward(model_.get(), data_.get());
}

}  // namespace rlrun::mujoco
