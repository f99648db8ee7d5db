#include "rlrun/wrappers/reward_shaping.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rlrun {

RewardShaping::RewardShaping(EnvPtr inner, const Config& config)
    : Wrapper(std::move(inner)), terms_(config.terms), streak_(config.terms.size(), 0) {
  const Space& obs_space = inner_->observation_space();
  for (size_t k = 0; k < terms_.size(); ++k) {
    const ShapingTerm& t = terms_[k];
    const std::string where = "RewardShaping term " + std::to_string(k) + " (" + t.type + ")";
    const bool uses_obs = t.type.rfind("obs_", 0) == 0;
    if (uses_obs && !obs_space.is_box())
      throw std::invalid_argument(where + " needs a Box observation space, " + inner_->id() +
                                  " has " + obs_space.describe());
    if (uses_obs && (t.index < 0 || t.index >= obs_space.flat_dim()))
      throw std::invalid_argument(where + ": index " + std::to_string(t.index) +
                                  " is outside the observation " + obs_space.describe() +
                                  " (valid: 0.." + std::to_string(obs_space.flat_dim() - 1) + ")");
    if (t.type == "action_sq" && !inner_->action_space().is_box())
      throw std::invalid_argument(where + " needs a Box action space, " + inner_->id() + " has " +
                                  inner_->action_space().describe());
    if ((t.type == "obs_above_for" || t.type == "obs_below_for") && t.steps < 1)
      throw std::invalid_argument(where + ": steps must be >= 1");
    if (t.type == "obs_above_for")
      kinds_.push_back(Kind::kObsAboveFor);
    else if (t.type == "obs_below_for")
      kinds_.push_back(Kind::kObsBelowFor);
    else if (t.type == "obs_abs")
      kinds_.push_back(Kind::kObsAbs);
    else if (t.type == "action_sq")
      kinds_.push_back(Kind::kActionSq);
    else if (t.type == "constant")
      kinds_.push_back(Kind::kConstant);
    else
      throw std::invalid_argument(where + ": unknown term type");
  }
}

void RewardShaping::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  inner_->reset(seed, obs);
  std::fill(streak_.begin(), streak_.end(), 0);
  last_shaping_ = 0.0;
}

StepResult RewardShaping::step(std::span<const float> action, std::span<float> obs) {
  StepResult result = inner_->step(action, obs);
  double shaping = 0.0;
  for (size_t k = 0; k < terms_.size(); ++k) {
    const ShapingTerm& t = terms_[k];
    switch (kinds_[k]) {
      case Kind::kObsAboveFor:
      case Kind::kObsBelowFor: {
        const double x = obs[t.index];
        const bool holds = kinds_[k] == Kind::kObsAboveFor ? x > t.threshold : x < t.threshold;
        streak_[k] = holds ? streak_[k] + 1 : 0;
        if (streak_[k] >= t.steps && (t.repeat || streak_[k] == t.steps)) shaping += t.penalty;
        break;
      }
      case Kind::kObsAbs: shaping += t.coef * std::abs(static_cast<double>(obs[t.index])); break;
      case Kind::kActionSq: {
        double sq = 0.0;
        for (float a : action) sq += static_cast<double>(a) * a;
        shaping += t.coef * sq;
        break;
      }
      case Kind::kConstant: shaping += t.value; break;
    }
  }
  last_shaping_ = shaping;
  result.reward += shaping;
  return result;
}

void RewardShaping::write_own_state(StateWriter& out) const {
  out.put_vector("reward_shaping/streaks", streak_);
}

void RewardShaping::read_own_state(const StateReader& in) {
  in.get_into<int64_t>("reward_shaping/streaks", streak_);
}

}  // namespace rlrun
