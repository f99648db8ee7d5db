#include "rlrun/runtime/io/model_budget.hpp"

#include <stdexcept>

#include "rlrun/core/npy.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/experiment/env_statistics.hpp"
#include "rlrun/wrappers/observation_tap.hpp"

namespace rlrun {

namespace {

// Saturating: budgets come from our own objects, but a config may ask for absurd sizes.
uint64_t add(uint64_t a, uint64_t b) {
  uint64_t sum = 0;
  return __builtin_add_overflow(a, b, &sum) ? UINT64_MAX : sum;
}
uint64_t mul(uint64_t a, uint64_t b) {
  uint64_t product = 0;
  return __builtin_mul_overflow(a, b, &product) ? UINT64_MAX : product;
}

uint64_t npy_member_bytes(const Tensor& t) {
  Tensor header_only;
  header_only.dtype = t.dtype;
  header_only.shape = t.shape;
  return add(encode_npy(header_only).size(), t.bytes.size());
}

}  // namespace

uint64_t tensor_map_charge(const TensorMap& tensors, const std::string& prefix) {
  uint64_t total = 0;
  for (const auto& [key, tensor] : tensors)
    total =
        add(total, tensor_member_charge(prefix.size() + key.size() + 4, npy_member_bytes(tensor)));
  return total;
}

uint64_t model_tensor_budget(const Algorithm& algorithm, Env& env) {
  TensorMap tensors;
  algorithm.save(tensors);
  save_model_statistics(env, tensors);
  const auto obs_dim = static_cast<uint64_t>(env.observation_space().flat_dim());
  return add(add(tensor_map_charge(tensors), mul(16, obs_dim)), kModelSlackBytes);
}

uint64_t replay_buffer_growth(const TensorMap& fresh_state) {
  const std::string capacity_key = "capacity";
  uint64_t growth = 0;
  for (const auto& [key, tensor] : fresh_state) {
    if (key.size() < capacity_key.size() ||
        key.compare(key.size() - capacity_key.size(), capacity_key.size(), capacity_key) != 0 ||
        tensor.dtype != DType::kInt64 || tensor.bytes.size() != sizeof(int64_t))
      continue;
    const int64_t capacity = *tensor.data<int64_t>();
    if (capacity <= 0) continue;
    const std::string prefix = key.substr(0, key.size() - capacity_key.size());
    for (auto it = fresh_state.lower_bound(prefix);
         it != fresh_state.end() && it->first.rfind(prefix, 0) == 0; ++it) {
      if (it->first.find('/', prefix.size()) != std::string::npos) continue;  // not a sibling
      const Tensor& t = it->second;
      uint64_t others = dtype_size(t.dtype);
      bool grows = false;
      for (const int64_t d : t.shape) {
        if (d == 0 && !grows)
          grows = true;
        else
          others = mul(others, static_cast<uint64_t>(d));
      }
      if (grows) growth = add(growth, mul(others, static_cast<uint64_t>(capacity)));
    }
  }
  return growth;
}

uint64_t checkpoint_tensor_budget(const Experiment& experiment, const Registry& registry) {
  const int n_envs = experiment.env.section.n_envs;
  const int tap_env = experiment.obs_log.freq > 0 ? experiment.obs_log.env : -1;
  VecEnv env = make_vec_env(experiment.env, registry, n_envs, /*monitor_dir=*/"", tap_env);
  const AlgorithmSetup setup{env.observation_space(), env.action_space(), env.num_envs(),
                             experiment.run.seed};
  std::unique_ptr<Algorithm> algorithm = make_algorithm(experiment, registry, setup);
  uint64_t budget = add(model_tensor_budget(*algorithm, env.env(0)), kCheckpointSlackBytes);
  if (!env.can_save_state()) return budget;  // its checkpoints hold no training state

  // The prefixes only matter for the name lengths charged: these are the trainer's.
  TensorMap state;
  StateWriter out(state, kTrainingStatePrefix);
  StateWriter algo_state = out.sub("algo");
  try {
    algorithm->save_training_state(algo_state);
  } catch (const std::logic_error&) {
    return budget;  // an algorithm without resume support (DDPG today): no training state
  }
  StateWriter env_state = out.sub("env");
  env.write_state(env_state);
  budget = add(budget, tensor_map_charge(state));
  budget = add(budget, replay_buffer_growth(state));
  budget = add(budget, mul(kCheckpointSlackPerEnvBytes, static_cast<uint64_t>(n_envs)));
  if (tap_env >= 0) {
    // ObsLogCallback::write_state: the rows since the last chunk (obs_log_callback.cpp reserves
    // freq / n_envs + 2 of them), float32, of the observation the tap sees.
    const ObservationTap* tap = find_wrapper<ObservationTap>(env.env(tap_env));
    const auto obs_dim = static_cast<uint64_t>(tap ? tap->observation_space().flat_dim() : 0);
    const auto rows = static_cast<uint64_t>(experiment.obs_log.freq / n_envs + 2);
    budget = add(budget, mul(mul(rows, obs_dim), sizeof(float)));
  }
  return budget;
}

ModelFile read_checkpoint(const std::string& path, const Experiment& experiment,
                          const Registry& registry) {
  ModelFile checkpoint = read_model_header(path);
  if (checkpoint.holds_training_state)
    read_model_tensors(checkpoint, ModelParts::kCheckpoint,
                       checkpoint_tensor_budget(experiment, registry));
  return checkpoint;
}

}  // namespace rlrun
