#pragma once
// SB3's ep_info_buffer (OnPolicyAlgorithm / OffPolicyAlgorithm): the last 100 finished episodes'
// return and length, read from the Monitor's `episode.r` / `episode.l` info, for
// rollout/ep_rew_mean and rollout/ep_len_mean; plus `is_success` for rollout/success_rate.
#include <cmath>
#include <deque>
#include <vector>

#include "rlrun/core/logger.hpp"
#include "rlrun/core/state_dict.hpp"
#include "rlrun/env/vec_env.hpp"

namespace rlrun {

class EpisodeStats {
 public:
  static constexpr std::size_t kWindow = 100;

  // Call after every VecEnv step.
  void update(const VecEnv& env) {
    for (int i = 0; i < env.num_envs(); ++i) {
      if (!env.done(i)) continue;
      const Info& info = env.info(i);
      const int r = info.find("episode.r"), l = info.find("episode.l");
      if (info.has(r) && info.has(l)) push(returns_, info.get(r), lengths_, info.get(l));
      const int s = info.find("is_success");
      if (info.has(s)) {
        successes_.push_back(info.get(s));
        if (successes_.size() > kWindow) successes_.pop_front();
      }
    }
  }

  void record(Logger& logger) const {
    if (!returns_.empty()) {
      logger.record("rollout/ep_rew_mean", mean(returns_));
      logger.record("rollout/ep_len_mean", mean(lengths_));
    }
    if (!successes_.empty()) logger.record("rollout/success_rate", mean(successes_));
  }

  void write_state(StateWriter out) const {
    out.put_vector("returns", std::vector<double>(returns_.begin(), returns_.end()));
    out.put_vector("lengths", std::vector<double>(lengths_.begin(), lengths_.end()));
    out.put_vector("successes", std::vector<double>(successes_.begin(), successes_.end()));
  }
  void read_state(const StateReader& in) {
    const auto load = [&](const char* name, std::deque<double>& d) {
      const std::vector<double> v = in.get_span<double>(name);
      if (v.size() > kWindow)
        throw StateMismatch(std::string("checkpoint episode statistics '") + name + "' hold " +
                            std::to_string(v.size()) + " episodes, more than the window of " +
                            std::to_string(kWindow));
      d.assign(v.begin(), v.end());
    };
    load("returns", returns_);
    load("lengths", lengths_);
    load("successes", successes_);
  }

  bool empty() const { return returns_.empty(); }
  double mean_return() const { return mean(returns_); }

 private:
  static void push(std::deque<double>& a, double x, std::deque<double>& b, double y) {
    a.push_back(x);
    b.push_back(y);
    if (a.size() > kWindow) {
      a.pop_front();
      b.pop_front();
    }
  }
  static double mean(const std::deque<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? std::nan("") : s / static_cast<double>(v.size());
  }
  std::deque<double> returns_, lengths_, successes_;
};

}  // namespace rlrun
