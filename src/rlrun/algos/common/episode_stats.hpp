#pragma once
// SB3's ep_info_buffer (OnPolicyAlgorithm / OffPolicyAlgorithm): the last 100 finished episodes'
// return and length, read from the Monitor's `episode.r` / `episode.l` info, for
// rollout/ep_rew_mean and rollout/ep_len_mean; `is_success` for rollout/success_rate (SB3's
// ep_success_buffer); and the Monitor's info keywords (`episode.<key>`, the env's task metrics
// such as the traffic task's avg_waiting_time) for rollout/<key>, each the mean over the last
// 100 episodes that reported it.
#include <cmath>
#include <deque>
#include <map>
#include <string>
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
      if (info.has(s)) push(successes_, info.get(s));
      const std::vector<std::string>& keys = info.keys();
      for (size_t k = 0; k < keys.size(); ++k) {
        if (keys[k].rfind("episode.", 0) != 0 || !info.has(static_cast<int>(k))) continue;
        const std::string name = keys[k].substr(8);
        if (name == "r" || name == "l" || name == "t" || name == "is_success") continue;
        push(metrics_[name], info.get(static_cast<int>(k)));
      }
    }
  }

  void record(Logger& logger) const {
    if (!returns_.empty()) {
      logger.record("rollout/ep_rew_mean", mean(returns_));
      logger.record("rollout/ep_len_mean", mean(lengths_));
    }
    if (!successes_.empty()) logger.record("rollout/success_rate", mean(successes_));
    for (const auto& [name, values] : metrics_) logger.record("rollout/" + name, mean(values));
  }

  void write_state(StateWriter out) const {
    out.put_vector("returns", std::vector<double>(returns_.begin(), returns_.end()));
    out.put_vector("lengths", std::vector<double>(lengths_.begin(), lengths_.end()));
    out.put_vector("successes", std::vector<double>(successes_.begin(), successes_.end()));
    std::string names;
    int i = 0;
    for (const auto& [name, values] : metrics_) {
      names += name + '\n';
      out.put_vector("metric_" + std::to_string(i++),
                     std::vector<double>(values.begin(), values.end()));
    }
    out.put_string("metric_names", names);
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
    if (lengths_.size() != returns_.size())  // push() keeps them in pairs
      throw StateMismatch("checkpoint episode statistics hold " + std::to_string(returns_.size()) +
                          " returns but " + std::to_string(lengths_.size()) + " lengths");
    metrics_.clear();
    if (!in.has("metric_names")) return;  // a checkpoint of an older rlrun: none
    const std::string names = in.get_string("metric_names");
    int i = 0;
    for (size_t start = 0, end; (end = names.find('\n', start)) != std::string::npos;
         start = end + 1)
      load(("metric_" + std::to_string(i++)).c_str(), metrics_[names.substr(start, end - start)]);
  }

  bool empty() const { return returns_.empty(); }
  double mean_return() const { return mean(returns_); }

 private:
  static void push(std::deque<double>& a, double x) {
    a.push_back(x);
    if (a.size() > kWindow) a.pop_front();
  }
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
  std::map<std::string, std::deque<double>> metrics_;  // by info keyword
};

}  // namespace rlrun
