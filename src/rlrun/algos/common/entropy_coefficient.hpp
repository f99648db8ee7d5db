#pragma once
// SAC's and TQC's entropy coefficient alpha (SB3 sac/sac.py _setup_model; Haarnoja et al. 2018b, "Soft
// Actor-Critic Algorithms and Applications", arXiv:1812.05905, section 5): either a fixed
// number, or learned ("auto", "auto_<initial>") by Adam on log(alpha). SB3 optimises log(alpha)
// rather than alpha (softlearning issue #37) and starts it at log(initial) (1.0 unless
// "auto_<initial>" says otherwise; sb3-contrib tqc/tqc.py _setup_model is the same code).
// update() is the temperature step of both algorithms' train().
#include <Eigen/Core>
#include <string>

#include "rlrun/core/state_dict.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/nn/adam.hpp"
#include "rlrun/nn/param_vector.hpp"

namespace rlrun {

// Constraints of the YAML strings (config_fields.hpp): "auto", "auto_<initial > 0>" or a
// number >= 0; "auto" or a number.
struct EntCoefSpec {
  std::string describe() const { return "auto, auto_<initial value > 0> or a number >= 0"; }
  std::string problem(const std::string& spec) const;
};
struct TargetEntropySpec {
  std::string describe() const { return "auto or a number"; }
  std::string problem(const std::string& spec) const;
};

class EntropyCoefficient {
 public:
  // spec: "auto", "auto_<positive number>" or a number (fixed). target_entropy: "auto"
  // (= -action_dim, SB3's -prod(action_space.shape)) or a number. Throws
  // std::invalid_argument naming the bad value.
  EntropyCoefficient(const std::string& spec, const std::string& target_entropy, int action_dim);
  EntropyCoefficient(const EntropyCoefficient&) = delete;
  EntropyCoefficient& operator=(const EntropyCoefficient&) = delete;

  bool learned() const { return learned_; }
  float target_entropy() const { return target_entropy_; }
  // alpha = exp(log_alpha) now (SB3 reads it before this step's update), or the fixed value.
  float value() const;
  float log_value() const { return log_ent_coef_.value(0); }

  // The temperature update (Haarnoja et al. 2018b, eq. 18; SB3 SAC.train): with a learned
  // coefficient, ent_coef_loss = -(log_ent_coef * (log_prob + target_entropy).detach()).mean()
  // and one Adam step on log_ent_coef, whose gradient is -mean(log_prob + target_entropy).
  // `log_prob` are the policy's log-probabilities of its own actions at the batch's states.
  // Returns the loss (0 for a fixed coefficient, which nothing updates).
  double update(const Eigen::RowVectorXf& log_prob, float lr);

  // SB3's log_ent_coef (learned() only) and its optimizer (Adam with torch's defaults).
  ParamVector& log_ent_coef() { return log_ent_coef_; }
  Adam& optimizer() { return adam_; }

  // SB3 saves the learned value as the pytorch variable `log_ent_coef`, a fixed one as
  // `ent_coef_tensor`.
  void save(TensorMap& tensors) const;
  void load(const TensorMap& tensors);

  const Adam& optimizer() const { return adam_; }
  // Exact resume: log_alpha's Adam moments (log_alpha itself is in the model tensors).
  void write_state(StateWriter out) const;
  void read_state(const StateReader& in);

 private:
  bool learned_ = true;
  float fixed_ = 0.0f;
  float target_entropy_ = 0.0f;
  ParamVector log_ent_coef_;
  Adam adam_;
};

}  // namespace rlrun
