#include "rlrun/runtime/io/sb3/sb3_vec_normalize.hpp"
#include "rlrun/runtime/io/sb3/rl_zoo_folder_name.hpp"

#include <fcntl.h>

#include <filesystem>
#include <vector>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/numpy_pickle.hpp"
#include "rlrun/core/pickle_reader.hpp"
#include "rlrun/core/regular_file.hpp"
#include "rlrun/runtime/io/non_finite_check.hpp"
#include "rlrun/runtime/io/sb3/sb3_spaces.hpp"
#include "rlrun/state.hpp"

namespace rlrun {

namespace {

// The pickle holds the spaces and the last observations of the training envs: a few KiB.
constexpr uint64_t kMaxVecNormalizeBytes = uint64_t{16} << 20;

bool vec_normalize_global(const std::string& module, const std::string& name) {
  if (module == "stable_baselines3.common.vec_env.vec_normalize") return name == "VecNormalize";
  if (module == "stable_baselines3.common.running_mean_std") return name == "RunningMeanStd";
  return is_sb3_space_global(module, name);
}

class VecNormalizeReader {
 public:
  VecNormalizeReader(const std::string& path, int64_t observation_dim)
      : path_(path), observation_dim_(observation_dim) {}

  Sb3VecNormalize read() {
    const FileDescriptor fd = open_regular_file(AT_FDCWD, path_, O_RDONLY, path_);
    if (!fd) fail("no such file");
    const std::string bytes = read_bounded(fd.get(), kMaxVecNormalizeBytes, path_);
    const PickleDocument document = read_pickle(reinterpret_cast<const uint8_t*>(bytes.data()),
                                                bytes.size(), path_, vec_normalize_global);
    const PickleValue& root = document.root();
    const PickleValue* callee = root.callee();
    if (!callee || callee->text != "VecNormalize" || !root.state)
      fail("holds " + describe_pickle_value(root) + ", not a VecNormalize");
    const PickleValue& state = *root.state;
    Sb3VecNormalize out;
    out.setting.enabled = true;
    out.setting.norm_obs = flag(state, "norm_obs");
    out.setting.norm_reward = flag(state, "norm_reward");
    out.setting.clip_obs = number(state, "clip_obs");
    out.setting.clip_reward = number(state, "clip_reward");
    out.setting.gamma = number(state, "gamma");
    out.setting.epsilon = number(state, "epsilon");
    if (out.setting.norm_obs)
      running_statistics(attribute(state, "obs_rms"), "NormalizeObservation", observation_dim_,
                         out.statistics);
    if (out.setting.norm_reward)
      running_statistics(attribute(state, "ret_rms"), "NormalizeReward", 1, out.statistics);
    const std::string problem = describe_non_finite(out.statistics, "statistic");
    if (!problem.empty()) fail(problem);
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw RuntimeFailure(path_ + ": " + why + " (SB3's vecnormalize.pkl: docs/sb3_models.md)");
  }

  // The attribute `name` of a pickled object's __dict__.
  const PickleValue& attribute(const PickleValue& state, const char* name) const {
    const PickleValue* found = pickle_dict_get(state, name);
    if (!found) fail(std::string("no '") + name + "' attribute");
    return *found;
  }
  bool flag(const PickleValue& state, const char* name) const {
    const PickleValue& value = attribute(state, name);
    if (value.kind != PickleKind::kBool) fail(std::string("'") + name + "' is not a bool");
    return value.boolean;
  }
  double number(const PickleValue& state, const char* name) const {
    return pickled_number(attribute(state, name), path_ + ": '" + name + "'");
  }

  // RunningMeanStd's mean, var (`dim` values) and count, under the names rlrun's own
  // RunningMeanStd::write gives them (wrappers/running_mean_std.cpp).
  void running_statistics(const PickleValue& rms, const char* wrapper, int64_t dim,
                          TensorMap& out) const {
    const PickleValue* callee = rms.callee();
    if (!callee || callee->text != "RunningMeanStd" || !rms.state)
      fail(std::string("its ") + (dim == 1 ? "ret_rms" : "obs_rms") + " is " +
           describe_pickle_value(rms) + ", not a RunningMeanStd of one array");
    StateWriter writer(out, std::string("wrappers/") + wrapper + "/");
    for (const char* field : {"mean", "var"})
      writer.put_vector(field, doubles(attribute(*rms.state, field), dim, field));
    writer.put_double("count", number(*rms.state, "count"));
  }
  std::vector<double> doubles(const PickleValue& value, int64_t dim, const char* field) const {
    std::vector<double> values;
    if (is_numpy_array(value))
      values = numpy_array(value, path_).to_doubles();
    else
      values = {pickled_number(value, path_)};
    if (static_cast<int64_t>(values.size()) != dim)
      fail(std::string("its ") + field + " holds " + std::to_string(values.size()) +
           " values, the model's observations " + std::to_string(dim));
    return values;
  }

  std::string path_;
  int64_t observation_dim_;
};

}  // namespace

std::optional<std::string> find_sb3_vec_normalize(const std::string& model_path) {
  const std::filesystem::path model(model_path);
  std::vector<std::filesystem::path> candidates = {
      model.parent_path() / "vecnormalize.pkl",
      model.parent_path() / model.stem() / "vecnormalize.pkl"};
  // An rl-zoo run folder <env>_<n>/ keeps them in <env>/ for every model in it (best_model.zip,
  // rl_model_<N>_steps.zip), as rl_zoo3.enjoy reads them.
  const std::string env = rl_zoo_folder_env(model.parent_path().filename().string());
  if (!env.empty()) candidates.push_back(model.parent_path() / env / "vecnormalize.pkl");
  std::error_code ec;
  for (const std::filesystem::path& candidate : candidates)
    if (std::filesystem::exists(candidate, ec)) return candidate.string();
  return std::nullopt;
}

Sb3VecNormalize read_sb3_vec_normalize(const std::string& path, int64_t observation_dim) {
  return VecNormalizeReader(path, observation_dim).read();
}

}  // namespace rlrun
