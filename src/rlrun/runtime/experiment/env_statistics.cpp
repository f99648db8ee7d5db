#include "rlrun/runtime/experiment/env_statistics.hpp"

#include <algorithm>
#include <map>
#include <string>

namespace rlrun {

namespace {

// Model-file key of each statistics wrapper: its name, then `.1`, `.2` for repeats.
std::vector<std::string> statistics_keys(const std::vector<ModelStatistics*>& stats) {
  std::map<std::string, int> seen;
  std::vector<std::string> keys;
  for (const ModelStatistics* s : stats) {
    const std::string name = s->statistics_name();
    const int k = seen[name]++;
    keys.push_back(kWrapperStatisticsPrefix + (k == 0 ? name : name + "." + std::to_string(k)));
  }
  return keys;
}

}  // namespace

std::vector<Wrapper*> wrapper_chain(Env& env) {
  std::vector<Wrapper*> chain;
  Env* e = &env;
  while (auto* w = dynamic_cast<Wrapper*>(e)) {
    chain.push_back(w);
    e = &w->inner();
  }
  return chain;
}

std::vector<ModelStatistics*> model_statistics(Env& env) {
  std::vector<ModelStatistics*> stats;
  for (Wrapper* w : wrapper_chain(env))
    if (auto* s = dynamic_cast<ModelStatistics*>(w)) stats.push_back(s);
  std::reverse(stats.begin(), stats.end());
  return stats;
}

void share_model_statistics(VecEnv& env) {
  const std::vector<ModelStatistics*> first = model_statistics(env.env(0));
  for (int i = 1; i < env.num_copies(); ++i) {
    const std::vector<ModelStatistics*> other = model_statistics(env.env(i));
    for (size_t k = 0; k < first.size() && k < other.size(); ++k)
      other[k]->share_statistics_with(*first[k]);
  }
}

void save_model_statistics(Env& env, TensorMap& tensors) {
  const std::vector<ModelStatistics*> stats = model_statistics(env);
  const std::vector<std::string> keys = statistics_keys(stats);
  for (size_t k = 0; k < stats.size(); ++k) {
    StateWriter out(tensors, keys[k] + "/");
    stats[k]->save_statistics(out);
  }
}

void load_model_statistics(Env& env, const TensorMap& tensors, bool training) {
  const std::vector<ModelStatistics*> stats = model_statistics(env);
  const std::vector<std::string> keys = statistics_keys(stats);
  for (size_t k = 0; k < stats.size(); ++k) {
    stats[k]->load_statistics(StateReader(tensors, keys[k] + "/"));
    stats[k]->set_training(training);
  }
}

void set_statistics_training(Env& env, bool training) {
  for (ModelStatistics* s : model_statistics(env)) s->set_training(training);
}

}  // namespace rlrun
