#include "rlrun/algos/common/entropy_coefficient.hpp"

#include "rlrun/algos/common/training_state.hpp"

#include <cmath>
#include <stdexcept>

namespace rlrun {

namespace {
// std::stod of the whole string (Python's float()); nullopt-like false on any leftover text.
bool parse_number(const std::string& text, double& out) {
  try {
    size_t used = 0;
    out = std::stod(text, &used);
    return used == text.size() && std::isfinite(out);
  } catch (const std::exception&) {
    return false;
  }
}
}  // namespace

std::string EntCoefSpec::problem(const std::string& spec) const {
  double value = 0.0;
  if (spec == "auto") return "";
  if (spec.rfind("auto_", 0) == 0 && parse_number(spec.substr(5), value) && value > 0.0) return "";
  if (spec.rfind("auto", 0) != 0 && parse_number(spec, value) && value >= 0.0) return "";
  return "'" + spec + "' is not " + describe();
}

std::string TargetEntropySpec::problem(const std::string& spec) const {
  double value = 0.0;
  if (spec == "auto" || parse_number(spec, value)) return "";
  return "'" + spec + "' is not " + describe();
}

EntropyCoefficient::EntropyCoefficient(const std::string& spec, const std::string& target_entropy,
                                       int action_dim) {
  double init = 1.0;
  if (spec.rfind("auto", 0) == 0) {
    learned_ = true;
    if (spec != "auto") {
      // SB3: init_value = float(ent_coef.split("_")[1]), asserted > 0.
      if (spec.size() < 6 || spec[4] != '_' || !parse_number(spec.substr(5), init) || init <= 0.0)
        throw std::invalid_argument("ent_coef '" + spec +
                                    "': expected auto, auto_<initial value > 0> or a number");
    }
  } else {
    double fixed = 0.0;
    if (!parse_number(spec, fixed))
      throw std::invalid_argument("ent_coef '" + spec +
                                  "': expected auto, auto_<initial value > 0> or a number");
    learned_ = false;
    fixed_ = static_cast<float>(fixed);
  }
  if (target_entropy == "auto") {
    target_entropy_ = -static_cast<float>(action_dim);
  } else {
    double t = 0.0;
    if (!parse_number(target_entropy, t))
      throw std::invalid_argument("target_entropy '" + target_entropy +
                                  "': expected auto or a number");
    target_entropy_ = static_cast<float>(t);
  }
  // th.log(th.ones(1) * init_value), a float32 tensor; Adam with torch's defaults (eps 1e-8).
  log_ent_coef_ = ParamVector(1, static_cast<float>(std::log(init)));
  adam_ = Adam({log_ent_coef_.block()});
}

float EntropyCoefficient::value() const {
  return learned_ ? std::exp(log_ent_coef_.value(0)) : fixed_;
}

double EntropyCoefficient::update(const Eigen::RowVectorXf& log_prob, float lr) {
  if (!learned_) return 0.0;
  const double shifted = static_cast<double>(log_prob.mean()) + target_entropy_;
  const double loss = -static_cast<double>(log_value()) * shifted;
  log_ent_coef_.grad(0) = static_cast<float>(-shifted);
  adam_.step(lr);
  return loss;
}

void EntropyCoefficient::save(TensorMap& tensors) const {
  if (learned_)
    tensors["log_ent_coef"] = to_tensor(log_ent_coef_.value);
  else
    tensors["ent_coef_tensor"] = scalar_tensor(fixed_);
}

void EntropyCoefficient::load(const TensorMap& tensors) {
  // A fixed coefficient comes from the config; only the learned one is state.
  if (learned_) from_tensor(tensors, "log_ent_coef", log_ent_coef_.value);
}

void EntropyCoefficient::write_state(StateWriter out) const {
  if (learned_) write_adam(out.sub("adam"), adam_);
}

void EntropyCoefficient::read_state(const StateReader& in) {
  if (learned_) read_adam(in.sub("adam"), adam_);
}

}  // namespace rlrun
