#pragma once
// The state of an env that simulates rigid bodies in generalised coordinates, as Gymnasium's
// MujocoEnv exposes it (gymnasium/envs/mujoco/mujoco_env.py): joint positions `qpos` (nq of
// them) and velocities `qvel` (nv), `set_state(qpos, qvel)` (then mj_forward, so positions of
// bodies and sites follow), and the observation the env would return now. With these, a
// transition can be checked against another implementation of the same task on the same
// simulator: set the same state, apply the same action, compare.
//
// The Python package offers them as env.unwrapped.set_state / env.unwrapped.data.qpos (python/,
// docs/mujoco.md); physics_state_of finds them through wrappers.
#include <span>

#include "rlrun/env.hpp"

namespace rlrun {

class PhysicsState {
 public:
  virtual ~PhysicsState() = default;
  virtual std::span<const double> qpos() const = 0;
  virtual std::span<const double> qvel() const = 0;
  // qpos and qvel at the model's rest pose, before reset noise (Gymnasium's init_qpos/init_qvel).
  virtual std::span<const double> init_qpos() const = 0;
  virtual std::span<const double> init_qvel() const = 0;
  // Throws std::invalid_argument when the sizes are not nq and nv.
  virtual void set_state(std::span<const double> qpos, std::span<const double> qvel) = 0;
  // The constraint solver's starting point for the next step (MuJoCo's qacc_warmstart, nv
  // values): not part of Gymnasium's set_state, but the solver's result depends on it in its last
  // digits, so replaying a recorded transition bit for bit sets it too (after set_state).
  virtual std::span<const double> qacc_warmstart() const = 0;
  virtual void set_qacc_warmstart(std::span<const double> values) = 0;
  // The observation of the current state (the env's _get_obs), observation_space().size() values.
  virtual void observe(std::span<float> obs) const = 0;
  // Simulated seconds per env step (timestep * frame_skip), and the physics steps per env step.
  virtual double dt() const = 0;
  virtual int frame_skip() const = 0;
};

// The PhysicsState under any wrappers, or nullptr when the env has none.
inline PhysicsState* physics_state_of(Env& env) {
  return dynamic_cast<PhysicsState*>(&env.unwrapped());
}

}  // namespace rlrun
