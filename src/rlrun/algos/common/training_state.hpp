#pragma once
// Checkpoint helpers shared by the algorithms' save_training_state / load_training_state:
// optimizer moments (torch's optimizer.state_dict(): exp_avg, exp_avg_sq, step; square_avg
// for RMSprop) and network parameters under a prefix. Shapes come from the configuration, so
// reading checks them and names the key that does not fit; moments and parameters must be
// finite (get_finite_matrix).
#include <string>
#include <vector>

#include "rlrun/core/state_dict.hpp"
#include "rlrun/nn/adam.hpp"
#include "rlrun/nn/mlp.hpp"
#include "rlrun/nn/rmsprop.hpp"
#include "rlrun/nn/state_dependent_noise.hpp"

namespace rlrun {

inline void write_adam(StateWriter out, const Adam& adam) {
  out.put_int("step", adam.steps());
  for (size_t i = 0; i < adam.exp_avg().size(); ++i) {
    put_matrix(out, "exp_avg." + std::to_string(i), adam.exp_avg()[i]);
    put_matrix(out, "exp_avg_sq." + std::to_string(i), adam.exp_avg_sq()[i]);
  }
}

inline void read_adam(const StateReader& in, Adam& adam) {
  adam.set_steps(in.get_int("step"));
  for (size_t i = 0; i < adam.exp_avg().size(); ++i) {
    get_finite_matrix(in, "exp_avg." + std::to_string(i), adam.exp_avg()[i]);
    get_finite_matrix(in, "exp_avg_sq." + std::to_string(i), adam.exp_avg_sq()[i]);
  }
}

// One optimizer per network (SAC's and TD3's critics): `<name><i>/...`.
inline void write_adams(StateWriter out, const std::string& name, const std::vector<Adam>& adams) {
  for (size_t i = 0; i < adams.size(); ++i) write_adam(out.sub(name + std::to_string(i)), adams[i]);
}
inline void read_adams(const StateReader& in, const std::string& name, std::vector<Adam>& adams) {
  for (size_t i = 0; i < adams.size(); ++i) read_adam(in.sub(name + std::to_string(i)), adams[i]);
}

inline void write_rmsprop(StateWriter out, const RmsProp& rmsprop) {
  out.put_int("step", rmsprop.steps());
  for (size_t i = 0; i < rmsprop.square_avg().size(); ++i)
    put_matrix(out, "square_avg." + std::to_string(i), rmsprop.square_avg()[i]);
}

inline void read_rmsprop(const StateReader& in, RmsProp& rmsprop) {
  rmsprop.set_steps(in.get_int("step"));
  for (size_t i = 0; i < rmsprop.square_avg().size(); ++i)
    get_finite_matrix(in, "square_avg." + std::to_string(i), rmsprop.square_avg()[i]);
}

// gSDE's exploration matrices and the draws behind them (log_std travels with the model).
inline void write_sde(StateWriter out, const StateDependentNoise& sde) {
  out.put_int("num_exploration_matrices", sde.num_exploration_matrices());
  put_matrix(out, "eps_mat", sde.eps_mat());
  put_matrix(out, "eps_matrices", sde.eps_matrices());
  put_matrix(out, "exploration_mat", sde.exploration_mat());
  put_matrix(out, "exploration_matrices", sde.exploration_matrices());
}

inline void read_sde(const StateReader& in, StateDependentNoise& sde) {
  const int64_t n = in.get_int("num_exploration_matrices");
  // A batch is one matrix per env: bounded like the env count a checkpoint may claim.
  if (n < 1 || n > (int64_t{1} << 20))
    throw StateMismatch("checkpoint state '" + in.prefix() +
                        "num_exploration_matrices' is out of range");
  Eigen::MatrixXf eps_mat(sde.latent_dim(), sde.action_dim()), mat = eps_mat;
  Eigen::MatrixXf eps_matrices(sde.latent_dim(), n * sde.action_dim()), matrices = eps_matrices;
  get_matrix(in, "eps_mat", eps_mat);
  get_matrix(in, "eps_matrices", eps_matrices);
  get_matrix(in, "exploration_mat", mat);
  get_matrix(in, "exploration_matrices", matrices);
  sde.restore_weights(eps_mat, eps_matrices, mat, matrices);
}

// The flat parameter vector (target networks and other state the model file does not hold).
inline void write_params(StateWriter& out, const std::string& name, const Mlp& net) {
  put_matrix(out, name, net.params());
}
inline void read_params(const StateReader& in, const std::string& name, Mlp& net) {
  get_finite_matrix(in, name, net.params());
}

}  // namespace rlrun
