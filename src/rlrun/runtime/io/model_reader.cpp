// Reading model files in two phases (model_file.hpp), without trusting what they declare.
#include <nlohmann/json.hpp>

#include <cstring>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/npy.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/core/zip_reader.hpp"
#include "rlrun/env/space_json.hpp"
#include "rlrun/runtime/experiment/env_statistics.hpp"
#include "rlrun/runtime/io/model_file.hpp"
#include "rlrun/runtime/io/non_finite_check.hpp"

namespace rlrun {

namespace {

bool is_tensor_member(const ZipEntry& e) {
  return !e.directory && e.name.size() > 4 && e.name.compare(e.name.size() - 4, 4, ".npy") == 0;
}

TensorMap& group_of(ModelFile& model, const std::string& key) {
  if (key.rfind(kWrapperStatisticsPrefix, 0) == 0) return model.wrapper_statistics;
  if (key.rfind(kTrainingStatePrefix, 0) == 0) return model.training_state;
  return model.tensors;
}

// meta.json's fields, each of the type rlrun writes (nlohmann's get<int>() on a float or an
// out-of-range number would convert it unchecked).
std::string text_field(const nlohmann::json& meta, const char* key) {
  const auto it = meta.find(key);
  if (it == meta.end() || !it->is_string())
    throw RuntimeFailure(std::string("'") + key + "' is missing or not a string");
  return it->get<std::string>();
}
int64_t integer_field(const nlohmann::json& meta, const char* key) {
  const auto it = meta.find(key);
  if (it == meta.end() || !it->is_number_integer() ||
      (it->is_number_unsigned() && it->get<uint64_t>() > uint64_t{INT64_MAX}))
    throw RuntimeFailure(std::string("'") + key + "' is missing or not an integer");
  return it->get<int64_t>();
}

// "env_spaces" (files written since rlrun recorded them): the env's own spaces, each as
// env/space_json.hpp decodes it, and its number of agents.
EnvSpaces env_spaces_field(const nlohmann::json& env) {
  if (!env.is_object()) throw RuntimeFailure("'env_spaces' is not a JSON object");
  EnvSpaces spaces;
  for (const auto& [key, space] : {std::pair{"observation_space", &spaces.observation},
                                   std::pair{"action_space", &spaces.action}}) {
    const auto it = env.find(key);
    if (it == env.end()) throw RuntimeFailure(std::string("'env_spaces' has no '") + key + "'");
    try {
      *space = space_from_json(*it);
    } catch (const std::invalid_argument& e) {
      throw RuntimeFailure(std::string("'env_spaces' ") + key + ": " + e.what());
    }
  }
  const int64_t agents = integer_field(env, "num_agents");
  if (agents < 1 || agents > kMaxModelAgents)
    throw RuntimeFailure("'env_spaces' num_agents is " + std::to_string(agents) + ", not 1 to " +
                         std::to_string(kMaxModelAgents));
  spaces.num_agents = static_cast<int>(agents);
  if (const auto render = env.find("render"); render != env.end()) {
    // The env's render size (written since AddRenderObservation needed it), as Frame bounds it.
    if (!render->is_object()) throw RuntimeFailure("'env_spaces' render is not a JSON object");
    const int64_t width = integer_field(*render, "width"),
                  height = integer_field(*render, "height");
    const auto fps = render->find("fps");
    if (width < 1 || width > 16384 || height < 1 || height > 16384 || fps == render->end() ||
        !fps->is_number() || !(fps->get<double>() > 0.0 && fps->get<double>() <= 1000.0))
      throw RuntimeFailure(
          "'env_spaces' render needs width and height of 1 to 16384 and fps of "
          "more than 0 to 1000");
    spaces.render = {static_cast<int>(width), static_cast<int>(height), fps->get<double>()};
  }
  return spaces;
}

ModelMeta parse_meta(const std::vector<uint8_t>& bytes, const std::string& path) {
  ModelMeta m;
  try {
    const auto meta = nlohmann::json::parse(bytes.begin(), bytes.end());
    if (!meta.is_object()) throw RuntimeFailure("not a JSON object");
    const int64_t version = integer_field(meta, "format_version");
    if (version != kModelFormatVersion) {
      const auto written_by = meta.find("rlrun_version");
      throw RuntimeFailure(path + ": model format version " + std::to_string(version) +
                           " (written by rlrun " +
                           (written_by != meta.end() && written_by->is_string()
                                ? written_by->get<std::string>().substr(0, 40)
                                : std::string("?")) +
                           ") is not supported by rlrun " RLRUN_VERSION ", which reads version " +
                           std::to_string(kModelFormatVersion));
    }
    m.format_version = kModelFormatVersion;
    m.rlrun_version = text_field(meta, "rlrun_version");
    m.algorithm = text_field(meta, "algorithm");
    m.env_id = text_field(meta, "env_id");
    m.observation_space = text_field(meta, "observation_space");
    m.action_space = text_field(meta, "action_space");
    m.num_timesteps = integer_field(meta, "num_timesteps");
    if (const auto env = meta.find("env_spaces"); env != meta.end())
      m.env_spaces = env_spaces_field(*env);
  } catch (const nlohmann::json::exception& e) {
    throw RuntimeFailure(path + ": meta.json is malformed: " + e.what());
  } catch (const RuntimeFailure& e) {
    const std::string what = e.what();
    if (what.rfind(path + ":", 0) == 0) throw;
    throw RuntimeFailure(path + ": meta.json is malformed: " + what);
  }
  return m;
}

// One `.npy` member, its header checked against the zip's declared size before the data is
// allocated; the allocation is then at most that size, which the caller's budget covered.
Tensor read_npy_member(const ZipReader& archive, const ZipEntry& entry) {
  const std::string what = archive.describe(entry);
  ZipMemberReader member(archive, entry);
  if (entry.size < kNpyPreludeBytes)
    throw RuntimeFailure(what + ": not a supported .npy array (only " +
                         count_of(static_cast<int64_t>(entry.size), "byte") + ")");
  std::vector<uint8_t> header(kNpyPreludeBytes);
  NpyHeader h;
  try {
    member.read(header.data(), header.size());
    const size_t header_len = npy_header_length(header.data(), header.size(), what);
    if (header_len > member.remaining())
      throw RuntimeFailure(what +
                           ": not a supported .npy array (its header is longer than "
                           "the member)");
    header.resize(kNpyPreludeBytes + header_len);  // at most 64 KiB + 10
    member.read(header.data() + kNpyPreludeBytes, header_len);
    h = parse_npy_header(header.data(), header.size(), what);
  } catch (const RuntimeFailure&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw RuntimeFailure(e.what());
  }
  if (h.data_bytes != member.remaining())
    throw RuntimeFailure(what + ": not a supported .npy array (its shape needs " +
                         count_of(static_cast<int64_t>(h.data_bytes), "byte") +
                         " of data, the zip declares " + std::to_string(member.remaining()) + ")");
  Tensor t;
  t.dtype = h.dtype;
  t.shape = std::move(h.shape);
  t.bytes.resize(static_cast<size_t>(h.data_bytes));
  member.read(t.bytes.data(), t.bytes.size());
  member.expect_end();
  return t;
}

// "statistic wrappers/NormalizeObservation/var has a negative value (-1.000000)" for the first
// variance or count below 0 (RunningMeanStd's `var` and `count`), or "".
std::string describe_negative_statistic(const TensorMap& statistics) {
  for (const auto& [name, tensor] : statistics) {
    const bool counted = name.ends_with("/var") || name.ends_with("/count");
    if (!counted || tensor.dtype != DType::kFloat64) continue;
    for (size_t at = 0; at + sizeof(double) <= tensor.bytes.size(); at += sizeof(double)) {
      double v = 0;
      std::memcpy(&v, tensor.bytes.data() + at, sizeof v);  // bytes need not be aligned
      if (v < 0) return "statistic " + name + " has a negative value (" + std::to_string(v) + ")";
    }
  }
  return "";
}

// Weights and normalisation statistics from anyone must be numbers: a NaN weight evaluates to
// a mean reward of nan with exit 0, and would be exported (issue 41). The training state is
// checked where it is read (get_finite_matrix, RunningMeanStd::read): some of it may be
// infinite (EvalCallback's best reward starts at -inf).
void check_numbers(const ModelFile& model) {
  std::string problem = describe_non_finite(model.tensors, "parameter");
  if (problem.empty()) problem = describe_non_finite(model.wrapper_statistics, "statistic");
  if (problem.empty()) problem = describe_negative_statistic(model.wrapper_statistics);
  if (!problem.empty()) throw RuntimeFailure(model.path + ": " + problem);
}

}  // namespace

ModelFile read_model_header(const std::string& path) {
  const ZipReader archive(path);
  const ZipEntry* meta = archive.find("meta.json");
  const ZipEntry* config = archive.find("config.yaml");
  if (!meta || !config)
    throw RuntimeFailure(path + ": not an rlrun model file (no meta.json or config.yaml inside)");
  ModelFile model;
  model.path = path;
  model.meta = parse_meta(archive.read(*meta, kMaxModelTextBytes), path);
  const std::vector<uint8_t> config_bytes = archive.read(*config, kMaxModelTextBytes);
  model.config_yaml.assign(config_bytes.begin(), config_bytes.end());
  for (const ZipEntry& e : archive.entries())
    if (is_tensor_member(e) && e.name.rfind(kTrainingStatePrefix, 0) == 0)
      model.holds_training_state = true;
  return model;
}

void read_model_tensors(ModelFile& model, ModelParts parts, uint64_t budget_bytes) {
  // The file is opened again: phase 2 checks everything it reads itself, so a file replaced
  // between the phases is no more dangerous than any other file.
  const ZipReader archive(model.path);
  std::vector<const ZipEntry*> selected;
  uint64_t charged = 0;
  for (const ZipEntry& e : archive.entries()) {
    if (!is_tensor_member(e)) continue;  // unknown members stay unread
    if (parts == ModelParts::kModel && e.name.rfind(kTrainingStatePrefix, 0) == 0) continue;
    selected.push_back(&e);
    if (__builtin_add_overflow(charged, tensor_member_charge(e.name.size(), e.size), &charged))
      charged = UINT64_MAX;
  }
  if (charged > budget_bytes)
    throw RuntimeFailure(model.path + ": its tensors declare " + std::to_string(charged) +
                         " bytes, more than the " + std::to_string(budget_bytes) +
                         " bytes a model of its configuration holds; the file is damaged or was "
                         "not written by rlrun for this configuration");
  for (const ZipEntry* e : selected) {
    const std::string key = e->name.substr(0, e->name.size() - 4);
    group_of(model, key)[key] = read_npy_member(archive, *e);
  }
  check_numbers(model);
}

ModelFile read_model(const std::string& path, uint64_t budget_bytes) {
  ModelFile model = read_model_header(path);
  read_model_tensors(model, ModelParts::kCheckpoint, budget_bytes);
  return model;
}

}  // namespace rlrun
